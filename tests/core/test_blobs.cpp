// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode's pixel side: "h,s,v" parsing, hue ranges that wrap, the range lookup table against the
// exact HSV test, sampling of packed and YUV frames, opening/closing, blob measures, learning a range.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "balls.hpp"
#include "colortrack/blobs.hpp"
#include "support/status_helpers.hpp"

using namespace colortrack;
using balls::Ball;
using balls::BallScene;
using balls::BallSceneConfig;

namespace {

HsvRange rangeOf(Hsv lower, Hsv upper) {
  HsvRange r;
  r.lower = lower;
  r.upper = upper;
  return r;
}

// A red ball whose hue (358 deg) sits just below 0, moving diagonally over clutter of other hues.
BallScene redBallScene(double saltPepper = 0, double highlight = 0) {
  BallSceneConfig config;
  config.saltPepper = saltPepper;
  Ball ball;
  ball.hue = 358;
  ball.radius = 24;
  ball.highlight = highlight;
  ball.path = {{0, {100, 90}}, {60, {520, 380}}};
  return BallScene(config, {ball});
}

const HsvRange kRedRange = rangeOf({345, 0.5, 0.25}, {15, 1, 1});

int countMismatches(const cv::Mat &a, const cv::Mat &b) {
  cv::Mat diff;
  cv::compare(a, b, diff, cv::CMP_NE);
  return cv::countNonZero(diff);
}

}  // namespace

TEST(ParseHsv, AcceptsAndFormats) {
  const auto hsv = parseHsv(" 350 , 0.5,1");
  ASSERT_TRUE(hsv);
  EXPECT_DOUBLE_EQ(hsv->h, 350);
  EXPECT_DOUBLE_EQ(hsv->s, 0.5);
  EXPECT_DOUBLE_EQ(hsv->v, 1);
  EXPECT_EQ(formatHsv(*hsv), "350,0.5,1");
  EXPECT_TRUE(parseHsv("360,0,0"));
}

TEST(ParseHsv, RejectsMalformedAndOutOfRangeWithReasons) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "expected"},
      {"1,2", "expected"},
      {"10,0.5,0.5,1", "expected"},
      {"red", "expected"},
      {"10,0.5,abc", "expected"},
      {"361,0.5,0.5", "hue"},
      {"-1,0.5,0.5", "hue"},
      {"10,1.5,0.5", "saturation"},
      {"10,0.5,-0.1", "value"},
      {"nan,0.5,0.5", "expected"},
  };
  for (const auto &[text, reason] : cases) {
    std::string error;
    EXPECT_FALSE(okOr(parseHsv(text), error)) << text;
    EXPECT_NE(error.find(reason), std::string::npos) << text << " -> " << error;
  }
  EXPECT_FALSE(validateRange(rangeOf({0, 0.8, 0}, {10, 0.5, 1})));
  EXPECT_FALSE(validateRange(rangeOf({0, 0, 0.9}, {10, 1, 0.2})));
  EXPECT_TRUE(validateRange(rangeOf({340, 0.5, 0.2}, {20, 1, 1})));
}

TEST(HsvRange, HueWrapsThroughZero) {
  const HsvRange red = rangeOf({340, 0.5, 0.2}, {20, 1, 1});
  for (double h : {340.0, 350.0, 359.9, 0.0, 10.0, 20.0}) EXPECT_TRUE(red.contains({h, 0.8, 0.8})) << h;
  for (double h : {339.0, 21.0, 180.0}) EXPECT_FALSE(red.contains({h, 0.8, 0.8})) << h;
  EXPECT_FALSE(red.contains({0, 0.3, 0.8}));  // too grey
  EXPECT_FALSE(red.contains({0, 0.8, 0.1}));  // too dark
  const HsvRange all = rangeOf({0, 0.5, 0.2}, {360, 1, 1});
  for (double h = 0; h < 360; h += 7.5) EXPECT_TRUE(all.contains({h, 0.8, 0.8})) << h;
}

