// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/start_likeness.hpp"

#include <algorithm>
#include <cmath>

namespace colortrack {

namespace {

// The start's usual match is the mean over the first kReferenceFrames matches (one frame's is too noisy, and
// a running mean follows the box onto whatever it slid to), and the score takes its ratio to the power
// kWeight. Chosen on the tune half (core harness, OPE + SRE + injected runs, offset 0,0, AUROC of the score
// tune / confirm / all): without 0.863 / 0.945 / 0.926; 20 frames 0.899 / 0.953 / 0.935; 40: 0.920 / 0.951 /
// 0.940; 80: 0.910 / 0.949 / 0.936 (all at 0.5); at 40 frames, weight 0.3: 0.916, 0.7: 0.914 on the tune
// half; a reference that follows the match (a running mean at rate 0.005-0.05) 0.815-0.853
// (docs/benchmarks-history.md).
constexpr int kReferenceFrames = 40;
constexpr double kWeight = 0.5;

}  // namespace

void StartLikeness::reset() {
  referenceSum_ = 0;
  referenceCount_ = 0;
  last_ = -1;
}

void StartLikeness::observe(double match) {
  last_ = match;
  if (referenceCount_ < kReferenceFrames) {
    referenceSum_ += match;
    ++referenceCount_;
  }
}

double StartLikeness::factor() const {
  if (last_ < 0 || referenceSum_ <= 0) return 1.0;
  const double reference = referenceSum_ / referenceCount_;
  return std::pow(std::min(1.0, last_ / reference), kWeight);
}

}  // namespace colortrack
