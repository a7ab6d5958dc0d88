// SPDX-License-Identifier: LGPL-2.1-or-later
// Histograms, masks, clipping and the weighted intersection, checked against values worked out by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/histogram.hpp"

using namespace colortrack;

namespace {

const BinLayout kLayout{{4, 2, 2}};  // channel offsets 0, 4, 6; 8 bins in all

// A 2x2 bin image (bins per pixel: H, S, V):
//   (0,0,0) (1,0,1)
//   (1,1,1) (3,1,0)
// Whole image: H = [1/4, 2/4, 0, 1/4], S = [1/2, 1/2], V = [1/2, 1/2].
// Top row:     H = [1/2, 1/2, 0, 0],   S = [1, 0],     V = [1/2, 1/2].
BinImage tinyImage(cv::Point origin = cv::Point()) {
  BinImage image;
  image.bins = cv::Mat(2, 2, CV_8UC3);
  image.bins.at<cv::Vec3b>(0, 0) = cv::Vec3b(0, 0, 0);
  image.bins.at<cv::Vec3b>(0, 1) = cv::Vec3b(1, 0, 1);
  image.bins.at<cv::Vec3b>(1, 0) = cv::Vec3b(1, 1, 1);
  image.bins.at<cv::Vec3b>(1, 1) = cv::Vec3b(3, 1, 0);
  image.origin = origin;
  return image;
}

void expectValues(const Histogram &h, const std::vector<float> &expected) {
  ASSERT_EQ(h.values.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_FLOAT_EQ(h.values[i], expected[i]) << "bin " << i;
}

ChannelWeights weights(double h, double s, double v) {
  ChannelWeights w;
  w.w = {h, s, v};
  return w;
}

}  // namespace

TEST(Histogram, WholeImageIsNormalisedPerChannel) {
  const BinImage image = tinyImage();
  const Histogram h = histogramOf(image, kLayout, cv::Rect(0, 0, 2, 2));
  EXPECT_EQ(h.pixelCount, 4);
  EXPECT_FALSE(h.empty());
  expectValues(h, {0.25f, 0.5f, 0, 0.25f, 0.5f, 0.5f, 0.5f, 0.5f});
  EXPECT_EQ(h.channel(1), h.values.data() + 4);
  EXPECT_EQ(h.channel(2), h.values.data() + 6);
}

TEST(Histogram, MaskSelectsPixels) {
  const BinImage image = tinyImage();
  cv::Mat mask = (cv::Mat_<std::uint8_t>(2, 2) << 255, 1, 0, 0);  // any non-zero value counts
  const Histogram h = histogramOf(image, kLayout, cv::Rect(0, 0, 2, 2), mask);
  EXPECT_EQ(h.pixelCount, 2);
  expectValues(h, {0.5f, 0.5f, 0, 0, 1, 0, 0.5f, 0.5f});

  const Histogram none = histogramOf(image, kLayout, cv::Rect(0, 0, 2, 2), cv::Mat::zeros(2, 2, CV_8UC1));
  EXPECT_TRUE(none.empty());
  expectValues(none, std::vector<float>(8, 0.0f));
}

TEST(Histogram, RectsAreFrameCoordinatesAndClipped) {
  const BinImage image = tinyImage(cv::Point(10, 20));
  // Frame rect (9,19)-(10,20) overlaps only bin pixel (0,0).
  const Histogram corner = histogramOf(image, kLayout, cv::Rect(9, 19, 2, 2));
  EXPECT_EQ(corner.pixelCount, 1);
  expectValues(corner, {1, 0, 0, 0, 1, 0, 1, 0});

  // The mask covers the unclipped rect: its bottom-right entry is the one over bin pixel (0,0).
  cv::Mat mask = (cv::Mat_<std::uint8_t>(2, 2) << 255, 255, 255, 0);
  EXPECT_TRUE(histogramOf(image, kLayout, cv::Rect(9, 19, 2, 2), mask).empty());
  mask = (cv::Mat_<std::uint8_t>(2, 2) << 0, 0, 0, 255);
  EXPECT_EQ(histogramOf(image, kLayout, cv::Rect(9, 19, 2, 2), mask).pixelCount, 1);

  // Bottom row through a rect hanging off the right and bottom edges.
  const Histogram bottom = histogramOf(image, kLayout, cv::Rect(10, 21, 5, 5));
  EXPECT_EQ(bottom.pixelCount, 2);
  expectValues(bottom, {0, 0.5f, 0, 0.5f, 0, 1, 0.5f, 0.5f});

  EXPECT_TRUE(histogramOf(image, kLayout, cv::Rect(0, 0, 10, 20)).empty());  // entirely outside

  std::vector<int> counts;
  countsOf(image, kLayout, cv::Rect(11, 0, 1, 100), counts);  // right column
  EXPECT_EQ(counts, (std::vector<int>{0, 1, 0, 1, 1, 1, 1, 1}));
  countsOf(image, kLayout, cv::Rect(0, 0, 5, 5), counts);
  EXPECT_EQ(counts, std::vector<int>(8, 0));
}

TEST(Intersection, HandValues) {
  const float window[] = {0.5f, 0.5f, 0, 0};
  const float model[] = {0.25f, 0.5f, 0, 0.25f};
  EXPECT_DOUBLE_EQ(intersection(window, model, 4), 0.75);  // (0.25 + 0.5) / 1
  const float unnormalised[] = {1, 1, 0, 0};
  const float small[] = {0.5f, 0.25f, 0, 2};
  EXPECT_DOUBLE_EQ(intersection(small, unnormalised, 4), 0.375);  // (0.5 + 0.25) / 2
  const float zeros[] = {0, 0, 0, 0};
  EXPECT_EQ(intersection(window, zeros, 4), 0.0);
  EXPECT_DOUBLE_EQ(intersection(model, model, 4), 1.0);
}

TEST(MatchValue, WeightedProductByHand) {
  const BinImage image = tinyImage();
  const Histogram model = histogramOf(image, kLayout, cv::Rect(0, 0, 2, 2));
  const Histogram top = histogramOf(image, kLayout, cv::Rect(0, 0, 2, 1));
  // Per channel: H = 0.25 + 0.5 = 0.75, S = min(1,.5) + min(0,.5) = 0.5, V = 1.
  EXPECT_NEAR(matchValue(top, model, weights(1, 1, 1)), 0.375, 1e-7);
  EXPECT_NEAR(matchValue(top, model, weights(1, 0, 1)), 0.75, 1e-7);  // S ignored
  EXPECT_NEAR(matchValue(top, model, weights(0.5, 1, 0)), std::sqrt(0.75) * 0.5, 1e-7);
  EXPECT_NEAR(matchValue(top, model, weights(0, 0.5, 0.3)), std::sqrt(0.5), 1e-7);
  EXPECT_EQ(matchValue(top, model, weights(0, 0, 0)), 1.0);
  EXPECT_NEAR(matchValue(model, model, ChannelWeights()), 1.0, 1e-7);

  // The same through raw counts: top row H [1,1,0,0], S [2,0], V [1,1] over 2 pixels.
  const int counts[] = {1, 1, 0, 0, 2, 0, 1, 1};
  EXPECT_NEAR(matchCounts(counts, 2, model, weights(1, 1, 1)), 0.375, 1e-12);
  EXPECT_NEAR(matchCounts(counts, 2, model, weights(0.5, 1, 0)), std::sqrt(0.75) * 0.5, 1e-12);
  EXPECT_NEAR(windowMatch(image, cv::Rect(0, 0, 2, 1), model, weights(1, 1, 1)), 0.375, 1e-12);
  // Bottom row H [0,1,0,1], S [0,2], V [1,1]: H 0.5 + 0.25 = 0.75, S 0.5, V 1.
  EXPECT_NEAR(windowMatch(image, cv::Rect(0, 1, 2, 1), model, weights(1, 0.5, 1)), 0.75 * std::sqrt(0.5),
              1e-12);
}

TEST(MatchValue, EmptyModelOrWindowScoresZero) {
  const BinImage image = tinyImage();
  const Histogram model = histogramOf(image, kLayout, cv::Rect(0, 0, 2, 2));
  const Histogram empty = histogramOf(image, kLayout, cv::Rect(5, 5, 1, 1));
  ASSERT_TRUE(empty.empty());
  EXPECT_EQ(matchValue(empty, model, ChannelWeights()), 0.0);
  EXPECT_EQ(matchValue(model, empty, ChannelWeights()), 0.0);
  const int zeros[8] = {};
  EXPECT_EQ(matchCounts(zeros, 0, model, ChannelWeights()), 0.0);
  EXPECT_EQ(windowMatch(image, cv::Rect(5, 5, 3, 3), model, ChannelWeights()), 0.0);
}

// On random bin images, the count path and the normalised-histogram path give the same value, and the
// value is bounded by 1 and falls when the window covers different colours.
TEST(MatchValue, CountsAndHistogramPathsAgree) {
  const BinLayout layout{{16, 16, 8}};
  cv::RNG rng(5);
  BinImage image;
  image.bins.create(60, 77, CV_8UC3);
  for (int y = 0; y < image.bins.rows; ++y)
    for (int x = 0; x < image.bins.cols; ++x)
      image.bins.at<cv::Vec3b>(y, x) = cv::Vec3b(rng.uniform(0, 16), rng.uniform(0, 16), rng.uniform(0, 8));
  image.origin = cv::Point(-30, 7);
  const Histogram model = histogramOf(image, layout, cv::Rect(-25, 10, 20, 15));
  const ChannelWeights w = weights(1, 0.7, 0.3);
  for (int trial = 0; trial < 50; ++trial) {
    const cv::Rect window(rng.uniform(-40, 50), rng.uniform(0, 70), rng.uniform(1, 30), rng.uniform(1, 30));
    const Histogram h = histogramOf(image, layout, window);
    const double viaHistogram = matchValue(h, model, w);
    const double direct = windowMatch(image, window, model, w);
    EXPECT_NEAR(direct, viaHistogram, 1e-6) << "window " << window;
    EXPECT_GE(direct, 0.0);
    EXPECT_LE(direct, 1.0 + 1e-12);
  }
  // Model values are floats, so the model's own window scores 1 to float precision only.
  EXPECT_NEAR(windowMatch(image, cv::Rect(-25, 10, 20, 15), model, w), 1.0, 1e-6);
}
