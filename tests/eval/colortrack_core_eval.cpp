// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack-core-eval: accuracy and per-frame cost of colortrack::Tracker on OTB-layout sequences, without
// GStreamer. Meant for quick tuning loops: it runs the core tracker directly on the decoded JPEGs, several
// sequences at once.
//
//   colortrack-core-eval [--set key=value ...] [--split tune|confirm|all] [--sre] [--start-offset DX,DY]
//                        [--threads N] [--frames-out DIR] SEQ_DIR_OR_PARENT...
//
// A SEQ_DIR holds img/<n>.jpg and groundtruth.txt (or OTB's groundtruth_rect.txt); a folder of such folders
// stands for all of them (sorted by name). For example, from the project root:
//
//   build/tests/eval/colortrack-core-eval --set method=discriminative ../shared/sequences
//
// --set key=value   a TrackerSettings field: method=indexing|discriminative|fused, match-threshold,
//                   likelihood-threshold, model-update-rate, search-margin, max-coast-frames, process-noise,
//                   measurement-noise, adapt-aspect=0|1, verify=none|edge-density|edge-energy|both.
// --split           which half of the shared sequences to run (tuneSplit() / confirmSplit() in
// sequences.cpp);
//                   sequences in neither list run with `all` (the default) only.
// --sre             spatial robustness too: 8 more runs per sequence from perturbed frame-1 boxes (sre.hpp);
//                   a sequence's SRE score is the mean AUC of those 8 runs.
// --inject         also the injected failures of injection.hpp (cuts, covers, a crossing copy of the target),
//                   each from the OPE start; the honesty report (honesty.hpp) then covers them too.
// --start-offset DX,DY  every start box (OPE and SRE) moved by whole pixels before the run. The means move
//                   by about 0.01 (SRE) to 0.05 (OPE) for a 1 px offset, so a change smaller than that
//                   spread, judged at one offset, is not yet a result (docs/benchmarks-history.md, noise floor).
// --threads N       runs processed in parallel, one Tracker per run (default 2). OpenCV runs
//                   single-threaded (cv::setNumThreads(1)), so the per-frame times are those of one core.
// --frames-out DIR  DIR/<sequence>.csv (SRE runs: DIR/<sequence>.<start>.csv): frame,x,y,w,h,state,score
//                   (the scored box; empty fields for a miss).
//
// The protocol is colortrack-eval's (OTB one-pass evaluation), so its figures compare with that tool's:
// - ground-truth x and y are shifted by 1 (OTB's 1-based boxes) into 0-based pixels; w and h are kept;
// - the init box is the shifted frame-1 box rounded to whole pixels and clipped to the frame, and frame 1 is
//   scored with it;
// - frames 2.. are scored with the tracker's box when it has one (TrackOutput::hasBox), rounded and clipped
//   to the frame as the element does before publishing it; no box, or a box outside the frame, is a miss;
// - frames without ground truth (NaN, no area) are not scored; success AUC and precision at 20 px come from
//   metrics.hpp, and the means weigh every sequence equally.
// Per-frame times cover Tracker::process() only (not decoding, not the frame-1 initialisation). "lost" counts
// the frames whose state is TrackState::Lost.
//
// Output: one row per sequence (the OPE run), the robustness summary (robustness.hpp: OPE and SRE per
// sequence and half, sequences that move between starts, alarm and re-acquisition figures from the states),
// the mean OPE AUC of each half and of all (over the sequences that ran), and last a machine-readable line
//   MEAN tune=%.4f confirm=%.4f all=%.4f
// with, after --sre only, " sre_tune=%.4f sre_confirm=%.4f sre_all=%.4f" appended (the mean SRE scores);
// "nan" for a half with no sequence. The first three fields keep their place and meaning with or without
// --sre. Exit status: 0, 1 when a sequence failed or could not be loaded, 2 for a bad command line.

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "colortrack/image_source.hpp"
#include "colortrack/detection_method.hpp"
#include "colortrack/tracker.hpp"
#include "honesty.hpp"
#include "injection.hpp"
#include "metrics.hpp"
#include "robustness.hpp"
#include "sequences.hpp"
#include "sre.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace colortrack::eval {
namespace {

// Subtracted from ground-truth x and y: OTB boxes are 1-based (MATLAB), as in colortrack-eval's default.
constexpr double kGtOrigin = 1.0;

constexpr const char *kUsage =
    "usage: colortrack-core-eval [--set key=value ...] [--split tune|confirm|all] [--sre] [--inject]\n"
    "                            [--start-offset DX,DY]\n"
    "                            [--threads N] [--frames-out DIR] SEQ_DIR_OR_PARENT...\n"
    "\n"
    "  SEQ_DIR_OR_PARENT   OTB layout (img/*.jpg + groundtruth.txt), or a folder of such folders\n"
    "  --set key=value     tracker setting: method=indexing|discriminative|fused, match-threshold,\n"
    "                      likelihood-threshold, model-update-rate, search-margin, max-coast-frames,\n"
    "                      process-noise, measurement-noise, adapt-aspect=0|1,\n"
    "                      verify=none|edge-density|edge-energy|both (repeatable)\n"
    "  --split S           tune, confirm or all (default all)\n"
    "  --sre               also 8 runs per sequence from perturbed start boxes (spatial robustness)\n"
    "  --inject            also runs with injected failures: cuts, covers, a crossing copy\n"
    "  --start-offset DX,DY  every start box moved by DX, DY whole pixels (the noise floor)\n"
    "  --threads N         runs in parallel (default 2)\n"
    "  --frames-out DIR    per-frame boxes and states in DIR/<sequence>.csv\n";

// A command-line error: usage text, exit status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class Split { Tune, Confirm, All };

struct Options {
  TrackerSettings settings;
  Split split = Split::All;
  bool sre = false;
  bool inject = false;
  cv::Point startOffset;  // added to every start box
  int threads = 2;
  std::string framesOut;
  std::vector<std::string> inputs;
};

// One run: a sequence from one start box, or from the OPE start with a failure injected.
struct Job {
  std::size_t sequence = 0;
  std::size_t start = 0;  // 0: OPE (and every injected run)
  StartBox box;
  std::optional<Injection> injection;
};

// What one run produced.
struct Result {
  StartOutcome outcome;
  std::string error;
  std::string warning;
  int frames = 0;
  double medianMs = 0, meanMs = 0, maxMs = 0;
  int lostFrames = 0;
  std::vector<FrameTruth> truth;  // per frame, for the honesty report
  std::vector<FrameReport> reports;
};

// ---------------------------------------------------------------------------------------------------------
// Small helpers

bool contains(const std::vector<std::string> &list, const std::string &name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

// ---------------------------------------------------------------------------------------------------------
// Command line

double parseNumber(const std::string &key, const std::string &value) {
  std::size_t used = 0;
  double number = 0;
  try {
    number = std::stod(value, &used);
  } catch (const std::exception &) {
    used = 0;
  }
  if (used == 0 || used != value.size() || !std::isfinite(number))
    throw UsageError("--set " + key + ": '" + value + "' is not a number");
  return number;
}

int parseInteger(const std::string &what, const std::string &value) {
  std::size_t used = 0;
  int number = 0;
  try {
    number = std::stoi(value, &used);
  } catch (const std::exception &) {
    used = 0;
  }
  if (used == 0 || used != value.size()) throw UsageError(what + ": '" + value + "' is not an integer");
  return number;
}

// "DX,DY" in whole pixels; `option` names the flag in the error.
cv::Point parseOffset(const std::string &option, const std::string &text) {
  const std::optional<cv::Point> offset = parseStartOffset(text);
  if (!offset) throw UsageError(option + " expects DX,DY in whole pixels, got '" + text + "'");
  return *offset;
}

// Splits "key=value"; `option` names the flag in the error.
std::pair<std::string, std::string> splitAssignment(const std::string &option, const std::string &text) {
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos || eq == 0) throw UsageError(option + " expects key=value, got '" + text + "'");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

void applySetting(TrackerSettings &s, const std::string &key, const std::string &value) {
  if (key == "method") {
    std::string names;
    for (const MethodDescriptor &d : methodDescriptors()) {
      if (value == d.nick) {
        s.method = d.value;
        return;
      }
      names += std::string(names.empty() ? "" : ", ") + d.nick;
    }
    throw UsageError("--set method: '" + value + "' is not one of " + names);
  } else if (key == "match-threshold") {
    s.matchThreshold = parseNumber(key, value);
  } else if (key == "likelihood-threshold") {
    s.likelihoodThreshold = parseNumber(key, value);
  } else if (key == "model-update-rate") {
    s.modelUpdateRate = parseNumber(key, value);
  } else if (key == "search-margin") {
    s.searchMargin = parseNumber(key, value);
  } else if (key == "max-coast-frames") {
    s.maxCoastFrames = parseInteger("--set " + key, value);
  } else if (key == "process-noise") {
    s.kalman.processNoise = parseNumber(key, value);
  } else if (key == "measurement-noise") {
    s.kalman.measurementNoise = parseNumber(key, value);
  } else if (key == "adapt-aspect") {
    if (value != "0" && value != "1") throw UsageError("--set adapt-aspect: '" + value + "' is not 0 or 1");
    s.adaptAspect = value == "1";
  } else if (key == "verify") {
    if (value == "none")
      s.verify = VerifyMode::None;
    else if (value == "edge-density")
      s.verify = VerifyMode::EdgeDensity;
    else if (value == "edge-energy")
      s.verify = VerifyMode::EdgeEnergy;
    else if (value == "both")
      s.verify = VerifyMode::Both;
    else
      throw UsageError("--set verify: '" + value + "' is not none, edge-density, edge-energy or both");
  } else {
    throw UsageError("--set: unknown key '" + key + "'");
  }
}

Options parseOptions(int argc, char **argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) throw UsageError(arg + " needs a value");
      return argv[++i];
    };
    if (arg == "-h" || arg == "--help") {
      std::fputs(kUsage, stdout);
      std::exit(0);
    } else if (arg == "--set") {
      const auto [key, value] = splitAssignment(arg, next());
      applySetting(options.settings, key, value);
    } else if (arg == "--split") {
      const std::string value = next();
      if (value == "tune")
        options.split = Split::Tune;
      else if (value == "confirm")
        options.split = Split::Confirm;
      else if (value == "all")
        options.split = Split::All;
      else
        throw UsageError("--split: '" + value + "' is not tune, confirm or all");
    } else if (arg == "--sre") {
      options.sre = true;
    } else if (arg == "--inject") {
      options.inject = true;
    } else if (arg == "--start-offset") {
      options.startOffset = parseOffset(arg, next());
    } else if (arg == "--threads") {
      options.threads = parseInteger(arg, next());
      if (options.threads < 1) throw UsageError("--threads must be at least 1");
    } else if (arg == "--frames-out") {
      options.framesOut = next();
    } else if (!arg.empty() && arg[0] == '-') {
      throw UsageError("unknown option " + arg);
    } else {
      options.inputs.push_back(arg);
    }
  }
  if (options.inputs.empty()) throw UsageError("no sequence given");
  return options;
}

