// SPDX-License-Identifier: LGPL-2.1-or-later
// A sudden fall of the reported score (issue 46: a track that went over to a look-alike, or slid off its
// target, keeps its usual peak and colour cues; what falls is the score weighted by the start's look,
// StartLikeness). A tracked frame whose score falls well under its recent level and under a low bar puts the
// track in doubt (the first one after untracked frames, by less and under a higher bar), and the doubt holds
// until a tracked frame's score is clearly back up: reported `coasting` meanwhile, so a robot waits. A fall,
// not a level: targets whose look drifts slowly from the start (a bag crumpling, a wakeboarder turning) reach
// low scores too, but gradually.
#pragma once

namespace colortrack {

class ScoreFall {
 public:
  void reset();
  // This frame's score; `tracked`: the track's own rules report the frame `tracking` (only such frames
  // move the recent level, start a doubt or end it).
  void observe(double score, bool tracked);
  bool fallen() const { return fallen_; }

 private:
  double recent_ = -1;  // running mean of the tracked frames' scores; negative: none yet
  bool fallen_ = false;
  bool lastTracked_ = true;  // the frame before was tracked (a track's first frame is no return)
};

}  // namespace colortrack
