// SPDX-License-Identifier: LGPL-2.1-or-later
// Failures injected into real footage, with exact truth (issue 46). Eighteen sequences hold few failures to
// learn from, so runs are made from them in which the truth of "the target is not there" and "the target is
// back" is known to the frame:
// - cut: the video cuts to another sequence's frames for kCutFrames, then back;
// - cover: the target's true box (a little enlarged) is covered by background of the same frame taken from
//   beside it, for 5, 15 or 45 frames;
// - copy: the target's appearance on the frame before is pasted and slid across its path, in front of it
// (over
//   it) or beside it, at two speeds.
// Where and when is chosen from the sequence's length and ground truth only, so every tracker meets the same
// runs. No GStreamer here: both evaluation tools use it.
#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sequences.hpp"

namespace colortrack::eval {

enum class InjectionKind { Cut, Cover, Copy };

// Frames of the other scene before the cut back.
constexpr int kCutFrames = 40;
// Cover lengths, in frames.
constexpr int kCoverLengths[] = {5, 15, 45};
// Crossing lengths: the copy travels from kCopyReach widths on one side of the target to kCopyReach on the
// other in this many frames (the slow and the fast crossing).
constexpr int kCopySlowFrames = 40;
constexpr int kCopyFastFrames = 20;
constexpr double kCopyReach = 2.5;
// After a cut, frames a tracker is given to notice it before a `tracking` counts as a false alarm.
constexpr int kCutGrace = 5;
// Frames every injection leaves after its end, so what follows it can be measured.
constexpr int kFramesAfter = 30;

struct Injection {
  InjectionKind kind = InjectionKind::Cut;
  std::string name;               // "cut@52", "cover15@40", "copy-front40@60", "copy-beside40@60"
  int first = 0;                  // first changed frame, 0-based
  int length = 0;                 // changed frames
  std::size_t otherSequence = 0;  // cut: whose frames are shown instead
  bool beside = false;            // copy: passes beside the target rather than over it
  int last() const { return first + length - 1; }
  bool covers(int frame) const { return frame >= first && frame <= last(); }
};

// The injections for sequence `index` of `sequences`: two cuts (to the sequence half the list away), the
// three covers, and three crossings (front slow, front fast, beside slow). A kind is left out where the
// sequence is too short or its ground truth has gaps around the place.
std::vector<Injection> planInjections(const std::vector<Sequence> &sequences, std::size_t index);

// The truth of one frame of a run.
struct FrameTruth {
  GroundTruthBox target;           // the target's box; empty when not annotated or absent
  bool absent = false;             // the injection took the target out of view (cut, cover)
  bool grace = false;              // a cut's first kCutGrace frames: a tracker may take a moment to see it
  std::optional<cv::Rect2d> copy;  // where the pasted copy is, on copy runs
};

// The truth of every frame of an uninjected run: the ground truth, nothing absent.
std::vector<FrameTruth> plainTruth(const Sequence &sequence);

// Reads frame `index` of sequence `sequence` (BGR).
using FrameReader = std::function<cv::Mat(std::size_t sequence, int index)>;

// One injected run of one sequence: its frames and their truth.
class InjectedRun {
 public:
  InjectedRun(const std::vector<Sequence> &sequences, std::size_t index, Injection injection);

  const Injection &injection() const { return injection_; }
  // Frame i with the injection applied; `read` gives the original frames (of this and the cut's sequence).
  cv::Mat frame(int i, const FrameReader &read);
  std::vector<FrameTruth> truth() const;

  // Where a cover is pasted on frame i and where its background is taken from; empty when no place fits.
  static std::optional<std::pair<cv::Rect, cv::Rect>> coverPlaces(const cv::Rect2d &target, cv::Size frame);
  // The copy's box on frame i of the crossing, given the target's box then and the copy's size.
  cv::Rect2d copyBox(int i, const cv::Rect2d &target, cv::Size copySize) const;

 private:
  // Where the copy is cut from: the target's box on the frame before the crossing, whole pixels, in the
  // frame.
  cv::Rect copySource() const;

  const std::vector<Sequence> &sequences_;
  std::size_t index_;
  Injection injection_;
  cv::Mat copy_;  // the target's appearance on the frame before the crossing
};

// The frame reader the tools use: the sequence's JPEGs decoded by OpenCV.
cv::Mat readSequenceFrame(const std::vector<Sequence> &sequences, std::size_t sequence, int index);

}  // namespace colortrack::eval
