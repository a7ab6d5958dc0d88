// SPDX-License-Identifier: LGPL-2.1-or-later
#include "eval_overhead.hpp"

#include <stdlib.h>

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "eval_pipeline.hpp"
#include "eval_report.hpp"
#include "scene.hpp"

namespace fs = std::filesystem;

namespace colortrack::eval {

namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0 : values[values.size() / 2];
}

// A temporary directory, removed with everything in it when this goes out of scope.
struct TemporaryDir {
  fs::path dir;
  TemporaryDir() {
    char pattern[] = "/tmp/colortrack-eval-1080p-XXXXXX";
    if (!mkdtemp(pattern)) throw std::runtime_error("cannot create a temporary directory");
    dir = pattern;
  }
  ~TemporaryDir() {
    std::error_code ignored;
    fs::remove_all(dir, ignored);
  }
};

// The benchmarks' scene, scaled to 1080p: a textured object that moves, turns, changes size and lighting.
Sequence writeSyntheticSequence(const fs::path &dir, int frames, Progress &progress) {
  fs::create_directories(dir / "img");
  scene::SceneConfig config;
  config.frameSize = cv::Size(1920, 1080);
  config.frames = frames;
  const int side = cvRound(72.0 * 1080 / 480);
  config.objectSize = cv::Size(side, side);
  config.scaleMin = 0.8;
  config.scaleMax = 1.25;
  config.rotationDegrees = 45;
  config.brightness = 0.2;
  const scene::Scene scene(config);
  Sequence sequence;
  sequence.name = "synthetic 1920x1080";
  sequence.dir = dir;
  sequence.frameSize = config.frameSize;
  for (int i = 0; i < frames; ++i) {
    const scene::SceneFrame frame = scene.render(i);
    cv::imwrite((dir / "img" / format("%04d.jpg", i + 1)).string(), frame.bgr,
                {cv::IMWRITE_JPEG_QUALITY, 90});
    sequence.groundTruth.push_back(frame.objectVisible ? GroundTruthBox(frame.box) : std::nullopt);
    progress.update(format("overhead: writing 1080p frame %d/%d", i + 1, frames));
  }
  sequence.pattern = {"", ".jpg", 4, 1, frames};
  sequence.initBox = scene.initBox();
  return sequence;
}

struct Variant {
  std::string label, fragment;
  bool draws;
  std::vector<double> fps, elementMs;
  RunResult last;
};

std::string overheadTable(const Options &options, const Sequence &sequence,
                          const std::vector<Variant> &variants) {
  const double baseFps = median(variants[0].fps);
  std::ostringstream md;
  md << "### Overhead at 1920x1080\n\n"
     << "`multifilesrc ! jpegdec ! videoconvert ! X ! appsink sync=false`, " << options.overheadFrames
     << " JPEG frames (quality 90) of the synthetic scene in a temporary directory; median of "
     << options.overheadRepeats << " runs per variant, runs interleaved.\n\n"
     << "| X | fps pipeline | ratio to identity | ms/frame in X | frames tracking | AUC |\n"
     << "|---|---:|---:|---:|---:|---:|\n";
  for (const Variant &v : variants) {
    const long tracking = std::count(v.last.states.begin(), v.last.states.end(), std::string("tracking"));
    std::vector<std::optional<cv::Rect2d>> boxes = v.last.boxes;
    if (!boxes.empty()) boxes[0] = cv::Rect2d(sequence.initBox);
    const SequenceScore score = scoreSequence(sequence.groundTruth, boxes);
    const bool isIdentity = &v == &variants[0];
    md << "| " << v.label << " | " << fpsText(median(v.fps)) << " | "
       << format("%.3f", median(v.fps) / baseFps) << " | " << format("%.2f", median(v.elementMs)) << " | "
       << (isIdentity ? "-" : format("%ld/%d", tracking, v.last.frames())) << " | "
       << (isIdentity ? "-" : format("%.3f", score.auc)) << " |\n";
  }
  return md.str();
}

}  // namespace

std::string measureOverhead(const Options &options, Progress &progress) {
  const TemporaryDir temporary;
  const Sequence sequence = writeSyntheticSequence(temporary.dir, options.overheadFrames, progress);
  std::vector<Variant> variants = {
      {"identity", "identity", false, {}, {}, {}},
      {options.overheadTracker, options.overheadTracker, false, {}, {}, {}},
      {options.overheadTracker + " (draw=box+trail+label)", options.overheadTracker, true, {}, {}, {}}};
  // One unmeasured run warms the page cache and the plugin loading.
  runPipeline(sequence, {"identity", "", std::nullopt, false}, [](int) {});
  for (int repeat = 0; repeat < options.overheadRepeats; ++repeat)
    for (Variant &v : variants) {
      RunResult run = runPipeline(sequence, {v.fragment, "", sequence.initBox, v.draws}, [&](int frames) {
        progress.update(format("overhead %d/%d: %s  frame %d/%d", repeat + 1, options.overheadRepeats,
                               v.label.c_str(), frames, options.overheadFrames));
      });
      if (!run.error.empty()) throw std::runtime_error("overhead run " + v.label + ": " + run.error);
      v.fps.push_back(run.pipelineFps());
      v.elementMs.push_back(1000.0 * run.elementSeconds / std::max(run.frames(), 1));
      v.last = std::move(run);
    }
  const double baseFps = median(variants[0].fps);
  progress.finish(format("overhead: identity %.1f fps, %s %.1f fps (ratio %.3f)", baseFps,
                         options.overheadTracker.c_str(), median(variants[1].fps),
                         median(variants[1].fps) / baseFps));
  return overheadTable(options, sequence, variants);
}

}  // namespace colortrack::eval
