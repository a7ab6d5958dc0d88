#include "colortrack/global_motion.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

// The small copy is about this wide (an even step: 160 px at 640x480, 213 at 1280x720): enough texture to
// agree on a shift within 2 px on the synthetic scene's smooth background (160 px at 1280x720: up to 4 px).
constexpr double kSmallWidth = 200;
// Only detail finer than this (small-copy px) is correlated: a smooth background's large light and dark
// areas, times the window, make a pattern that stays put whatever the camera does.
constexpr double kDetailSigma = 1.0;
// The excluded box fades out over this many small-copy px (a hard edge would be a still pattern too).
constexpr double kExcludeFade = 2.0;
// A peak response under this is noise: a frame that changed wholly, or whose parts disagree.
constexpr double kMinResponse = 0.1;
// Mean absolute detail (grey levels) under this: no texture to correlate (a flat frame, fog, night).
constexpr double kMinDetail = 0.5;

}  // namespace

GlobalMotion::Shift GlobalMotion::measure(const ImageSource &frame, const cv::Rect2d &exclude) {
  if (frame.size() != frameSize_) previous_.release();
  frameSize_ = frame.size();
  smallCopy(frame);
  Shift out;
  const bool textured = cv::mean(cv::abs(current_))[0] >= kMinDetail;
  if (!previous_.empty() && textured && current_.cols >= 8 && current_.rows >= 8) {
    weights(exclude);
    const cv::Point2d s = cv::phaseCorrelate(previous_, current_, weights_, &out.response);
    out.offset = s * scale_;
    out.valid = std::isfinite(out.response) && out.response >= kMinResponse;
  }
  std::swap(previous_, current_);
  return out;
}

// current_: the frame's detail, grey, on a copy about kSmallWidth px wide.
void GlobalMotion::smallCopy(const ImageSource &frame) {
  const cv::Size size = frame.size();
  // Read at half the final step and average pairs: nearest-neighbour samples alone alias fine texture, which
  // then moves differently from the scene. An even step keeps the averaging a whole factor of 2 (a step of 3
  // read every pixel of a 640x480 frame and resized by 1/3: 2 ms).
  const int step = std::max(2, 2 * cvRound(size.width / (2 * kSmallWidth)));
  const int readStep = step / 2;
  const cv::Rect frameRect(cv::Point(), size);
  const cv::Size readSize = sampledSize(frameRect, readStep);
  cv::Mat read = read_.view(readSize, CV_8UC3);
  frame.sampledBgr(frameRect, readStep, read);
  const cv::Size smallSize(std::max(1, size.width / step), std::max(1, size.height / step));
  if (smallSize == readSize)
    read.copyTo(small_);
  else
    cv::resize(read, small_, smallSize, 0, 0, cv::INTER_AREA);
  scale_ = static_cast<double>(size.width) / smallSize.width;
  cv::cvtColor(small_, grey_, cv::COLOR_BGR2GRAY);
  grey_.convertTo(current_, CV_32F);
  cv::GaussianBlur(current_, smooth_, cv::Size(), kDetailSigma);
  current_ -= smooth_;
}

// weights_: a Hanning window (phase correlation's usual taper) with the excluded box faded out.
void GlobalMotion::weights(const cv::Rect2d &exclude) {
  const cv::Size size = current_.size();
  if (hanning_.size() != size) cv::createHanningWindow(hanning_, size, CV_32F);
  if (exclude.empty()) {
    hanning_.copyTo(weights_);
    return;
  }
  mask_.create(size, CV_32F);
  mask_.setTo(1);
  const cv::Rect box(cvFloor(exclude.x / scale_), cvFloor(exclude.y / scale_),
                     cvCeil(exclude.width / scale_) + 1, cvCeil(exclude.height / scale_) + 1);
  mask_(box & cv::Rect(cv::Point(), size)).setTo(0);
  cv::GaussianBlur(mask_, mask_, cv::Size(), kExcludeFade);
  cv::multiply(hanning_, mask_, weights_);
}

}  // namespace colortrack
