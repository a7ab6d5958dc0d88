// SPDX-License-Identifier: LGPL-2.1-or-later
// The whole tracker on the synthetic scene, without GStreamer: accuracy under motion, rotation, scale and
// lighting; decoys; loss and re-acquisition; bad input.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "colortrack/tracker.hpp"
#include "scene.hpp"

using namespace colortrack;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;
using colortrack::scene::SceneFrame;

namespace {

SceneConfig hardConfig() {
  SceneConfig c;
  c.frameSize = {640, 480};
  c.frames = 200;
  c.rotationDegrees = 90;
  c.scaleMin = 0.7;
  c.scaleMax = 1.4;
  c.brightness = 0.4;
  return c;
}

// The behaviour tests run for every method: the paper's colour indexing, the colour-only discriminative
// method and the fused default.
class TrackerMethod : public ::testing::TestWithParam<Method> {
 protected:
  TrackerSettings settings() const {
    TrackerSettings s;
    s.method = GetParam();
    return s;
  }
};

}  // namespace

INSTANTIATE_TEST_SUITE_P(Methods, TrackerMethod,
                         ::testing::Values(Method::Indexing, Method::Discriminative, Method::Fused),
                         [](const auto &info) {
                           return std::string(info.param == Method::Indexing         ? "Indexing"
                                              : info.param == Method::Discriminative ? "Discriminative"
                                                                                     : "Fused");
                         });

TEST_P(TrackerMethod, FollowsMovingTurningScalingObjectUnderLightChanges) {
  const Scene scene(hardConfig());
  Tracker tracker(settings());
  const SceneFrame first = scene.render(0);
  tracker.setTemplateFromBox(MatImageSource(first.bgr), scene.initBox());
  double iouSum = 0;
  int tracked = 0;
  double widthAtSmall = 0, widthAtLarge = 0, gtSmall = 1e9, gtLarge = 0;
  for (int i = 0; i < scene.config().frames; ++i) {
    const SceneFrame f = scene.render(i);
    const TrackOutput out = tracker.process(MatImageSource(f.bgr));
    iouSum += out.hasBox ? scene::iou(out.box, f.box) : 0;
    tracked += out.state == TrackState::Tracking;
    if (out.hasBox && f.objectScale < gtSmall) gtSmall = f.objectScale, widthAtSmall = out.box.width;
    if (out.hasBox && f.objectScale > gtLarge) gtLarge = f.objectScale, widthAtLarge = out.box.width;
  }
  const double meanIou = iouSum / scene.config().frames;
  std::printf("mean IoU %.3f, tracked %d/%d, box width %.1f at scale %.2f, %.1f at scale %.2f\n", meanIou,
              tracked, scene.config().frames, widthAtSmall, gtSmall, widthAtLarge, gtLarge);
  EXPECT_GE(meanIou, 0.6);
  EXPECT_GE(tracked, scene.config().frames * 9 / 10);
  // Dynamic scale: the box is clearly larger where the object is (gtLarge/gtSmall = 2 here).
  EXPECT_GT(widthAtLarge / widthAtSmall, 1.5);
}

TEST_P(TrackerMethod, StartsTrackingAtTheInitBox) {
  const Scene scene(hardConfig());
  Tracker tracker(settings());
  const SceneFrame first = scene.render(0);
  tracker.setTemplateFromBox(MatImageSource(first.bgr), scene.initBox());
  const TrackOutput out = tracker.process(MatImageSource(first.bgr));
  EXPECT_EQ(out.state, TrackState::Tracking);
  EXPECT_EQ(out.id, 1);
  EXPECT_GT(scene::iou(out.box, first.box), 0.8);
  EXPECT_TRUE(out.verified);
}

TEST_P(TrackerMethod, AcquiresFromTemplateImageAnywhere) {
  SceneConfig c = hardConfig();
  c.rotationDegrees = 0;
  c.scaleMin = c.scaleMax = 1.0;
  const Scene scene(c);
  cv::Mat bgr, mask;
  scene.objectTemplate(bgr, mask);
  Tracker tracker(settings());
  tracker.setTemplate(bgr, mask);
  TrackOutput out;
  for (int i = 0; i < 3; ++i) out = tracker.process(MatImageSource(scene.render(i).bgr));
  EXPECT_EQ(out.state, TrackState::Tracking);
  EXPECT_GT(scene::iou(out.box, scene.render(2).box), 0.6);
  EXPECT_TRUE(out.verified);
}

