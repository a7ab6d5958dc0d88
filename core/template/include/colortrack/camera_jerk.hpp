// SPDX-License-Identifier: LGPL-2.1-or-later
// A camera that jerks: the whole picture jumps further in one frame than the fused method's window reaches (a
// bump, a gimbal that snaps, a robot that turns in bursts). On a frame where the window lost the target,
// GlobalMotion compares a small copy of it with the frame before's; a shift of more than kJerkSides target
// sides is a jerk, and FusedMethod then looks for the target where the jerk took it. GlobalMotion alone is
// not trusted to move the track: on real footage its shift is more than 2 px off a feature-based reference
// on 16 % of the frames (colortrack-motion-eval, docs/benchmarks-history.md), and following it every frame lost
// accuracy (issue 21); the target must be found where the jerk says.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/global_motion.hpp"
#include "colortrack/image_source.hpp"

namespace colortrack {

class CameraJerk {
 public:
  // Every frame the track follows: the frame, the target's last box (left out: it moves on its own), its side
  // (the square root of its area) and whether the window lost the target on this frame. Returns the
  // background's shift since the frame before when the target was lost and the shift is a jerk. Only such
  // frames are measured: every frame keeps a small copy for the next one, which costs a tenth of measuring.
  std::optional<cv::Point2d> observe(const ImageSource &frame, const cv::Rect2d &target, double side,
                                     bool lost);
  // The next frame starts afresh (a new track, another scene).
  void reset() { previous_.release(); }

 private:
  cv::Mat previous_, current_;  // small BGR copies of the frame before and this one
  GlobalMotion motion_;
};

}  // namespace colortrack
