// A camera that jerks: the whole picture jumps further in one frame than the fused method's window reaches (a
// bump, a gimbal that snaps, a robot that turns in bursts). GlobalMotion measures how the background moved;
// a shift of more than kJerkSides target sides is a jerk, and FusedMethod then looks for the target where the
// jerk took it. GlobalMotion alone is not trusted to move the track: on real footage its shift is more than
// 2 px off a feature-based reference on 16 % of the frames (colortrack-motion-eval, docs/benchmarks.md), and
// following it every frame lost accuracy (issue 21); the target must be found where the jerk says.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/global_motion.hpp"
#include "colortrack/image_source.hpp"

namespace colortrack {

class CameraJerk {
 public:
  // Every frame the track follows: the frame, the target's last box (left out: it moves on its own) and its
  // side (the square root of its area). Returns the background's shift since the last frame when it is a
  // jerk.
  std::optional<cv::Point2d> observe(const ImageSource &frame, const cv::Rect2d &target, double side);
  // The next frame starts afresh (a new track, another scene).
  void reset() { motion_.reset(); }

 private:
  // A copy 64 px wide: a jerk needs a side's precision, not GlobalMotion's 2 px, and at its default 214 px
  // the measure cost 0.6-0.8 ms a 1080p frame, about as much as the tracking itself (64: 0.08-0.11 ms).
  GlobalMotion motion_{64};
};

}  // namespace colortrack