TEST_P(TrackerMethod, DecoyIsReportedUnverified) {
  SceneConfig c = hardConfig();
  c.decoy = true;
  c.leaveFrom = 0;  // the object is away: only the same-colour, untextured decoy is in view
  c.leaveTo = 60;
  const Scene scene(c);
  cv::Mat bgr, mask;
  scene.objectTemplate(bgr, mask);
  Tracker tracker(settings());
  tracker.setTemplate(bgr, mask);
  int onDecoy = 0, verifiedOnDecoy = 0;
  for (int i = 0; i < 40; ++i) {
    const SceneFrame f = scene.render(i);
    const TrackOutput out = tracker.process(MatImageSource(f.bgr));
    if (out.hasBox && out.state == TrackState::Tracking && scene::iou(out.box, f.decoyBox) > 0.3) {
      ++onDecoy;
      verifiedOnDecoy += out.verified;
    }
  }
  EXPECT_GT(onDecoy, 0) << "the decoy has the object's colour; colour alone should find it";
  EXPECT_EQ(verifiedOnDecoy, 0);
}

TEST_P(TrackerMethod, LosesAndReacquiresElsewhere) {
  SceneConfig c = hardConfig();
  c.leaveFrom = 60;
  c.leaveTo = 90;
  const Scene scene(c);
  Tracker tracker(settings());
  tracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
  bool sawLost = false;
  int reacquiredAt = -1;
  for (int i = 0; i < 130 && reacquiredAt < 0; ++i) {
    const SceneFrame f = scene.render(i);
    const TrackOutput out = tracker.process(MatImageSource(f.bgr));
    if (i >= 60 && i < 90) {
      EXPECT_FALSE(out.state == TrackState::Tracking)
          << "frame " << i << ": tracking an object that is not there";
      sawLost |= out.state == TrackState::Lost || out.state == TrackState::Searching;
    }
    if (i >= 90 && out.state == TrackState::Tracking && scene::iou(out.box, f.box) > 0.5) reacquiredAt = i;
  }
  EXPECT_TRUE(sawLost);
  ASSERT_GE(reacquiredAt, 90);
  EXPECT_LE(reacquiredAt, 95);
}

// What the element does on new caps: the template stays, the track is reset, frames are another size.
TEST_P(TrackerMethod, ReacquiresAfterResetOnAnotherFrameSize) {
  SceneConfig small;
  small.frameSize = cv::Size(160, 120);
  small.objectSize = cv::Size(32, 32);
  SceneConfig large = small;
  large.frameSize = cv::Size(240, 180);
  const Scene a(small), b(large);
  Tracker tracker(settings());
  tracker.setTemplateFromBox(MatImageSource(a.render(0).bgr), a.initBox());
  for (int i = 1; i < 10; ++i) tracker.process(MatImageSource(a.render(i).bgr));
  tracker.reset();
  int found = 0;
  for (int i = 10; i < 30; ++i) {
    const SceneFrame f = b.render(i);
    const TrackOutput out = tracker.process(MatImageSource(f.bgr));
    if (i >= 15 && out.hasBox && scene::iou(out.box, f.box) > 0.5) ++found;
  }
  EXPECT_GE(found, 13);
}

TEST(Tracker, RejectsTemplateLargerThanFrame) {
  Tracker tracker;
  tracker.setTemplate(cv::Mat(100, 100, CV_8UC3, cv::Scalar(0, 0, 255)));
  const cv::Mat small(80, 120, CV_8UC3, cv::Scalar(0, 0, 0));
  EXPECT_THROW(tracker.process(MatImageSource(small)), TrackerError);
}

TEST(Tracker, RejectsBadBoxes) {
  Tracker tracker;
  const cv::Mat frame(120, 160, CV_8UC3, cv::Scalar(0, 0, 255));
  EXPECT_THROW(tracker.setTemplateFromBox(MatImageSource(frame), cv::Rect(150, 10, 20, 20)), TrackerError);
  EXPECT_THROW(tracker.setTemplateFromBox(MatImageSource(frame), cv::Rect(10, 10, 0, 20)), TrackerError);
  EXPECT_FALSE(tracker.hasTemplate());
}

