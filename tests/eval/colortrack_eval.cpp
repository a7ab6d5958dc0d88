// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack-eval: accuracy and speed of GStreamer tracker elements on OTB-layout sequences, side by side.
//
//   colortrack-eval [options] SEQUENCE_DIR... --tracker FRAGMENT [--tracker FRAGMENT ...]
//                   [--formats BGRx,I420] [--sre] [--inject] [--start-offset DX,DY]
//
// A SEQUENCE_DIR holds img/<n>.jpg and groundtruth.txt (or OTB's groundtruth_rect.txt); a folder of such
// folders stands for all of them. Each tracker is a gst-launch fragment whose last element is the tracker,
// e.g. "colortrack" or "cvtracker algorithm=CSRT". For every sequence and tracker a real pipeline runs:
//
//   multifilesrc location=<dir>/img/%04d.jpg start-index=<first> stop-index=<last>
//       caps=image/jpeg,framerate=30/1 ! jpegdec ! videoconvert ! video/x-raw,format=F ! <fragment>
//       ! appsink sync=false
//
// once for each format F of --formats (default BGRx,I420), so a tracker is measured on the pixel layouts it
// will meet. cvtracker negotiates its own input (it takes RGB only), so it runs without the caps filter,
// once per sequence and start, and that one result stands in every format column ("[own caps]").
// --sre adds OTB's spatial robustness evaluation: 8 more runs per sequence from perturbed frame-1 boxes
// (sre.hpp); the SRE score of a sequence is the mean AUC of those 8 runs. --start-offset DX,DY moves every
// start box by whole pixels for every tracker alike: a 1 px shift moves the means by up to 0.015 (SRE). The
// robustness summary (robustness.hpp) ends the report: OPE and SRE per sequence and half, the spread between
// formats, the sequences that move by more than 0.1, and colortrack's alarm and re-acquisition figures,
// computed from the state it reports per frame (its element message, post-messages=true, else its ROI meta's
// params). The honesty section (eval_honesty.hpp) follows: off-target frames reported `tracking`, the AUROC
// of the score, and with --inject what each tracker does through failures injected into the sequences (a
// cut, a cover, a copy of the target crossing it; injection.hpp).
//
// The tracker is initialised with frame 1's ground-truth box (or a perturbed one, --sre) (colortrack:
// init-box; cvtracker: object-initial-x/y/width/height) and every buffer reaching the appsink is scored by
// its GstVideoRegionOfInterestMeta (colortrack: type "colortrack", cvtracker: "object", any other element:
// its first ROI meta). A buffer without one is a miss. Drawing is switched off (colortrack draw=0, cvtracker
// draw-rect=false) unless the fragment sets it, and so is QoS, so no frame is dropped.
//
// Conventions, chosen to match the OTB toolkit (Wu, Lim, Yang, "Online Object Tracking: A Benchmark"):
// - Ground truth is 1-based as published (MATLAB); x and y are shifted by --gt-origin (default 1) into the
//   0-based pixel coordinates the elements use, for initialisation and scoring alike. w and h are kept.
// - The init box is the shifted frame-1 box (SRE: perturbed) rounded to whole pixels and clipped to the
//   frame; frame 1 is scored with that box for every tracker (its result by definition, as in OTB), frames
//   2.. with the meta.
// - Frames whose ground truth is NaN or has no area are left out of the scores.
// - Success AUC = mean over IoU thresholds 0, 0.05, ..., 1 of the fraction of frames with IoU > threshold;
//   precision = fraction of frames with centre error <= 20 px. The mean row averages sequences equally.
// - ROI meta coordinates are guint; they are read back as signed 32-bit, since cvtracker casts negative
//   positions (box partly left of or above the frame) to guint.
// - fps pipeline = frames / wall time from setting PLAYING to the appsink's EOS (decoding included).
//   fps element = frames / time spent inside the tracker element: for each buffer, the time between its
//   arrival at the element's sink pad and its departure from the src pad (pad probes, same thread), summed.
//   It includes everything the element does per frame (colortrack's colour conversion, cvtracker's wrap of
//   the frame) and, on frame 1, initialisation and caps negotiation.
//
// --overhead renders a 1920x1080 JPEG sequence of the synthetic scene into a temporary directory and compares
// `... ! jpegdec ! videoconvert ! colortrack ! appsink` with the same pipeline with identity in its place.

#include <gst/gst.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "eval_honesty.hpp"
#include "eval_options.hpp"
#include "eval_overhead.hpp"
#include "eval_pipeline.hpp"
#include "eval_plot.hpp"
#include "eval_progress.hpp"
#include "eval_report.hpp"
#include "metrics.hpp"
#include "robustness.hpp"
#include "sequences.hpp"
#include "sre.hpp"

namespace fs = std::filesystem;

