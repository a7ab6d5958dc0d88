// Track state machine.
#pragma once

#include <string>

namespace colortrack {

// searching -> tracking -> coasting -> lost -> searching
enum class TrackState { Searching, Tracking, Coasting, Lost };

const char *toString(TrackState state);

}  // namespace colortrack
