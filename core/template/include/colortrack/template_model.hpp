// SPDX-License-Identifier: LGPL-2.1-or-later
// What the template tracker knows about the target's looks: the template image, its colour histogram, its
// edges, and the object-versus-surroundings colour likelihood the colour-learning methods share.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/edges.hpp"
#include "colortrack/histogram.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/likelihood.hpp"
#include "colortrack/tracker_settings.hpp"

namespace colortrack {

class TemplateModel {
 public:
  // A new template (checked by the caller); the likelihood starts unlearnt.
  void setTemplate(const cv::Mat &bgr, const cv::Mat &mask, const TrackerSettings &settings);
  // Follows the settings' colour model: a new colour space or bin layout rebuilds the bin mapper and forgets
  // the likelihood (it was learnt in the old bins), and the histogram is computed again.
  void rebuild(const TrackerSettings &settings);

  bool hasTemplate() const { return !templateBgr_.empty(); }
  cv::Size templateSize() const { return templateBgr_.size(); }
  const BinMapper &mapper() const { return *mapper_; }
  const Histogram &histogram() const { return histogram_; }
  // Shared, not owned by one method: it survives a change of method, as a template does.
  ColorLikelihood &likelihood() { return likelihood_; }
  const ColorLikelihood &likelihood() const { return likelihood_; }

  // The paper's match value (weighted histogram intersection) of `box` (clipped to the frame) against the
  // template's histogram, which is never updated: how much the box still looks like the start.
  double matchStart(const ImageSource &frame, const cv::Rect &box, const TrackerSettings &settings);

  // The edge check of `box` against the template's edges (true when the settings verify nothing).
  bool verify(const ImageSource &frame, const cv::Rect &box, const TrackerSettings &settings);

 private:
  cv::Mat templateBgr_, templateMask_;
  std::optional<BinMapper> mapper_;
  Histogram histogram_;
  EdgeVerifier verifier_;
  ColorLikelihood likelihood_;

  cv::Mat bgr_, gray_;  // scratch reused across frames
  BinImage boxBins_;
};

}  // namespace colortrack
