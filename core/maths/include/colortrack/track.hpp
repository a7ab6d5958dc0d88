// SPDX-License-Identifier: LGPL-2.1-or-later
// Track state machine.
#pragma once

#include <optional>
#include <string>

namespace colortrack {

// searching -> tracking -> coasting -> lost -> searching
enum class TrackState { Searching, Tracking, Coasting, Lost };

const char *toString(TrackState state);
// The state `toString` names; nullopt for null or any other text.
std::optional<TrackState> parseTrackState(const char *text);

}  // namespace colortrack