TEST(Tracker, NoTemplateMeansNoTrack) {
  Tracker tracker;
  const cv::Mat frame(120, 160, CV_8UC3, cv::Scalar(0, 0, 255));
  const TrackOutput out = tracker.process(MatImageSource(frame));
  EXPECT_FALSE(out.hasBox);
  EXPECT_EQ(out.state, TrackState::Searching);
}

TEST(Tracker, MissingTemplateFileNamesThePath) {
  cv::Mat bgr, mask;
  try {
    loadTemplate("/nonexistent/dir/ball.png", bgr, mask);
    FAIL() << "no error";
  } catch (const TrackerError &e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/ball.png"), std::string::npos);
  }
}

TEST(ImageSource, SamplesEveryStepthPixelFromTheCorner) {
  cv::Mat image(37, 53, CV_8UC3);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) image.at<cv::Vec3b>(y, x) = cv::Vec3b(x, y, 7);
  const MatImageSource source(image);
  const cv::Rect rect(3, 2, 47, 33);  // neither side a multiple of the step
  cv::Mat sample;
  source.sampledBgr(rect, 4, sample);
  ASSERT_EQ(sample.size(), cv::Size(11, 8));
  for (int j = 0; j < sample.rows; ++j)
    for (int i = 0; i < sample.cols; ++i) {
      const cv::Vec3b p = sample.at<cv::Vec3b>(j, i);
      ASSERT_EQ(p[0], rect.x + 4 * i) << i << "," << j;
      ASSERT_EQ(p[1], rect.y + 4 * j) << i << "," << j;
    }
}

// The fused method's confidence: a grey board hides the object for 30 frames while it keeps moving. The
// confidence (the output's score) falls under the loss threshold, nothing is reported as tracking behind
// the board, and the object is found again within 10 frames where it comes out.
TEST(FusedTracker, ConfidenceFallsBehindAnOccluderAndTheTargetIsReacquired) {
  const Scene scene(hardConfig());
  Tracker tracker;  // the defaults: method fused
  ASSERT_EQ(tracker.settings().method, Method::Fused);
  tracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
  constexpr int kFrom = 60, kTo = 90;
  int trackingBehind = 0, lowConfidence = 0, reacquiredAt = -1;
  double visibleScore = 0;
  for (int i = 1; i < 120 && reacquiredAt < 0; ++i) {
    SceneFrame f = scene.render(i);
    const bool hidden = i >= kFrom && i < kTo;
    if (hidden) {
      const cv::Rect2d board(f.box.x - 0.2 * f.box.width, f.box.y - 0.2 * f.box.height, 1.4 * f.box.width,
                             1.4 * f.box.height);
      cv::rectangle(f.bgr, cv::Rect(board) & cv::Rect(cv::Point(), f.bgr.size()), cv::Scalar(128, 128, 128),
                    cv::FILLED);
    }
    const TrackOutput out = tracker.process(MatImageSource(f.bgr));
    if (i < kFrom && i >= 10) visibleScore += out.score / (kFrom - 10);
    if (hidden) {
      trackingBehind += out.state == TrackState::Tracking;
      lowConfidence += out.score < 0.5;
    }
    if (i >= kTo && out.state == TrackState::Tracking && scene::iou(out.box, f.box) > 0.5) reacquiredAt = i;
  }
  std::printf(
      "mean score while visible %.2f; behind the board: %d/%d frames under 0.5, %d tracking; "
      "reacquired at frame %d\n",
      visibleScore, lowConfidence, kTo - kFrom, trackingBehind, reacquiredAt);
  // Well above the loss bar of 0.5 while visible. Not 0.8 any more: the score also weighs how much the box
  // still looks like the start (StartLikeness), which this scene's turning object under +-40 % light lowers
  // (0.79 with it, 0.8 and more without).
  EXPECT_GT(visibleScore, 0.75);
  EXPECT_GE(lowConfidence, kTo - kFrom - 1);
  EXPECT_LE(trackingBehind, 1);
  ASSERT_GE(reacquiredAt, kTo);
  EXPECT_LT(reacquiredAt, kTo + 10);
}

