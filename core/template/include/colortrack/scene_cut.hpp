// SPDX-License-Identifier: LGPL-2.1-or-later
// A cut to another scene: the picture's colours change as a whole between two frames (a camera switched, a
// stream that jumps, an edited video). The target cannot be where it was then, so the track is lost at once
// instead of coasting on the new scene.
#pragma once

#include <opencv2/core.hpp>

#include "colortrack/image_source.hpp"

namespace colortrack {

class SceneCut {
 public:
  // Whether `frame` shows another scene than the frame before it (false on the first frame and after a
  // change of frame size).
  bool observe(const ImageSource &frame);
  // How far the last frame's colours were from the frame before (Bhattacharyya distance, 0 = same).
  double lastDistance() const { return lastDistance_; }

 private:
  cv::Mat previous_;  // colour histogram of the frame before
  cv::Size previousSize_;
  cv::Mat sample_, histogram_;
  double lastDistance_ = 0;
};

}  // namespace colortrack
