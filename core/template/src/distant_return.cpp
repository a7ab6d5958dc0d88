// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/distant_return.hpp"

#include <cmath>

namespace colortrack {

namespace {

// Held for kHeldFrames tracked frames, as long as the probation of a re-detection far away (FusedMethod gives
// the far bar and the figures). The same bar on the track's own coasts only (a detection after frames that
// were not, far from the last confirmed place: a jump, new id and probation) changed nothing: most such
// returns come after frames that were detections but doubted.
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
  if (afterUntracked_ && lastTracked_ && cv::norm(centre - *lastTracked_) > farSides_ * side)
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
