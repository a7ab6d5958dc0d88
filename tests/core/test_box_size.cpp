// SPDX-License-Identifier: LGPL-2.1-or-later
// The default (fused) method's box size against the target's (issue 21): a box that holds a ring of
// background is brought back onto the target by the colour map; a target whose colours fill only a part of
// its box keeps the box it was given.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "colortrack/tracker.hpp"
#include "noise_texture.hpp"

using namespace colortrack;

namespace {

constexpr int kSide = 60;  // the target's side, px

// Grey blurred noise tinted by `tint` (B, G, R shares): texture of the same grain in any colour.
cv::Mat tinted(cv::Size size, int seed, cv::Scalar tint) {
  cv::Mat grey, out;
  cv::cvtColor(colortrack::test::noiseTexture(size, seed, 3.0), grey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(grey, out, cv::COLOR_GRAY2BGR);
  cv::multiply(out, tint, out);
  return out;
}

// The background: texture of the target's grain, in green, so that only the colour tells them apart.
cv::Mat background() {
  return tinted(cv::Size(640, 480), 3, cv::Scalar(0.3, 0.8, 0.3));
}

double iou(const cv::Rect2d &a, const cv::Rect2d &b) {
  const double overlap = (a & b).area();
  return overlap / (a.area() + b.area() - overlap);
}

// Tracks `patch` moving right at 2 px a frame over the background for `frames` frames, its side going
// from the patch's to `lastSide` px over the first `shrinkFrames` of them, started on the patch's box;
// returns the last reported box relative to the patch's last place.
cv::Rect2d lastBoxOnPatch(const cv::Mat &patch, int frames, int lastSide, int shrinkFrames) {
  const cv::Mat scene = background();
  const cv::Point start(120, 200);
  cv::Rect target(start, patch.size());
  auto render = [&] {
    cv::Mat frame = scene.clone();
    cv::resize(patch, frame(target), target.size(), 0, 0, cv::INTER_AREA);
    return frame;
  };
  TrackerSettings s;
  s.method = Method::Fused;
  Tracker tracker(s);
  tracker.setTemplateFromBox(MatImageSource(render()), target);
  cv::Rect2d box;
  for (int i = 1; i <= frames; ++i) {
    const double progress = std::min(1.0, double(i) / shrinkFrames);
    const int side = cvRound(patch.cols + (lastSide - patch.cols) * progress);
    target = cv::Rect(start + cv::Point(2 * i, 0), cv::Size(side, side));
    const TrackOutput out = tracker.process(MatImageSource(render()));
    EXPECT_TRUE(out.hasBox) << "frame " << i;
    box = out.box;
  }
  return box - cv::Point2d(target.tl());
}

}  // namespace

// The target shrinks to two thirds of its side over 60 frames (it moves away). The scale filter lags behind
// and its box holds a ring of background; the colour map shows the object inside it, and the size the
// filters search at takes a step towards it on each such frame.
TEST(BoxSize, TheBoxFollowsATargetThatShrinks) {
  const cv::Mat patch = tinted(cv::Size(kSide, kSide), 17, cv::Scalar(0.3, 0.4, 1.0));
  const int lastSide = 2 * kSide / 3;
  const cv::Rect2d last = lastBoxOnPatch(patch, 120, lastSide, 15);
  std::printf("last box %.0f x %.0f at %.0f, %.0f (target %d x %d at 0, 0)\n", last.width, last.height,
              last.x, last.y, lastSide, lastSide);
  EXPECT_LE(last.width, 1.15 * lastSide);
  EXPECT_LE(last.height, 1.15 * lastSide);
  EXPECT_GE(iou(last, cv::Rect2d(0, 0, lastSide, lastSide)), 0.75);
}

// A target whose colours stand out only in its middle (a walker's shirt: the rest of it is of the
// background's colours), given its whole box: the colour map says the object is smaller from the first
// frame, and the box is not shrunk onto the middle.
TEST(BoxSize, ATargetWhoseColoursFillAPartKeepsItsBox) {
  cv::Mat patch = tinted(cv::Size(kSide, kSide), 29, cv::Scalar(0.3, 0.8, 0.3));
  const int part = kSide / 2;
  tinted(cv::Size(part, part), 17, cv::Scalar(0.3, 0.4, 1.0))
      .copyTo(patch(cv::Rect((kSide - part) / 2, (kSide - part) / 2, part, part)));
  const cv::Rect2d last = lastBoxOnPatch(patch, 120, kSide, 1);
  std::printf("last box %.0f x %.0f at %.0f, %.0f (target %d x %d at 0, 0)\n", last.width, last.height,
              last.x, last.y, kSide, kSide);
  EXPECT_GE(iou(last, cv::Rect2d(0, 0, kSide, kSide)), 0.7);
}
