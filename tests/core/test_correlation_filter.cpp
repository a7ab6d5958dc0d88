// SPDX-License-Identifier: LGPL-2.1-or-later
// The shape cue of the fused method: gradient-orientation cell features, the translation and scale
// correlation filters, the peak-to-sidelobe confidence, and the fused detector on synthetic images with a
// known shift and scale.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

#include "colortrack/cell_features.hpp"
#include "colortrack/correlation_filter.hpp"
#include "colortrack/fused_detector.hpp"
#include "noise_texture.hpp"

using namespace colortrack;

namespace {

// Blurred noise, CV_8UC3: plenty of gradients in every direction.
cv::Mat texture(cv::Size size, int seed) {
  return colortrack::test::noiseTexture(size, seed, 2.0);
}

// The same texture as grey levels in [0, 1] (CV_32FC1), what the cell features read.
cv::Mat grayTexture(cv::Size size, int seed) {
  cv::Mat gray;
  cv::cvtColor(texture(size, seed), gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(gray, CV_32F, 1.0 / 255);
  return gray;
}

// A 24 x 24-cell filter learnt from `channels` alone.
CorrelationFilter filterTrainedOn(const std::vector<cv::Mat> &channels) {
  CorrelationFilter filter;
  filter.init(cv::Size(24, 24), 1.0, 1e-3);
  filter.train(channels, 1.0);
  return filter;
}

// Where `filter` answers `channels` most strongly, and how strongly.
cv::Point peakOf(const CorrelationFilter &filter, const std::vector<cv::Mat> &channels,
                 double *value = nullptr) {
  cv::Mat response;
  filter.respond(channels, response);
  cv::Point peak;
  cv::minMaxLoc(response, nullptr, value, nullptr, &peak);
  return peak;
}

// `image` moved by (dx, dy) and scaled by `scale` about `centre` (bilinear, border repeated).
cv::Mat warped(const cv::Mat &image, cv::Point2d centre, double scale, double dx, double dy) {
  const cv::Matx23d m(scale, 0, (1 - scale) * centre.x + dx, 0, scale, (1 - scale) * centre.y + dy);
  cv::Mat out;
  cv::warpAffine(image, out, m, image.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

}  // namespace

TEST(CellFeatures, GridSizeAndChannels) {
  cv::Mat gray(48, 64, CV_32F, cv::Scalar(0.25));
  std::vector<cv::Mat> channels;
  cellFeatures(gray, 4, channels);
  ASSERT_EQ(static_cast<int>(channels.size()), kCellChannels);
  for (const cv::Mat &c : channels) EXPECT_EQ(c.size(), cv::Size(16, 12));
  // A flat patch: no orientation energy, intensity channel = grey level - 0.5.
  for (int o = 0; o < kOrientations; ++o) EXPECT_EQ(cv::countNonZero(channels[o]), 0);
  EXPECT_NEAR(channels[kCellChannels - 1].at<float>(5, 5), -0.25, 1e-5);
}

TEST(CellFeatures, OrientationOfAnEdge) {
  // Vertical stripes: horizontal gradients only (angle 0), shared between the two bins around 0 degrees.
  cv::Mat gray(32, 32, CV_32F);
  for (int x = 0; x < 32; ++x) gray.col(x).setTo((x / 4) % 2 ? 1.0 : 0.0);
  std::vector<cv::Mat> channels;
  cellFeatures(gray, 4, channels);
  double inBinsAroundZero = 0, elsewhere = 0;
  for (int o = 0; o < kOrientations; ++o)
    (o == 0 || o == kOrientations - 1 ? inBinsAroundZero : elsewhere) += cv::sum(channels[o])[0];
  EXPECT_GT(inBinsAroundZero, 0);
  EXPECT_NEAR(elsewhere, 0, 1e-4);
  // Horizontal stripes: vertical gradients (90 degrees), all in the middle bin.
  cv::Mat turned = gray.t();
  cellFeatures(turned, 4, channels);
  double middle = 0, others = 0;
  for (int o = 0; o < kOrientations; ++o)
    (o == kOrientations / 2 ? middle : others) += cv::sum(channels[o])[0];
  EXPECT_GT(middle, 0);
  EXPECT_NEAR(others, 0, 1e-4);
}

// The integral-image path (the scale filter's samples) gives the same features as the direct one for a
// rectangle on the cell grid, away from its border (where the direct path repeats the patch's edge and the
// integral one sees the image beyond it).
TEST(CellFeatures, IntegralPathMatchesDirectPath) {
  const cv::Mat gray = grayTexture(cv::Size(96, 96), 4);
  const cv::Rect rect(12, 16, 64, 64);
  std::vector<cv::Mat> direct, integral;
  cellFeatures(gray(rect), 4, direct);
  CellFeatureIntegral sums;
  sums.build(gray);
  sums.features(cv::Rect2d(rect), cv::Size(16, 16), integral);
  ASSERT_EQ(integral.size(), direct.size());
  for (size_t c = 0; c < direct.size(); ++c) {
    const cv::Rect inner(2, 2, 12, 12);
    EXPECT_LT(cv::norm(direct[c](inner), integral[c](inner), cv::NORM_INF), 1e-4) << "channel " << c;
  }
}

TEST(PatchSampler, PatchCoversTheRectangleItReports) {
  // x + 2y as the blue channel: a patch's pixels say where they came from.
  cv::Mat image(120, 160, CV_8UC3);
  for (int y = 0; y < image.rows; ++y)
    for (int x = 0; x < image.cols; ++x) image.at<cv::Vec3b>(y, x) = cv::Vec3b((x + 2 * y) / 2, 0, 0);
  PatchSampler sampler;
  const cv::Rect2d wanted(20.4, 30.6, 40.2, 30.1);
  sampler.load(MatImageSource(image), wanted, 1);
  cv::Mat patch;
  const cv::Rect2d got = sampler.extract(wanted, cv::Size(40, 30), patch);
  EXPECT_NEAR(got.x, wanted.x, 0.5);
  EXPECT_NEAR(got.y, wanted.y, 0.5);
  EXPECT_EQ(got.size(), cv::Size2d(40, 30));
  EXPECT_EQ(patch.at<cv::Vec3b>(0, 0)[0], image.at<cv::Vec3b>(cvRound(got.y), cvRound(got.x))[0]);
  // Reaching outside the frame repeats its border instead of failing.
  const cv::Rect2d outside(-30, -20, 60, 40);
  sampler.load(MatImageSource(image), outside, 2);
  const cv::Rect2d got2 = sampler.extract(outside, cv::Size(30, 20), patch);
  EXPECT_EQ(got2.size(), cv::Size2d(60, 40));
  EXPECT_EQ(patch.at<cv::Vec3b>(0, 0), image.at<cv::Vec3b>(0, 0));
}

TEST(CorrelationFilter, PeaksAtTheShiftOfTheTrainingPatch) {
  const cv::Mat gray = grayTexture(cv::Size(160, 160), 3);
  std::vector<cv::Mat> trained, shifted;
  cellFeatures(gray(cv::Rect(32, 32, 96, 96)), 4, trained);
  cellFeatures(gray(cv::Rect(32 + 12, 32 - 8, 96, 96)), 4, shifted);  // the target moved by (-3, +2) cells
  const CorrelationFilter filter = filterTrainedOn(trained);
  double peakValue = 0;
  EXPECT_EQ(peakOf(filter, trained, &peakValue), cv::Point(12, 12));
  EXPECT_GT(peakValue, 0.5);
  EXPECT_EQ(peakOf(filter, shifted), cv::Point(12 - 3, 12 + 2));
}

// Learning from the search patch with the label moved to where the target was found is the same as learning
// from a patch centred on it: afterwards the centred patch peaks in the middle, a shifted one at its shift.
TEST(CorrelationFilter, LearnsFromTheSearchPatchWithTheLabelMoved) {
  const cv::Mat gray = grayTexture(cv::Size(160, 160), 7);
  std::vector<cv::Mat> centred, searched, other;
  cellFeatures(gray(cv::Rect(32, 32, 96, 96)), 4, centred);
  cellFeatures(gray(cv::Rect(32 - 8, 32 + 4, 96, 96)), 4, searched);  // the target at (+2, -1) cells
  cellFeatures(gray(cv::Rect(32 + 8, 32 + 12, 96, 96)), 4, other);    // the target at (-2, -3) cells
  CorrelationFilter filter = filterTrainedOn(centred);
  ASSERT_EQ(peakOf(filter, searched), cv::Point(12 + 2, 12 - 1));
  // Replace the model by what the search patch shows (rate 1), the label at the target's offset.
  filter.trainOnLastResponse(cv::Point2d(2, -1), 1.0);
  EXPECT_EQ(peakOf(filter, centred), cv::Point(12, 12));
  cv::Mat response;
  filter.respond(other, response);
  cv::Point peak;
  cv::minMaxLoc(response, nullptr, nullptr, nullptr, &peak);
  const cv::Point2d at = subCellPeak(response, peak);
  EXPECT_NEAR(at.x, 12 - 2, 0.25);
  EXPECT_NEAR(at.y, 12 - 3, 0.25);
  // A label half a cell beyond the target teaches the filter to answer half a cell further: the fraction
  // carries through.
  peakOf(filter, searched);
  filter.trainOnLastResponse(cv::Point2d(2.5, -1), 1.0);
  filter.respond(centred, response);
  cv::minMaxLoc(response, nullptr, nullptr, nullptr, &peak);
  EXPECT_NEAR(subCellPeak(response, peak).x, 12 + 0.5, 0.2);
}

TEST(CorrelationFilter, SubCellPeakOfAGaussianIsExact) {
  cv::Mat response(21, 21, CV_32F);
  const cv::Point2d truth(9.3, 11.8);
  for (int y = 0; y < 21; ++y)
    for (int x = 0; x < 21; ++x)
      response.at<float>(y, x) = static_cast<float>(
          std::exp(-0.5 * ((x - truth.x) * (x - truth.x) + (y - truth.y) * (y - truth.y)) / 1.5));
  const cv::Point2d found = subCellPeak(response, cv::Point(9, 12));
  EXPECT_NEAR(found.x, truth.x, 1e-3);
  EXPECT_NEAR(found.y, truth.y, 1e-3);
}

TEST(CorrelationFilter, PeakToSidelobeSeparatesOnePeakFromNoise) {
  cv::Mat sharp(24, 24, CV_32F), noise(24, 24, CV_32F);
  cv::RNG rng(5);
  rng.fill(noise, cv::RNG::UNIFORM, 0.0, 0.2);
  noise.copyTo(sharp);
  sharp.at<float>(10, 10) = 1.0f;
  noise.at<float>(10, 10) = 0.25f;
  EXPECT_GT(peakToSidelobe(sharp, cv::Point(10, 10), 2), 10.0);
  EXPECT_LT(peakToSidelobe(noise, cv::Point(10, 10), 2), 4.0);
}

namespace {

// A 24 x 32 response on a floor of 0.1: a peak of height 1 at (firstX, 12) whose width grows with `spread`
// (4: as sharp as the second), and another of `secondHeight` at (22, 12).
cv::Mat twoPeaks(int firstX, double spread, double secondHeight) {
  cv::Mat r(24, 32, CV_32F);
  for (int y = 0; y < r.rows; ++y)
    for (int x = 0; x < r.cols; ++x)
      r.at<float>(y, x) =
          static_cast<float>(0.1 + std::exp(-(std::pow(x - firstX, 2) + std::pow(y - 12, 2)) / spread) +
                             secondHeight * std::exp(-(std::pow(x - 22, 2) + std::pow(y - 12, 2)) / 4.0));
  return r;
}

}  // namespace

// Two Gaussian peaks: the lower one's height, above the response's floor, as a share of the higher one's; a
// peak's own shoulder (inside its area) does not count.
TEST(CorrelationFilter, RivalPeakRatioIsTheSecondPeakShare) {
  const cv::Size2d ownArea(4, 4);
  EXPECT_LT(rivalPeakRatio(twoPeaks(8, 4, 0), cv::Point(8, 12), ownArea), 0.02);
  EXPECT_NEAR(rivalPeakRatio(twoPeaks(8, 4, 0.5), cv::Point(8, 12), ownArea), 0.5, 0.02);
  EXPECT_NEAR(rivalPeakRatio(twoPeaks(8, 4, 0.95), cv::Point(8, 12), ownArea), 0.95, 0.02);
  // A peak at the response's edge: its area is clipped, the rival measured as before.
  EXPECT_NEAR(rivalPeakRatio(twoPeaks(0, 4, 0.5), cv::Point(0, 12), ownArea), 0.5, 0.02);
  // An area that takes in the whole response leaves nothing to compare with.
  EXPECT_EQ(rivalPeakRatio(twoPeaks(8, 4, 0.5), cv::Point(8, 12), cv::Size2d(40, 40)), 0.0);
}

// A second object (another local maximum) counts for secondPeakRatio as for rivalPeakRatio; a broad peak's
// own shoulder, past the peak's area but no maximum of its own, counts only for rivalPeakRatio.
TEST(CorrelationFilter, SecondPeakRatioCountsObjectsNotShoulders) {
  const cv::Size2d ownArea(4, 4);
  const cv::Mat broad = twoPeaks(8, 60, 0);
  EXPECT_GT(rivalPeakRatio(broad, cv::Point(8, 12), ownArea), 0.5);
  EXPECT_LT(secondPeakRatio(broad, cv::Point(8, 12), ownArea), 0.05);
  cv::Point second(-1, -1);
  EXPECT_NEAR(secondPeakRatio(twoPeaks(8, 4, 0.75), cv::Point(8, 12), ownArea, &second), 0.75, 0.02);
  EXPECT_EQ(second, cv::Point(22, 12));
  // An area that takes in the whole response leaves no second object, and no place for one.
  second = cv::Point(-1, -1);
  EXPECT_EQ(secondPeakRatio(twoPeaks(8, 4, 0.5), cv::Point(8, 12), cv::Size2d(40, 40), &second), 0.0);
  EXPECT_EQ(second, cv::Point(-1, -1));
}

// The fused detector's shape cue alone (no colour likelihood) on a textured image: a known sub-window shift
// is recovered to under a pixel, a known change of size to within 3 %.
TEST(FusedDetector, RecoversKnownShiftAndScale) {
  const cv::Mat image = texture(cv::Size(320, 240), 7);
  const cv::Rect2d box(130, 90, 60, 50);
  const cv::Point2d centre(box.x + box.width / 2, box.y + box.height / 2);
  const BinMapper colours(ColorSpace::Hsv, BinLayout());
  const ColorLikelihood noColour;
  struct Case {
    double dx, dy, scale;
  };
  for (const Case c : {Case{5.5, -3.25, 1.0}, Case{-7.75, 4.5, 1.0}, Case{0, 0, 1.08}, Case{0, 0, 0.93},
                       Case{3.5, 2.0, 1.05}}) {
    FusedDetector detector;
    detector.start(MatImageSource(image), box);
    const cv::Mat moved = warped(image, centre, c.scale, c.dx, c.dy);
    FusedDetector::Estimate e = detector.locate(MatImageSource(moved), centre, box.size(), colours, noColour);
    // The scale filter measures at most one step of its range per frame; a second frame at the new place
    // refines it, as in tracking.
    e = detector.locate(MatImageSource(moved), e.centre, e.size, colours, noColour);
    const double error = std::hypot(e.centre.x - (centre.x + c.dx), e.centre.y - (centre.y + c.dy));
    const double scale = std::sqrt(e.size.area() / box.area());
    std::printf("shift (%.2f, %.2f) scale %.2f: position error %.2f px, scale %.3f, confidence %.1f\n", c.dx,
                c.dy, c.scale, error, scale, e.confidence);
    EXPECT_LT(error, 1.0);
    EXPECT_NEAR(scale / c.scale, 1.0, 0.03);
    EXPECT_GT(e.confidence, 8.0);
  }
}

TEST(FusedDetector, ConfidenceFallsWhenTheTargetIsGone) {
  const cv::Mat image = texture(cv::Size(320, 240), 7);
  const cv::Rect2d box(130, 90, 60, 50);
  const cv::Point2d centre(box.x + box.width / 2, box.y + box.height / 2);
  FusedDetector detector;
  detector.start(MatImageSource(image), box);
  const BinMapper colours(ColorSpace::Hsv, BinLayout());
  const ColorLikelihood noColour;
  // The target a little moved, resized and darker, with sensor noise: a normal next frame.
  cv::Mat next = warped(image, centre, 1.03, 2.5, -1.5) * 0.9, noise(image.size(), CV_8UC3);
  cv::RNG(11).fill(noise, cv::RNG::UNIFORM, 0, 12);
  next += noise;
  const double seen = detector.locate(MatImageSource(next), centre, box.size(), colours, noColour).confidence;
  const cv::Mat other = texture(cv::Size(320, 240), 99);  // another texture where the target was
  const double gone =
      detector.locate(MatImageSource(other), centre, box.size(), colours, noColour).confidence;
  std::printf("confidence with the target %.1f, without %.1f\n", seen, gone);
  // The tracker stops trusting a frame whose confidence is under half its usual one.
  EXPECT_LT(gone, 0.5 * seen);
}

// The colour cue must put the target where the shape cue does. A red box on grey of the same brightness
// leaves the shape cue nothing to prefer, so the colour cue alone places it. The window's grid is 24 x 24
// cells for 40 x 40, 25 x 24 for 50 x 40 and 24 x 25 for 40 x 50: on an odd side the middle element lies half
// a cell beyond middle * cell, and reading it there put the box 0.45 px off.
TEST(FusedDetector, ColourCueCentresTheTargetOnOddAndEvenGrids) {
  const BinMapper colours(ColorSpace::Hsv, BinLayout());
  for (const cv::Size2d size : {cv::Size2d(40, 40), cv::Size2d(50, 40), cv::Size2d(40, 50)}) {
    cv::Mat image(240, 320, CV_8UC3, cv::Scalar(100, 100, 100));
    const cv::Rect2d box(137, 93, size.width, size.height);
    image(box).setTo(cv::Scalar(44, 60, 200));  // BGR; grey level 100 as the background's
    BinImage bins{cv::Mat(), cv::Point()};
    colours.map(image, bins.bins);
    ColorLikelihood likelihood;
    likelihood.learn(bins, box, cv::Rect(97, 53, 80 + box.width, 80 + box.height), 1.0);
    FusedDetector detector;
    detector.start(MatImageSource(image), box);
    const cv::Point2d centre(box.x + box.width / 2, box.y + box.height / 2);
    const FusedDetector::Estimate e =
        detector.locate(MatImageSource(image), centre, size, colours, likelihood);
    std::printf("%.0f x %.0f: centre off by (%.2f, %.2f) px\n", size.width, size.height,
                e.centre.x - centre.x, e.centre.y - centre.y);
    EXPECT_NEAR(e.centre.x, centre.x, 0.25);
    EXPECT_NEAR(e.centre.y, centre.y, 0.25);
  }
}
