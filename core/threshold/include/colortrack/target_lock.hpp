// SPDX-License-Identifier: LGPL-2.1-or-later
// Which of several tracked objects a robot follows, and keeping to it: once locked onto a track, robotctl
// follows that track's id until the track is gone, instead of switching whenever another object becomes the
// lowest id or the largest.
#pragma once

#include <optional>
#include <map>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/choice.hpp"
#include "colortrack/track.hpp"

namespace colortrack {

// How a new target is chosen when there is none (or the locked one is gone).
enum class LockOn {
  FirstConfirmed,  // the oldest track (lowest id): the object that was there first
  Largest,         // the largest box
  NearestCentre,   // the box whose centre is nearest the frame's centre
};
inline constexpr Choice<LockOn> kLockOns[] = {
    {LockOn::FirstConfirmed, "first-confirmed", "The oldest track (lowest id)"},
    {LockOn::Largest, "largest", "The largest box"},
    {LockOn::NearestCentre, "nearest-centre", "The box nearest the frame's centre"},
};

struct TargetCandidate {
  int id = 0;
  cv::Rect2d box;
  TrackState state = TrackState::Tracking;
};

class TargetLock {
 public:
  TargetLock() = default;
  explicit TargetLock(LockOn policy) : policy_(policy) {}
  void setPolicy(LockOn policy) { policy_ = policy; }

  // The index in `candidates` of the target to follow this frame, or -1 when there is none. `fixedId` >= 0
  // follows that id only. Otherwise the locked id while it is among the candidates; when it is gone, a new
  // lock by the policy, among the tracks never seen beside a locked one. Candidates that are `lost` are
  // never chosen.
  int choose(const std::vector<TargetCandidate> &candidates, cv::Size frame, int fixedId = -1);

  std::optional<int> locked() const { return locked_; }
  // Forgets the lock and the tracks seen beside it (a flush: what comes next may be another scene).
  void release() {
    locked_.reset();
    others_.clear();
  }

 private:
  LockOn policy_ = LockOn::FirstConfirmed;
  std::optional<int> locked_;
  // Ids seen at the same time as a locked track: other objects. A same-coloured ball that rolled in front of
  // the target and hid it is such a track, and taking it when the target's track ended is how the robot
  // went after the decoy (issue 47). The robot waits instead (lost-timeout stops it) for a track that is
  // not one of them: the target back from behind the decoy. Each id maps to the choose() call that last
  // saw it; one unseen for kForgetCalls calls is forgotten, so a long run's memory stays bounded.
  std::map<int, long> others_;
  long calls_ = 0;
};

}  // namespace colortrack
