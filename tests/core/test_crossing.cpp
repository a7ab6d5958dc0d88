// Identities through a crossing (issue 46): the window's two peaks are followed as the target and a
// look-alike; when they part after meeting, the one that continues the target's motion is the target.
#include <optional>

#include <gtest/gtest.h>

#include "colortrack/crossing.hpp"

using colortrack::Crossing;

namespace {

const cv::Size2d kSize(40, 80);

// The target stands at x = 200 (y = 100); a look-alike comes from the left at `speed` px per frame. The
// window's peak is whichever the caller says; the second peak is the other while they are more than half a
// width apart, and there is none while they overlap.
struct Scene {
  double lookAlike = 100;
  double speed = 8;
  cv::Point2d target() const { return {200, 100}; }
  cv::Point2d other() const { return {lookAlike, 100}; }
  bool apart() const { return std::abs(lookAlike - 200) > kSize.width / 2; }
};

}  // namespace

TEST(Crossing, APeakThatLeavesWithTheLookAlikeIsGivenBack) {
  Crossing crossing;
  Scene scene;
  for (int i = 0; i < 20; ++i) ASSERT_FALSE(crossing.observe(scene.target(), std::nullopt, kSize));
  std::optional<cv::Point2d> back;
  for (int frame = 0; frame < 40 && !back; ++frame) {
    scene.lookAlike += scene.speed;
    // In front of the target: once they meet, the peak is the look-alike's and goes on with it.
    const bool peakOnLookAlike = scene.lookAlike >= 200 - kSize.width / 2;
    const cv::Point2d peak = peakOnLookAlike ? scene.other() : scene.target();
    const cv::Point2d second = peakOnLookAlike ? scene.target() : scene.other();
    back = crossing.observe(peak, scene.apart() ? std::optional(second) : std::nullopt, kSize);
  }
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, scene.target());
  EXPECT_GT(scene.lookAlike, 200 + kSize.width / 2);  // given back as soon as they parted
}

TEST(Crossing, APeakThatStaysOnTheTargetIsKept) {
  Crossing crossing;
  Scene scene;
  for (int i = 0; i < 20; ++i) crossing.observe(scene.target(), std::nullopt, kSize);
  for (int frame = 0; frame < 40; ++frame) {
    scene.lookAlike += scene.speed;
    const auto second = scene.apart() ? std::optional(scene.other()) : std::nullopt;
    ASSERT_FALSE(crossing.observe(scene.target(), second, kSize)) << "frame " << frame;
  }
}

TEST(Crossing, AHopOntoTheLookAlikeBeforeTheyMeetIsUndone) {
  Crossing crossing;
  Scene scene;
  for (int i = 0; i < 20; ++i) crossing.observe(scene.target(), std::nullopt, kSize);
  for (int frame = 0; frame < 5; ++frame) {
    scene.lookAlike += scene.speed;
    ASSERT_FALSE(crossing.observe(scene.target(), scene.other(), kSize));
  }
  scene.lookAlike += scene.speed;  // still a width and a half apart, the peak jumps to the look-alike
  const auto back = crossing.observe(scene.other(), scene.target(), kSize);
  ASSERT_TRUE(back);
  EXPECT_EQ(*back, scene.target());
}

TEST(Crossing, SecondPeaksWithNoMotionOfTheirOwnNeverSwap) {
  // A crowd: the second peak is somewhere else each frame, so no look-alike's motion is ever known.
  Crossing crossing;
  const cv::Point2d places[] = {{120, 100}, {260, 60}, {150, 160}, {240, 140}};
  for (int frame = 0; frame < 80; ++frame) {
    const cv::Point2d target(200 + frame % 3, 100);
    ASSERT_FALSE(crossing.observe(target, places[frame % 4], kSize)) << "frame " << frame;
  }
}

TEST(Crossing, ResetForgetsBothMotions) {
  Crossing crossing;
  Scene scene;
  for (int i = 0; i < 20; ++i) crossing.observe(scene.target(), std::nullopt, kSize);
  for (int frame = 0; frame < 5; ++frame) {
    scene.lookAlike += scene.speed;
    crossing.observe(scene.target(), scene.other(), kSize);
  }
  crossing.reset();
  scene.lookAlike += scene.speed;
  EXPECT_FALSE(crossing.observe(scene.other(), scene.target(), kSize));
}
