// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold-mode scenes with exact multi-object ground truth, the kinds an outside test found hard: balls
// crossing (a small one over a big one), eight balls at random, balls entering, leaving and passing behind a
// board, a lighting ramp with a shadow band, red balls among orange and magenta objects and red specks. The
// targets are red, the colour threshold mode selects by default; the other balls are distractors.
#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "balls.hpp"
#include "mot_metrics.hpp"

namespace colortrack::eval {

struct MotScene {
  std::string name;
  balls::BallScene balls;
  std::vector<bool> isTarget;  // per ball: red (counts) or a distractor
  cv::Rect board;              // drawn over the balls (empty: none)
  cv::Rect shadow;             // darkened band (empty: none)
  double shadowFactor = 0.55;
  int frames = 240;

  // Frame `index` with its ground truth: targets at least `minVisibleFraction` visible and `minArea` pixels
  // in `truth` (box: their visible pixels, not behind the board, the frame's edge or a ball drawn over them),
  // the other targets in `ignored` when any part of them lies in the
  // frame (a box there is neither right nor wrong).
  cv::Mat render(int index, MotFrame &truth, double minVisibleFraction = 0.25, int minArea = 50) const;
};

// The scenes, deterministic.
std::vector<MotScene> motScenes();

}  // namespace colortrack::eval
