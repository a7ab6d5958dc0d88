// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/target_lock.hpp"

#include <cmath>
#include <iterator>

#include "colortrack/box.hpp"

namespace colortrack {

namespace {

// Higher is better for the policy.
double preference(const TargetCandidate &c, LockOn policy, cv::Size frame) {
  switch (policy) {
    case LockOn::FirstConfirmed:
      return -c.id;
    case LockOn::Largest:
      return c.box.area();
    case LockOn::NearestCentre: {
      const cv::Point2d centre = boxCentre(c.box);
      return -std::hypot(centre.x - frame.width / 2.0, centre.y - frame.height / 2.0);
    }
  }
  return 0;
}

// An object not seen for this many frames (30 s at 30 fps) is forgotten: it may be locked again.
constexpr long kForgetCalls = 900;

}  // namespace

int TargetLock::choose(const std::vector<TargetCandidate> &candidates, cv::Size frame, int fixedId) {
  const auto indexOf = [&](int id) {
    for (int i = 0; i < static_cast<int>(candidates.size()); ++i)
      if (candidates[i].id == id && candidates[i].state != TrackState::Lost) return i;
    return -1;
  };
  if (fixedId >= 0) {
    locked_ = fixedId;
    return indexOf(fixedId);
  }
  ++calls_;
  // Forgotten: unseen by more than kForgetCalls calls before this one.
  for (auto it = others_.begin(); it != others_.end();)
    it = calls_ - 1 - it->second > kForgetCalls ? others_.erase(it) : std::next(it);
  int chosen = locked_ ? indexOf(*locked_) : -1;
  if (chosen < 0) {
    locked_.reset();
    for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
      if (candidates[i].state == TrackState::Lost || others_.count(candidates[i].id)) continue;
      if (chosen < 0 ||
          preference(candidates[i], policy_, frame) > preference(candidates[chosen], policy_, frame))
        chosen = i;
    }
    if (chosen >= 0) locked_ = candidates[chosen].id;
  }
  // Every other track in view beside the locked one is another object; one known stays known while in view,
  // locked or not.
  for (const TargetCandidate &c : candidates) {
    const bool beside = locked_ && c.id != *locked_ && c.state != TrackState::Lost;
    if (beside || others_.count(c.id)) others_[c.id] = calls_;
  }
  return chosen;
}

}  // namespace colortrack
