// SPDX-License-Identifier: LGPL-2.1-or-later
// Dynamic scale: the box must hold its size on a still object and follow one that grows or shrinks,
// without the slow collapse a raw intersection maximum causes.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "colortrack/color.hpp"
#include "colortrack/histogram.hpp"
#include "colortrack/scale.hpp"

using namespace colortrack;

namespace {

// A textured red-orange object of `side` pixels centred in a 320x320 textured green/blue background.
cv::Mat makeScene(int side, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat img(320, 320, CV_8UC3);
  for (int y = 0; y < img.rows; ++y)
    for (int x = 0; x < img.cols; ++x)
      img.at<cv::Vec3b>(y, x) = cv::Vec3b(rng.uniform(90, 200), rng.uniform(90, 200), rng.uniform(0, 60));
  const int x0 = 160 - side / 2, y0 = 160 - side / 2;
  for (int y = y0; y < y0 + side; ++y)
    for (int x = x0; x < x0 + side; ++x) {
      const bool stripe = ((x - x0) / 6 + (y - y0) / 6) % 2 == 0;
      img.at<cv::Vec3b>(y, x) =
          stripe ? cv::Vec3b(rng.uniform(0, 30), rng.uniform(40, 90), rng.uniform(200, 255))
                 : cv::Vec3b(rng.uniform(0, 30), rng.uniform(100, 140), rng.uniform(150, 200));
    }
  return img;
}

struct Fixture {
  BinMapper mapper{ColorSpace::Hsv, BinLayout{}};
  ChannelWeights weights;
  ScaleParams params;
  Histogram model;

  explicit Fixture(int templateSide) {
    const cv::Mat scene = makeScene(templateSide, 7);
    BinImage bins;
    mapper.map(scene, bins.bins);
    const int x0 = 160 - templateSide / 2;
    model = histogramOf(bins, mapper.layout(), cv::Rect(x0, x0, templateSide, templateSide));
  }

  // Runs the refinement `frames` times on the scene with an object of `side`, starting from `startSide`.
  double settle(int side, double startSide, int frames) {
    const cv::Mat scene = makeScene(side, 11);
    BinImage bins;
    mapper.map(scene, bins.bins);
    cv::Rect2d box(160 - startSide / 2, 160 - startSide / 2, startSide, startSide);
    for (int i = 0; i < frames; ++i) box = refineScale(bins, box, model, weights, params).box;
    return box.width;
  }
};

}  // namespace

TEST(Scale, HoldsSizeOnStillObject) {
  Fixture f(60);
  const double width = f.settle(60, 60, 100);
  EXPECT_NEAR(width, 60, 60 * 0.06) << "the box drifted over 100 refinements";
}

TEST(Scale, FollowsGrowingObject) {
  Fixture f(60);
  const double width = f.settle(84, 60, 30);  // 1.4x the template: 6% a frame gets there in ~6 frames
  EXPECT_NEAR(width, 84, 84 * 0.08);
}

TEST(Scale, FollowsShrinkingObject) {
  Fixture f(60);
  const double width = f.settle(42, 60, 30);  // 0.7x
  EXPECT_NEAR(width, 42, 42 * 0.08);
}

TEST(Scale, KeepsCentreAndStaysInsideBins) {
  Fixture f(60);
  const cv::Mat scene = makeScene(60, 3);
  BinImage bins;
  f.mapper.map(scene, bins.bins);
  // A box touching the image border: larger windows leave the bins and must be skipped, not read outside.
  const cv::Rect2d box(0, 0, 60, 60);
  const ScaleResult r = refineScale(bins, box, f.model, f.weights, f.params);
  EXPECT_LE(r.factor, 1.0);
  EXPECT_NEAR(r.box.x + r.box.width / 2, 30, 1e-9);
  EXPECT_NEAR(r.box.y + r.box.height / 2, 30, 1e-9);
}