bool selected(const Sequence &sequence, Split split) {
  switch (split) {
    case Split::Tune:
      return contains(tuneSplit(), sequence.name);
    case Split::Confirm:
      return contains(confirmSplit(), sequence.name);
    case Split::All:
      return true;
  }
  return false;
}

// ---------------------------------------------------------------------------------------------------------
// Tracking

// The box as the element publishes it: rounded to whole pixels, clipped to the frame.
cv::Rect roundedClippedBox(const cv::Rect2d &box, cv::Size frame) {
  const int x0 = static_cast<int>(std::lround(box.x)), y0 = static_cast<int>(std::lround(box.y));
  const int x1 = static_cast<int>(std::lround(box.x + box.width));
  const int y1 = static_cast<int>(std::lround(box.y + box.height));
  return cv::Rect(cv::Point(x0, y0), cv::Point(x1, y1)) & cv::Rect(cv::Point(), frame);
}

double median(std::vector<double> values) {
  if (values.empty()) return 0;
  const auto middle = values.begin() + values.size() / 2;
  std::nth_element(values.begin(), middle, values.end());
  if (values.size() % 2 == 1) return *middle;
  return (*middle + *std::max_element(values.begin(), middle)) / 2;
}

void writeFrames(const fs::path &path, const std::vector<std::optional<cv::Rect2d>> &boxes,
                 const std::vector<std::string> &states, const std::vector<double> &scores) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error("cannot write " + path.string());
  out << "frame,x,y,w,h,state,score\n";
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    out << i + 1;
    if (boxes[i])
      out << format(",%.0f,%.0f,%.0f,%.0f", boxes[i]->x, boxes[i]->y, boxes[i]->width, boxes[i]->height);
    else
      out << ",,,,";
    out << "," << states[i] << format(",%.3f", scores[i]) << "\n";
  }
}

