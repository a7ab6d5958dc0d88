// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's choice of target among several tracks: each policy picks as it says, and a lock holds while its
// track is there, whatever the other tracks do.
#include <gtest/gtest.h>

#include "colortrack/target_lock.hpp"

using namespace colortrack;

namespace {

const cv::Size kFrame(640, 480);

TargetCandidate candidate(int id, double x, double y, double side) {
  return TargetCandidate{id, cv::Rect2d(x - side / 2, y - side / 2, side, side), TrackState::Tracking};
}

}  // namespace

TEST(TargetLock, EachPolicyPicksItsTarget) {
  const std::vector<TargetCandidate> tracks = {candidate(5, 100, 100, 20), candidate(3, 600, 400, 30),
                                               candidate(8, 330, 250, 10)};
  EXPECT_EQ(TargetLock(LockOn::FirstConfirmed).choose(tracks, kFrame), 1);  // id 3
  EXPECT_EQ(TargetLock(LockOn::Largest).choose(tracks, kFrame), 1);         // side 30
  EXPECT_EQ(TargetLock(LockOn::NearestCentre).choose(tracks, kFrame), 2);   // next to (320, 240)
}

TEST(TargetLock, HoldsTheLockedTrackUntilItIsGone) {
  TargetLock lock(LockOn::Largest);
  std::vector<TargetCandidate> tracks = {candidate(1, 100, 100, 40)};
  ASSERT_EQ(lock.choose(tracks, kFrame), 0);
  // A larger object appears, or passes in front: the lock stays on track 1.
  tracks.push_back(candidate(2, 120, 110, 80));
  EXPECT_EQ(lock.choose(tracks, kFrame), 0);
  std::swap(tracks[0], tracks[1]);
  EXPECT_EQ(lock.choose(tracks, kFrame), 1);
  EXPECT_EQ(lock.locked(), 1);
  // Coasting still counts; lost or gone does not, and a new lock is taken by the policy, but never on
  // track 2, seen beside track 1: it is another object (the decoy that hid the target). A new track is
  // taken.
  tracks[1].state = TrackState::Coasting;
  EXPECT_EQ(lock.choose(tracks, kFrame), 1);
  tracks[1].state = TrackState::Lost;
  EXPECT_EQ(lock.choose(tracks, kFrame), -1);
  EXPECT_FALSE(lock.locked().has_value());
  tracks.push_back(candidate(3, 100, 100, 40));
  EXPECT_EQ(lock.choose(tracks, kFrame), 2);
  EXPECT_EQ(lock.locked(), 3);
  EXPECT_EQ(lock.choose({}, kFrame), -1);
  EXPECT_FALSE(lock.locked().has_value());
  // After a release (a flush) every track may be taken again.
  lock.release();
  EXPECT_EQ(lock.choose({candidate(2, 120, 110, 80)}, kFrame), 0);
}

TEST(TargetLock, AFixedIdIsFollowedAndNothingElse) {
  TargetLock lock;
  const std::vector<TargetCandidate> tracks = {candidate(1, 100, 100, 40), candidate(4, 300, 200, 40)};
  EXPECT_EQ(lock.choose(tracks, kFrame, 4), 1);
  EXPECT_EQ(lock.choose(tracks, kFrame, 7), -1);
}

// A track seen beside the target stays another object while it is in view, however long the robot waits;
// one out of view for 900 frames (30 s at 30 fps) is forgotten, so a long run's memory stays bounded.
TEST(TargetLock, AnotherObjectIsForgottenOnlyOnceOutOfViewForLong) {
  TargetLock lock;
  const TargetCandidate target = candidate(1, 100, 100, 40), other = candidate(2, 300, 200, 40);
  ASSERT_EQ(lock.choose({target, other}, kFrame), 0);
  for (int i = 0; i < 1000; ++i) ASSERT_EQ(lock.choose({other}, kFrame), -1) << "frame " << i;
  for (int i = 0; i < 900; ++i) lock.choose({}, kFrame);
  EXPECT_EQ(lock.choose({other}, kFrame), -1);  // seen 900 frames ago: still known
  for (int i = 0; i < 901; ++i) lock.choose({}, kFrame);
  EXPECT_EQ(lock.choose({other}, kFrame), 0);
  EXPECT_EQ(lock.locked(), 2);
}
