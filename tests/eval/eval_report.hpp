// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack-eval's results and what is written from them: the markdown tables, results.csv, curves.csv,
// the per-frame files, and the robustness summary's table.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "eval_pipeline.hpp"
#include "metrics.hpp"
#include "robustness.hpp"
#include "sequences.hpp"

namespace colortrack::eval {

// One run of one tracker, scored.
struct Evaluation {
  RunResult run;
  SequenceScore score;
  AlarmFigures alarm;
  bool hasStates = false;  // the tracker reported a state on some frame
  std::string warning;     // frame-count mismatch and the like; error text when the run failed
  bool ok = false;
};

struct EvalResults {
  std::vector<std::string> trackers;
  std::vector<std::string> formats;
  std::vector<bool> runOnce;            // per tracker: one run, copied under every format (cvtracker)
  std::vector<std::string> startNames;  // "ope", then the SRE starts
  std::vector<std::vector<std::vector<std::vector<Evaluation>>>> runs;  // [sequence][tracker][format][start]

  // What the tables show: each tracker in each format, a run-once tracker once.
  struct Column {
    std::size_t tracker, format;
    std::string label;
  };
  std::vector<Column> columns() const;
};

std::string fpsText(double fps);
// A file-name-safe form of a tracker fragment.
std::string slug(const std::string &text);

std::string markdownTables(const std::vector<Sequence> &sequences, const EvalResults &results);
void writeCsv(const std::filesystem::path &path, const std::vector<Sequence> &sequences,
              const EvalResults &results);
// Per-frame boxes, states and scores of one run, for looking into a tracker's failures. For an injected run
// `sequence` is the original: its ground truth, while the run's name says where the target was cut away or
// covered.
void writeFrames(const std::filesystem::path &path, const Sequence &sequence, const cv::Rect &start,
                 const RunResult &run);
// The folder under <out>/frames of one column's runs: the tracker's slug, and the format unless it runs once.
std::string framesFolder(const EvalResults &results, std::size_t tracker, std::size_t format);
// The OPE curves of every column, averaged over the sequences.
void writeCurves(const std::filesystem::path &path, const std::vector<std::string> &labels,
                 const std::vector<SequenceScore> &means);
RobustnessTable robustnessTable(const std::vector<Sequence> &sequences, const EvalResults &results);

// The machine, the plugin a factory comes from, the time: for the report's header.
std::string machineDescription();
std::string pluginOf(const char *factoryName);
std::string utcNow();

}  // namespace colortrack::eval
