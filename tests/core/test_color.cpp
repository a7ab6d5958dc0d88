// SPDX-License-Identifier: LGPL-2.1-or-later
// RGB -> HSV, bin lookup tables and the vectorised whole-image mapping against the exact per-pixel path.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"

using namespace colortrack;

namespace {

void expectHsv(std::uint8_t r, std::uint8_t g, std::uint8_t b, double h, double s, double v) {
  const Hsv hsv = rgbToHsv(r, g, b);
  SCOPED_TRACE(testing::Message() << "rgb " << int(r) << "," << int(g) << "," << int(b));
  EXPECT_NEAR(hsv.h, h, 1e-9);
  EXPECT_NEAR(hsv.s, s, 1e-9);
  EXPECT_NEAR(hsv.v, v, 1e-9);
}

// Bin distance; hue is circular, so its last and first bins are neighbours.
int binDistance(int a, int b, int n, bool circular) {
  const int d = std::abs(a - b);
  return circular ? std::min(d, n - d) : d;
}

}  // namespace

TEST(RgbToHsv, PrimaryAndGreyColours) {
  expectHsv(255, 0, 0, 0, 1, 1);
  expectHsv(0, 255, 0, 120, 1, 1);
  expectHsv(0, 0, 255, 240, 1, 1);
  expectHsv(255, 255, 0, 60, 1, 1);
  expectHsv(0, 255, 255, 180, 1, 1);
  expectHsv(255, 0, 255, 300, 1, 1);
  expectHsv(0, 0, 0, 0, 0, 0);
  expectHsv(255, 255, 255, 0, 0, 1);
  expectHsv(128, 128, 128, 0, 0, 128 / 255.0);
}

TEST(RgbToHsv, MidColoursByHand) {
  // (200,100,50): max r=200, min b=50, diff 150; h = 60*(100-50)/150 = 20; s = 150/200; v = 200/255.
  expectHsv(200, 100, 50, 20, 0.75, 200 / 255.0);
  // (50,100,200): max b, h = 60*((50-100)/150 + 4) = 220.
  expectHsv(50, 100, 200, 220, 0.75, 200 / 255.0);
  // (200,50,100): max r, g < b: h = 60*(50-100)/150 + 360 = 340.
  expectHsv(200, 50, 100, 340, 0.75, 200 / 255.0);
  // (100,200,50): max g, h = 60*((50-100)/150 + 2) = 100.
  expectHsv(100, 200, 50, 100, 0.75, 200 / 255.0);
}

TEST(RgbToHsv, HueAlwaysBelow360) {
  // The largest hue comes from r max, b just above g.
  const Hsv hsv = rgbToHsv(255, 0, 1);
  EXPECT_LT(hsv.h, 360.0);
  EXPECT_GT(hsv.h, 359.0);
}

TEST(BinMapper, BinOfFollowsTheFormulas) {
  const BinMapper hsv(ColorSpace::Hsv, BinLayout{{16, 16, 8}});
  // Red: h 0 -> bin 0; s 1 and v 1 clamp into the last bins.
  EXPECT_EQ(hsv.binOf(255, 0, 0), (std::array<int, 3>{0, 15, 7}));
  // Blue: h 240 -> floor(240/360*16) = 10.
  EXPECT_EQ(hsv.binOf(0, 0, 255), (std::array<int, 3>{10, 15, 7}));
  // (200,100,50): h 20 -> floor(0.888) = 0; s 0.75 -> 12; v 200/255 -> floor(6.27) = 6.
  EXPECT_EQ(hsv.binOf(200, 100, 50), (std::array<int, 3>{0, 12, 6}));
  // (200,50,100): h 340 -> floor(15.11) = 15.
  EXPECT_EQ(hsv.binOf(200, 50, 100)[0], 15);
  EXPECT_EQ(hsv.binOf(0, 0, 0), (std::array<int, 3>{0, 0, 0}));

  const BinMapper rgb(ColorSpace::Rgb, BinLayout{{4, 2, 256}});
  // r 64/255*4 = 1.004 -> 1; g 127/255*2 = 0.996 -> 0; b: 256 bins, one per value.
  EXPECT_EQ(rgb.binOf(64, 127, 77), (std::array<int, 3>{1, 0, 77}));
  EXPECT_EQ(rgb.binOf(255, 255, 255), (std::array<int, 3>{3, 1, 255}));
  EXPECT_EQ(rgb.binOf(63, 128, 0), (std::array<int, 3>{0, 1, 0}));
}

