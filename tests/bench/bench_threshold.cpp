// SPDX-License-Identifier: LGPL-2.1-or-later
// Per-frame cost of threshold mode on one thread: segmentation through the range table, opening/closing,
// connected components, the camera's motion (follow-camera) and the multi-object tracker, at three frame
// sizes with 1 and 8 balls, read from BGR and from I420 planes (as the element reads them, without converting
// the frame). The stage split and the tracking outcome are printed from the same run.
//
//   bench-threshold [--frames N] [--strict]
//
// --strict exits non-zero when a 1920x1080 median misses the 3 ms target.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "balls.hpp"
#include "colortrack/blobs.hpp"
#include "colortrack/global_motion.hpp"
#include "colortrack/multi_tracker.hpp"
#include "colortrack/threshold_tracker.hpp"

namespace {

using namespace colortrack;
using Clock = std::chrono::steady_clock;

constexpr double kTargetMs = 3.0;    // per 1920x1080 frame
constexpr int kDistinctFrames = 24;  // rendered once, cycled (rendering is not what is measured)

double msSince(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

double median(std::vector<double> v) {
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// `objects` balls of evenly spread hues bouncing over a low-saturation cluttered background.
balls::BallScene sceneFor(cv::Size size, int objects) {
  balls::BallSceneConfig config;
  config.frameSize = size;
  config.clutterHueClearance = 0;
  config.clutterSaturation = 0.35;
  std::vector<balls::Ball> list;
  cv::RNG rng(11);
  const double radius = size.height / 24.0;
  for (int i = 0; i < objects; ++i) {
    balls::Ball b;
    b.hue = objects == 1 ? 0 : 360.0 * i / objects;
    b.radius = radius;
    // Out and back over the cycle of rendered frames, so replaying it is continuous motion.
    const cv::Point2d start(rng.uniform(5 * radius, size.width - 5 * radius),
                            rng.uniform(5 * radius, size.height - 5 * radius));
    const cv::Point2d turn =
        start + cv::Point2d(rng.uniform(-4 * radius, 4 * radius), rng.uniform(-4 * radius, 4 * radius));
    b.path = {{0, start}, {kDistinctFrames / 2, turn}, {kDistinctFrames, start}};
    list.push_back(b);
  }
  return balls::BallScene(config, list);
}

SampledFrame sampledI420(const cv::Mat &i420, cv::Size size) {
  const cv::Size half((size.width + 1) / 2, (size.height + 1) / 2);
  SampledFrame f;
  f.size = size;
  f.encoding = PixelEncoding::Yuv;
  f.channels[0] = {i420.rowRange(0, size.height), 0, 1, 1, 1};
  f.channels[1] = {cv::Mat(half, CV_8UC1, const_cast<uchar *>(i420.ptr(size.height))), 0, 1, 2, 2};
  f.channels[2] = {cv::Mat(half, CV_8UC1, const_cast<uchar *>(i420.ptr(size.height)) + half.area()), 0, 1, 2,
                   2};
  return f;
}

struct BenchResult {
  double meanMs = 0, medianMs = 0, maxMs = 0;
  double segmentMs = 0, cleanMs = 0, labelMs = 0;  // medians of the stages, measured separately
  double cameraMs = 0;                             // median of the camera's motion (in the total)
  double meanReported = 0;
};

BenchResult run(cv::Size size, int objects, bool i420, int frames) {
  const balls::BallScene scene = sceneFor(size, objects);
  std::vector<cv::Mat> rendered;
  for (int i = 0; i < kDistinctFrames; ++i) {
    cv::Mat bgr = scene.render(i);
    if (i420) cv::cvtColor(bgr, bgr, cv::COLOR_BGR2YUV_I420);
    rendered.push_back(bgr);
  }
  BlobSettings settings;
  settings.range.lower = {objects == 1 ? 340.0 : 0.0, 0.5, 0.25};
  settings.range.upper = {objects == 1 ? 20.0 : 360.0, 1, 1};
  BlobDetector detector(settings);
  MultiTracker tracker;
  GlobalMotion camera(kCameraCopyWidth);  // as ThresholdTracker
  BenchResult r;
  std::vector<double> total, seg, clean, label, cameraCost;
  const int d = autoDecimation(size);
  const RangeLut lut(settings.range, i420 ? PixelEncoding::Yuv : PixelEncoding::Rgb);
  const int kernel = d == 1 ? settings.morphSize : 3;  // what detect() uses for morph-size 5
  cv::Mat mask, labels;
  for (int i = -5; i < frames; ++i) {  // 5 warm-up frames
    const cv::Mat &frame = rendered[(i + kDistinctFrames) % kDistinctFrames];
    const SampledFrame sampled = i420 ? sampledI420(frame, size) : sampledBgr(frame);
    auto start = Clock::now();
    // As ThresholdTracker runs it: the camera's motion measured with the blobs left out, and the labels
    // (shared blobs and new touching objects are split).
    const std::vector<Blob> blobs = detector.detect(sampled);
    const auto cameraStart = Clock::now();
    const GlobalMotion::Shift moved = camera.measure(sampled, movingObjects(blobs));
    if (moved.valid) tracker.followCamera(moved.offset);
    const double cameraMs = msSince(cameraStart);
    const std::vector<TrackedObject> reported = tracker.update(blobs, size, 1.0, detector.labels());
    const double ms = msSince(start);
    // The stages on their own, for the split (same work as inside detect()).
    start = Clock::now();
    segment(sampled, lut, d, mask);
    const double segMs = msSince(start);
    start = Clock::now();
    cleanMask(mask, kernel);
    const double cleanMsValue = msSince(start);
    start = Clock::now();
    cv::connectedComponents(mask, labels, 8, CV_32S);
    const double labelMs = msSince(start);
    if (i < 0) continue;
    total.push_back(ms);
    seg.push_back(segMs);
    clean.push_back(cleanMsValue);
    label.push_back(labelMs);
    cameraCost.push_back(cameraMs);
    r.meanReported += reported.size();
  }
  for (double t : total) r.meanMs += t;
  r.meanMs /= total.size();
  r.medianMs = median(total);
  r.maxMs = *std::max_element(total.begin(), total.end());
  r.segmentMs = median(seg);
  r.cleanMs = median(clean);
  r.labelMs = median(label);
  r.cameraMs = median(cameraCost);
  r.meanReported /= total.size();
  return r;
}

}  // namespace

int main(int argc, char **argv) {
  int frames = 200;
  bool strict = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--frames" && i + 1 < argc && std::atoi(argv[i + 1]) > 0) {
      frames = std::atoi(argv[++i]);
    } else if (arg == "--strict") {
      strict = true;
    } else {
      std::fprintf(stderr, "usage: %s [--frames N] [--strict]\n", argv[0]);
      return 2;
    }
  }
  cv::setNumThreads(1);  // per-core figures

