// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/camera_jerk.hpp"

#include <algorithm>

namespace colortrack {

namespace {

// A shift of more than this many target sides is a jerk: the window (about 2.5 sides) loses the target, or
// holds it near its edge where the filter's taper weakens it. Core harness, SRE + injected runs, offsets
// 0,0 / 1,0 / 0,1 / -1,-1, OPE confirm 0.5153 / 0.5421 / 0.5082 / 0.4995 -> 0.5159 / 0.5422 / 0.5086 /
// 0.5024, SRE confirm 0.5099 / 0.5105 / 0.4926 / 0.4997 -> 0.5105 / 0.5107 / 0.4932 / 0.4999, the tune
// half and off-target `tracking` unchanged (docs/benchmarks-history.md).
constexpr double kJerkSides = 1.0;
// The copies are about this many px wide (GlobalMotion halves them again): a jerk needs a side's precision,
// not GlobalMotion's 2 px. Measuring every frame at GlobalMotion's default 214 px cost 0.6-0.8 ms a 1080p
// frame, as much as the tracking (at 64 px, 0.09 ms on 640x360); keeping the copy costs 0.04-0.08 ms a
// 1080p frame (bench-tracker) and nothing measurable on DragonBaby in BGRx (docs/benchmarks-history.md).
constexpr int kCopyWidth = 128;

}  // namespace

std::optional<cv::Point2d> CameraJerk::observe(const ImageSource &frame, const cv::Rect2d &target,
                                               double side, bool lost) {
  const cv::Rect whole(cv::Point(), frame.size());
  const int step = std::max(1, whole.width / kCopyWidth);
  frame.sampledBgr(whole, step, current_);
  std::optional<cv::Point2d> jerk;
  if (lost && !previous_.empty() && previous_.size() == current_.size()) {
    const double scale = static_cast<double>(whole.width) / current_.cols;
    const cv::Rect2d small(target.x / scale, target.y / scale, target.width / scale, target.height / scale);
    motion_.reset();
    motion_.measure(MatImageSource(previous_), small);
    const GlobalMotion::Shift shift = motion_.measure(MatImageSource(current_), small);
    if (shift.valid && cv::norm(shift.offset) * scale > kJerkSides * side) jerk = shift.offset * scale;
  }
  std::swap(previous_, current_);
  return jerk;
}

}  // namespace colortrack
