#include "colortrack/track.hpp"

namespace colortrack {

const char *toString(TrackState state) {
  switch (state) {
    case TrackState::Searching:
      return "searching";
    case TrackState::Tracking:
      return "tracking";
    case TrackState::Coasting:
      return "coasting";
    case TrackState::Lost:
      return "lost";
  }
  return "unknown";  // unreachable for valid enum values; keeps -Wreturn-type quiet
}

}  // namespace colortrack
