// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/scale.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "colortrack/box.hpp"

namespace colortrack {

namespace {

// How much of the model's colour mass the ring holds: the weighted mean of the per-channel intersections.
// A mean, not the product used for windows: the product of small fractions is vanishingly small, which
// would make a ring that still holds some of the object look empty and let the box shrink.
double ringIntersection(const std::vector<int> &counts, double area, const Histogram &model,
                        const ChannelWeights &weights) {
  if (area <= 0) return 0;
  double weighted = 0, weightSum = 0;
  std::vector<float> normalised;
  for (int c = 0; c < 3; ++c) {
    if (weights.w[c] <= 0) continue;
    const int n = model.layout.bins[c];
    const int *channelCounts = counts.data() + model.layout.offset(c);
    normalised.assign(n, 0.f);
    for (int j = 0; j < n; ++j) normalised[j] = static_cast<float>(channelCounts[j] / area);
    weighted += weights.w[c] * intersection(normalised.data(), model.channel(c), n);
    weightSum += weights.w[c];
  }
  return weightSum > 0 ? weighted / weightSum : 0;
}

}  // namespace

ScaleResult refineScale(const BinImage &bins, const cv::Rect2d &box, const Histogram &model,
                        const ChannelWeights &weights, const ScaleParams &params) {
  ScaleResult best;
  best.box = box;
  best.factor = 1.0;
  best.criterion = -1e9;
  const cv::Rect limits = bins.frameRect();
  const cv::Point2d centre = boxCentre(box);
  const double step = params.step > 0 ? params.step : 1.0;

  // Factor 1 first, so that ties keep the current size instead of drifting.
  std::vector<double> factors{1.0};
  for (double f = params.minFactor; f <= params.maxFactor + 1e-9; f += step)
    if (std::abs(f - 1.0) > 1e-9) factors.push_back(f);

  std::vector<int> inner, outer;
  for (double f : factors) {
    const double w = box.width * f, h = box.height * f;
    const cv::Rect window(cvRound(centre.x - w / 2), cvRound(centre.y - h / 2), std::max(1, cvRound(w)),
                          std::max(1, cvRound(h)));
    if ((window & limits) != window) continue;
    const int ring = std::max(1, cvRound(params.ringWidth * std::min(w, h)));
    const cv::Rect outerRect =
        cv::Rect(window.x - ring, window.y - ring, window.width + 2 * ring, window.height + 2 * ring) &
        limits;
    countsOf(bins, model.layout, window, inner);
    countsOf(bins, model.layout, outerRect, outer);
    const double windowArea = window.area();
    const double ringArea = outerRect.area() - windowArea;
    const double match = matchCounts(inner.data(), windowArea, model, weights);
    for (size_t i = 0; i < outer.size(); ++i) outer[i] -= inner[i];
    const double criterion = match - ringIntersection(outer, ringArea, model, weights);
    if (criterion > best.criterion + 1e-9) {
      best.criterion = criterion;
      best.match = match;
      best.factor = f;
      best.box = cv::Rect2d(centre.x - w / 2, centre.y - h / 2, w, h);
    }
  }
  return best;
}

}  // namespace colortrack