// The table decides each 4x4x4 cell by its centre: it may differ from the exact test only near the range's
// surface, so on random colours nearly all agree, and every disagreement flips within +-2 per channel.
TEST(RangeLut, AgreesWithExactTestAwayFromTheEdges) {
  const HsvRange range = rangeOf({340, 0.4, 0.3}, {25, 0.95, 0.9});
  const RangeLut lut(range, PixelEncoding::Rgb);
  cv::RNG rng(7);
  int mismatches = 0, farMismatches = 0;
  const int n = 200000;
  for (int i = 0; i < n; ++i) {
    const int r = rng.uniform(0, 256), g = rng.uniform(0, 256), b = rng.uniform(0, 256);
    const bool exact = range.contains(rgbToHsv(r, g, b));
    if (exact == (lut.at(r, g, b) != 0)) continue;
    ++mismatches;
    bool nearEdge = false;
    for (int dr = -3; dr <= 3 && !nearEdge; ++dr)
      for (int dg = -3; dg <= 3 && !nearEdge; ++dg)
        for (int db = -3; db <= 3 && !nearEdge; ++db) {
          const int rr = std::clamp(r + dr, 0, 255), gg = std::clamp(g + dg, 0, 255),
                    bb = std::clamp(b + db, 0, 255);
          nearEdge = range.contains(rgbToHsv(rr, gg, bb)) != exact;
        }
    if (!nearEdge) ++farMismatches;
  }
  std::printf("LUT vs exact: %d of %d random colours differ (%.2f%%), %d away from the range's surface\n",
              mismatches, n, 100.0 * mismatches / n, farMismatches);
  EXPECT_LT(mismatches, n / 100);
  EXPECT_EQ(farMismatches, 0);
}

// A frame read straight from I420 planes through the YUV table matches the BGR the same planes convert to.
TEST(Segment, YuvPlanesMatchTheirBgrConversion) {
  const BallScene scene = redBallScene();
  const cv::Mat bgr = scene.render(10);
  cv::Mat i420, back;
  cv::cvtColor(bgr, i420, cv::COLOR_BGR2YUV_I420);
  cv::cvtColor(i420, back, cv::COLOR_YUV2BGR_I420);
  const cv::Size s = bgr.size(), half(s.width / 2, s.height / 2);
  SampledFrame yuv;
  yuv.encoding = PixelEncoding::Yuv;
  yuv.size = s;
  yuv.channels[0] = {i420.rowRange(0, s.height), 0, 1, 1, 1};
  const cv::Mat u(half, CV_8UC1, i420.ptr(s.height)), v(half, CV_8UC1, i420.ptr(s.height) + half.area());
  yuv.channels[1] = {u, 0, 1, 2, 2};
  yuv.channels[2] = {v, 0, 1, 2, 2};
  cv::Mat fromYuv, fromBgr;
  segment(yuv, RangeLut(kRedRange, PixelEncoding::Yuv), 2, fromYuv);
  segment(sampledBgr(back), RangeLut(kRedRange, PixelEncoding::Rgb), 2, fromBgr);
  ASSERT_EQ(fromYuv.size(), cv::Size(320, 240));
  const int inside = cv::countNonZero(fromBgr), differ = countMismatches(fromYuv, fromBgr);
  std::printf("I420 vs its BGR: %d of %d inside samples, %d differ\n", inside, int(fromBgr.total()), differ);
  EXPECT_GT(inside, 300);
  EXPECT_LT(differ, inside / 20);
}

// RGBA read in place (byte offsets) gives exactly the mask of the same pixels as BGR.
TEST(Segment, PackedFormatsByByteOffsets) {
  const cv::Mat bgr = redBallScene().render(5);
  cv::Mat rgba;
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  SampledFrame packed;
  packed.size = bgr.size();
  const cv::Mat bytes(rgba.rows, rgba.cols * 4, CV_8UC1, rgba.data, rgba.step);
  packed.channels = {ChannelSampler{bytes, 0, 4, 1, 1}, ChannelSampler{bytes, 1, 4, 1, 1},
                     ChannelSampler{bytes, 2, 4, 1, 1}};
  const RangeLut lut(kRedRange, PixelEncoding::Rgb);
  for (int d : {1, 2, 3}) {
    cv::Mat a, b;
    segment(packed, lut, d, a);
    segment(sampledBgr(bgr), lut, d, b);
    EXPECT_EQ(a.size(), cv::Size((640 + d - 1) / d, (480 + d - 1) / d));
    EXPECT_EQ(countMismatches(a, b), 0) << "decimation " << d;
    EXPECT_GT(cv::countNonZero(a), 1000 / (d * d));
  }
}

