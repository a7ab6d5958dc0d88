#include "colortrack/target_lock.hpp"

#include <cmath>

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
  if (locked_) {
    const int kept = indexOf(*locked_);
    if (kept >= 0) {
      for (const TargetCandidate &c : candidates)
        if (c.id != *locked_ && c.state != TrackState::Lost) others_.insert(c.id);
      return kept;
    }
    locked_.reset();
  }
  int best = -1;
  for (int i = 0; i < static_cast<int>(candidates.size()); ++i) {
    if (candidates[i].state == TrackState::Lost || others_.count(candidates[i].id)) continue;
    if (best < 0 || preference(candidates[i], policy_, frame) > preference(candidates[best], policy_, frame))
      best = i;
  }
  if (best >= 0) locked_ = candidates[best].id;
  return best;
}

}  // namespace colortrack
