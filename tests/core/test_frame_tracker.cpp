// SPDX-License-Identifier: LGPL-2.1-or-later
// The interface the element drives: both trackers, seen only as FrameTracker, report what their own outputs
// say, with the primary target among the tracks, and forget their tracks on reset().
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "balls.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/threshold_tracker.hpp"
#include "colortrack/tracker.hpp"
#include "scene.hpp"

using namespace colortrack;

namespace {

// Two balls of different sizes moving apart over a cluttered background.
balls::BallScene twoBalls() {
  balls::Ball big, small;
  big.hue = 0;
  big.radius = 30;
  big.path = {{0, {200, 240}}, {60, {260, 200}}};
  small.hue = 220;
  small.radius = 14;
  small.path = {{0, {460, 240}}, {60, {420, 300}}};
  balls::BallSceneConfig config;
  config.clutterSaturation = 0.3;  // under the range's saturation: only the balls are selected
  return balls::BallScene(config, {big, small});
}

BlobSettings saturatedColours() {
  BlobSettings settings;
  settings.range.lower = {0, 0.5, 0.25};
  settings.range.upper = {360, 1, 1};
  return settings;
}

}  // namespace

TEST(ThresholdTracker, ReportsEveryBallWithTheLargestAsPrimary) {
  const balls::BallScene scene = twoBalls();
  ThresholdTracker threshold(saturatedColours());
  FrameTracker &tracker = threshold;
  FrameReport report;
  for (int i = 0; i < 30; ++i) {
    const cv::Mat frame = scene.render(i);
    report = tracker.track(MatImageSource(frame), 1.0);
  }
  EXPECT_TRUE(report.listsTracks);
  ASSERT_EQ(report.tracks.size(), 2u);
  EXPECT_FALSE(report.mask.empty());
  EXPECT_GE(report.maskStep, 1);
  const balls::BallTruth big = scene.truthOf(0, 29), small = scene.truthOf(1, 29);
  // The primary is the big ball, and each report's centre and area belong to its ball.
  EXPECT_EQ(report.primary.state, TrackState::Tracking);
  EXPECT_LT(cv::norm(report.primary.centre - big.centre), 3.0);
  for (const TrackReport &t : report.tracks) {
    ASSERT_TRUE(t.area.has_value());
    const balls::BallTruth &truth =
        cv::norm(t.centre - big.centre) < cv::norm(t.centre - small.centre) ? big : small;
    EXPECT_LT(cv::norm(t.centre - truth.centre), 3.0);
    EXPECT_NEAR(*t.area, CV_PI * truth.radius * truth.radius, 0.25 * CV_PI * truth.radius * truth.radius);
    EXPECT_TRUE(t.verified);
  }
  EXPECT_NE(report.tracks[0].id, report.tracks[1].id);

  tracker.reset();
  const FrameReport afterReset = tracker.track(MatImageSource(scene.render(30)), 1.0);
  EXPECT_TRUE(afterReset.tracks.empty()) << "new tracks must be confirmed again after a reset";
  EXPECT_EQ(afterReset.primary.state, TrackState::Searching);
  EXPECT_TRUE(afterReset.primary.box.empty());
}

TEST(ThresholdTracker, BallsThatAppearOverlappingGetATrackEach) {
  // One blob from the first frame until they part (frame ~12): their shape tells the two balls apart.
  balls::Ball big, small;
  big.radius = 24;
  big.path = {{0, {300, 240}}, {30, {240, 240}}};
  small.radius = 13;
  small.path = {{0, {330, 222}}, {30, {390, 222}}};
  balls::BallSceneConfig config;
  config.clutterSaturation = 0.3;
  const balls::BallScene scene(config, {big, small});
  ThresholdTracker tracker(saturatedColours());
  for (int i = 0; i < 6; ++i) {
    const FrameReport report = tracker.track(MatImageSource(scene.render(i)), 1.0);
    if (i < 2) continue;  // tracks are confirmed on their third frame
    ASSERT_EQ(report.tracks.size(), 2u) << "frame " << i;
    for (int b = 0; b < 2; ++b) {
      const balls::BallTruth truth = scene.truthOf(b, i);
      const auto near = std::count_if(report.tracks.begin(), report.tracks.end(), [&](const TrackReport &t) {
        return cv::norm(t.centre - truth.centre) < 0.5 * truth.radius;
      });
      EXPECT_EQ(near, 1) << "ball " << b << ", frame " << i;
    }
  }
}

TEST(ThresholdTracker, ABallThatAppearsTouchingATrackedOneGetsItsOwnTrack) {
  // A tracked red ball; from frame 5 a second one lies against it (one blob), and the first keeps its id.
  ThresholdTracker tracker;  // the default range: red
  const auto frameAt = [](int i) {
    cv::Mat bgr(480, 640, CV_8UC3, cv::Scalar(40, 40, 40));
    cv::circle(bgr, {200 + 2 * i, 200}, 30, cv::Scalar(0, 0, 220), cv::FILLED);
    if (i >= 5) cv::circle(bgr, {245 + 2 * i, 218}, 16, cv::Scalar(0, 0, 220), cv::FILLED);
    return bgr;
  };
  FrameReport report;
  for (int i = 0; i < 5; ++i) report = tracker.track(MatImageSource(frameAt(i)), 1.0);
  ASSERT_EQ(report.tracks.size(), 1u);
  const int firstId = report.tracks[0].id;
  for (int i = 5; i < 9; ++i) report = tracker.track(MatImageSource(frameAt(i)), 1.0);
  ASSERT_EQ(report.tracks.size(), 2u);
  const cv::Point2d big(200 + 2 * 8, 200), small(245 + 2 * 8, 218);
  const auto isSmall = [&](const TrackReport &t) { return cv::norm(t.centre - small) < 5.0; };
  ASSERT_EQ(std::count_if(report.tracks.begin(), report.tracks.end(), isSmall), 1);
  for (const TrackReport &t : report.tracks) {
    EXPECT_EQ(!isSmall(t), t.id == firstId);
    // The big ball's track is fed the whole blob once both are reported (the tracker's merge rule): near
    // the big ball, not on it.
    if (!isSmall(t)) {
      EXPECT_LT(cv::norm(t.centre - big), 15.0);
    }
  }
}

TEST(TemplateTracker, ReportsItsTrackAsThePrimaryAndOnlyTrack) {
  scene::SceneConfig config;
  const scene::Scene scene(config);
  Tracker templateTracker;
  templateTracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
  FrameTracker &tracker = templateTracker;
  for (int i = 1; i < 20; ++i) {
    const scene::SceneFrame frame = scene.render(i);
    const FrameReport report = tracker.track(MatImageSource(frame.bgr), 1.0);
    EXPECT_FALSE(report.listsTracks);
    ASSERT_EQ(report.tracks.size(), 1u) << "frame " << i;
    const TrackReport &t = report.tracks[0];
    EXPECT_EQ(t.id, report.primary.id);
    EXPECT_EQ(t.box, report.primary.box);
    EXPECT_GT(scene::iou(t.box, frame.box), 0.6) << "frame " << i;
    EXPECT_NEAR(t.centre.x, t.box.x + t.box.width / 2, 1e-9);
    EXPECT_FALSE(t.area.has_value());
    EXPECT_FALSE(report.searchRegion.empty());
  }
  // Lost on purpose: a reset forgets the track, and the next frame reports no box until it is found again.
  tracker.reset();
  EXPECT_TRUE(templateTracker.hasTemplate());
}
