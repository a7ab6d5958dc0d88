// SPDX-License-Identifier: LGPL-2.1-or-later
// YUV frames read as BGR byte for byte as GStreamer's videoconvert converts them to RGB (the frame's own
// matrix and range in videoconvert's integer maths, each chroma sample covering its block of pixels), so that
// the tracker sees the same image whether a source delivers YUV or RGB converted upstream.
#pragma once

#include <opencv2/core.hpp>

#include "colortrack/image_source.hpp"

namespace colortrack {

// Writes every `step`-th pixel of `rect` (inside the frame) of a PixelEncoding::Yuv frame as CV_8UC3 BGR:
// size sampledSize(rect, step), pixel (i, j) from frame pixel (rect.x + i * step, rect.y + j * step).
void yuvToBgr(const SampledFrame &frame, const cv::Rect &rect, int step, cv::Mat &out);

// A SampledFrame over an I420 image as cv::cvtColor lays it out (CV_8UC1, height * 3 / 2 rows, even size).
SampledFrame sampledI420(const cv::Mat &i420, cv::Size size, const YuvColorimetry &colorimetry);

// An ImageSource over the planes of a YUV frame (tests, the evaluation harness): `frame`'s planes must
// outlive it.
class YuvImageSource : public ImageSource {
 public:
  explicit YuvImageSource(const SampledFrame &frame) : frame_(frame) {}
  cv::Size size() const override { return frame_.size; }
  void bgr(const cv::Rect &rect, cv::Mat &out) const override { yuvToBgr(frame_, rect, 1, out); }
  void sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const override {
    yuvToBgr(frame_, rect, step, out);
  }
  SampledFrame channels(cv::Mat &) const override { return frame_; }

 private:
  SampledFrame frame_;
};

}  // namespace colortrack
