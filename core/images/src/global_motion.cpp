// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/global_motion.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

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

GlobalMotion::Shift GlobalMotion::measure(const ImageSource &frame, const std::vector<cv::Rect2d> &exclude) {
  return measure(frame.channels(converted_), exclude);
}

GlobalMotion::Shift GlobalMotion::measure(const SampledFrame &frame, const std::vector<cv::Rect2d> &exclude) {
  if (frame.size != frameSize_) previous_.release();
  frameSize_ = frame.size;
  smallCopy(frame);
  Shift out;
  const bool textured = cv::mean(cv::abs(detail_))[0] >= kMinDetail;
  if (!textured || detail_.cols < 8 || detail_.rows < 8) {
    previous_.release();
    return out;
  }
  weights(exclude);
  spectrum();
  if (!previous_.empty()) {
    const cv::Point2d s = correlate(out.response);
    out.offset = s * scale_;
    out.valid = std::isfinite(out.response) && out.response >= kMinResponse;
  }
  std::swap(previous_, current_);
  return out;
}

// current_ becomes the spectrum of the frame's detail times its weights, zero-padded to a size the DFT is
// fast at. Each frame keeps its own weights (its own objects left out), so the previous frame's spectrum is
// reused as it is: one forward and one inverse transform a frame in single precision, where
// cv::phaseCorrelate transforms both frames again in double precision (0.74 ms against about 0.15 ms for a
// 160x120 copy).
void GlobalMotion::spectrum() {
  const cv::Size padded(cv::getOptimalDFTSize(detail_.cols), cv::getOptimalDFTSize(detail_.rows));
  windowed_.create(padded, CV_32F);
  windowed_.setTo(0);
  cv::multiply(detail_, weights_, windowed_(cv::Rect(cv::Point(), detail_.size())));
  cv::dft(windowed_, current_, cv::DFT_COMPLEX_OUTPUT);
}

