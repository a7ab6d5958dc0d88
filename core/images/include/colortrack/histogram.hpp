// SPDX-License-Identifier: LGPL-2.1-or-later
// Per-channel normalised histograms and the weighted histogram-intersection match value.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"

namespace colortrack {

// Per-channel weights W_c in [0,1]. Default: H and S fully, V weighted down (lighting robustness).
struct ChannelWeights {
  std::array<double, 3> w{1.0, 1.0, 0.3};
};

// One normalised histogram per channel, concatenated: channel c occupies [layout.offset(c),
// layout.offset(c) + layout.bins[c]). Each channel sums to 1 (all zero when no pixel was counted).
struct Histogram {
  BinLayout layout;
  std::vector<float> values;
  double pixelCount = 0;  // pixels counted (mask applied)

  const float *channel(int c) const { return values.data() + layout.offset(c); }
  bool empty() const { return pixelCount <= 0; }
};

// Histogram of the pixels of `rect` (frame coordinates, clipped to the bin image). A non-empty mask
// (CV_8UC1, same size as `rect`) selects the pixels to count: a PNG alpha channel, for instance.
Histogram histogramOf(const BinImage &bins, const BinLayout &layout, const cv::Rect &rect,
                      const cv::Mat &mask = cv::Mat());

// Raw per-bin counts of `rect` (concatenated channels, layout.total() entries).
void countsOf(const BinImage &bins, const BinLayout &layout, const cv::Rect &rect, std::vector<int> &counts);

// Σ_j min(I_j, T_j) / Σ_j T_j for one channel (0 when T is empty).
double intersection(const float *window, const float *model, int n);

// H(I,M) = Π_c (Σ_j min(I_j,T_j) / Σ_j T_j)^{W_c}, in [0,1].
double matchValue(const Histogram &window, const Histogram &model, const ChannelWeights &weights);

// The same from raw counts of a window of `area` pixels, without building a normalised histogram.
double matchCounts(const int *counts, double area, const Histogram &model, const ChannelWeights &weights);

// Exact match value of one window, counting its pixels directly (O(area)).
double windowMatch(const BinImage &bins, const cv::Rect &window, const Histogram &model,
                   const ChannelWeights &weights);

}  // namespace colortrack
