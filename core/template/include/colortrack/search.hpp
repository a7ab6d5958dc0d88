// SPDX-License-Identifier: LGPL-2.1-or-later
// Sweeping a window over a search region: the fast path (cell integral histograms on a coarse grid,
// then running histograms at full resolution) and the brute-force reference.
#pragma once

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/histogram.hpp"

namespace colortrack {

struct SearchParams {
  int coarseStep = 0;  // grid step in pixels; 0 = automatic (about 1/6 of the window's smaller side)
  int candidates = 3;  // best coarse positions refined at full resolution
};

struct SearchResult {
  bool found = false;  // false when the window does not fit in the region
  cv::Rect box;        // best window, frame coordinates
  double score = 0;    // its exact match value
};

// Finds the window of size `window` inside `region` (frame coordinates; the whole window must lie inside
// the region and the bin image) with the highest match value. The returned score is exact (computed on
// the full-resolution bins). Cost: O(region pixels) + O(positions / step^2 * bins) + refinement.
SearchResult searchWindow(const BinImage &bins, const cv::Rect &region, cv::Size window,
                          const Histogram &model, const ChannelWeights &weights,
                          const SearchParams &params = SearchParams());

// Every position, exact match value each: O(positions * window area). The reference for tests.
SearchResult searchWindowBruteForce(const BinImage &bins, const cv::Rect &region, cv::Size window,
                                    const Histogram &model, const ChannelWeights &weights);

}  // namespace colortrack
