#include "colortrack/image_source.hpp"

#include <algorithm>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

cv::Size sampledSize(const cv::Rect &rect, int step) {
  return cv::Size(std::max(1, rect.width / step), std::max(1, rect.height / step));
}

}  // namespace

void ImageSource::sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const {
  if (step <= 1) return bgr(rect, out);
  cv::Mat full;
  bgr(rect, full);
  cv::resize(full, out, sampledSize(rect, step), 0, 0, cv::INTER_NEAREST);
}

void MatImageSource::sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const {
  if (step <= 1) return bgr(rect, out);
  cv::resize(bgr_(rect), out, sampledSize(rect, step), 0, 0, cv::INTER_NEAREST);
}

}  // namespace colortrack