void setTimes(Result &result, const std::vector<double> &processMs) {
  result.medianMs = median(processMs);
  // The mean is what decides throughput: re-detection frames cost several times a tracking frame.
  result.meanMs =
      processMs.empty() ? 0 : std::accumulate(processMs.begin(), processMs.end(), 0.0) / processMs.size();
  result.maxMs = processMs.empty() ? 0 : *std::max_element(processMs.begin(), processMs.end());
}

Result runSequence(const std::vector<Sequence> &sequences, const Job &job, const Options &options) {
  Result result;
  const Sequence &sequence = sequences[job.sequence];
  const StartBox &start = job.box;
  try {
    const int frames = sequence.pattern.count;
    const FrameReader read = [&](std::size_t s, int i) { return readSequenceFrame(sequences, s, i); };
    std::optional<InjectedRun> injected;
    if (job.injection) injected.emplace(sequences, job.sequence, *job.injection);
    result.truth = injected ? injected->truth() : plainTruth(sequence);
    std::vector<std::optional<cv::Rect2d>> boxes;  // scored box per frame
    std::vector<std::string> states;
    std::vector<double> scores, processMs;

    Tracker tracker(options.settings);
    for (int i = 0; i < frames; ++i) {
      const cv::Mat image = injected ? injected->frame(i, read) : read(job.sequence, i);
      const MatImageSource source(image);
      if (i == 0) {
        tracker.setTemplateFromBox(source, start.box);
        boxes.emplace_back(cv::Rect2d(start.box));  // frame 1's result is the start box (OTB)
        states.emplace_back("init");
        scores.push_back(0);
        result.reports.push_back({cv::Rect2d(start.box), "init", 0});
        continue;
      }
      const Clock::time_point begin = Clock::now();
      const TrackOutput out = tracker.process(source);
      processMs.push_back(std::chrono::duration<double, std::milli>(Clock::now() - begin).count());

      const cv::Rect box = out.hasBox ? roundedClippedBox(out.box, image.size()) : cv::Rect();
      boxes.push_back(box.empty() ? std::nullopt : std::optional<cv::Rect2d>(cv::Rect2d(box)));
      states.emplace_back(toString(out.state));
      scores.push_back(out.score);
      result.reports.push_back({boxes.back(), states.back(), out.score});
      if (out.state == TrackState::Lost) ++result.lostFrames;
    }

    result.frames = frames;
    result.outcome.score = scoreSequence(sequence.groundTruth, boxes);
    result.outcome.alarm = alarmFigures(sequence.groundTruth, boxes, states, sequence.frameSize);
    if (injected) result.outcome.alarm = AlarmFigures();  // injected runs are judged by the honesty report
    result.outcome.hasStates = true;
    setTimes(result, processMs);
    if (frames != static_cast<int>(sequence.groundTruth.size()))
      result.warning = format("%d frames, %zu ground-truth lines", frames, sequence.groundTruth.size());
    if (!options.framesOut.empty()) {
      const std::string name = sequence.name + (start.name == "ope" ? "" : "." + start.name) + ".csv";
      writeFrames(fs::path(options.framesOut) / name, boxes, states, scores);
    }
    result.outcome.ok = true;
  } catch (const TrackerError &e) {
    result.error = std::string("TrackerError: ") + e.what();
  } catch (const std::exception &e) {
    result.error = e.what();
  }
  return result;
}

