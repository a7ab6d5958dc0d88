// SPDX-License-Identifier: LGPL-2.1-or-later
// The weighted score's sudden fall (issue 46): a tracked track whose score drops from its usual level to
// under the low bar is in doubt until a tracked frame scores well again, and so is one that comes back from
// untracked frames under its level; a score that sinks slowly (a target whose look drifts from the start)
// is no fall, and frames the track does not report `tracking` change nothing else.
#include <gtest/gtest.h>

#include "colortrack/score_fall.hpp"

using colortrack::ScoreFall;

namespace {

void observe(ScoreFall &fall, double score, int frames, bool tracked = true) {
  for (int i = 0; i < frames; ++i) fall.observe(score, tracked);
}

}  // namespace

TEST(ScoreFall, ASuddenFallHoldsUntilTheScoreIsBackUp) {
  ScoreFall fall;
  observe(fall, 0.8, 20);
  EXPECT_FALSE(fall.fallen());
  fall.observe(0.35, true);  // a look-alike took the box
  EXPECT_TRUE(fall.fallen());
  observe(fall, 0.55, 30);  // as good as a usual frame of a hard sequence, but not back
  EXPECT_TRUE(fall.fallen());
  fall.observe(0.6, true);
  EXPECT_FALSE(fall.fallen());
}

TEST(ScoreFall, ASlowDriftIsNoFall) {
  ScoreFall fall;
  double score = 0.8;
  for (int i = 0; i < 100; ++i, score -= 0.005) {
    fall.observe(score, true);
    ASSERT_FALSE(fall.fallen()) << "at " << score;
  }
  EXPECT_LT(score, 0.35);
}

TEST(ScoreFall, OnlyTrackedFramesCount) {
  ScoreFall fall;
  observe(fall, 0.8, 20);
  observe(fall, 0.1, 10, false);  // coasting under a cover: its guesses score low by construction
  EXPECT_FALSE(fall.fallen());
  fall.observe(0.3, true);
  ASSERT_TRUE(fall.fallen());
  observe(fall, 0.9, 5, false);  // nor do untracked frames end a doubt
  EXPECT_TRUE(fall.fallen());
}

TEST(ScoreFall, AReturnFromUntrackedFramesMustComeBackNearItsLevel) {
  ScoreFall fall;
  observe(fall, 0.57, 20);   // a hard target's usual level
  fall.observe(0.46, true);  // the same drop while tracked all along is no fall
  EXPECT_FALSE(fall.fallen());
  observe(fall, 0.57, 20);
  observe(fall, 0.15, 8, false);  // covered; then the window's peak is taken on a neighbour
  fall.observe(0.46, true);
  EXPECT_TRUE(fall.fallen());
  observe(fall, 0.6, 1);
  observe(fall, 0.15, 8, false);
  fall.observe(0.55, true);  // back at its level after the cover: the target
  EXPECT_FALSE(fall.fallen());
}

TEST(ScoreFall, ResetForgetsTheDoubtAndTheLevel) {
  ScoreFall fall;
  observe(fall, 0.8, 20);
  fall.observe(0.3, true);
  ASSERT_TRUE(fall.fallen());
  fall.reset();
  EXPECT_FALSE(fall.fallen());
  fall.observe(0.3, true);  // a first frame has no level to fall from
  EXPECT_FALSE(fall.fallen());
}
