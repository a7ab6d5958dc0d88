// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/histogram.hpp"

#include <algorithm>
#include <cmath>

namespace colortrack {

namespace {

// `rect` (frame coordinates) clipped to the bin image, in bin-image coordinates.
cv::Rect clipToBins(const BinImage &bins, const cv::Rect &rect) {
  const cv::Rect clipped = rect & bins.frameRect();
  if (clipped.empty()) return cv::Rect();
  return clipped - bins.origin;
}

// Adds the pixels of `local` (bin-image coordinates, already clipped) selected by `mask` (may be empty;
// otherwise indexed from `maskOrigin`) to `counts`; returns how many were counted.
int accumulate(const BinImage &bins, const BinLayout &layout, const cv::Rect &local, const cv::Mat &mask,
               cv::Point maskOrigin, std::vector<int> &counts) {
  const int off1 = layout.offset(1), off2 = layout.offset(2);
  int counted = 0;
  for (int y = local.y; y < local.br().y; ++y) {
    const auto *px = bins.bins.ptr<cv::Vec3b>(y);
    const std::uint8_t *m = mask.empty() ? nullptr : mask.ptr<std::uint8_t>(y - local.y + maskOrigin.y);
    for (int x = local.x; x < local.br().x; ++x) {
      if (m && !m[x - local.x + maskOrigin.x]) continue;
      const cv::Vec3b &p = px[x];
      ++counts[p[0]];
      ++counts[off1 + p[1]];
      ++counts[off2 + p[2]];
      ++counted;
    }
  }
  return counted;
}

}  // namespace

void countsOf(const BinImage &bins, const BinLayout &layout, const cv::Rect &rect, std::vector<int> &counts) {
  counts.assign(layout.total(), 0);
  const cv::Rect local = clipToBins(bins, rect);
  if (local.empty()) return;
  accumulate(bins, layout, local, cv::Mat(), cv::Point(), counts);
}

Histogram histogramOf(const BinImage &bins, const BinLayout &layout, const cv::Rect &rect,
                      const cv::Mat &mask) {
  CV_Assert(bins.bins.empty() || bins.bins.type() == CV_8UC3);
  CV_Assert(mask.empty() || (mask.type() == CV_8UC1 && mask.size() == rect.size()));
  Histogram hist;
  hist.layout = layout;
  hist.values.assign(layout.total(), 0.0f);
  const cv::Rect local = clipToBins(bins, rect);
  if (local.empty()) return hist;

  std::vector<int> counts(layout.total(), 0);
  // The mask covers the unclipped rect: skip the part of it that fell outside the bin image.
  const cv::Point maskOrigin = (local + bins.origin).tl() - rect.tl();
  const int counted = accumulate(bins, layout, local, mask, maskOrigin, counts);
  hist.pixelCount = counted;
  if (counted == 0) return hist;
  // Every counted pixel adds one to each channel, so each channel sums to `counted`.
  for (int i = 0; i < layout.total(); ++i) hist.values[i] = static_cast<float>(counts[i] / double(counted));
  return hist;
}

double intersection(const float *window, const float *model, int n) {
  double common = 0, modelSum = 0;
  for (int j = 0; j < n; ++j) {
    common += std::min(window[j], model[j]);
    modelSum += model[j];
  }
  return modelSum > 0 ? common / modelSum : 0.0;
}

double matchValue(const Histogram &window, const Histogram &model, const ChannelWeights &weights) {
  CV_Assert(window.layout == model.layout);
  double value = 1.0;
  for (int c = 0; c < 3; ++c) {
    if (weights.w[c] == 0) continue;  // x^0 = 1, even for an empty channel
    value *= std::pow(intersection(window.channel(c), model.channel(c), model.layout.bins[c]), weights.w[c]);
  }
  return value;
}

double matchCounts(const int *counts, double area, const Histogram &model, const ChannelWeights &weights) {
  // This is the one place where match values of counts are computed: the fast search and the brute
  // force both come here, so their scores are bit-identical and ties compare exactly.
  double value = 1.0;
  for (int c = 0; c < 3; ++c) {
    const double weight = weights.w[c];
    if (weight == 0) continue;
    if (area <= 0) return 0.0;
    const int n = model.layout.bins[c];
    const int *windowCounts = counts + model.layout.offset(c);
    const float *modelValues = model.channel(c);
    // Σ min(I_j / area, T_j) computed as Σ min(count_j, T_j * area) / area: one division per channel.
    // Four partial sums break the addition dependency chain (this runs for every searched position).
    constexpr int kLanes = 4;
    double common[kLanes] = {}, modelSum[kLanes] = {};
    int j = 0;
    for (; j + kLanes <= n; j += kLanes)
      for (int k = 0; k < kLanes; ++k) {
        common[k] += std::min(static_cast<double>(windowCounts[j + k]), modelValues[j + k] * area);
        modelSum[k] += modelValues[j + k];
      }
    for (; j < n; ++j) {
      common[0] += std::min(static_cast<double>(windowCounts[j]), modelValues[j] * area);
      modelSum[0] += modelValues[j];
    }
    const double commonTotal = (common[0] + common[1]) + (common[2] + common[3]);
    const double modelTotal = (modelSum[0] + modelSum[1]) + (modelSum[2] + modelSum[3]);
    const double channelValue = modelTotal > 0 ? commonTotal / (area * modelTotal) : 0.0;
    value *= weight == 1 ? channelValue : std::pow(channelValue, weight);  // pow(x, 1) == x: skip the call
  }
  return value;
}

double windowMatch(const BinImage &bins, const cv::Rect &window, const Histogram &model,
                   const ChannelWeights &weights) {
  std::vector<int> counts;
  countsOf(bins, model.layout, window, counts);
  const cv::Rect clipped = window & bins.frameRect();
  return matchCounts(counts.data(), clipped.area(), model, weights);
}

}  // namespace colortrack