  std::printf("colortrack threshold-mode benchmark: 1 thread, %d frames per case, OpenCV %s\n", frames,
              CV_VERSION);
  std::printf(
      "detect (segment + clean + label) + camera motion + multi-object update; split: segment / "
      "open+close / label / camera\n");
  std::printf("%-10s %4s %-5s %3s %8s %9s %7s %7s %7s %7s %7s %6s %8s\n", "size", "objs", "input", "dec",
              "mean ms", "median ms", "max ms", "seg", "morph", "label", "camera", "target", "tracks");
  const cv::Size sizes[] = {{640, 480}, {1280, 720}, {1920, 1080}};
  bool missed = false;
  for (const cv::Size size : sizes) {
    for (int objects : {1, 8}) {
      for (bool i420 : {false, true}) {
        const BenchResult r = run(size, objects, i420, frames);
        const bool hasTarget = size == cv::Size(1920, 1080);
        const bool ok = !hasTarget || r.medianMs <= kTargetMs;
        missed = missed || !ok;
        std::printf("%4dx%-5d %4d %-5s %3d %8.3f %9.3f %7.3f %7.3f %7.3f %7.3f %7.3f %6s %8.2f\n", size.width,
                    size.height, objects, i420 ? "I420" : "BGR", autoDecimation(size), r.meanMs, r.medianMs,
                    r.maxMs, r.segmentMs, r.cleanMs, r.labelMs, r.cameraMs,
                    hasTarget ? (ok ? "ok" : "MISS") : "-", r.meanReported);
      }
    }
  }
  return strict && missed ? 1 : 0;
}
