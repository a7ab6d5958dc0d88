// SPDX-License-Identifier: LGPL-2.1-or-later
// A cut to another scene (issue 46): SceneCut tells it from a pan, a change of light and a moving object, and
// the template tracker declares its track lost on the cut's first frame, then takes the target back after
// the cut back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "colortrack/scene_cut.hpp"
#include "colortrack/tracker.hpp"
#include "scene.hpp"

using namespace colortrack;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;

namespace {

// The project's moving, turning, growing object under changing light, on a background panning 6 px right and
// 2 px down a frame: everything but a cut.
SceneConfig busyScene() {
  SceneConfig c;
  c.seed = 1;
  c.scaleMin = 0.8;
  c.scaleMax = 1.3;
  c.rotationDegrees = 30;
  c.brightness = 0.4;
  c.backgroundVelocity = cv::Point(6, 2);
  return c;
}

// Another scene: other textures and colours, and no object (it is out of the picture throughout).
SceneConfig otherScene() {
  SceneConfig c;
  c.seed = 9;
  c.leaveFrom = 0;
  c.leaveTo = c.frames;
  return c;
}

}  // namespace

TEST(SceneCut, PanLightAndMotionAreNotCuts) {
  const Scene scene(busyScene());
  SceneCut cut;
  double largest = 0;
  for (int i = 0; i < scene.config().frames; ++i) {
    EXPECT_FALSE(cut.observe(MatImageSource(scene.render(i).bgr))) << "frame " << i;
    largest = std::max(largest, cut.lastDistance());
  }
  std::printf("largest distance between consecutive frames: %.3f\n", largest);
}

TEST(SceneCut, AnotherSceneIsACutEachWay) {
  const Scene a(busyScene()), b(otherScene());
  SceneCut cut;
  int cuts = 0;
  for (int i = 0; i < 60; ++i) {
    const bool inB = i >= 20 && i < 40;
    const bool reported = cut.observe(MatImageSource((inB ? b : a).render(i).bgr));
    EXPECT_EQ(reported, i == 20 || i == 40) << "frame " << i << ", distance " << cut.lastDistance();
    cuts += reported;
  }
  EXPECT_EQ(cuts, 2);
}

TEST(SceneCut, NoCutOnTheFirstFrameOrAfterAResize) {
  const Scene a(busyScene()), b(otherScene());
  SceneCut cut;
  EXPECT_FALSE(cut.observe(MatImageSource(a.render(0).bgr)));
  cv::Mat smaller;
  cv::resize(b.render(0).bgr, smaller, cv::Size(320, 240));
  EXPECT_FALSE(cut.observe(MatImageSource(smaller)));
}

// The tracker follows the object; at frame 30 the video cuts to another scene for 40 frames, then back. The
// track is lost on the cut's first frame, nothing in the other scene is reported `tracking` after 5 frames,
// the box is back on the object (IoU >= 0.5) within 10 frames of the cut back, and after the probation of a
// track found after a cut (30 confirmed frames, reported `coasting`) it is `tracking` again.
TEST(SceneCut, TrackerLosesTheTrackOnACutAndFindsTheTargetAfterTheCutBack) {
  const Scene a(busyScene()), b(otherScene());
  Tracker tracker;
  tracker.setTemplateFromBox(MatImageSource(a.render(0).bgr), a.initBox());
  constexpr int kCut = 30, kBack = 70;
  int trackingInOther = 0, boxBackAfter = -1, trackingBackAfter = -1;
  for (int i = 1; i < kBack + 60; ++i) {
    const bool inOther = i >= kCut && i < kBack;
    const scene::SceneFrame frame = (inOther ? b : a).render(i);
    const TrackOutput out = tracker.process(MatImageSource(frame.bgr));
    if (i == kCut) {
      EXPECT_EQ(out.state, TrackState::Lost);
      EXPECT_FALSE(out.hasBox);
    }
    if (i < kCut) {
      EXPECT_EQ(out.state, TrackState::Tracking) << "frame " << i;
    }
    if (inOther && i >= kCut + 5) trackingInOther += out.state == TrackState::Tracking;
    const bool onTarget = i >= kBack && out.hasBox && scene::iou(out.box, frame.box) >= 0.5;
    if (onTarget && boxBackAfter < 0) boxBackAfter = i - kBack;
    if (onTarget && trackingBackAfter < 0 && out.state == TrackState::Tracking) trackingBackAfter = i - kBack;
  }
  std::printf(
      "tracking in the other scene: %d frames; after the cut back, the box back on the target in %d frames, "
      "`tracking` in %d\n",
      trackingInOther, boxBackAfter, trackingBackAfter);
  EXPECT_EQ(trackingInOther, 0);
  EXPECT_GE(boxBackAfter, 0);
  EXPECT_LE(boxBackAfter, 10);
  EXPECT_GE(trackingBackAfter, boxBackAfter + 30);
  EXPECT_LE(trackingBackAfter, boxBackAfter + 40);
}
