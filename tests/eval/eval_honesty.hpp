// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack-eval's honesty section (issue 46): for every tracker and format, the honesty report
// (honesty.hpp) over its plain runs and, with --inject, over runs with failures injected (injection.hpp).
// An injected run's frames are written once, as JPEG, to a temporary sequence folder that every tracker and
// format then reads through the same pipeline as the plain runs.
#pragma once

#include <string>
#include <vector>

#include "eval_options.hpp"
#include "eval_progress.hpp"
#include "eval_report.hpp"
#include "sequences.hpp"

namespace colortrack::eval {

// The markdown section. A tracker that reports no state (cvtracker) is taken as `tracking` whenever it
// gives a box and `lost` when it gives none, with a score of 0: that is how a robot acting on it would read
// it.
std::string honestySection(const std::vector<Sequence> &sequences, const EvalResults &results,
                           const Options &options, Progress &progress);

}  // namespace colortrack::eval