namespace colortrack::eval {
namespace {

// Puts this build's plugin first on the plugin path, so the colortrack just built is the one measured.
void useBuildPlugin() {
#ifdef COLORTRACK_EVAL_PLUGIN_DIR
  if (!fs::is_directory(COLORTRACK_EVAL_PLUGIN_DIR)) return;
  // GST_PLUGIN_PATH_1_0, when set, replaces GST_PLUGIN_PATH.
  const char *variable = g_getenv("GST_PLUGIN_PATH_1_0") ? "GST_PLUGIN_PATH_1_0" : "GST_PLUGIN_PATH";
  const char *current = g_getenv(variable);
  const std::string value =
      std::string(COLORTRACK_EVAL_PLUGIN_DIR) + (current && *current ? std::string(":") + current : "");
  g_setenv(variable, value.c_str(), TRUE);
#endif
}

Evaluation evaluate(const Sequence &sequence, const PipelineRequest &request, const std::string &label,
                    Progress &progress) {
  Evaluation evaluation;
  const int expected = static_cast<int>(sequence.groundTruth.size());
  evaluation.run = runPipeline(sequence, request, [&](int frames) {
    progress.update(format("%s  frame %d/%d", label.c_str(), frames, expected));
  });
  RunResult &run = evaluation.run;
  if (!run.error.empty()) {
    evaluation.warning = run.error;
    return evaluation;
  }
  std::vector<std::optional<cv::Rect2d>> scored = run.boxes;
  if (!scored.empty()) scored[0] = cv::Rect2d(*request.initBox);  // frame 1's result is the start box (OTB)
  evaluation.score = scoreSequence(sequence.groundTruth, scored);
  evaluation.hasStates =
      std::any_of(run.states.begin(), run.states.end(), [](const std::string &s) { return !s.empty(); });
  if (evaluation.hasStates)
    evaluation.alarm = alarmFigures(sequence.groundTruth, scored, run.states, sequence.frameSize);
  if (run.frames() != expected)
    evaluation.warning = format("%d frames received, %d ground-truth lines", run.frames(), expected);
  evaluation.ok = true;
  return evaluation;
}

// Runs counted for the progress label: a run-once tracker runs once per start, the others once per format.
int countRuns(const std::vector<Sequence> &sequences, const EvalResults &results) {
  int perStart = 0;
  for (std::size_t t = 0; t < results.trackers.size(); ++t)
    perStart += results.runOnce[t] ? 1 : static_cast<int>(results.formats.size());
  return static_cast<int>(sequences.size() * results.startNames.size()) * perStart;
}

std::string framesPath(const EvalResults &results, std::size_t t, std::size_t f, const Sequence &sequence,
                       std::size_t start) {
  const std::string dir = framesFolder(results, t, f);
  const std::string name = start == 0 ? sequence.name : sequence.name + "." + results.startNames[start];
  return dir + "/" + name + ".csv";
}

// Every tracker on every sequence from every start, in every format (a run-once tracker once, copied).
EvalResults evaluateAll(const std::vector<Sequence> &sequences, const std::vector<std::string> &trackers,
                        const Options &options, Progress &progress) {
  EvalResults results;
  results.trackers = trackers;
  results.formats = options.formats;
  for (const std::string &fragment : trackers)
    results.runOnce.push_back(trackerFactory(fragment) == "cvtracker");
  const cv::Point2d offset(options.startOffsetX, options.startOffsetY);
  for (const StartBox &start :
       startBoxes(*sequences[0].groundTruth[0] + offset, sequences[0].frameSize, options.sre))
    results.startNames.push_back(start.name);
  const int runs = countRuns(sequences, results);
  int done = 0;
  results.runs.resize(sequences.size());
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    const Sequence &seq = sequences[s];
    const std::vector<StartBox> starts = startBoxes(*seq.groundTruth[0] + offset, seq.frameSize, options.sre);
    results.runs[s].assign(
        trackers.size(),
        std::vector<std::vector<Evaluation>>(results.formats.size(), std::vector<Evaluation>(starts.size())));
    for (std::size_t t = 0; t < trackers.size(); ++t) {
      const std::size_t formats = results.runOnce[t] ? 1 : results.formats.size();
      for (std::size_t f = 0; f < formats; ++f)
        for (std::size_t i = 0; i < starts.size(); ++i) {
          const std::string format_ = results.runOnce[t] ? "" : results.formats[f];
          const std::string label =
              format("[%d/%d] %s %s  %s [%s]", ++done, runs, seq.name.c_str(), starts[i].name.c_str(),
                     trackers[t].c_str(), format_.empty() ? "own caps" : format_.c_str());
          Evaluation &e = results.runs[s][t][f][i];
          e = evaluate(seq, {trackers[t], format_, starts[i].box, false}, label, progress);
          if (e.ok)
            progress.finish(format("%s  AUC %.3f  P@20 %.3f  %s fps pipeline  %s fps element%s%s",
                                   label.c_str(), e.score.auc, e.score.precisionAt20,
                                   fpsText(e.run.pipelineFps()).c_str(), fpsText(e.run.elementFps()).c_str(),
                                   e.warning.empty() ? "" : "  WARNING: ", e.warning.c_str()));
          else
            progress.finish(format("%s  FAILED: %s", label.c_str(), e.warning.c_str()));
          if (options.writeFrames)
            writeFrames(fs::path(options.outDir) / "frames" / framesPath(results, t, f, seq, i), seq,
                        starts[i].box, e.run);
        }
      // cvtracker's input does not depend on the format: its one run stands in every column.
      for (std::size_t f = formats; f < results.formats.size(); ++f)
        results.runs[s][t][f] = results.runs[s][t][0];
    }
  }
  return results;
}

// The tables, results.csv, curves.csv, the plots and the robustness summary; returns the markdown.
std::string writeResults(const std::vector<Sequence> &sequences, const EvalResults &results,
                         const fs::path &outDir) {
  std::string md = markdownTables(sequences, results);
  writeCsv(outDir / "results.csv", sequences, results);
  std::vector<std::string> labels;
  std::vector<SequenceScore> means;
  std::vector<Curve> success, precision;
  for (const EvalResults::Column &c : results.columns()) {
    std::vector<SequenceScore> scores;
    for (std::size_t s = 0; s < sequences.size(); ++s)
      if (results.runs[s][c.tracker][c.format].front().ok)
        scores.push_back(results.runs[s][c.tracker][c.format].front().score);
    labels.push_back(c.label);
    means.push_back(averageScores(scores));
    success.push_back({c.label, means.back().success, means.back().auc});
    precision.push_back({c.label, means.back().precision, means.back().precisionAt20});
  }
  writeCurves(outDir / "curves.csv", labels, means);
  const std::string over = format("%zu sequence%s", sequences.size(), sequences.size() == 1 ? "" : "s");
  drawPlot("Success plots of OPE (" + over + ")", "Overlap threshold", 1.0, 0.1, "%.1f", success,
           outDir / "success.png");
  drawPlot("Precision plots of OPE (" + over + ")", "Location error threshold (px)", 50.0, 5.0, "%.0f",
           precision, outDir / "precision.png");
  md += "\n![success](success.png) ![precision](precision.png)\n";
  md += "\n### Robustness\n\n```\n" + robustnessReport(robustnessTable(sequences, results)) + "```\n";
  return md;
}

std::string reportHeader(const Options &options, bool haveSequences) {
  std::ostringstream header;
  header << "# colortrack-eval results\n\n"
         << "- Date: " << utcNow() << "\n"
         << "- Machine: " << machineDescription() << "\n"
         << "- colortrack plugin: " << pluginOf("colortrack") << "\n"
         << "- cvtracker plugin: " << pluginOf("cvtracker") << "\n"
         << "- Command: `" << options.commandLine << "`\n";
  if (haveSequences) {
    header << "- Protocol: OTB one-pass evaluation, initialised with frame 1's ground truth (x, y minus "
           << options.gtOrigin
           << " into 0-based pixels); frames without ground truth are not scored; a frame "
              "without the tracker's ROI meta is a miss.\n";
    std::string formats;
    for (const std::string &f : options.formats) formats += (formats.empty() ? "" : ", ") + f;
    header << "- Formats forced before the tracker: " << formats
           << " (cvtracker: its own caps, one run per sequence and start, shown under every format)\n";
    if (options.sre)
      header << "- SRE: 8 more runs per sequence from the frame-1 box shifted by 10 % left, right, up, down, "
                "up-left, down-right and scaled by 0.9 and 1.1; SRE score = their mean AUC\n";
  }
  return header.str() + "\n";
}

int run(int argc, char **argv) {
  Options options;
  try {
    options = parseOptions(argc, argv);
  } catch (const std::invalid_argument &e) {
    if (*e.what()) std::fprintf(stderr, "colortrack-eval: %s\n\n", e.what());
    std::fputs(kEvalUsage, stderr);
    return 2;
  }
  if (options.help) {
    std::fputs(kEvalUsage, stdout);
    return 0;
  }
  if (options.useBuildPlugin) useBuildPlugin();
  gst_init(nullptr, nullptr);
  if (options.openCvThreads > 0) cv::setNumThreads(options.openCvThreads);

  std::vector<std::string> trackers = options.trackers;
  if (options.allCvtracker)
    for (const std::string &fragment : cvtrackerFragments())
      if (std::find(trackers.begin(), trackers.end(), fragment) == trackers.end())
        trackers.push_back(fragment);

  const std::vector<Sequence> sequences = findSequences(options.inputs, options.gtOrigin);
  const fs::path outDir(options.outDir);
  fs::create_directories(outDir);
  Progress progress;

  std::string body;
  if (!sequences.empty()) {
    const EvalResults results = evaluateAll(sequences, trackers, options, progress);
    body = writeResults(sequences, results, outDir) + honestySection(sequences, results, options, progress);
  }
  if (options.overhead) body += (sequences.empty() ? "" : "\n") + measureOverhead(options, progress);

  const std::string report = reportHeader(options, !sequences.empty()) + body;
  std::fputs(report.c_str(), stdout);
  std::ofstream(outDir / "results.md") << report;
  std::fprintf(stderr, "written to %s/\n", outDir.string().c_str());
  return 0;
}

}  // namespace
}  // namespace colortrack::eval

int main(int argc, char **argv) {
  try {
    return colortrack::eval::run(argc, argv);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "colortrack-eval: %s\n", e.what());
    return 1;
  }
}
