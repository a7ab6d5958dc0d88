// SPDX-License-Identifier: LGPL-2.1-or-later
// The window's peak moving onto the place where the window before showed a second object (issue 46): the
// target does not jump to where its twin stood, so the track has most likely gone over to the look-alike. The
// frame before need not have been a detection: a twin beside a target that is briefly hard to see lowers the
// frame's score, and the next frame's peak is on the twin.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

namespace colortrack {

class LookAlikeTakeover {
 public:
  void reset() { second_.reset(); }
  // A window's outcome: where its peak puts the target's centre, where the window was centred (where the
  // track last was), where its second object puts the centre if it reached the look-alike bar, and the
  // target's side (the square root of its area). Returns whether the peak moved onto the second object of the
  // window before.
  bool observe(cv::Point2d peak, cv::Point2d windowCentre, std::optional<cv::Point2d> second, double side);
  // The camera jerked (CameraJerk): the second object's place moves with the picture.
  void shift(cv::Point2d by) {
    if (second_) *second_ += by;
  }

 private:
  std::optional<cv::Point2d> second_;  // the window before's second object
};

}  // namespace colortrack
