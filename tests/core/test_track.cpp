// SPDX-License-Identifier: LGPL-2.1-or-later
// Track states as text: parseTrackState reads back what toString writes.
#include <gtest/gtest.h>

#include "colortrack/track.hpp"

namespace colortrack {
namespace {

TEST(TrackStateText, RoundTripsEveryState) {
  for (TrackState state :
       {TrackState::Searching, TrackState::Tracking, TrackState::Coasting, TrackState::Lost})
    EXPECT_EQ(parseTrackState(toString(state)), state) << toString(state);
}

TEST(TrackStateText, RejectsNullAndUnknownText) {
  EXPECT_EQ(parseTrackState(nullptr), std::nullopt);
  EXPECT_EQ(parseTrackState(""), std::nullopt);
  EXPECT_EQ(parseTrackState("Tracking"), std::nullopt);  // case matters, as in the metadata
  EXPECT_EQ(parseTrackState("unknown"), std::nullopt);
}

}  // namespace
}  // namespace colortrack
