// SPDX-License-Identifier: LGPL-2.1-or-later
// Method::Discriminative: the colour search with the learnt colour likelihood as its cue.
#include "colortrack/method_discriminative.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "colortrack/box.hpp"
#include "colortrack/histogram.hpp"
#include "colortrack/likelihood.hpp"

namespace colortrack {

namespace {

// The motion prior's standard deviation in box sizes (sqrt of the box area), and the width of the
// surroundings the likelihood is learnt against, in box sizes per side.
constexpr double kMotionPriorSigma = 1.0;
constexpr double kSurroundings = 0.5;
// Sizing: the ring the box's mean likelihood is compared with, as a fraction of the box's smaller side.
// Narrower than the indexing ring: the likelihood map is sharper than a window's histogram, and a wide ring
// reaches neighbouring object-coloured clutter. 0.1-0.2 all give mean AUC 0.55-0.57 on the shared sequences,
// 0.25 gives 0.52, 0.5 gives 0.33 (docs/benchmarks-history.md).
constexpr double kLikelihoodRing = 0.15;

cv::Size wholeWindow(cv::Size2d size) {
  return cv::Size(std::max(1, cvRound(size.width)), std::max(1, cvRound(size.height)));
}

}  // namespace

std::optional<Detection> LikelihoodCue::detectIn(const ImageSource &frame, const cv::Rect &region,
                                                 double scale, const cv::Point2d *prior) {
  if (context_.model.likelihood().empty()) return histogram_.detectIn(frame, region, scale, prior);
  return detectByLikelihood(frame, region, scale, prior);
}

std::optional<cv::Point> LikelihoodCue::bestCoarseWindow(const BinImage &coarse, cv::Size window) {
  const ColorLikelihood &likelihood = context_.model.likelihood();
  if (likelihood.empty()) return histogram_.bestCoarseWindow(coarse, window);
  likelihood.map(coarse, probability_);
  cv::Mat meanP;  // mean likelihood of the window centred at each pixel
  cv::boxFilter(probability_, meanP, CV_32F, window, cv::Point(-1, -1), true, cv::BORDER_CONSTANT);
  const int x0 = window.width / 2, y0 = window.height / 2;
  const cv::Rect valid(x0, y0, coarse.bins.cols - window.width + 1, coarse.bins.rows - window.height + 1);
  if (valid.width <= 0 || valid.height <= 0) return std::nullopt;
  cv::Point at;
  cv::minMaxLoc(meanP(valid), nullptr, nullptr, nullptr, &at);
  return at;
}

// Every window of the current size scored by its mean P(object | colour), weighted by a Gaussian motion
// prior around `prior` (none while searching the whole frame); then the width and height of the box.
std::optional<Detection> LikelihoodCue::detectByLikelihood(const ImageSource &frame, const cv::Rect &region,
                                                           double scale, const cv::Point2d *prior) {
  const TrackerSettings &s = context_.settings;
  const cv::Size2d size = context_.track.windowSize(scale);
  const int pad = cvRound(std::max(size.width, size.height) * std::max(0.0, s.scale.maxFactor - 1.0)) + 2;
  const auto reduced = reader_.read(frame, region, size, pad, context_.model.mapper());
  if (!reduced) return std::nullopt;
  const BinImage &bins = reader_.bins();
  const ColorLikelihood &likelihood = context_.model.likelihood();
  likelihood.map(bins, probability_);
  cv::integral(probability_, integralP_, CV_64F);
  const cv::Point best = bestWindowPosition(*reduced, prior);
  const cv::Size window = wholeWindow(reduced->sizeL);
  const cv::Rect2d boxL =
      bestBoxAround(cv::Point2d(best.x + window.width / 2.0, best.y + window.height / 2.0), reduced->sizeL);
  const cv::Rect r = roundRect(boxL) & cv::Rect(cv::Point(), probability_.size());
  if (likelihood.confidence(bins, r) < s.likelihoodThreshold) return std::nullopt;
  Detection d;
  d.box = reduced->toFull(boxL);
  // The score reported is the paper's match value against the template, so that it means the same in both
  // methods; acceptance here is the likelihood's (the template was one frame's look, the likelihood follows
  // the object as it changes).
  d.score = windowMatch(bins, r, context_.model.histogram(), s.weights);
  d.verified = context_.model.verify(frame, roundRect(d.box), s);
  return d;
}

// The top-left corner of the window with the best prior-weighted mean likelihood (integralP_, local
// coordinates): a coarse grid, then every pixel around its best.
cv::Point LikelihoodCue::bestWindowPosition(const ReducedRegion &reduced, const cv::Point2d *prior) const {
  const cv::Size2d sizeL = reduced.sizeL;
  const cv::Size window = wholeWindow(sizeL);
  const cv::Rect searchL = reduced.searchL;
  const std::optional<cv::Point2d> priorL =
      prior ? std::optional<cv::Point2d>(reduced.toLocal(prior->x, prior->y)) : std::nullopt;
  const double sigma = kMotionPriorSigma * std::sqrt(sizeL.width * sizeL.height);
  auto windowScore = [&](int x, int y) {
    const double mean = boxSum(integralP_, cv::Rect(x, y, window.width, window.height)) / window.area();
    if (!priorL) return mean;
    const double dx = x + window.width / 2.0 - priorL->x, dy = y + window.height / 2.0 - priorL->y;
    return mean * std::exp(-(dx * dx + dy * dy) / (2 * sigma * sigma));
  };
  const int step = std::max(1, std::min(window.width, window.height) / 12);
  const int maxX = searchL.br().x - window.width, maxY = searchL.br().y - window.height;
  cv::Point best = searchL.tl();
  double bestScore = -1;
  for (int y = searchL.y; y <= maxY; y += step)
    for (int x = searchL.x; x <= maxX; x += step)
      if (const double v = windowScore(x, y); v > bestScore) bestScore = v, best = cv::Point(x, y);
  const cv::Point coarse = best;
  for (int y = std::max(searchL.y, coarse.y - step); y <= std::min(maxY, coarse.y + step); ++y)
    for (int x = std::max(searchL.x, coarse.x - step); x <= std::min(maxX, coarse.x + step); ++x)
      if (const double v = windowScore(x, y); v > bestScore) bestScore = v, best = cv::Point(x, y);
  return best;
}

// Size: the box (local coordinates) whose mean likelihood most exceeds that of the ring around it, i.e. the
// box that sits on the border between object-like and background-like pixels. (A fixed level such as
// sum(P - 1/2) shrinks the box onto the most object-like part whenever the object holds colours the
// background shares.)
cv::Rect2d LikelihoodCue::bestBoxAround(cv::Point2d centre, cv::Size2d sizeL) const {
  const ScaleParams &scale = context_.settings.scale;
  const cv::Rect limits(cv::Point(), probability_.size());
  cv::Rect2d boxL = centredBox(centre.x, centre.y, sizeL);
  double bestMass = -1e18;
  const double stepFactor = scale.step > 0 ? scale.step : 1.0;
  for (double fw = scale.minFactor; fw <= scale.maxFactor + 1e-9; fw += stepFactor)
    for (double fh = scale.minFactor; fh <= scale.maxFactor + 1e-9; fh += stepFactor) {
      if (!context_.settings.adaptAspect && std::abs(fw - fh) > 1e-9) continue;
      const cv::Rect2d box = centredBox(centre.x, centre.y, cv::Size2d(sizeL.width * fw, sizeL.height * fh));
      const cv::Rect r = roundRect(box);
      if ((r & limits) != r) continue;
      const int ring = std::max(1, cvRound(kLikelihoodRing * std::min(box.width, box.height)));
      const cv::Rect outer =
          cv::Rect(r.x - ring, r.y - ring, r.width + 2 * ring, r.height + 2 * ring) & limits;
      const double inside = boxSum(integralP_, r);
      const double ringArea = outer.area() - r.area();
      const double ringMean = ringArea > 0 ? (boxSum(integralP_, outer) - inside) / ringArea : 0;
      // Prefer the current size on ties, so noise does not make the box wander.
      const double mass = inside / r.area() - ringMean - 1e-6 * (std::abs(fw - 1) + std::abs(fh - 1));
      if (mass > bestMass) bestMass = mass, boxL = box;
    }
  return boxL;
}

void LikelihoodCue::learn(const ImageSource &frame, const cv::Rect2d &box) {
  if (context_.model.likelihood().empty())
    learnLikelihood(frame, box, 1.0);
  else if (context_.settings.modelUpdateRate > 0)
    learnLikelihood(frame, box, context_.settings.modelUpdateRate);
}

// Learns the likelihood from `box` and the ring around it (rate 1 replaces the model).
void LikelihoodCue::learnLikelihood(const ImageSource &frame, const cv::Rect2d &box, double rate) {
  const cv::Rect frameRect(cv::Point(), frame.size());
  const double grow = kSurroundings * std::max(box.width, box.height);
  const cv::Rect object = roundRect(box) & frameRect;
  const cv::Rect around =
      roundRect(cv::Rect2d(box.x - grow, box.y - grow, box.width + 2 * grow, box.height + 2 * grow)) &
      frameRect;
  if (object.empty()) return;
  // A sample of the pixels, as in the search: learning every pixel of a large box and its surroundings
  // would cost more than the search itself.
  const int f = std::max(1, static_cast<int>(std::min(box.width, box.height) / kReducedWindowSide));
  frame.sampledBgr(around, f, learnPixels_);
  context_.model.mapper().map(learnPixels_, learnBins_.bins);
  learnBins_.origin = cv::Point();
  const cv::Rect objectL(cvRound(double(object.x - around.x) / f), cvRound(double(object.y - around.y) / f),
                         std::max(1, object.width / f), std::max(1, object.height / f));
  context_.model.likelihood().learn(learnBins_, objectL, cv::Rect(cv::Point(), learnBins_.bins.size()), rate);
}

std::unique_ptr<DetectionMethod> makeDiscriminativeMethod(const MethodContext &context) {
  return std::make_unique<ColorSearchMethod<LikelihoodCue>>(context);
}

}  // namespace colortrack
