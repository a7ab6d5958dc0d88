#include "colortrack/distant_return.hpp"

#include <cmath>

namespace colortrack {

namespace {

// Further than this many sides from the last `tracking` place is far: the bar at which a re-detection while
// coasting starts a new id (kJumpSides in method_fused.cpp). Held for kHeldFrames tracked frames, as long as
// that probation. Core harness, SRE + injected runs, offsets 0,0 / 1,0 / 0,1 / -1,-1 (docs/benchmarks.md):
// off-target frames reported `tracking` 3.0 / 2.2 / 5.0 / 9.9 % -> 1.5 / 2.1 / 2.9 / 9.2 %, AUROC 0.954 /
// 0.961 / 0.944 / 0.925 -> 0.957 / 0.960 / 0.948 / 0.923, recall of `tracking` 0.827 / 0.832 / 0.810 / 0.825
// -> 0.807 / 0.816 / 0.779 / 0.798. The same bar on the track's own coasts only (a detection after frames
// that were not, far from the last confirmed place: a jump, new id and probation) changed nothing: most such
// returns come after frames that were detections but doubted.
constexpr double kFarSides = 1.5;
constexpr int kHeldFrames = 30;

}  // namespace

void DistantReturn::reset() {
  lastTracked_.reset();
  afterUntracked_ = false;
  held_ = 0;
}

bool DistantReturn::observe(bool tracked, cv::Point2d centre, double side) {
  if (!tracked) {
    afterUntracked_ = true;
    return false;
  }
  if (afterUntracked_ && lastTracked_ && cv::norm(centre - *lastTracked_) > kFarSides * side)
    held_ = kHeldFrames;
  afterUntracked_ = false;
  if (held_ > 0) {
    --held_;
    return true;
  }
  lastTracked_ = centre;
  return false;
}

}  // namespace colortrack