// Runs every job on `threads` workers, each taking the next job not yet started.
std::vector<Result> runAll(const std::vector<Sequence> &sequences, const std::vector<Job> &jobs,
                           const Options &options) {
  std::vector<Result> results(jobs.size());
  std::atomic<std::size_t> nextIndex{0};
  std::mutex printMutex;
  auto worker = [&]() {
    for (std::size_t i = nextIndex++; i < jobs.size(); i = nextIndex++) {
      const Sequence &sequence = sequences[jobs[i].sequence];
      results[i] = runSequence(sequences, jobs[i], options);
      const std::lock_guard<std::mutex> lock(printMutex);
      std::fprintf(stderr, "  %-14s %-10s %s\n", sequence.name.c_str(), jobs[i].box.name.c_str(),
                   results[i].outcome.ok ? format("AUC %.3f", results[i].outcome.score.auc).c_str()
                                         : ("FAILED: " + results[i].error).c_str());
    }
  };
  const int count = static_cast<int>(std::min<std::size_t>(options.threads, jobs.size()));
  std::vector<std::thread> threads;
  for (int t = 0; t < count; ++t) threads.emplace_back(worker);
  for (std::thread &thread : threads) thread.join();
  return results;
}

// ---------------------------------------------------------------------------------------------------------

// Every sequence from its OPE start and, with --sre, from the perturbed ones; each moved by `offset`. With
// `inject`, the injected runs follow (after every plain run, so the robustness table's jobs come first).
std::vector<Job> makeJobs(const std::vector<Sequence> &sequences, bool sre, bool inject, cv::Point offset) {
  std::vector<Job> jobs;
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    const cv::Rect2d first = *sequences[s].groundTruth[0] + cv::Point2d(offset);
    const std::vector<StartBox> starts = startBoxes(first, sequences[s].frameSize, sre);
    for (std::size_t i = 0; i < starts.size(); ++i) jobs.push_back({s, i, starts[i], std::nullopt});
  }
  if (!inject) return jobs;
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    const cv::Rect2d first = *sequences[s].groundTruth[0] + cv::Point2d(offset);
    StartBox ope = startBoxes(first, sequences[s].frameSize, false).front();
    for (const Injection &injection : planInjections(sequences, s)) {
      ope.name = injection.name;
      jobs.push_back({s, 0, ope, injection});
    }
  }
  return jobs;
}

