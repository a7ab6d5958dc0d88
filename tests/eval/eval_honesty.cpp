// SPDX-License-Identifier: LGPL-2.1-or-later
#include "eval_honesty.hpp"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

#include <opencv2/imgcodecs.hpp>

#include "honesty.hpp"
#include "injection.hpp"
#include "metrics.hpp"
#include "sre.hpp"

namespace fs = std::filesystem;

namespace colortrack::eval {

namespace {

// High enough that the re-encoding changes the footage less than the original JPEGs' own loss.
constexpr int kJpegQuality = 95;

// A temporary folder, removed with its contents when the object goes.
class TemporaryDirectory {
 public:
  TemporaryDirectory() {
    std::string pattern = (fs::temp_directory_path() / "colortrack-eval-inject-XXXXXX").string();
    if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot make a temporary folder in /tmp");
    path_ = pattern;
  }
  ~TemporaryDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path &path() const { return path_; }

 private:
  fs::path path_;
};

// Writes the injected run's frames as <dir>/img/00000.jpg ... and returns the sequence that reads them.
Sequence writeInjected(const std::vector<Sequence> &sequences, std::size_t index, InjectedRun &run,
                       const fs::path &dir) {
  fs::create_directories(dir / "img");
  const Sequence &original = sequences[index];
  Sequence written = original;
  written.dir = dir;
  written.pattern = FramePattern{"", ".jpg", 5, 0, original.pattern.count};
  const FrameReader read = [&](std::size_t s, int i) { return readSequenceFrame(sequences, s, i); };
  for (int i = 0; i < original.pattern.count; ++i) {
    const fs::path path = dir / "img" / format("%05d.jpg", i);
    if (!cv::imwrite(path.string(), run.frame(i, read), {cv::IMWRITE_JPEG_QUALITY, kJpegQuality}))
      throw std::runtime_error("cannot write " + path.string());
  }
  return written;
}

// A run's per-frame reports; a tracker without states is read as the docs above say.
std::vector<FrameReport> reportsOf(const RunResult &run, const cv::Rect &start, bool hasStates) {
  std::vector<FrameReport> reports;
  for (int i = 0; i < run.frames(); ++i) {
    FrameReport r{run.boxes[i], i < static_cast<int>(run.states.size()) ? run.states[i] : "",
                  i < static_cast<int>(run.scores.size()) ? run.scores[i] : 0.0};
    if (!hasStates) r.state = r.box ? "tracking" : "lost";
    reports.push_back(r);
  }
  if (!reports.empty()) reports[0] = {cv::Rect2d(start), "init", 0};  // frame 1 is the start box (OTB)
  return reports;
}

bool reportsStates(const RunResult &run) {
  return std::any_of(run.states.begin(), run.states.end(), [](const std::string &s) { return !s.empty(); });
}

// The plain runs (OPE and SRE) of one column, as records.
void addPlainRuns(const std::vector<Sequence> &sequences, const EvalResults &results,
                  const EvalResults::Column &column, const cv::Point2d &offset, bool sre,
                  std::vector<RunRecord> &records) {
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    const std::vector<StartBox> starts =
        startBoxes(*sequences[s].groundTruth[0] + offset, sequences[s].frameSize, sre);
    for (std::size_t i = 0; i < starts.size(); ++i) {
      const Evaluation &e = results.runs[s][column.tracker][column.format][i];
      if (!e.ok) continue;
      records.push_back({sequences[s].name, halfOf(sequences[s].name), starts[i].name, std::nullopt,
                         plainTruth(sequences[s]), reportsOf(e.run, starts[i].box, reportsStates(e.run))});
    }
  }
}

// Every injected run of every sequence, through every column; records[c] are column c's.
void addInjectedRuns(const std::vector<Sequence> &sequences, const EvalResults &results,
                     const Options &options, Progress &progress,
                     std::vector<std::vector<RunRecord>> &records) {
  const std::vector<EvalResults::Column> columns = results.columns();
  const cv::Point2d offset(options.startOffsetX, options.startOffsetY);
  TemporaryDirectory temporary;
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    const cv::Rect start =
        startBoxes(*sequences[s].groundTruth[0] + offset, sequences[s].frameSize, false).front().box;
    for (const Injection &injection : planInjections(sequences, s)) {
      InjectedRun run(sequences, s, injection);
      const fs::path dir = temporary.path() / (sequences[s].name + "." + injection.name);
      const Sequence written = writeInjected(sequences, s, run, dir);
      for (std::size_t c = 0; c < columns.size(); ++c) {
        const std::string fragment = results.trackers[columns[c].tracker];
        const std::string pixelFormat =
            results.runOnce[columns[c].tracker] ? "" : results.formats[columns[c].format];
        const std::string label =
            format("%s %s  %s [%s]", sequences[s].name.c_str(), injection.name.c_str(), fragment.c_str(),
                   pixelFormat.empty() ? "own caps" : pixelFormat.c_str());
        const RunResult result = runPipeline(written, {fragment, pixelFormat, start, false}, [&](int frames) {
          progress.update(format("%s  frame %d", label.c_str(), frames));
        });
        progress.finish(label + (result.error.empty() ? "" : "  FAILED: " + result.error));
        if (!result.error.empty()) continue;
        if (options.writeFrames)
          writeFrames(fs::path(options.outDir) / "frames" /
                          framesFolder(results, columns[c].tracker, columns[c].format) /
                          (sequences[s].name + "." + injection.name + ".csv"),
                      sequences[s], start, result);
        records[c].push_back({sequences[s].name, halfOf(sequences[s].name), injection.name, injection,
                              run.truth(), reportsOf(result, start, reportsStates(result))});
      }
      fs::remove_all(dir);
    }
  }
}

}  // namespace

std::string honestySection(const std::vector<Sequence> &sequences, const EvalResults &results,
                           const Options &options, Progress &progress) {
  const std::vector<EvalResults::Column> columns = results.columns();
  const cv::Point2d offset(options.startOffsetX, options.startOffsetY);
  std::vector<std::vector<RunRecord>> records(columns.size());
  for (std::size_t c = 0; c < columns.size(); ++c)
    addPlainRuns(sequences, results, columns[c], offset, options.sre, records[c]);
  if (options.inject) addInjectedRuns(sequences, results, options, progress, records);
  std::string md = "\n### Honesty\n";
  for (std::size_t c = 0; c < columns.size(); ++c)
    md += "\n#### " + columns[c].label + "\n\n```\n" + honestyReport(records[c]) + "```\n";
  return md;
}

}  // namespace colortrack::eval
