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

}  // namespace colortrack