// Settings that change while the fused method tracks: another colour model (the filters learnt with the old
// one) and a round trip through another method (the filters went stale meanwhile). The track carries on.
TEST(FusedTracker, KeepsTrackingThroughSettingChanges) {
  const Scene scene(hardConfig());
  Tracker tracker;
  tracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
  auto follow = [&](int from, int to) {
    int good = 0;
    for (int i = from; i < to; ++i) {
      const SceneFrame f = scene.render(i);
      const TrackOutput out = tracker.process(MatImageSource(f.bgr));
      good += out.hasBox && scene::iou(out.box, f.box) > 0.5;
    }
    return good;
  };
  EXPECT_GE(follow(1, 20), 18);
  TrackerSettings s = tracker.settings();
  s.bins.bins = {8, 8, 4};
  tracker.setSettings(s);
  EXPECT_GE(follow(20, 50), 27) << "after the colour model changed";
  s.method = Method::Discriminative;
  tracker.setSettings(s);
  EXPECT_GE(follow(50, 80), 27) << "after switching to discriminative";
  s.method = Method::Fused;
  tracker.setSettings(s);
  EXPECT_GE(follow(80, 110), 27) << "after switching back to fused";
}

// The fused method spreads a frame's independent pieces over OpenCV's thread pool. Each piece computes every
// value as one thread would, so the boxes and scores are the same to the bit with one thread and with two.
TEST(FusedTracker, SameResultOnOneThreadAsOnSeveral) {
  const Scene scene(hardConfig());
  const int threadsBefore = cv::getNumThreads();
  auto run = [&](int threads) {
    cv::setNumThreads(threads);
    Tracker tracker;
    tracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
    std::vector<TrackOutput> outputs;
    for (int i = 1; i < 60; ++i) outputs.push_back(tracker.process(MatImageSource(scene.render(i).bgr)));
    return outputs;
  };
  const std::vector<TrackOutput> one = run(1), several = run(2);
  cv::setNumThreads(threadsBefore);
  ASSERT_EQ(one.size(), several.size());
  int tracking = 0;
  for (size_t i = 0; i < one.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(i + 1));
    EXPECT_EQ(one[i].state, several[i].state);
    EXPECT_EQ(one[i].box, several[i].box);
    EXPECT_EQ(one[i].score, several[i].score);
    tracking += one[i].state == TrackState::Tracking;
  }
  EXPECT_GE(tracking, 50);  // the comparison is over a track, not over empty outputs
}

// Camera motion is not target motion (issue 21): the default method holds a target that stays put in the
// image while the textured background scrolls 8 px/frame under it (a camera following the target), and one
// that moves 8 px/frame over a still textured background, for 300 frames, at IoU >= 0.6 in every frame.
// main passes it as it is (the window at the last position covers 8 px/frame either way): a guard for
// changes to the search centre, not the reason for one.
TEST(FusedTracker, HoldsTheTargetWhetherTheCameraOrTheTargetMoves) {
  struct Case {
    const char *name;
    double circleSpeed;
    cv::Point backgroundVelocity;
  };
  for (const Case &k : {Case{"background scrolls", 0, {8, 0}}, Case{"target moves", 8, {0, 0}}}) {
    SCOPED_TRACE(k.name);
    SceneConfig c;
    c.frames = 300;
    c.speed = 0;
    c.circleSpeed = k.circleSpeed;
    c.backgroundVelocity = k.backgroundVelocity;
    const Scene scene(c);
    Tracker tracker;
    tracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
    double worst = 1, sum = 0;
    int tracking = 0;
    for (int i = 1; i < 300; ++i) {
      const SceneFrame f = scene.render(i);
      const TrackOutput out = tracker.process(MatImageSource(f.bgr));
      const double overlap = out.hasBox ? scene::iou(out.box, f.box) : 0;
      worst = std::min(worst, overlap);
      sum += overlap;
      tracking += out.state == TrackState::Tracking;
    }
    std::printf("%s: worst IoU %.3f, mean %.3f, tracking %d/299\n", k.name, worst, sum / 299, tracking);
    EXPECT_GE(worst, 0.6);
    EXPECT_EQ(tracking, 299);
  }
}