// Every layout segment() special-cases (packed 3- and 4-byte pixels, planar and semi-planar 4:2:0, packed
// 4:2:2) and the general one give exactly the samples the ChannelSampler definition names, looked up one by
// one, for even and odd sizes, a row stride wider than the row, and decimations 1 to 3.
TEST(Segment, EveryLayoutMatchesPerSampleLookup) {
  const HsvRange range = rangeOf({300, 0.2, 0.1}, {120, 0.9, 0.95});  // about half of all colours
  const RangeLut rgbLut(range, PixelEncoding::Rgb), yuvLut(range, PixelEncoding::Yuv);
  cv::RNG rng(3);
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(641, 363), cv::Size(37, 21), cv::Size(2, 1)}) {
    const cv::Size half((size.width + 1) / 2, (size.height + 1) / 2);
    // Rows 5 bytes wider than used, so reading past a row's end would show as a mismatch or a crash.
    cv::Mat store(size.height + 2 * half.height, size.width * 4 + 5, CV_8UC1);
    rng.fill(store, cv::RNG::UNIFORM, 0, 256);
    const auto bytes = [&](int firstRow, int rows, int cols) {
      return store(cv::Rect(0, firstRow, cols, rows));
    };
    struct Layout {
      const char *name;
      std::array<ChannelSampler, 3> channels;
      PixelEncoding encoding;
    };
    const int w = size.width, h = size.height, cw = half.width, ch = half.height;
    const std::vector<Layout> layouts{
        {"BGR",
         {{{bytes(0, h, 3 * w), 2, 3}, {bytes(0, h, 3 * w), 1, 3}, {bytes(0, h, 3 * w), 0, 3}}},
         PixelEncoding::Rgb},
        {"RGB",
         {{{bytes(0, h, 3 * w), 0, 3}, {bytes(0, h, 3 * w), 1, 3}, {bytes(0, h, 3 * w), 2, 3}}},
         PixelEncoding::Rgb},
        {"RGBx",
         {{{bytes(0, h, 4 * w), 0, 4}, {bytes(0, h, 4 * w), 1, 4}, {bytes(0, h, 4 * w), 2, 4}}},
         PixelEncoding::Rgb},
        {"xBGR",
         {{{bytes(0, h, 4 * w), 3, 4}, {bytes(0, h, 4 * w), 2, 4}, {bytes(0, h, 4 * w), 1, 4}}},
         PixelEncoding::Rgb},
        {"I420",
         {{{bytes(0, h, w), 0, 1}, {bytes(h, ch, cw), 0, 1, 2, 2}, {bytes(h + ch, ch, cw), 0, 1, 2, 2}}},
         PixelEncoding::Yuv},
        {"NV12",
         {{{bytes(0, h, w), 0, 1}, {bytes(h, ch, 2 * cw), 0, 2, 2, 2}, {bytes(h, ch, 2 * cw), 1, 2, 2, 2}}},
         PixelEncoding::Yuv},
        {"YUY2",
         {{{bytes(0, h, 2 * w), 0, 2}, {bytes(0, h, 2 * w), 1, 4, 2, 1}, {bytes(0, h, 2 * w), 3, 4, 2, 1}}},
         PixelEncoding::Yuv},
    };
    for (const Layout &layout : layouts) {
      SampledFrame frame;
      frame.channels = layout.channels;
      frame.encoding = layout.encoding;
      frame.size = size;
      const RangeLut &lut = layout.encoding == PixelEncoding::Rgb ? rgbLut : yuvLut;
      for (int d : {1, 2, 3}) {
        cv::Mat mask;
        segment(frame, lut, d, mask);
        ASSERT_EQ(mask.size(), cv::Size((w + d - 1) / d, (h + d - 1) / d));
        int mismatches = 0, inside = 0;
        for (int y = 0; y < mask.rows; ++y)
          for (int x = 0; x < mask.cols; ++x) {
            std::array<std::uint8_t, 3> c;
            for (int k = 0; k < 3; ++k) {
              const ChannelSampler &s = frame.channels[k];
              c[k] = s.plane.ptr(y * d / s.ySub)[(x * d / s.xSub) * s.sampleBytes + s.byteOffset];
            }
            const std::uint8_t expected = lut.at(c[0], c[1], c[2]);
            mismatches += mask.at<std::uint8_t>(y, x) != expected;
            inside += expected != 0;
          }
        EXPECT_EQ(mismatches, 0) << layout.name << " " << size << " decimation " << d;
        // Both answers occur (random YUV bytes are mostly out of the RGB gamut: about 5% inside).
        if (mask.total() > 1000) {
          EXPECT_GT(inside, static_cast<int>(mask.total() / 50)) << layout.name;
        }
      }
    }
  }
}

