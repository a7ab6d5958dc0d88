// SPDX-License-Identifier: LGPL-2.1-or-later
// A track reported `tracking` again, after frames it was not, far from where it was last reported `tracking`
// (issue 46): whatever it followed meanwhile (a coast's unconfident peaks, a look-alike's doubt, a fallen
// score) led it there, and it may be on something else. Its next tracked frames are held back (reported
// `coasting`) until kHeldFrames of them have passed.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

namespace colortrack {

class DistantReturn {
 public:
  // Far is more than `farSides` sides (the square root of the box's area) from the last `tracking` place.
  explicit DistantReturn(double farSides) : farSides_(farSides) {}
  // Forgets the last `tracking` place (a new start, or no track: there is no place to return to).
  void reset();
  // A frame with a box: whether the other rules report it `tracking`, the box's centre and side (the square
  // root of its area). Returns whether the frame is held back.
  bool observe(bool tracked, cv::Point2d centre, double side);
  // The camera jerked (CameraJerk): the place moves with the picture.
  void shift(cv::Point2d by) {
    if (lastTracked_) *lastTracked_ += by;
  }

 private:
  double farSides_;
  std::optional<cv::Point2d> lastTracked_;  // the centre of the last frame reported `tracking`
  bool afterUntracked_ = false;             // the frame before was not reported `tracking`
  int held_ = 0;                            // tracked frames still to hold back
};

}  // namespace colortrack
