// SPDX-License-Identifier: LGPL-2.1-or-later
// The peak moving onto the second object of the window before (issue 46): taken for a takeover by a
// look-alike; a peak that stays, that moves elsewhere, or a second object that comes to the peak is not.
#include <gtest/gtest.h>

#include "colortrack/look_alike_takeover.hpp"

using colortrack::LookAlikeTakeover;

namespace {

constexpr double kSide = 40;
const cv::Point2d kTarget(100, 100), kTwin(140, 100);  // the twin one side to the right

}  // namespace

TEST(LookAlikeTakeover, APeakOnTheTwinSeenBeforeIsATakeover) {
  LookAlikeTakeover t;
  EXPECT_FALSE(t.observe(kTarget, kTarget, kTwin, kSide));
  EXPECT_TRUE(t.observe(kTwin + cv::Point2d(3, 2), kTarget, std::nullopt, kSide));
}

// A twin standing close beside a target that stays (both peaks within half a side of each other): the peak is
// near the twin's place, but it did not move there.
TEST(LookAlikeTakeover, APeakThatStaysIsNone) {
  LookAlikeTakeover t;
  const cv::Point2d closeTwin = kTarget + cv::Point2d(15, 0);
  for (int i = 0; i < 10; ++i)
    EXPECT_FALSE(t.observe(kTarget + cv::Point2d(i, 0), kTarget, closeTwin, kSide));
}

TEST(LookAlikeTakeover, AJumpElsewhereIsNone) {
  LookAlikeTakeover t;
  t.observe(kTarget, kTarget, kTwin, kSide);
  EXPECT_FALSE(t.observe(kTarget - cv::Point2d(40, 0), kTarget, std::nullopt, kSide));  // the other way
}

TEST(LookAlikeTakeover, OnlyTheWindowJustBeforeCounts) {
  LookAlikeTakeover t;
  t.observe(kTarget, kTarget, kTwin, kSide);
  t.observe(kTarget, kTarget, std::nullopt, kSide);  // the twin no longer shown
  EXPECT_FALSE(t.observe(kTwin, kTarget, std::nullopt, kSide));
}

// A twin that walks up to the target, whose peak stays put, is no takeover, however near the two come.
TEST(LookAlikeTakeover, ATwinComingToThePeakIsNone) {
  LookAlikeTakeover t;
  for (int x = 140; x >= 110; x -= 5)
    EXPECT_FALSE(t.observe(kTarget, kTarget, cv::Point2d(x, 100), kSide)) << x;
}

TEST(LookAlikeTakeover, ResetForgetsTheTwin) {
  LookAlikeTakeover t;
  t.observe(kTarget, kTarget, kTwin, kSide);
  t.reset();
  EXPECT_FALSE(t.observe(kTwin, kTarget, std::nullopt, kSide));
}
