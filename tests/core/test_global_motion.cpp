// SPDX-License-Identifier: LGPL-2.1-or-later
// GlobalMotion: the background's shift between frames of the synthetic scene, whatever the object does.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "colortrack/global_motion.hpp"
#include "colortrack/yuv_image.hpp"
#include "scene.hpp"

using namespace colortrack;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;

namespace {

SceneConfig panningScene(cv::Point velocity, cv::Size frameSize) {
  SceneConfig c;
  c.frameSize = frameSize;
  c.frames = 60;
  c.speed = 0;  // the object holds still in the image
  c.backgroundVelocity = velocity;
  return c;
}

// The object's box grown by `margin` px on each side: what is left out.
cv::Rect2d around(const cv::Rect2d &box, double margin) {
  return cv::Rect2d(box.x - margin, box.y - margin, box.width + 2 * margin, box.height + 2 * margin);
}

}  // namespace

TEST(GlobalMotion, FirstFrameHasNoShift) {
  const Scene scene(panningScene({8, 0}, {640, 480}));
  GlobalMotion motion;
  EXPECT_FALSE(motion.measure(MatImageSource(scene.render(0).bgr)).valid);
  EXPECT_TRUE(motion.measure(MatImageSource(scene.render(1).bgr)).valid);
  motion.reset();
  EXPECT_FALSE(motion.measure(MatImageSource(scene.render(2).bgr)).valid);
}

// The camera pans: every frame's shift is the background's, not the still object's (left out: on this
// smooth background its stripes would outweigh everything else), at every frame size (the small copy is
// read at different steps): within 2 px with the default copy, within 4 px with threshold mode's (128 px).
TEST(GlobalMotion, MeasuresThePanNotTheObject) {
  for (const auto &[maxWidth, tolerance] : {std::pair{214.0, 2.0}, std::pair{128.0, 4.0}})
    for (const cv::Size frameSize : {cv::Size(320, 240), cv::Size(640, 480), cv::Size(1280, 720)}) {
      for (const cv::Point velocity : {cv::Point(8, 0), cv::Point(-5, 3), cv::Point(0, -12)}) {
        SCOPED_TRACE(std::to_string(frameSize.width) + " px, velocity " + std::to_string(velocity.x) + "," +
                     std::to_string(velocity.y) + ", copy " + std::to_string(maxWidth));
        const Scene scene(panningScene(velocity, frameSize));
        GlobalMotion motion(maxWidth);
        const scene::SceneFrame first = scene.render(0);
        motion.measure(MatImageSource(first.bgr),
                       around(first.box, 8));  // each frame leaves its own object out
        for (int i = 1; i < 20; ++i) {
          const scene::SceneFrame f = scene.render(i);
          const GlobalMotion::Shift s = motion.measure(MatImageSource(f.bgr), around(f.box, 8));
          ASSERT_TRUE(s.valid) << "frame " << i;
          // Half a small-copy px at 640x480 (step 4): this background is smooth at that scale.
          EXPECT_NEAR(s.offset.x, velocity.x, tolerance) << "frame " << i;
          EXPECT_NEAR(s.offset.y, velocity.y, tolerance) << "frame " << i;
        }
      }
    }
}

// A still camera: the object moving 8 px/frame over the background does not move the frame.
TEST(GlobalMotion, StillBackgroundUnderAMovingObject) {
  SceneConfig c;
  c.circleSpeed = 8;
  const Scene scene(c);
  GlobalMotion motion;
  motion.measure(MatImageSource(scene.render(0).bgr));
  for (int i = 1; i < 20; ++i) {
    // Left out where the object was last seen, grown by its motion, as the tracker does.
    const GlobalMotion::Shift s =
        motion.measure(MatImageSource(scene.render(i).bgr), around(scene.render(i - 1).box, 16));
    ASSERT_TRUE(s.valid) << "frame " << i;
    EXPECT_LT(std::hypot(s.offset.x, s.offset.y), 0.5) << "frame " << i;
  }
}

// Nothing to correlate (a flat frame) or a new frame size: no shift is claimed.
TEST(GlobalMotion, FlatFramesAndNewSizesGiveNoShift) {
  GlobalMotion motion;
  const cv::Mat flat(240, 320, CV_8UC3, cv::Scalar(90, 120, 150));
  motion.measure(MatImageSource(flat));
  EXPECT_FALSE(motion.measure(MatImageSource(flat)).valid);
  const Scene scene(panningScene({8, 0}, {640, 480}));
  EXPECT_FALSE(motion.measure(MatImageSource(scene.render(0).bgr)).valid) << "the flat frame was 320x240";
  EXPECT_TRUE(motion.measure(MatImageSource(scene.render(1).bgr)).valid);
}

// The same pan read from I420 planes (the Y plane itself) and from BGR: the same shift within 1.5 px (they
// agree within 0.1 px on 10 of 11 frames; the smooth background leaves a pixel of noise).
TEST(GlobalMotion, SameShiftFromYuvAndFromBgr) {
  const Scene scene(panningScene({-5, 3}, {640, 480}));
  GlobalMotion fromBgr, fromYuv;
  int measured = 0;
  for (int i = 0; i < 12; ++i) {
    const scene::SceneFrame f = scene.render(i);
    cv::Mat i420;
    cv::cvtColor(f.bgr, i420, cv::COLOR_BGR2YUV_I420);
    const GlobalMotion::Shift a = fromBgr.measure(MatImageSource(f.bgr), around(f.box, 8));
    const GlobalMotion::Shift b =
        fromYuv.measure(YuvImageSource(sampledI420(i420, f.bgr.size(), YuvColorimetry())), around(f.box, 8));
    ASSERT_EQ(a.valid, b.valid) << "frame " << i;
    if (!a.valid) continue;
    ++measured;
    EXPECT_LT(cv::norm(a.offset - b.offset), 1.5)
        << "frame " << i << " BGR " << a.offset << " YUV " << b.offset;
  }
  EXPECT_GE(measured, 10);
}