// The paper's case: a red ball (hue across 0 deg) on clutter. Centroid within 2 px on average, one blob.
TEST(BlobDetector, RedBallCentroidOnClutter) {
  const BallScene scene = redBallScene();
  for (int decimation : {1, 2}) {
    BlobSettings settings;
    settings.range = kRedRange;
    settings.decimation = decimation;
    BlobDetector detector(settings);
    double sum = 0, worst = 0;
    int frames = 0;
    for (int i = 0; i <= 60; i += 3) {
      std::vector<balls::BallTruth> truth;
      const cv::Mat frame = scene.render(i, &truth);
      const std::vector<Blob> blobs = detector.detect(MatImageSource(frame));
      ASSERT_EQ(blobs.size(), 1u) << "frame " << i << " decimation " << decimation;
      const double error = cv::norm(blobs[0].centroid - truth[0].centre);
      sum += error;
      worst = std::max(worst, error);
      ++frames;
      const double disc = CV_PI * 24 * 24;
      EXPECT_NEAR(blobs[0].area, disc, 0.12 * disc);
      EXPECT_NEAR(blobs[0].fill, CV_PI / 4, 0.08);
      EXPECT_NEAR(blobs[0].box.width, 49, 4);
    }
    std::printf("decimation %d: mean centroid error %.3f px, worst %.3f px\n", decimation, sum / frames,
                worst);
    EXPECT_LE(sum / frames, 2.0);
    EXPECT_LE(worst, 3.0);
  }
}

// 2% of the pixels replaced by the ball's colour, white or black: without clean-up every speck is a blob;
// the opening removes all of them, even with min-area 1.
TEST(BlobDetector, OpeningRemovesSaltAndPepper) {
  const cv::Mat frame = redBallScene(0.02).render(20);
  BlobSettings settings;
  settings.range = kRedRange;
  settings.minArea = 1;
  settings.decimation = 1;
  settings.morphSize = 0;
  BlobDetector raw(settings);
  const size_t rawCount = raw.detect(MatImageSource(frame)).size();
  settings.morphSize = 5;
  settings.maxObjects = 100;
  BlobDetector cleaned(settings);
  const std::vector<Blob> blobs = cleaned.detect(MatImageSource(frame));
  std::printf("salt and pepper: %zu blobs raw (max-objects 8), %zu after opening\n", rawCount, blobs.size());
  EXPECT_EQ(rawCount, 8u);  // capped by max-objects: there are far more
  ASSERT_EQ(blobs.size(), 1u);
  EXPECT_LT(cv::norm(blobs[0].centroid - redBallScene().truthOf(0, 20).centre), 2.0);
}

// A specular highlight punches a hole in the colour blob; the closing fills it, restoring area and centroid.
TEST(BlobDetector, ClosingFillsAHole) {
  const BallScene scene = redBallScene(0, 2.5);
  std::vector<balls::BallTruth> truth;
  const cv::Mat frame = scene.render(30, &truth);
  const cv::Point2d spot = truth[0].centre + cv::Point2d(-0.35 * 24, -0.35 * 24);
  BlobSettings settings;
  settings.range = kRedRange;
  settings.decimation = 1;
  settings.morphSize = 0;
  BlobDetector raw(settings);
  const std::vector<Blob> open = raw.detect(MatImageSource(frame));
  ASSERT_EQ(open.size(), 1u);
  EXPECT_EQ(raw.mask().at<uchar>(cvRound(spot.y), cvRound(spot.x)), 0) << "the highlight should be a hole";
  settings.morphSize = 5;
  BlobDetector cleaned(settings);
  const std::vector<Blob> filled = cleaned.detect(MatImageSource(frame));
  ASSERT_EQ(filled.size(), 1u);
  EXPECT_EQ(cleaned.mask().at<uchar>(cvRound(spot.y), cvRound(spot.x)), 255);
  std::printf("hole: area %.0f -> %.0f (disc %.0f)\n", open[0].area, filled[0].area, CV_PI * 24 * 24);
  EXPECT_GT(filled[0].area, open[0].area + 10);
  EXPECT_LT(cv::norm(filled[0].centroid - truth[0].centre), 1.0);
}

