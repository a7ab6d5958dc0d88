// SPDX-License-Identifier: LGPL-2.1-or-later
// The frame's global motion: how the background (the camera's view) moved in the image since the last frame,
// from the phase correlation of small grey copies of consecutive frames, the target's box left out.
#pragma once

#include <array>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/image_source.hpp"

namespace colortrack {

class GlobalMotion {
 public:
  struct Shift {
    cv::Point2d offset;   // frame px: how far a background point moved since the last frame
    double response = 0;  // phase correlation peak: how much of the frame agrees on `offset`
    bool valid = false;   // measured (a previous frame of the same size, texture) and trustworthy
  };

  // The small copy is at most `maxWidth` px wide, at the smallest even step that fits: precision against
  // cost (the default agrees within 2 px on the synthetic scene's smooth background; 128 px within 4 px at
  // half the cost).
  explicit GlobalMotion(double maxWidth = 214) : maxWidth_(maxWidth) {}
  // A copy would share the spectra's pixels with the original (cv::Mat): not allowed.
  GlobalMotion(const GlobalMotion &) = delete;
  GlobalMotion &operator=(const GlobalMotion &) = delete;
  GlobalMotion(GlobalMotion &&) = default;
  GlobalMotion &operator=(GlobalMotion &&) = default;

  // Reads a small copy of `frame` and measures its shift from the frame measured last, leaving out
  // `exclude` (frame px; the target, which moves on its own; empty: nothing). The first frame, a frame of
  // another size and a frame without texture give an invalid shift.
  Shift measure(const ImageSource &frame, const cv::Rect2d &exclude = cv::Rect2d()) {
    return measure(frame, std::vector<cv::Rect2d>{exclude});
  }
  // The same, leaving out every box of `exclude` (several objects that move on their own).
  Shift measure(const ImageSource &frame, const std::vector<cv::Rect2d> &exclude);
  // The same from the frame's bytes where they lie (threshold mode has them already).
  Shift measure(const SampledFrame &frame, const std::vector<cv::Rect2d> &exclude);
  // The next frame starts afresh.
  void reset() { previous_.release(); }

 private:
  void smallCopy(const SampledFrame &frame);
  // Every `step`-th pixel's luma (CV_32FC1), read where the frame's bytes lie.
  void sampledLuma(const SampledFrame &frame, int step, cv::Mat &out);
  void weights(const std::vector<cv::Rect2d> &exclude);
  void spectrum();
  cv::Point2d correlate(double &response);

  std::array<std::vector<int>, 3> columns_;  // sampledLuma: byte offset of each sampled column, per channel
  cv::Mat converted_;  // the frame as BGR, for sources that cannot describe their bytes in place
  cv::Mat read_, smooth_, detail_, hanning_, mask_, weights_, windowed_;
  cv::Mat current_, previous_;  // spectra of this frame's and the last frame's weighted detail
  cv::Mat cross_, surface_;
  cv::Size frameSize_;
  double maxWidth_;
  double scale_ = 1;  // frame px per small-copy px
};

}  // namespace colortrack