// Every run's frames, truth and reports, for the honesty report.
std::vector<RunRecord> runRecords(const std::vector<Sequence> &sequences, const std::vector<Job> &jobs,
                                  std::vector<Result> &results) {
  std::vector<RunRecord> records;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (!results[i].outcome.ok) continue;
    const std::string &name = sequences[jobs[i].sequence].name;
    records.push_back({name, halfOf(name), jobs[i].box.name, jobs[i].injection, std::move(results[i].truth),
                       std::move(results[i].reports)});
  }
  return records;
}

// The results as the robustness summary's table: one tracker (the core one), no formats.
RobustnessTable makeTable(const std::vector<Sequence> &sequences, const std::vector<Job> &jobs,
                          const std::vector<Result> &results) {
  RobustnessTable table;
  for (const Sequence &sequence : sequences) table.sequences.push_back(sequence.name);
  for (const Job &job : jobs)
    if (job.sequence == 0 && !job.injection) table.startNames.push_back(job.box.name);
  table.trackers = {"colortrack (core)"};
  table.formats = {""};
  table.runOnce = {false};
  Cell empty;
  empty.starts.resize(table.startNames.size());
  table.cells.assign(sequences.size(), std::vector<std::vector<Cell>>(1, std::vector<Cell>(1, empty)));
  for (std::size_t i = 0; i < jobs.size(); ++i)
    if (!jobs[i].injection) table.cells[jobs[i].sequence][0][0].starts[jobs[i].start] = results[i].outcome;
  return table;
}