// The detector labels only the foreground's bounding box; its labels must be those of labelling the whole
// mask, numbers included, frame after frame (boxes at odd and even corners, growing, shrinking, empty), on
// one thread and on OpenCV's parallel labelling alike.
TEST(BlobDetector, LabelsMatchLabellingTheWholeMask) {
  BlobSettings settings;
  settings.range = kRedRange;
  settings.morphSize = 0;
  settings.minArea = 1;
  settings.maxObjects = 1000;
  settings.decimation = 1;
  const int threads = cv::getNumThreads();
  for (int numThreads : {1, std::max(2, threads)}) {
    cv::setNumThreads(numThreads);
    BlobDetector detector(settings);
    cv::RNG rng(7);
    for (int frame = 0; frame < 40; ++frame) {
      cv::Mat bgr(241, 323, CV_8UC3, cv::Scalar(0, 0, 0));
      const int shapes = frame % 10 == 9 ? 0 : rng.uniform(1, 30);  // every tenth frame empty
      for (int i = 0; i < shapes; ++i) {
        const cv::Point centre(rng.uniform(0, bgr.cols), rng.uniform(0, bgr.rows));
        if (rng.uniform(0, 2))
          cv::circle(bgr, centre, rng.uniform(0, 12), cv::Scalar(0, 0, 255), cv::FILLED);
        else
          bgr.at<cv::Vec3b>(centre) = cv::Vec3b(0, 0, 255);  // single pixels, at odd coordinates too
      }
      const std::vector<Blob> blobs = detector.detect(sampledBgr(bgr));
      cv::Mat expected;
      const int count = cv::connectedComponents(detector.mask(), expected, 8, CV_32S);
      ASSERT_EQ(countMismatches(detector.labels().labels, expected), 0) << "frame " << frame;
      EXPECT_EQ(static_cast<int>(blobs.size()), count - 1) << "frame " << frame;
    }
  }
  cv::setNumThreads(threads);
}

TEST(BlobDetector, MinAreaAndMaxObjectsKeepTheLargest) {
  std::vector<Ball> five;
  for (int i = 0; i < 5; ++i) {
    Ball b;
    b.hue = 120;
    b.radius = 8 + 4 * i;
    b.path = {{0, {60.0 + 120 * i, 240}}};
    five.push_back(b);
  }
  BallSceneConfig config;
  config.clutterPatches = 0;
  const BallScene scene(config, five);
  const cv::Mat frame = scene.render(0);
  BlobSettings settings;
  settings.range = rangeOf({100, 0.5, 0.2}, {140, 1, 1});
  settings.maxObjects = 3;
  BlobDetector detector(settings);
  std::vector<Blob> blobs = detector.detect(MatImageSource(frame));
  ASSERT_EQ(blobs.size(), 3u);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(blobs[i].centroid.x, 60.0 + 120 * (4 - i), 1.0);
  settings.maxObjects = 8;
  settings.minArea = static_cast<int>(CV_PI * 14 * 14);  // between radius 12 and 16: three stay
  detector.setSettings(settings);
  blobs = detector.detect(MatImageSource(frame));
  EXPECT_EQ(blobs.size(), 3u);
}

// init-box on the ball: the learnt range wraps through 0, and finds the ball at -30% and +30% brightness
// with nothing from the clutter.
TEST(LearnRange, FromABoxAndUnderBrightnessChange) {
  BallSceneConfig config;
  config.brightness = 0.3;
  config.brightnessPeriod = 40;
  Ball ball;
  ball.hue = 2;
  ball.radius = 26;
  ball.path = {{0, {200, 200}}, {40, {440, 280}}};
  const BallScene scene(config, {ball});
  const cv::Mat first = scene.render(0);
  const HsvRange learnt = learnRange(MatImageSource(first), scene.boxOf(0, 0));
  std::printf("learnt range %s .. %s\n", formatHsv(learnt.lower).c_str(), formatHsv(learnt.upper).c_str());
  EXPECT_TRUE(learnt.wrapsHue());
  EXPECT_TRUE(learnt.contains({2, 0.85, 0.7}));
  EXPECT_TRUE(validateRange(learnt));
  BlobSettings settings;
  settings.range = learnt;
  BlobDetector detector(settings);
  for (int i : {10, 30, 0, 20}) {  // brightest (+30%), darkest (-30%), normal, normal
    std::vector<balls::BallTruth> truth;
    const cv::Mat frame = scene.render(i, &truth);
    const std::vector<Blob> blobs = detector.detect(MatImageSource(frame));
    ASSERT_EQ(blobs.size(), 1u) << "frame " << i;
    EXPECT_LT(cv::norm(blobs[0].centroid - truth[0].centre), 2.0) << "frame " << i;
    EXPECT_GT(blobs[0].area, 0.85 * CV_PI * 26 * 26) << "frame " << i;
  }
}

TEST(LearnRange, GreyObjectGetsEveryHue) {
  cv::Mat frame(100, 100, CV_8UC3, cv::Scalar(30, 30, 30));
  cv::circle(frame, {50, 50}, 30, cv::Scalar(180, 182, 178), cv::FILLED);
  const HsvRange learnt = learnRange(MatImageSource(frame), cv::Rect(20, 20, 61, 61));
  EXPECT_GE(learnt.upper.h - learnt.lower.h, 360.0);
  EXPECT_LT(learnt.upper.s, 0.3);
  EXPECT_GT(learnt.lower.v, 0.3);
}
