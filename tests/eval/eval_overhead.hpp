// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack-eval --overhead: what the tracker costs at 1920x1080 next to identity, on a synthetic sequence.
#pragma once

#include <string>

#include "eval_options.hpp"
#include "eval_progress.hpp"

namespace colortrack::eval {

// Renders the synthetic scene as JPEGs in a temporary directory, runs decode + identity and decode + the
// tracker (with and without drawing) interleaved, and returns a markdown section with the medians.
std::string measureOverhead(const Options &options, Progress &progress);

}  // namespace colortrack::eval