TEST(BinMapper, RejectsBadLayouts) {
  EXPECT_THROW(BinMapper(ColorSpace::Hsv, BinLayout{{0, 16, 8}}), std::invalid_argument);
  EXPECT_THROW(BinMapper(ColorSpace::Rgb, BinLayout{{16, 257, 8}}), std::invalid_argument);
}

TEST(BinMapper, RgbMapIsExactAndInRgbOrder) {
  cv::RNG rng(7);
  cv::Mat bgr(37, 53, CV_8UC3);
  rng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
  const BinMapper mapper(ColorSpace::Rgb, BinLayout{{5, 16, 3}});
  cv::Mat out;
  mapper.map(bgr, out);
  ASSERT_EQ(out.type(), CV_8UC3);
  ASSERT_EQ(out.size(), bgr.size());
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      const auto expected = mapper.binOf(p[2], p[1], p[0]);
      const cv::Vec3b got = out.at<cv::Vec3b>(y, x);
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(got[c], expected[c]) << "at " << x << "," << y << " channel " << c;
    }
}

// map() computes HSV bins in integer/float SIMD arithmetic; binOf() goes through the double-precision
// rgbToHsv(). They must agree on every one of the 2^24 colours (the header allows a neighbouring bin at
// borders; this implementation is exact, so the test holds it to that).
TEST(BinMapper, HsvMapAgreesWithExactBinsOnEveryColour) {
  cv::Mat bgr(4096, 4096, CV_8UC3);
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const int i = y * bgr.cols + x;
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(i & 255, (i >> 8) & 255, i >> 16);
    }
  // Power-of-two, odd and extreme layouts: odd counts put bin borders on exact fractions like 1/3, 2/5.
  for (const BinLayout layout : {BinLayout{{16, 16, 8}}, BinLayout{{15, 5, 3}}, BinLayout{{1, 256, 255}}}) {
    const BinMapper mapper(ColorSpace::Hsv, layout);
    cv::Mat out;
    mapper.map(bgr, out);
    ASSERT_EQ(out.size(), bgr.size());
    long mismatches = 0, worst = 0;
    std::string first;
    for (int y = 0; y < bgr.rows; ++y)
      for (int x = 0; x < bgr.cols; ++x) {
        const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
        const auto exact = mapper.binOf(p[2], p[1], p[0]);
        const cv::Vec3b got = out.at<cv::Vec3b>(y, x);
        bool same = true;
        for (int c = 0; c < 3; ++c) {
          worst = std::max<long>(worst, binDistance(got[c], exact[c], layout.bins[c], c == 0));
          same = same && got[c] == exact[c];
        }
        if (!same && mismatches++ == 0)
          first = cv::format("rgb %d,%d,%d: map %d,%d,%d vs binOf %d,%d,%d", p[2], p[1], p[0], got[0], got[1],
                             got[2], exact[0], exact[1], exact[2]);
      }
    std::printf("bins %d,%d,%d: %ld of 16777216 colours differ from binOf (worst %ld bins)\n", layout.bins[0],
                layout.bins[1], layout.bins[2], mismatches, worst);
    EXPECT_EQ(mismatches, 0) << first;
    EXPECT_LE(worst, 1);
  }
}

