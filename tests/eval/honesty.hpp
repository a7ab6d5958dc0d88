// SPDX-License-Identifier: LGPL-2.1-or-later
// Whether a tracker knows when it is wrong (issue 46): how often it says `tracking` while its box is off the
// target, how well its per-frame score separates on-target from off-target frames (AUROC, no threshold), and
// what it does through each injected failure (injection.hpp). Plain text, no GStreamer.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "injection.hpp"

namespace colortrack::eval {

// A frame whose box has at least this IoU with the target is on it (AUROC's positives; precision of
// `tracking`); under kWrongIou (metrics.hpp) it is off it.
constexpr double kOnIou = 0.3;
// How soon a cut must be noticed (state lost or searching), and how soon a target must be taken back after a
// cover or a cut back, in frames.
constexpr int kDeclareWithin = 10;
constexpr int kBackWithin = 30;

// What a tracker reported on one frame; `state` as colortrack spells it ("" when the tracker has none).
struct FrameReport {
  std::optional<cv::Rect2d> box;
  std::string state;
  double score = 0;
};

// Pooled over frames and runs. Frame 1 (the start), frames without truth and a cut's grace frames are left
// out of every count.
struct HonestyFigures {
  int offTarget = 0;          // the target absent with a box shown, or in view with IoU < kWrongIou
  int offTargetTracking = 0;  // of those, reported `tracking`
  int tracking = 0;           // frames reported `tracking`
  int trackingOnTarget = 0;   // of those, IoU >= kOnIou
  int onTarget = 0;           // frames with IoU >= kOnIou
  // (score, on target) of each frame that is clearly on (IoU >= kOnIou) or off (IoU < kWrongIou, or any box
  // while the target is absent) the target and has a box; frames without a box are left out, since a lost
  // frame's score says nothing.
  std::vector<std::pair<double, bool>> scores;

  HonestyFigures &operator+=(const HonestyFigures &other);
};

HonestyFigures honestyFigures(const std::vector<FrameTruth> &truth, const std::vector<FrameReport> &reports);

// The area under the ROC curve of `scores` (ties count a half); NaN when either class is empty.
double auroc(std::vector<std::pair<double, bool>> scores);

// What a tracker did through one injection.
struct InjectionOutcome {
  // cut: changed frames processed until the state said lost or searching (1: on the first); -1 never
  int declaredAfter = -1;
  int absentFrames = 0;    // cut and cover: frames counted as absent (after a cut's grace)
  int absentTracking = 0;  // of those, reported `tracking` (with a box)
  // cut and cover: frames from the end of the injection to the first frame with IoU >= kFoundIou (1: the
  // first frame after it); -1 not within kFramesAfter
  int backAfter = -1;
  double meanIouAfter = 0;  // over the kFramesAfter frames after the injection
  // copy: at the crossing's last frame
  bool endsOnTarget = false;        // IoU with the target >= kOnIou
  bool endsOnCopyTracking = false;  // IoU with the copy >= kOnIou and reported `tracking`
  double scoreBefore = 0;           // mean score over the 10 frames before the crossing
  double scoreConfusable = 0;       // mean score while the copy is within 1.5 target sides of it
};

InjectionOutcome injectionOutcome(const Injection &injection, const std::vector<FrameTruth> &truth,
                                  const std::vector<FrameReport> &reports);

// One run of one tracker, as the report takes it.
struct RunRecord {
  std::string sequence;
  std::string half;                    // "tune", "confirm" or "-"
  std::string start;                   // "ope", an SRE start, or the injection's name
  std::optional<Injection> injection;  // injected runs only
  std::vector<FrameTruth> truth;
  std::vector<FrameReport> reports;
};

// The honesty report of one tracker's runs: per half and in total, the off-target frames called `tracking`
// and the AUROC of the score over the plain runs, the injected runs and both; then each kind of injection.
std::string honestyReport(const std::vector<RunRecord> &runs);

}  // namespace colortrack::eval
