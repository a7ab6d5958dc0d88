// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode's multi-object accuracy: the ThresholdTracker (what the element runs, default settings) on
// the scenes of mot_scenes.hpp, scored with CLEAR-MOT and IDF1 (IoU >= 0.3). Also counts reported boxes that
// break the element's promises: outside the frame, or smaller than min-area allows.
//
//   colortrack-mot-eval [--scene NAME] [--exclude NAME] [--no-follow-camera] [--frames-out DIR]
//                       [--min-mota X] [--min-idf1 X] [--per-scene]
//
// Prints one row per scene and the mean. --scene runs the scenes whose name starts with NAME, --exclude
// leaves out those whose name starts with NAME (either may be given more than once);
// --no-follow-camera leaves the camera's motion in the predictions (follow-camera=false); --frames-out writes
// each scene's per-frame tracks and ground truth as CSV. With --min-mota / --min-idf1 (the test suite's
// regression guard) it exits 1 when a mean (--per-scene: any scene) falls below them or when any reported box
// lies outside the frame or under min-area.

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include "colortrack/threshold_tracker.hpp"
#include "mot_metrics.hpp"
#include "mot_scenes.hpp"

namespace {

using namespace colortrack;
using namespace colortrack::eval;

struct SceneResult {
  MotScore score;
  int outsideFrame = 0, tooSmall = 0;
};

SceneResult runScene(const MotScene &scene, const std::string &framesOut, bool followCamera) {
  ThresholdTracker tracker;  // the element's defaults: the red range, morph-size 5, min-area 50, 8 objects
  MultiTrackerSettings trackSettings;
  trackSettings.followCamera = followCamera;
  tracker.setTrackSettings(trackSettings);
  const int minArea = tracker.blobSettings().minArea;
  std::vector<MotFrame> frames;
  SceneResult r;
  std::ofstream csv;
  if (!framesOut.empty()) {
    csv.open(framesOut + "/" + scene.name + ".csv");
    csv << "frame,kind,id,x,y,w,h,state\n";
  }
  for (int i = 0; i < scene.frames; ++i) {
    MotFrame f;
    const cv::Mat bgr = scene.render(i, f);
    const FrameReport report = tracker.track(MatImageSource(bgr), 1.0);
    const cv::Rect2d frameRect(0, 0, bgr.cols, bgr.rows);
    for (const TrackReport &t : report.tracks) {
      if ((t.box & frameRect) != t.box) ++r.outsideFrame;
      if (t.box.area() < minArea) ++r.tooSmall;
      f.tracks.push_back({t.id, t.box});
      if (csv)
        csv << i << ",track," << t.id << "," << t.box.x << "," << t.box.y << "," << t.box.width << ","
            << t.box.height << "," << toString(t.state) << "\n";
    }
    if (csv) {
      for (const MotBox &g : f.truth)
        csv << i << ",truth," << g.id << "," << g.box.x << "," << g.box.y << "," << g.box.width << ","
            << g.box.height << ",\n";
      for (const MotBox &g : f.ignored)
        csv << i << ",ignored," << g.id << "," << g.box.x << "," << g.box.y << "," << g.box.width << ","
            << g.box.height << ",\n";
    }
    frames.push_back(f);
  }
  r.score = scoreMot(frames);
  return r;
}

struct Options {
  std::string framesOut;
  std::vector<std::string> scenePrefixes, excludePrefixes;  // each option may be given more than once
  double minMota = 0, minIdf1 = 0;
  bool guard = false, perScene = false, followCamera = true;
};

bool parseOptions(int argc, char **argv, Options &o) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    const bool hasValue = i + 1 < argc;
    if (arg == "--frames-out" && hasValue) {
      o.framesOut = argv[++i];
    } else if (arg == "--scene" && hasValue) {
      o.scenePrefixes.push_back(argv[++i]);
    } else if (arg == "--exclude" && hasValue) {
      o.excludePrefixes.push_back(argv[++i]);
    } else if (arg == "--no-follow-camera") {
      o.followCamera = false;
    } else if (arg == "--per-scene") {
      o.perScene = true;
    } else if (arg == "--min-mota" && hasValue) {
      o.minMota = std::atof(argv[++i]);
      o.guard = true;
    } else if (arg == "--min-idf1" && hasValue) {
      o.minIdf1 = std::atof(argv[++i]);
      o.guard = true;
    } else {
      std::fprintf(stderr,
                   "usage: %s [--scene NAME] [--exclude NAME] [--no-follow-camera] [--frames-out DIR] "
                   "[--min-mota X] [--min-idf1 X] [--per-scene]\n",
                   argv[0]);
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char **argv) {
  Options o;
  if (!parseOptions(argc, argv, o)) return 2;
  std::vector<MotScene> scenes = motScenes();
  const auto startsWithAny = [](const std::string &name, const std::vector<std::string> &prefixes) {
    return std::any_of(prefixes.begin(), prefixes.end(),
                       [&](const std::string &prefix) { return name.rfind(prefix, 0) == 0; });
  };
  scenes.erase(
      std::remove_if(scenes.begin(), scenes.end(),
                     [&](const MotScene &s) {
                       return (!o.scenePrefixes.empty() && !startsWithAny(s.name, o.scenePrefixes)) ||
                              startsWithAny(s.name, o.excludePrefixes);
                     }),
      scenes.end());
  if (scenes.empty()) {
    std::fprintf(stderr, "no scene left to run\n");
    return 2;
  }
  std::printf("%-18s %6s %6s %6s %6s %5s %5s %5s %5s %7s %6s\n", "scene", "MOTA", "IDF1", "MOTP", "truth",
              "miss", "FP", "IDSW", "IDTP", "outside", "small");
  double mota = 0, idf1 = 0, worstMota = 1, worstIdf1 = 1;
  int outside = 0, small = 0;
  for (const MotScene &scene : scenes) {
    const SceneResult r = runScene(scene, o.framesOut, o.followCamera);
    const MotScore &s = r.score;
    std::printf("%-18s %6.3f %6.3f %6.3f %6d %5d %5d %5d %5d %7d %6d\n", scene.name.c_str(), s.mota, s.idf1,
                s.motp, s.truthBoxes, s.misses, s.falsePositives, s.idSwitches, s.idTruePositives,
                r.outsideFrame, r.tooSmall);
    mota += s.mota;
    idf1 += s.idf1;
    worstMota = std::min(worstMota, s.mota);
    worstIdf1 = std::min(worstIdf1, s.idf1);
    outside += r.outsideFrame;
    small += r.tooSmall;
  }
  const double n = static_cast<double>(scenes.size());
  std::printf(
      "%-18s %6.3f %6.3f   (worst scene: MOTA %.3f, IDF1 %.3f; boxes outside the frame %d, too small %d)\n",
      "mean", mota / n, idf1 / n, worstMota, worstIdf1, outside, small);
  const double judgedMota = o.perScene ? worstMota : mota / n, judgedIdf1 = o.perScene ? worstIdf1 : idf1 / n;
  if (o.guard && (judgedMota < o.minMota || judgedIdf1 < o.minIdf1 || outside > 0 || small > 0)) {
    std::fprintf(stderr,
                 "FAIL: %s MOTA %.3f (at least %.3f), IDF1 %.3f (at least %.3f), %d boxes outside the "
                 "frame, %d under min-area (none allowed)\n",
                 o.perScene ? "worst scene's" : "mean", judgedMota, o.minMota, judgedIdf1, o.minIdf1, outside,
                 small);
    return 1;
  }
  return 0;
}
