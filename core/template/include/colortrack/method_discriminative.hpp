// SPDX-License-Identifier: LGPL-2.1-or-later
// Method::Discriminative's colour cue, which the fused method also searches with until its filters start.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/color_search.hpp"
#include "colortrack/method_indexing.hpp"
#include "colortrack/reduced_region.hpp"

namespace colortrack {

// The object-versus-surroundings colour likelihood (the template model's): windows scored by their mean
// P(object | colour) with a motion prior, box width and height where the box's mean most exceeds its ring's.
// Until the likelihood has been learnt (a template file has no surroundings: the first detection teaches
// it), the histogram cue searches instead.
class LikelihoodCue : public ColorCue {
 public:
  explicit LikelihoodCue(const MethodContext &context) : context_(context), histogram_(context) {}

  std::optional<Detection> detectIn(const ImageSource &frame, const cv::Rect &region, double scale,
                                    const cv::Point2d *prior) override;
  std::optional<cv::Point> bestCoarseWindow(const BinImage &coarse, cv::Size window) override;
  // Learnt from scratch the first time, then adapted at the settings' model update rate.
  void learn(const ImageSource &frame, const cv::Rect2d &box) override;

 private:
  std::optional<Detection> detectByLikelihood(const ImageSource &frame, const cv::Rect &region, double scale,
                                              const cv::Point2d *prior);
  cv::Point bestWindowPosition(const ReducedRegion &reduced, const cv::Point2d *prior) const;
  cv::Rect2d bestBoxAround(cv::Point2d centre, cv::Size2d sizeL) const;
  void learnLikelihood(const ImageSource &frame, const cv::Rect2d &box, double rate);

  MethodContext context_;
  HistogramCue histogram_;
  RegionReader reader_;
  cv::Mat probability_, integralP_, learnPixels_;  // scratch reused across frames
  BinImage learnBins_;
};

}  // namespace colortrack
