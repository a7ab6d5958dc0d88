// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/track.hpp"

#include <cstring>

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

std::optional<TrackState> parseTrackState(const char *text) {
  if (!text) return std::nullopt;
  for (TrackState state :
       {TrackState::Searching, TrackState::Tracking, TrackState::Coasting, TrackState::Lost})
    if (!std::strcmp(text, toString(state))) return state;
  return std::nullopt;
}

}  // namespace colortrack
