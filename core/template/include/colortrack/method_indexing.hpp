// SPDX-License-Identifier: LGPL-2.1-or-later
// Method::Indexing's colour cue, which the discriminative method falls back on until it has learnt its
// likelihood.
#pragma once

#include <optional>

#include "colortrack/color_search.hpp"
#include "colortrack/reduced_region.hpp"

namespace colortrack {

// The paper's modified colour indexing: the template's per-channel histograms against every window by
// weighted histogram intersection, then the scale whose window-versus-ring match is best.
class HistogramCue : public ColorCue {
 public:
  explicit HistogramCue(const MethodContext &context) : context_(context) {}

  std::optional<Detection> detectIn(const ImageSource &frame, const cv::Rect &region, double scale,
                                    const cv::Point2d *prior) override;
  std::optional<cv::Point> bestCoarseWindow(const BinImage &coarse, cv::Size window) override;
  // The template histogram is fixed: nothing to learn.
  void learn(const ImageSource &, const cv::Rect2d &) override {}

 private:
  MethodContext context_;
  RegionReader reader_;
};

}  // namespace colortrack
