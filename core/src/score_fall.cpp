#include "colortrack/score_fall.hpp"

namespace colortrack {

namespace {

// A doubt starts where a tracked frame's score is under kFallenBelow and at least kFall under the running
// mean (rate kRecentRate) of the tracked frames before it, and ends at a tracked frame scoring kBackAt.
// Chosen offline on the tune half from per-frame dumps of the core harness (OPE + SRE + injected, offset
// 0,0), off-target frames reported `tracking` and the recall of `tracking`, tune / confirm: without 28.2 % /
// 17.8 %, recall 0.932 / 0.930; these values 2.7 % / 13.6 %, 0.910 / 0.909. Any score under 0.4 (no fall
// needed): 2.7 % / 12.6 %, recall 0.853 / 0.903, bag's right frames -41 % (docs/benchmarks.md).
constexpr double kFallenBelow = 0.4;
constexpr double kFall = 0.15;
constexpr double kBackAt = 0.6;
constexpr double kRecentRate = 0.1;

}  // namespace

void ScoreFall::reset() {
  recent_ = -1;
  fallen_ = false;
}

void ScoreFall::observe(double score, bool tracked) {
  if (!tracked) return;
  if (score < kFallenBelow && recent_ >= 0 && recent_ - score > kFall)
    fallen_ = true;
  else if (score >= kBackAt)
    fallen_ = false;
  recent_ = recent_ < 0 ? score : recent_ + kRecentRate * (score - recent_);
}

}  // namespace colortrack
