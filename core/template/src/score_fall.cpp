// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/score_fall.hpp"

namespace colortrack {

namespace {

// A doubt starts where a tracked frame's score is under kFallenBelow and at least kFall under the running
// mean (rate kRecentRate) of the tracked frames before it, and ends at a tracked frame scoring kBackAt. The
// first tracked frame after untracked ones (a cover, a crossing, a loss: where a look-alike is taken) must
// come back nearer its level: under kReturnBelow and kReturnFall under the mean is a fall too.
// Chosen offline on the tune half from per-frame dumps of the core harness (OPE + SRE + injected, offset
// 0,0), off-target frames reported `tracking` and the recall of `tracking`, tune / confirm: without 28.2 % /
// 17.8 %, recall 0.932 / 0.930; these values 2.7 % / 13.6 %, 0.910 / 0.909. Any score under 0.4 (no fall
// needed): 2.7 % / 12.6 %, recall 0.853 / 0.903, bag's right frames -41 % (docs/benchmarks-history.md). The return's
// bar, from the element's dumps (colortrack-eval, BGRx, OPE + injected) checked on the core harness's:
// element 13.4 % / 8.8 %, recall 0.871 / 0.902 -> 3.6 % / 5.9 %, 0.848 / 0.899; core 2.7 % / 13.6 % -> 2.6 %
// / 13.5 %, recall 0.910 / 0.909 -> 0.903 / 0.908.
constexpr double kFallenBelow = 0.4;
constexpr double kFall = 0.15;
constexpr double kBackAt = 0.6;
constexpr double kRecentRate = 0.1;
constexpr double kReturnBelow = 0.5;
constexpr double kReturnFall = 0.05;

}  // namespace

void ScoreFall::reset() {
  recent_ = -1;
  fallen_ = false;
  lastTracked_ = true;
}

void ScoreFall::observe(double score, bool tracked) {
  const bool returning = tracked && !lastTracked_;
  lastTracked_ = tracked;
  if (!tracked) return;
  const bool fell = recent_ >= 0 && ((score < kFallenBelow && recent_ - score > kFall) ||
                                     (returning && score < kReturnBelow && recent_ - score > kReturnFall));
  if (fell)
    fallen_ = true;
  else if (score >= kBackAt)
    fallen_ = false;
  recent_ = recent_ < 0 ? score : recent_ + kRecentRate * (score - recent_);
}

}  // namespace colortrack
