// SPDX-License-Identifier: LGPL-2.1-or-later
// The multi-object metrics on hand-made tracks whose MOTA and IDF1 are worked out by hand.
#include <gtest/gtest.h>

#include <vector>

#include "mot_metrics.hpp"

using namespace colortrack::eval;

namespace {

cv::Rect2d boxAt(double x) {
  return cv::Rect2d(x, 100, 20, 20);
}

}  // namespace

TEST(MotMetrics, PerfectTrackingScoresOne) {
  std::vector<MotFrame> frames(10);
  for (int i = 0; i < 10; ++i) {
    frames[i].truth = {{1, boxAt(10 * i)}, {2, boxAt(300 - 10 * i)}};
    frames[i].tracks = {{7, boxAt(10 * i + 1)}, {9, boxAt(300 - 10 * i)}};
  }
  const MotScore s = scoreMot(frames);
  EXPECT_EQ(s.truthBoxes, 20);
  EXPECT_EQ(s.matches, 20);
  EXPECT_EQ(s.idSwitches, 0);
  EXPECT_DOUBLE_EQ(s.mota, 1.0);
  EXPECT_DOUBLE_EQ(s.idf1, 1.0);
  EXPECT_GT(s.motp, 0.9);
}

TEST(MotMetrics, MissesAndFalsePositives) {
  // One object over 10 frames: not reported in two frames, and a stray box in two others.
  std::vector<MotFrame> frames(10);
  for (int i = 0; i < 10; ++i) {
    frames[i].truth = {{1, boxAt(10 * i)}};
    if (i != 3 && i != 4) frames[i].tracks.push_back({1, boxAt(10 * i)});
    if (i == 7 || i == 8) frames[i].tracks.push_back({5, boxAt(400)});
  }
  const MotScore s = scoreMot(frames);
  EXPECT_EQ(s.misses, 2);
  EXPECT_EQ(s.falsePositives, 2);
  EXPECT_DOUBLE_EQ(s.mota, 1.0 - 4.0 / 10);
  // IDTP 8 of 10 truth boxes and 10 track boxes.
  EXPECT_EQ(s.idTruePositives, 8);
  EXPECT_DOUBLE_EQ(s.idf1, 16.0 / 20);
}

TEST(MotMetrics, AnIdentitySwitchCostsOnceInMotaAndHalfTheIdentities) {
  std::vector<MotFrame> frames(10);
  for (int i = 0; i < 10; ++i) {
    frames[i].truth = {{1, boxAt(10 * i)}};
    frames[i].tracks = {{i < 5 ? 1 : 2, boxAt(10 * i)}};
  }
  const MotScore s = scoreMot(frames);
  EXPECT_EQ(s.idSwitches, 1);
  EXPECT_DOUBLE_EQ(s.mota, 0.9);
  EXPECT_EQ(s.idTruePositives, 5);
  EXPECT_DOUBLE_EQ(s.idf1, 0.5);
}

TEST(MotMetrics, AMatchIsKeptWhileItQualifiesEvenIfAnotherBoxFitsBetter) {
  // Track 1 follows the object; from frame 2 track 2 sits exactly on it while track 1 drifts but still
  // overlaps enough: CLEAR-MOT keeps track 1 (no switch) and counts track 2 as a false positive.
  std::vector<MotFrame> frames(4);
  for (int i = 0; i < 4; ++i) {
    frames[i].truth = {{1, boxAt(100)}};
    frames[i].tracks = {{1, boxAt(100 + (i >= 2 ? 6 : 0))}};
    if (i >= 2) frames[i].tracks.push_back({2, boxAt(100)});
  }
  const MotScore s = scoreMot(frames);
  EXPECT_EQ(s.idSwitches, 0);
  EXPECT_EQ(s.falsePositives, 2);
  EXPECT_EQ(s.matches, 4);
}

TEST(MotMetrics, BelowTheIouThresholdIsAMissAndAFalsePositive) {
  std::vector<MotFrame> frames(1);
  frames[0].truth = {{1, boxAt(100)}};
  frames[0].tracks = {{1, boxAt(114)}};  // IoU 6*20 / (2*400 - 120) = 0.18
  const MotScore s = scoreMot(frames, 0.3);
  EXPECT_EQ(s.misses, 1);
  EXPECT_EQ(s.falsePositives, 1);
  EXPECT_DOUBLE_EQ(s.mota, -1.0);
}

TEST(MotMetrics, BoxesOnIgnoredObjectsCountNeitherWay) {
  std::vector<MotFrame> frames(5);
  for (int i = 0; i < 5; ++i) {
    frames[i].truth = {{1, boxAt(10 * i)}};
    frames[i].ignored = {{2, boxAt(300)}};  // an object hidden behind a board
    frames[i].tracks = {{1, boxAt(10 * i)}, {3, boxAt(302)}};
  }
  const MotScore s = scoreMot(frames);
  EXPECT_EQ(s.falsePositives, 0);
  EXPECT_DOUBLE_EQ(s.mota, 1.0);
  EXPECT_DOUBLE_EQ(s.idf1, 1.0);
}

TEST(MotMetrics, IdentitiesArePairedForTheMostOverlap) {
  // Truth 1 is covered by track A for 6 frames and track B for 4; truth 2 by track B for 5. Pairing 1-A and
  // 2-B gives 11 overlapping frames; the greedy choice 1-A then 2-B is the same here, but pairing 1-B would
  // leave only 4 + 0: the solver must find 11.
  std::vector<MotFrame> frames;
  for (int i = 0; i < 10; ++i) {
    MotFrame f;
    f.truth = {{1, boxAt(0)}};
    f.tracks = {{i < 6 ? 10 : 20, boxAt(0)}};
    frames.push_back(f);
  }
  for (int i = 0; i < 5; ++i) {
    MotFrame f;
    f.truth = {{2, boxAt(200)}};
    f.tracks = {{20, boxAt(200)}};
    frames.push_back(f);
  }
  const MotScore s = scoreMot(frames);
  EXPECT_EQ(s.idTruePositives, 11);
  EXPECT_DOUBLE_EQ(s.idf1, 2.0 * 11 / (15 + 15));
}