TEST(BinMapper, HsvMapOddWidthUsesTheScalarTail) {
  cv::RNG rng(11);
  cv::Mat bgr(40, 301, CV_8UC3);  // 301 = 18 * 16 + 13: the last 13 pixels of each row go the scalar way
  rng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
  const BinMapper mapper(ColorSpace::Hsv, BinLayout{{36, 10, 4}});
  cv::Mat out;
  mapper.map(bgr, out);
  for (int y = 0; y < bgr.rows; ++y)
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
      const auto exact = mapper.binOf(p[2], p[1], p[0]);
      for (int c = 0; c < 3; ++c) ASSERT_EQ(out.at<cv::Vec3b>(y, x)[c], exact[c]) << "at " << x << "," << y;
    }
}

TEST(BinMapper, HsvMapHandlesGreysAndRoiViews) {
  const BinMapper mapper(ColorSpace::Hsv, BinLayout{{16, 16, 8}});
  cv::Mat big(10, 20, CV_8UC3, cv::Scalar(0, 0, 255));  // red, BGR
  cv::Mat roi = big(cv::Rect(3, 2, 7, 5));              // non-continuous view
  roi.setTo(cv::Scalar(90, 90, 90));                    // grey
  cv::Mat out;
  mapper.map(roi, out);
  ASSERT_EQ(out.size(), roi.size());
  const auto grey = mapper.binOf(90, 90, 90);
  for (int y = 0; y < out.rows; ++y)
    for (int x = 0; x < out.cols; ++x)
      for (int c = 0; c < 3; ++c) ASSERT_EQ(out.at<cv::Vec3b>(y, x)[c], grey[c]);
}

// Every 8-bit value for many bin counts: the vectorised path and the tables agree with binOf().
TEST(BinMapper, RgbMapEveryValue) {
  cv::Mat bgr(1, 256, CV_8UC3);
  for (int k = 0; k < 256; ++k) bgr.at<cv::Vec3b>(0, k) = cv::Vec3b(k, 255 - k, k / 2);
  for (int n = 1; n <= 256; ++n) {
    const BinMapper mapper(ColorSpace::Rgb, BinLayout{{n, n, n}});
    cv::Mat out;
    mapper.map(bgr, out);
    for (int k = 0; k < 256; ++k) {
      const cv::Vec3b p = bgr.at<cv::Vec3b>(0, k);
      const auto exact = mapper.binOf(p[2], p[1], p[0]);
      for (int c = 0; c < 3; ++c)
        ASSERT_EQ(out.at<cv::Vec3b>(0, k)[c], exact[c]) << "n " << n << " value " << k;
    }
  }
}

TEST(BinMapper, MapInPlace) {
  cv::RNG rng(21);
  cv::Mat bgr(9, 35, CV_8UC3);
  rng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
  for (const ColorSpace space : {ColorSpace::Hsv, ColorSpace::Rgb}) {
    const BinMapper mapper(space, BinLayout{{16, 16, 8}});
    cv::Mat expected, image = bgr.clone();
    mapper.map(bgr, expected);
    mapper.map(image, image);
    EXPECT_EQ(cv::norm(image, expected, cv::NORM_INF), 0.0);
  }
}

// Not a timing assertion: prints the cost of mapping a full-HD frame for the report.
TEST(BinMapper, FullHdTiming) {
  cv::RNG rng(3);
  cv::Mat bgr(1080, 1920, CV_8UC3);
  rng.fill(bgr, cv::RNG::UNIFORM, 0, 256);
  const int threads = cv::getNumThreads();
  for (const ColorSpace space : {ColorSpace::Hsv, ColorSpace::Rgb})
    for (const int useThreads : {1, threads}) {
      const BinMapper mapper(space, BinLayout{{16, 16, 8}});
      cv::setNumThreads(useThreads);
      cv::Mat out;
      mapper.map(bgr, out);  // warm-up (allocation)
      const int runs = 10;
      const auto start = std::chrono::steady_clock::now();
      for (int i = 0; i < runs; ++i) mapper.map(bgr, out);
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / runs;
      std::printf("BinMapper::map (%s) on 1920x1080, %d thread(s): %.2f ms per frame\n",
                  space == ColorSpace::Hsv ? "HSV" : "RGB", useThreads, ms);
      EXPECT_EQ(out.size(), bgr.size());
    }
  cv::setNumThreads(threads);
}