// The OPE run of each sequence: accuracy, times, lost frames.
bool printOpeRows(const std::vector<Sequence> &sequences, const std::vector<Job> &jobs,
                  const std::vector<Result> &results) {
  std::printf("%-14s %-7s %6s %6s %6s %8s %8s %8s %5s\n", "sequence", "half", "frames", "AUC", "P@20",
              "med ms", "mean ms", "max ms", "lost");
  bool failed = false;
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    const Result &r = results[i];
    failed = failed || !r.outcome.ok;
    if (jobs[i].start != 0 || jobs[i].injection) continue;
    const Sequence &s = sequences[jobs[i].sequence];
    if (!r.outcome.ok) {
      std::printf("%-14s %-7s FAILED: %s\n", s.name.c_str(), halfOf(s.name), r.error.c_str());
      continue;
    }
    std::printf("%-14s %-7s %6d %6.3f %6.3f %8.2f %8.2f %8.2f %5d%s\n", s.name.c_str(), halfOf(s.name),
                r.frames, r.outcome.score.auc, r.outcome.score.precisionAt20, r.medianMs, r.meanMs, r.maxMs,
                r.lostFrames, r.warning.empty() ? "" : ("  (" + r.warning + ")").c_str());
  }
  return failed;
}

int run(int argc, char **argv) {
  const Options options = parseOptions(argc, argv);
  cv::setNumThreads(1);

  std::vector<Sequence> sequences;
  for (Sequence &sequence : findSequences(options.inputs, kGtOrigin))
    if (selected(sequence, options.split)) sequences.push_back(std::move(sequence));
  if (sequences.empty()) throw std::runtime_error("no sequence of the chosen split among the inputs");
  if (!options.framesOut.empty()) fs::create_directories(options.framesOut);

  const std::vector<Job> jobs = makeJobs(sequences, options.sre, options.inject, options.startOffset);
  const Clock::time_point start = Clock::now();
  std::vector<Result> results = runAll(sequences, jobs, options);
  const double wallSeconds = std::chrono::duration<double>(Clock::now() - start).count();

  const bool failed = printOpeRows(sequences, jobs, results);
  const RobustnessTable table = makeTable(sequences, jobs, results);
  std::printf("\n%s", robustnessReport(table).c_str());
  std::printf("\n%s", honestyReport(runRecords(sequences, jobs, results)).c_str());

  const HalfMeans ope = halfMeans(table, 0, 0, false);
  std::printf("\n");
  std::printf("mean AUC tune     %.3f  (%d sequences)\n", ope.tune, ope.tuneCount);
  std::printf("mean AUC confirm  %.3f  (%d sequences)\n", ope.confirm, ope.confirmCount);
  std::printf("mean AUC all      %.3f  (%d sequences)\n", ope.all, ope.allCount);
  std::printf("wall time %.1f s, %zu runs, %d thread%s\n", wallSeconds, jobs.size(), options.threads,
              options.threads == 1 ? "" : "s");
  std::string mean = format("MEAN tune=%.4f confirm=%.4f all=%.4f", ope.tune, ope.confirm, ope.all);
  if (options.sre) {
    const HalfMeans sre = halfMeans(table, 0, 0, true);
    mean += format(" sre_tune=%.4f sre_confirm=%.4f sre_all=%.4f", sre.tune, sre.confirm, sre.all);
  }
  std::printf("%s\n", mean.c_str());
  return failed ? 1 : 0;
}

}  // namespace
}  // namespace colortrack::eval

int main(int argc, char **argv) {
  try {
    return colortrack::eval::run(argc, argv);
  } catch (const colortrack::eval::UsageError &e) {
    std::fprintf(stderr, "colortrack-core-eval: %s\n\n%s", e.what(), colortrack::eval::kUsage);
    return 2;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "colortrack-core-eval: %s\n", e.what());
    return 1;
  }
}
