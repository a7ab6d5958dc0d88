// SPDX-License-Identifier: LGPL-2.1-or-later
// One-pass evaluation (OPE) metrics of the OTB benchmark (Wu, Lim, Yang, CVPR 2013), plus the parsing of an
// OTB-layout sequence folder. No GStreamer here, so the unit test can check the figures on hand-made boxes.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace colortrack::eval {

// Success-plot thresholds: IoU 0, 0.05, ..., 1 (21 values); precision-plot thresholds: 0, 1, ..., 50 px.
constexpr int kSuccessSteps = 21;
constexpr int kPrecisionSteps = 51;
constexpr double kPrecisionThresholdPx = 20.0;

// One ground-truth line: empty when the object is not annotated (NaN line: fully occluded or out of view).
using GroundTruthBox = std::optional<cv::Rect2d>;

// Parses groundtruth.txt: one "x,y,w,h" per line, separated by commas, tabs or spaces, CRLF or LF.
// `originOffset` is subtracted from x and y: 1 turns OTB's 1-based (MATLAB) coordinates into the 0-based
// pixel coordinates GStreamer elements use, 0 keeps them. Lines with NaN, or with a box of no area, give an
// empty entry (the OTB toolkit also leaves those frames out of the scores). Returns false and sets `error`
// for a line that is neither four numbers nor NaN; trailing blank lines are ignored.
bool parseGroundTruth(const std::string &text, double originOffset, std::vector<GroundTruthBox> &boxes,
                      std::string *error);

// printf into a std::string (up to 1023 characters), for the tools' tables.
std::string format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

// Intersection over union; 0 when either box is empty.
double overlap(const cv::Rect2d &a, const cv::Rect2d &b);
// Distance between the box centres.
double centreDistance(const cv::Rect2d &a, const cv::Rect2d &b);

// Per-sequence scores of one tracker.
struct SequenceScore {
  int scoredFrames = 0;           // frames with a ground-truth box
  std::vector<double> success;    // kSuccessSteps fractions: IoU > threshold
  std::vector<double> precision;  // kPrecisionSteps fractions: centre error <= threshold
  double auc = 0;                 // mean of `success` (OTB's "AUC")
  double precisionAt20 = 0;       // precision[20]
};

// Scores tracker output against ground truth, frame by frame. A frame without a tracker box (nullopt, or past
// the end of `tracked`) is a miss: IoU 0 and an infinite centre error. Frames without ground truth are left
// out, so a tracker is neither rewarded nor punished while the object is invisible.
SequenceScore scoreSequence(const std::vector<GroundTruthBox> &groundTruth,
                            const std::vector<std::optional<cv::Rect2d>> &tracked);

// Curves averaged over sequences (each sequence weighs the same, as in the OTB plots).
SequenceScore averageScores(const std::vector<SequenceScore> &scores);

// Whether a tracker's own report can be trusted, from its per-frame states (spelled as colortrack's
// toString(TrackState) spells them: "tracking", "coasting", "lost", "searching"; "" when unknown). Frame 1
// (the start) is left out of every count; so are frames without ground truth.
struct AlarmFigures {
  // Honest alarm: frames whose IoU with the ground truth is under kWrongIou, and of those the frames
  // reported as "tracking" (a frame without a box never counts as tracking). Lower is more honest.
  int wrongFrames = 0;
  int wrongTracking = 0;
  // Runs (sequences) that declared a loss ("lost" or "searching"), and of those the runs that came back to
  // the target (IoU >= kFoundIou on a frame after the first declared loss). Pooled figures add runs.
  int runs = 0;
  int lossRuns = 0;
  int reacquiredRuns = 0;
  // Frames after the first declared loss, and of those the ones on the target (IoU >= kFoundIou); again only
  // over frames where the target is in view (at least half of its ground-truth box inside the frame).
  int afterLossFrames = 0;
  int afterLossFound = 0;
  int afterLossInView = 0;
  int afterLossInViewFound = 0;

  AlarmFigures &operator+=(const AlarmFigures &other);
};

constexpr double kWrongIou = 0.1;
constexpr double kFoundIou = 0.5;

// `boxes` and `states` are per frame (shorter vectors: the missing frames have no box and no state).
AlarmFigures alarmFigures(const std::vector<GroundTruthBox> &groundTruth,
                          const std::vector<std::optional<cv::Rect2d>> &boxes,
                          const std::vector<std::string> &states, cv::Size frameSize);

// How a folder's frames are named: <prefix><index, zero-padded to `digits`><suffix>, indices consecutive.
struct FramePattern {
  std::string prefix, suffix;
  int digits = 0;
  int startIndex = 0;
  int count = 0;
  // printf-style pattern for multifilesrc, e.g. "%04d.jpg".
  std::string printfPattern() const;
};

// Detects the pattern from the file names of img/ (any order; non-.jpg/.jpeg names are ignored). Returns
// false with `error` set when the names do not share one zero-padded numbering with consecutive indices.
bool detectFramePattern(const std::vector<std::string> &fileNames, FramePattern &pattern, std::string *error);

}  // namespace colortrack::eval
