// SPDX-License-Identifier: LGPL-2.1-or-later
// A return to `tracking` far from the last `tracking` place (issue 46): held back for 30 tracked frames; a
// return near it, a track that never stopped being tracked, and a track begun after a loss are not.
#include <gtest/gtest.h>

#include "colortrack/distant_return.hpp"

using colortrack::DistantReturn;

namespace {

constexpr double kSide = 40;
constexpr double kFarSides = 1.5;

// Frames at `x` (y 100), tracked or not; returns how many were held back.
int observe(DistantReturn &r, double x, int frames, bool tracked = true) {
  int held = 0;
  for (int i = 0; i < frames; ++i) held += r.observe(tracked, cv::Point2d(x, 100), kSide);
  return held;
}

}  // namespace

TEST(DistantReturn, AReturnFarFromTheLastTrackingPlaceIsHeldForThirtyTrackedFrames) {
  DistantReturn r(kFarSides);
  EXPECT_EQ(observe(r, 100, 20), 0);
  observe(r, 130, 5, false);           // coasting, drifting away
  EXPECT_EQ(observe(r, 170, 30), 30);  // 70 px: more than 1.5 sides
  EXPECT_EQ(observe(r, 172, 10), 0);   // then reported as usual
}

TEST(DistantReturn, AReturnNearTheLastTrackingPlaceIsNotHeld) {
  DistantReturn r(kFarSides);
  observe(r, 100, 20);
  observe(r, 200, 5, false);          // the box wandered while not tracked ...
  EXPECT_EQ(observe(r, 150, 10), 0);  // ... and came back 50 px from where it was: under 1.5 sides
}

TEST(DistantReturn, MovingWhileTrackedIsNoReturn) {
  DistantReturn r(kFarSides);
  int held = 0;
  for (int i = 0; i < 100; ++i) held += r.observe(true, cv::Point2d(100 + 5.0 * i, 100), kSide);
  EXPECT_EQ(held, 0);
}

TEST(DistantReturn, ATrackBegunAfterALossHasNoPlaceToReturnTo) {
  DistantReturn r(kFarSides);
  observe(r, 100, 20);
  observe(r, 100, 3, false);
  r.reset();
  EXPECT_EQ(observe(r, 400, 10), 0);
}

// The far bar is the caller's: at 2 sides, a return 70 px (1.75 sides) away is near.
TEST(DistantReturn, TheFarBarIsTheCallers) {
  DistantReturn r(2.0);
  observe(r, 100, 20);
  observe(r, 130, 5, false);
  EXPECT_EQ(observe(r, 170, 10), 0);
}
