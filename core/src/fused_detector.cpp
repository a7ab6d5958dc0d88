#include "colortrack/fused_detector.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include <opencv2/imgproc.hpp>

#include "colortrack/cell_features.hpp"

namespace colortrack {

namespace {

double tune(const char *name, double fallback) {
  const char *v = std::getenv((std::string("COLORTRACK_TUNE_") + name).c_str());
  return v ? std::atof(v) : fallback;
}

const double kCell = 4;
const double kWindowArea = tune("WINDOW_AREA", 9216);       // normalised search window, px^2 (96 x 96)
const double kPadding = tune("PADDING", 1.5);               // window = target + padding * mean side
const double kLabelSigma = tune("LABEL_SIGMA", 1.0 / 16);   // of the desired response, per target side
const double kLambda = 1e-3;
const double kTranslationRate = tune("CF_RATE", 0.01);
const double kColourWeight = tune("COLOUR_WEIGHT", 0.3);
const int kScales = static_cast<int>(tune("SCALES", 33));
const double kScaleStep = tune("SCALE_STEP", 1.02);
const double kScaleRate = tune("SCALE_RATE", 0.025);
const double kScaleModelArea = tune("SCALE_AREA", 512);
const double kReuseScale = tune("REUSE_SCALE", 1);
const double kCandidateSide = 16;
const double kAspectStep = tune("ASPECT_STEP", 0.0);
const double kAspectRing = tune("ASPECT_RING", 0.15);

}  // namespace

cv::Size2d FusedDetector::windowFor(cv::Size2d size) const {
  return cv::Size2d(size.width * windowRatio_.width, size.height * windowRatio_.height);
}

void FusedDetector::start(const ImageSource &frame, const cv::Rect2d &box) {
  const cv::Size2d size = box.size();
  const double pad = kPadding * (size.width + size.height) / 2;
  const cv::Size2d window(size.width + pad, size.height + pad);
  const double z = std::sqrt(kWindowArea / window.area());
  window_ = cv::Size(std::max(4, cvRound(window.width * z / kCell)) * static_cast<int>(kCell),
                     std::max(4, cvRound(window.height * z / kCell)) * static_cast<int>(kCell));
  windowRatio_ = cv::Size2d(window.width / size.width, window.height / size.height);
  const double targetCells = std::sqrt(size.area()) * z / kCell;
  translation_.init(cv::Size(window_.width / static_cast<int>(kCell), window_.height / static_cast<int>(kCell)),
                    std::max(0.5, kLabelSigma * targetCells), kLambda);

  const double zs = std::min(1.0, std::sqrt(kScaleModelArea / size.area()));
  scaleModel_ = cv::Size(std::max(2, cvRound(size.width * zs / kCell)) * static_cast<int>(kCell),
                         std::max(2, cvRound(size.height * zs / kCell)) * static_cast<int>(kCell));
  scale_.init(kScales, kScaleStep, std::sqrt(static_cast<double>(kScales)) / 4, 1e-2);
  const cv::Point2d centre(box.x + box.width / 2, box.y + box.height / 2);
  windowFeatures(frame, centre, size);
  translation_.train(channels_, 1.0);
  scaleSamples(frame, centre, size);
  scale_.train(scaleSamples_, 1.0);
}

void FusedDetector::windowFeatures(const ImageSource &frame, cv::Point2d centre, cv::Size2d size) {
  const cv::Size2d window = windowFor(size);
  const cv::Rect2d rect(centre.x - window.width / 2, centre.y - window.height / 2, window.width, window.height);
  sampler_.load(frame, rect, PatchSampler::stepFor(window, window_));
  sampler_.extract(rect, window_, patch_);
  cv::cvtColor(patch_, gray_, cv::COLOR_BGR2GRAY);
  gray_.convertTo(gray_, CV_32F, 1.0 / 255);
  cellFeatures(gray_, static_cast<int>(kCell), channels_);
}

void FusedDetector::scaleSamples(const ImageSource &frame, cv::Point2d centre, cv::Size2d size) {
  const std::vector<double> &factors = scale_.factors();
  const cv::Size2d largest = size * factors.back();
  sampler_.load(frame,
                cv::Rect2d(centre.x - largest.width / 2, centre.y - largest.height / 2, largest.width,
                           largest.height),
                PatchSampler::stepFor(size * factors.front(), scaleModel_));
  sampler_.toGray();
  cv::Mat gray;
  std::vector<cv::Mat> channels;
  for (size_t i = 0; i < factors.size(); ++i) {
    const cv::Size2d s = size * factors[i];
    sampler_.extract(cv::Rect2d(centre.x - s.width / 2, centre.y - s.height / 2, s.width, s.height), scaleModel_,
                     gray);
    cellFeatures(gray, static_cast<int>(kCell), channels);
    const int perChannel = channels[0].rows * channels[0].cols;
    if (i == 0) scaleSamples_.create(static_cast<int>(factors.size()), perChannel * kCellChannels, CV_32F);
    float *row = scaleSamples_.ptr<float>(static_cast<int>(i));
    for (int c = 0; c < kCellChannels; ++c) {
      const cv::Mat flat = channels[c].reshape(1, 1);
      std::copy(flat.ptr<float>(), flat.ptr<float>() + perChannel, row + c * perChannel);
    }
  }
}

void FusedDetector::colourResponse(const BinMapper &colors, const ColorLikelihood &likelihood,
                                   cv::Size2d targetNormalised, cv::Mat &response) {
  const cv::Size cells = translation_.cells();
  response = cv::Mat::zeros(cells, CV_32F);
  colors.map(patch_, bins_);
  BinImage image{bins_, cv::Point()};
  likelihood.map(image, probability_);
  cv::integral(probability_, integral_, CV_64F);
  const cv::Rect limits(cv::Point(), probability_.size());
  const double area = std::max(1.0, targetNormalised.area());
  // Response element (x, y) stands for the target centred at pixel (x * cell, y * cell) of the window (the
  // correlation response's convention: the middle element is the window's centre).
  for (int y = 0; y < cells.height; ++y)
    for (int x = 0; x < cells.width; ++x) {
      const cv::Rect box(cvRound(x * kCell - targetNormalised.width / 2),
                         cvRound(y * kCell - targetNormalised.height / 2), cvRound(targetNormalised.width),
                         cvRound(targetNormalised.height));
      response.at<float>(y, x) = static_cast<float>(boxSum(integral_, box & limits) / area);
    }
}

cv::Size2d FusedDetector::refineAspect(cv::Point2d centre, cv::Size2d size) const {
  const cv::Rect limits(cv::Point(), probability_.size());
  cv::Size2d best = size;
  double bestContrast = -1e18;
  for (int i = -1; i <= 1; ++i)
    for (int j = -1; j <= 1; ++j) {
      if (i == j && i != 0) continue;  // uniform changes are the scale filter's
      const cv::Size2d s(size.width * (1 + i * kAspectStep), size.height * (1 + j * kAspectStep));
      const cv::Rect box(cvRound(centre.x - s.width / 2), cvRound(centre.y - s.height / 2), cvRound(s.width),
                         cvRound(s.height));
      const int ring = std::max(1, cvRound(kAspectRing * std::min(s.width, s.height)));
      const cv::Rect inner = box & limits;
      const cv::Rect outer = cv::Rect(box.x - ring, box.y - ring, box.width + 2 * ring, box.height + 2 * ring) & limits;
      if (inner.area() <= 0 || outer.area() <= inner.area()) continue;
      const double inside = boxSum(integral_, inner);
      const double ringMean = (boxSum(integral_, outer) - inside) / (outer.area() - inner.area());
      const double contrast = inside / inner.area() - ringMean - 1e-6 * (std::abs(i) + std::abs(j));
      if (contrast > bestContrast) bestContrast = contrast, best = s;
    }
  return best;
}

FusedDetector::Estimate FusedDetector::locate(const ImageSource &frame, cv::Point2d centre, cv::Size2d size,
                                              const BinMapper &colors, const ColorLikelihood &likelihood,
                                              bool withScale) {
  windowFeatures(frame, centre, size);
  cv::Mat response;
  translation_.respond(channels_, response);
  const cv::Size2d window = windowFor(size);
  const double z = window_.width / window.width;  // normalised px per frame px
  cv::Mat shape = response.clone(), colour;
  if (!likelihood.empty() && kColourWeight > 0) {
    colourResponse(colors, likelihood, size * z, colour);
    cv::addWeighted(response, 1 - kColourWeight, colour, kColourWeight, 0, response);
  }
  cv::Point peak;
  cv::minMaxLoc(response, nullptr, nullptr, nullptr, &peak);
  const cv::Point2d at = subCellPeak(response, peak);
  Estimate e;
  e.centre = cv::Point2d(centre.x + (at.x - response.cols / 2) * kCell / z,
                         centre.y + (at.y - response.rows / 2) * kCell / z);
  e.size = size;
  e.shapePeak = shape.at<float>(peak);
  e.colourPeak = colour.empty() ? 0 : colour.at<float>(peak);
  e.confidence = peakToSidelobe(response, peak, std::max(1, cvRound(0.2 * std::min(response.cols, response.rows))));
  if (withScale) {
    scaleSamples(frame, e.centre, size);
    e.size = size * scale_.estimate(scaleSamples_);
    if (kAspectStep > 0 && !likelihood.empty() && kColourWeight > 0) {
      const cv::Point2d inWindow((at.x * kCell), (at.y * kCell));
      e.size = refineAspect(inWindow, e.size * z) * (1 / z);
    }
  }
  return e;
}

void FusedDetector::learn(const ImageSource &frame, cv::Point2d centre, cv::Size2d size) {
  windowFeatures(frame, centre, size);
  translation_.train(channels_, kTranslationRate);
  if (kReuseScale <= 0 || scaleSamples_.empty()) scaleSamples(frame, centre, size);
  scale_.train(scaleSamples_, kScaleRate);
}

std::vector<cv::Point2d> FusedDetector::colourCandidates(const ImageSource &frame, cv::Size2d size,
                                                         const BinMapper &colors,
                                                         const ColorLikelihood &likelihood, int count) {
  std::vector<cv::Point2d> out;
  if (likelihood.empty()) return out;
  const cv::Size frameSize = frame.size();
  const int f = std::max(1, static_cast<int>(std::min(size.width, size.height) / kCandidateSide));
  frame.sampledBgr(cv::Rect(cv::Point(), frameSize), f, reduced_);
  colors.map(reduced_, bins_);
  likelihood.map(BinImage{bins_, cv::Point()}, probability_);
  const cv::Size window(std::max(1, cvRound(size.width / f)), std::max(1, cvRound(size.height / f)));
  cv::Mat mean;
  cv::boxFilter(probability_, mean, CV_32F, window, cv::Point(-1, -1), true, cv::BORDER_CONSTANT);
  for (int i = 0; i < count; ++i) {
    double best;
    cv::Point at;
    cv::minMaxLoc(mean, nullptr, &best, nullptr, &at);
    if (best <= 0) break;
    out.emplace_back((at.x + 0.5) * f, (at.y + 0.5) * f);
    // Suppress the neighbourhood so the next candidate is another place.
    cv::rectangle(mean, cv::Rect(at.x - window.width, at.y - window.height, 2 * window.width + 1,
                                 2 * window.height + 1),
                  cv::Scalar(0), cv::FILLED);
  }
  return out;
}

}  // namespace colortrack
