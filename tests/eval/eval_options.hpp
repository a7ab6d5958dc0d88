// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack-eval's command line.
#pragma once

#include <string>
#include <vector>

namespace colortrack::eval {

extern const char *const kEvalUsage;

struct Options {
  bool help = false;  // -h / --help: the usage on stdout, exit 0
  std::vector<std::string> inputs;
  std::vector<std::string> trackers;
  std::vector<std::string> formats = {"BGRx", "I420"};
  bool sre = false;
  bool inject = false;                     // --inject: also runs with failures injected (injection.hpp)
  int startOffsetX = 0, startOffsetY = 0;  // --start-offset: added to every start box, in pixels
  bool allCvtracker = false;
  std::string outDir = "eval-out";
  double gtOrigin = 1.0;
  int openCvThreads = -1;
  bool writeFrames = true;
  bool useBuildPlugin = true;
  bool overhead = false;
  int overheadFrames = 300;
  int overheadRepeats = 3;
  std::string overheadTracker = "colortrack";
  std::string commandLine;
};

// Throws std::invalid_argument naming the problem (empty text for --help).
Options parseOptions(int argc, char **argv);

}  // namespace colortrack::eval
