// SPDX-License-Identifier: LGPL-2.1-or-later
// The robustness summary both evaluation tools print: OPE and SRE per sequence and per half, how far the
// scores move between pixel formats and between starts, and whether the tracker's own state can be trusted
// (alarm and re-acquisition figures). Plain text, no GStreamer.
#pragma once

#include <string>
#include <vector>

#include "metrics.hpp"

namespace colortrack::eval {

// One run of a tracker from one start box.
struct StartOutcome {
  bool ok = false;
  SequenceScore score;
  AlarmFigures alarm;
  bool hasStates = false;  // the tracker reported its state (colortrack): `alarm` means something
};

// One tracker on one sequence in one format: starts[0] is the OPE run, starts[1..] the SRE runs.
struct Cell {
  std::vector<StartOutcome> starts;
};

// The OPE AUC; NaN when that run failed.
double opeAuc(const Cell &cell);
// The SRE score: the mean AUC over the perturbed runs that did not fail; NaN when none ran.
double sreAuc(const Cell &cell);

struct RobustnessTable {
  std::vector<std::string> sequences;
  std::vector<std::string> startNames;  // "ope", then the SRE starts (when --sre)
  std::vector<std::string> trackers;
  std::vector<std::string> formats;  // one "" when the tool has no choice of format
  std::vector<bool> runOnce;         // per tracker: one run stands for every format (its input is the same)
  std::vector<std::vector<std::vector<Cell>>> cells;  // [sequence][tracker][format]

  bool sre() const { return startNames.size() > 1; }
};

// Mean OPE AUC (or SRE score) of one tracker and format over the sequences of each half and over all that
// ran; NaN for a half with none.
struct HalfMeans {
  double tune = 0, confirm = 0, all = 0;
  int tuneCount = 0, confirmCount = 0, allCount = 0;
};
HalfMeans halfMeans(const RobustnessTable &table, std::size_t tracker, std::size_t format, bool sre);

// Sequences whose score moves by more than this between formats or between starts are flagged.
constexpr double kFlagMove = 0.1;

std::string robustnessReport(const RobustnessTable &table);

}  // namespace colortrack::eval