// The shift from the previous frame to this one: the peak of the normalised cross-power spectrum's inverse,
// refined by the weighted centroid of its 5x5 neighbourhood (as cv::phaseCorrelate does). `response`: the
// centroid's mass, about 1 for a whole-frame shift.
cv::Point2d GlobalMotion::correlate(double &response) {
  // previous times the conjugate of current, each product scaled to magnitude 1, in one pass (OpenCV's own
  // normalisation, magSpectrums and divSpectrums, is not public; split, magnitude, divide and merge took
  // twice as long).
  cross_.create(current_.size(), CV_32FC2);
  for (int y = 0; y < cross_.rows; ++y) {
    const cv::Vec2f *p = previous_.ptr<cv::Vec2f>(y), *q = current_.ptr<cv::Vec2f>(y);
    cv::Vec2f *c = cross_.ptr<cv::Vec2f>(y);
    for (int x = 0; x < cross_.cols; ++x) {
      const float re = p[x][0] * q[x][0] + p[x][1] * q[x][1], im = p[x][1] * q[x][0] - p[x][0] * q[x][1];
      const float scale = 1.0f / (std::sqrt(re * re + im * im) + 1e-12f);
      c[x] = cv::Vec2f(re * scale, im * scale);
    }
  }
  cv::idft(cross_, surface_, cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
  cv::Point peak;
  cv::minMaxLoc(surface_, nullptr, nullptr, nullptr, &peak);
  double mass = 0;
  cv::Point2d weighted;
  for (int dy = -2; dy <= 2; ++dy)
    for (int dx = -2; dx <= 2; ++dx) {
      // The surface wraps around: a shift of -1 peaks in the last column.
      const int x = (peak.x + dx + surface_.cols) % surface_.cols,
                y = (peak.y + dy + surface_.rows) % surface_.rows;
      const double v = surface_.at<float>(y, x);
      mass += v;
      weighted += v * cv::Point2d(peak.x + dx, peak.y + dy);
    }
  response = mass;
  cv::Point2d at = mass > 0 ? weighted / mass : cv::Point2d(peak);
  // Peaks past the middle are negative shifts.
  if (at.x > surface_.cols / 2.0) at.x -= surface_.cols;
  if (at.y > surface_.rows / 2.0) at.y -= surface_.rows;
  return -at;
}

// Every `step`-th pixel's luma as CV_32FC1 of sampledSize(frame, step), read where the bytes lie: a YUV
// frame's Y sample itself, an RGB frame's BT.601 weighting, unrounded (on a smooth scene, rounding to whole
// levels moved the measured shift by half a small-copy pixel). Reading BGR first and converting it cost
// twice as much: YUV frames were converted to BGR for nothing. Only detail is correlated, so a limited-range
// Y needs no scaling.
void GlobalMotion::sampledLuma(const SampledFrame &frame, int step, cv::Mat &out) {
  const cv::Size size = sampledSize(cv::Rect(cv::Point(), frame.size), step);
  out.create(size, CV_32FC1);
  const bool yuv = frame.encoding == PixelEncoding::Yuv;
  const int used = yuv ? 1 : 3;  // Y alone, or R, G and B
  // Byte offset of every sampled column in each channel's row (a division per sample cost 1 ms a frame).
  for (int c = 0; c < used; ++c) {
    const ChannelSampler &ch = frame.channels[c];
    columns_[c].resize(size.width);
    for (int i = 0; i < size.width; ++i)
      columns_[c][i] = (i * step / ch.xSub) * ch.sampleBytes + ch.byteOffset;
  }
  for (int j = 0; j < size.height; ++j) {
    const int y = j * step;
    float *dst = out.ptr<float>(j);
    const ChannelSampler &c0 = frame.channels[0];
    const uchar *r0 = c0.plane.ptr(y / c0.ySub);
    const int *x0 = columns_[0].data();
    if (yuv) {
      for (int i = 0; i < size.width; ++i) dst[i] = r0[x0[i]];
      continue;
    }
    const ChannelSampler &c1 = frame.channels[1], &c2 = frame.channels[2];
    const uchar *r1 = c1.plane.ptr(y / c1.ySub), *r2 = c2.plane.ptr(y / c2.ySub);
    const int *x1 = columns_[1].data(), *x2 = columns_[2].data();
    for (int i = 0; i < size.width; ++i)
      dst[i] = 0.299f * r0[x0[i]] + 0.587f * r1[x1[i]] + 0.114f * r2[x2[i]];
  }
}

// detail_: the frame's detail, grey, on a copy at most maxWidth_ px wide, at the smallest even step that fits
// (at 214: 160 px at 320x240 and 640x480, 144 at 576x432, 213 at 1280x720, 192 at 1920x1080; 160 px at
// 1280x720 was up to 4 px off on the synthetic scene). Rounding the step to the nearest instead made a 576 px
// frame's copy 288 px wide, read at every pixel: 4.5 ms a frame.
void GlobalMotion::smallCopy(const SampledFrame &frame) {
  const cv::Size size = frame.size;
  // Read at half the final step and average pairs: nearest-neighbour samples alone alias fine texture, which
  // then moves differently from the scene. An even step keeps the averaging a whole factor of 2 (a step of 3
  // read every pixel of a 640x480 frame and resized by 1/3: 2 ms).
  const int step = std::max(2, 2 * static_cast<int>(std::ceil(size.width / (2 * maxWidth_))));
  const int readStep = step / 2;
  sampledLuma(frame, readStep, read_);
  const cv::Size smallSize(std::max(1, size.width / step), std::max(1, size.height / step));
  if (smallSize == read_.size())
    read_.copyTo(detail_);
  else
    cv::resize(read_, detail_, smallSize, 0, 0, cv::INTER_AREA);
  scale_ = static_cast<double>(size.width) / smallSize.width;
  cv::GaussianBlur(detail_, smooth_, cv::Size(), kDetailSigma);
  detail_ -= smooth_;
}

// weights_: a Hanning window (phase correlation's usual taper) with the excluded boxes faded out.
void GlobalMotion::weights(const std::vector<cv::Rect2d> &exclude) {
  const cv::Size size = detail_.size();
  if (hanning_.size() != size) cv::createHanningWindow(hanning_, size, CV_32F);
  const bool any =
      std::any_of(exclude.begin(), exclude.end(), [](const cv::Rect2d &r) { return !r.empty(); });
  if (!any) {
    hanning_.copyTo(weights_);
    return;
  }
  mask_.create(size, CV_32F);
  mask_.setTo(1);
  for (const cv::Rect2d &r : exclude) {
    if (r.empty()) continue;
    const cv::Rect box(cvFloor(r.x / scale_), cvFloor(r.y / scale_), cvCeil(r.width / scale_) + 1,
                       cvCeil(r.height / scale_) + 1);
    mask_(box & cv::Rect(cv::Point(), size)).setTo(0);
  }
  cv::GaussianBlur(mask_, mask_, cv::Size(), kExcludeFade);
  cv::multiply(hanning_, mask_, weights_);
}

}  // namespace colortrack
