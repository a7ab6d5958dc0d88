#include "colortrack/image_source.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace colortrack {

cv::Size sampledSize(const cv::Rect &rect, int step) {
  return cv::Size(std::max(1, rect.width / step), std::max(1, rect.height / step));
}

cv::Rect sampledCover(const cv::Rect &rect, int step) {
  const cv::Size size = sampledSize(rect, step);
  return cv::Rect(rect.x, rect.y, std::min(rect.width, size.width * step),
                  std::min(rect.height, size.height * step));
}

void ImageSource::sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const {
  if (step <= 1) return bgr(rect, out);
  cv::Mat full;
  bgr(sampledCover(rect, step), full);
  cv::resize(full, out, sampledSize(rect, step), 0, 0, cv::INTER_NEAREST);
}

void MatImageSource::sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const {
  if (step <= 1) return bgr(rect, out);
  cv::resize(bgr_(sampledCover(rect, step)), out, sampledSize(rect, step), 0, 0, cv::INTER_NEAREST);
}

void PatchSampler::load(const ImageSource &frame, const cv::Rect2d &region, int step) {
  const cv::Rect frameRect(cv::Point(), frame.size());
  const cv::Rect wanted(cvFloor(region.x), cvFloor(region.y),
                        cvCeil(region.x + region.width) - cvFloor(region.x) + 1,
                        cvCeil(region.y + region.height) - cvFloor(region.y) + 1);
  cv::Rect inside = wanted & frameRect;
  if (inside.empty()) {
    // Wholly outside: the nearest border pixel stands for everything.
    const int x = std::clamp(wanted.x, 0, frameRect.width - 1),
              y = std::clamp(wanted.y, 0, frameRect.height - 1);
    inside = cv::Rect(x, y, 1, 1);
  }
  step_ = std::max(1, step);
  frame.sampledBgr(inside, step_, pixels_);
  origin_ = inside.tl();
}

void PatchSampler::toGray() {
  cv::Mat gray;
  cv::cvtColor(pixels_, gray, cv::COLOR_BGR2GRAY);
  gray.convertTo(pixels_, CV_32F, 1.0 / 255);
}

void PatchSampler::extract(const cv::Rect2d &rect, cv::Size size, cv::Mat &out) const {
  // Output pixel i has its centre at frame x = rect.x + (i + 0.5) * rect.width / size.width - 0.5 (pixel
  // centres at whole coordinates), which is sample (x - origin.x) / step.
  const double sx = rect.width / size.width, sy = rect.height / size.height;
  const cv::Matx23d toSample(sx / step_, 0, (rect.x + 0.5 * sx - 0.5 - origin_.x) / step_, 0, sy / step_,
                             (rect.y + 0.5 * sy - 0.5 - origin_.y) / step_);
  cv::warpAffine(pixels_, out, toSample, size, cv::INTER_LINEAR | cv::WARP_INVERSE_MAP, cv::BORDER_REPLICATE);
}

int PatchSampler::stepFor(const cv::Size2d &rect, cv::Size size) {
  return std::max(1, static_cast<int>(std::min(rect.width / size.width, rect.height / size.height)));
}

}  // namespace colortrack
