// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/template_model.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

// Fill the pixels outside the mask with the mean of those inside, so that the edge check sees the object's
// own edges and not the arbitrary colour of a transparent background.
cv::Mat flattenOutsideMask(const cv::Mat &gray, const cv::Mat &mask) {
  if (mask.empty()) return gray;
  cv::Mat out = gray.clone();
  const cv::Scalar inside = cv::mean(gray, mask);
  cv::Mat outside;
  cv::bitwise_not(mask, outside);
  out.setTo(inside, outside);
  return out;
}

}  // namespace

void TemplateModel::setTemplate(const cv::Mat &bgr, const cv::Mat &mask, const TrackerSettings &settings) {
  templateBgr_ = bgr.clone();
  templateMask_ = mask.empty() ? cv::Mat() : mask.clone();
  likelihood_ = ColorLikelihood(settings.bins);
  rebuild(settings);
}

void TemplateModel::rebuild(const TrackerSettings &settings) {
  if (!mapper_ || mapper_->space() != settings.colorSpace || !(mapper_->layout() == settings.bins)) {
    mapper_.emplace(settings.colorSpace, settings.bins);
    likelihood_ = ColorLikelihood(settings.bins);
  }
  if (!hasTemplate()) return;
  BinImage templateBins;
  mapper_->map(templateBgr_, templateBins.bins);
  histogram_ =
      histogramOf(templateBins, settings.bins, cv::Rect(cv::Point(), templateBgr_.size()), templateMask_);
  cv::Mat templateGray;
  cv::cvtColor(templateBgr_, templateGray, cv::COLOR_BGR2GRAY);
  verifier_.setTemplate(flattenOutsideMask(templateGray, templateMask_));
}

double TemplateModel::matchStart(const ImageSource &frame, const cv::Rect &box,
                                 const TrackerSettings &settings) {
  const cv::Rect inside = box & cv::Rect(cv::Point(), frame.size());
  if (inside.area() <= 0 || histogram_.empty()) return 0;
  // A sample of about kMatchPixels pixels is enough for a histogram, and keeps a large box cheap.
  constexpr double kMatchPixels = 4096;
  const int step = std::max(1, static_cast<int>(std::sqrt(inside.area() / kMatchPixels)));
  frame.sampledBgr(inside, step, bgr_);
  mapper_->map(bgr_, boxBins_.bins);
  return windowMatch(boxBins_, cv::Rect(cv::Point(), bgr_.size()), histogram_, settings.weights);
}

bool TemplateModel::verify(const ImageSource &frame, const cv::Rect &box, const TrackerSettings &settings) {
  if (settings.verify == VerifyMode::None) return true;
  const cv::Rect inside = box & cv::Rect(cv::Point(), frame.size());
  if (inside.area() <= 0) return false;
  frame.bgr(inside, bgr_);
  cv::cvtColor(bgr_, gray_, cv::COLOR_BGR2GRAY);
  if (!templateMask_.empty()) {
    cv::Mat mask;
    cv::resize(templateMask_, mask, gray_.size(), 0, 0, cv::INTER_NEAREST);
    gray_ = flattenOutsideMask(gray_, mask);
  }
  return verifier_.verify(verifier_.signature(gray_), settings.verify, settings.verifyTolerance);
}

}  // namespace colortrack
