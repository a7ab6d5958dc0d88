// SPDX-License-Identifier: LGPL-2.1-or-later
#include "eval_options.hpp"

#include <algorithm>
#include <cstdlib>
#include <optional>
#include <stdexcept>

#include "sre.hpp"

namespace colortrack::eval {

const char *const kEvalUsage =
    "usage: colortrack-eval [options] SEQUENCE_DIR... --tracker FRAGMENT [--tracker FRAGMENT ...]\n"
    "\n"
    "  SEQUENCE_DIR          OTB layout (img/*.jpg + groundtruth.txt), or a folder of such folders\n"
    "  --tracker FRAGMENT    gst-launch fragment ending in the tracker, e.g. colortrack or\n"
    "                        \"cvtracker algorithm=CSRT\" (repeatable; order kept)\n"
    "  --all-cvtracker       add cvtracker with every algorithm it offers\n"
    "  --formats LIST        pixel formats forced before the tracker, comma-separated, from BGRx, I420,\n"
    "                        RGB, NV12, YUY2, BGR (default BGRx,I420; cvtracker keeps its own caps and\n"
    "                        runs once, its result shown under every format)\n"
    "  --sre                 also 8 runs per sequence from perturbed start boxes (spatial robustness)\n"
    "  --inject              also runs with injected failures (a cut to another sequence, the target\n"
    "                        covered, a copy of it crossing its path) and the honesty report on them\n"
    "  --start-offset DX,DY  every start box (OPE and SRE) moved by DX, DY whole pixels, for every\n"
    "                        tracker alike (the noise floor of a result)\n"
    "  --out DIR             results.md, results.csv, curves.csv, success.png, precision.png, frames/\n"
    "                        (default eval-out)\n"
    "  --gt-origin N         subtracted from ground-truth x and y (default 1: OTB's 1-based boxes)\n"
    "  --opencv-threads N    cv::setNumThreads(N) for the whole process, trackers included (default: "
    "OpenCV's)\n"
    "  --no-frames           do not write the per-frame boxes, states and scores (also of the\n"
    "                        injected runs) to DIR/frames/\n"
    "  --no-build-plugin     do not add this build's gst/ directory to the plugin path\n"
    "  --overhead            also measure 1920x1080 decode + colortrack against decode + identity\n"
    "  --overhead-frames N   frames of the synthetic 1080p sequence (default 300)\n"
    "  --overhead-repeats N  runs of each variant; the median counts (default 3)\n"
    "  --overhead-tracker F  fragment measured against identity (default colortrack)\n";

namespace {

// The formats colortrack takes that are worth comparing: packed RGB with and without padding, and the
// YUV layouts cameras and decoders deliver.
const std::vector<std::string> kKnownFormats = {"BGRx", "I420", "RGB", "NV12", "YUY2", "BGR"};

std::vector<std::string> parseFormats(const std::string &list) {
  std::vector<std::string> formats;
  std::size_t begin = 0;
  while (begin <= list.size()) {
    const std::size_t end = std::min(list.find(',', begin), list.size());
    const std::string name = list.substr(begin, end - begin);
    if (std::find(kKnownFormats.begin(), kKnownFormats.end(), name) == kKnownFormats.end())
      throw std::invalid_argument("--formats: '" + name + "' is not one of BGRx, I420, RGB, NV12, YUY2, BGR");
    if (std::find(formats.begin(), formats.end(), name) == formats.end()) formats.push_back(name);
    begin = end + 1;
  }
  return formats;
}

// Options that take no value; false when `arg` is not one of them.
bool parseFlag(const std::string &arg, Options &options) {
  if (arg == "--all-cvtracker")
    options.allCvtracker = true;
  else if (arg == "--sre")
    options.sre = true;
  else if (arg == "--inject")
    options.inject = true;
  else if (arg == "--no-frames")
    options.writeFrames = false;
  else if (arg == "--no-build-plugin")
    options.useBuildPlugin = false;
  else if (arg == "--overhead")
    options.overhead = true;
  else
    return false;
  return true;
}

// "DX,DY" as two whole numbers of pixels.
void parseOffset(const std::string &arg, const std::string &value, Options &options) {
  const std::optional<cv::Point> offset = parseStartOffset(value);
  if (!offset) throw std::invalid_argument(arg + " expects DX,DY in whole pixels, got '" + value + "'");
  options.startOffsetX = offset->x;
  options.startOffsetY = offset->y;
}

int positive(const std::string &arg, const std::string &value) {
  const int n = std::atoi(value.c_str());
  if (n <= 0) throw std::invalid_argument(arg + " must be a positive number");
  return n;
}

// Options followed by a value; false when `arg` is not one of them.
bool parseValued(const std::string &arg, const std::string &value, Options &options) {
  if (arg == "--tracker")
    options.trackers.push_back(value);
  else if (arg == "--formats")
    options.formats = parseFormats(value);
  else if (arg == "--start-offset")
    parseOffset(arg, value, options);
  else if (arg == "--out")
    options.outDir = value;
  else if (arg == "--gt-origin")
    options.gtOrigin = std::atof(value.c_str());
  else if (arg == "--opencv-threads")
    options.openCvThreads = positive(arg, value);
  else if (arg == "--overhead-frames")
    options.overheadFrames = positive(arg, value);
  else if (arg == "--overhead-repeats")
    options.overheadRepeats = positive(arg, value);
  else if (arg == "--overhead-tracker")
    options.overheadTracker = value;
  else
    return false;
  return true;
}

bool takesValue(const std::string &arg) {
  return arg == "--tracker" || arg == "--formats" || arg == "--start-offset" || arg == "--out" ||
         arg == "--gt-origin" || arg == "--opencv-threads" || arg.rfind("--overhead-", 0) == 0;
}

}  // namespace

Options parseOptions(int argc, char **argv) {
  Options options;
  for (int i = 0; i < argc; ++i) options.commandLine += (i ? " " : "") + std::string(argv[i]);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      options.help = true;
      return options;
    }
    if (parseFlag(arg, options)) continue;
    if (takesValue(arg)) {
      if (i + 1 >= argc) throw std::invalid_argument(arg + " needs a value");
      if (!parseValued(arg, argv[++i], options)) throw std::invalid_argument("unknown option " + arg);
      continue;
    }
    if (arg.rfind("--", 0) == 0) throw std::invalid_argument("unknown option " + arg);
    options.inputs.push_back(arg);
  }
  if (options.inputs.empty() && !options.overhead) throw std::invalid_argument("no sequence folder given");
  if (!options.inputs.empty() && options.trackers.empty() && !options.allCvtracker)
    throw std::invalid_argument("no tracker given (--tracker FRAGMENT or --all-cvtracker)");
  return options;
}

}  // namespace colortrack::eval
