// SPDX-License-Identifier: LGPL-2.1-or-later
// The window the fused method cuts every frame is shrunk by shrinkByArea: it must average as OpenCV's
// INTER_AREA does, whatever the ratio, the channel count or the row padding of the source.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "colortrack/area_resample.hpp"

using namespace colortrack;

namespace {

cv::Mat randomImage(cv::Size size, int type, unsigned seed) {
  cv::RNG rng(seed);
  cv::Mat image(size, type);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  // Smooth part of it, so that both flat areas and fine texture are covered.
  cv::GaussianBlur(image(cv::Rect(0, 0, size.width / 2, size.height)),
                   image(cv::Rect(0, 0, size.width / 2, size.height)), cv::Size(7, 7), 2);
  return image;
}

void expectLikeInterArea(const cv::Mat &source, cv::Size size, double meanDifference = 0.05) {
  cv::Mat ours, opencv;
  shrinkByArea(source, size, ours);
  cv::resize(source, opencv, size, 0, 0, cv::INTER_AREA);
  ASSERT_EQ(ours.size(), size);
  ASSERT_EQ(ours.type(), source.type());
  cv::Mat difference;
  cv::absdiff(ours, opencv, difference);
  double largest = 0;
  cv::minMaxLoc(difference.reshape(1), nullptr, &largest);
  EXPECT_LE(largest, 1.0) << source.size() << " -> " << size;
  EXPECT_LT(cv::mean(difference.reshape(1))[0], meanDifference) << source.size() << " -> " << size;
}

}  // namespace

TEST(ShrinkByArea, MatchesInterAreaAtFractionalRatios) {
  const cv::Mat source = randomImage(cv::Size(151, 163), CV_8UC3, 1);
  for (const cv::Size size : {cv::Size(96, 104), cv::Size(120, 150), cv::Size(100, 81), cv::Size(37, 29)})
    expectLikeInterArea(source, size);
}

TEST(ShrinkByArea, MatchesInterAreaAtWholeRatiosAndUnchangedSize) {
  const cv::Mat source = randomImage(cv::Size(192, 96), CV_8UC3, 2);
  // At whole ratios OpenCV sums integers and rounds halves up; the averages here round halves to even as its
  // fractional path does, so a quarter or so of the values, those exactly halfway, differ by one.
  expectLikeInterArea(source, cv::Size(96, 48), 0.2);
  expectLikeInterArea(source, cv::Size(64, 32), 0.2);
  expectLikeInterArea(source, source.size());
}

TEST(ShrinkByArea, AnyChannelCountAndAPaddedSource) {
  for (int channels = 1; channels <= 4; ++channels) {
    const cv::Mat big = randomImage(cv::Size(220, 180), CV_8UC(channels), 3 + channels);
    const cv::Mat view = big(cv::Rect(13, 7, 141, 122));  // rows not contiguous
    ASSERT_FALSE(view.isContinuous());
    expectLikeInterArea(view, cv::Size(96, 80));
  }
}

TEST(ShrinkByArea, KeepsAFlatImageFlat) {
  const cv::Mat source(77, 91, CV_8UC3, cv::Scalar(200, 17, 90));
  cv::Mat out;
  shrinkByArea(source, cv::Size(50, 40), out);
  EXPECT_EQ(cv::norm(out, cv::Mat(40, 50, CV_8UC3, cv::Scalar(200, 17, 90)), cv::NORM_INF), 0.0);
}
