// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack-eval's pipelines: one sequence through a tracker element, its boxes, states and timings.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "sequences.hpp"

namespace colortrack::eval {

// What one pipeline run produced.
struct RunResult {
  std::string error;                             // empty when the run reached EOS
  std::vector<std::optional<cv::Rect2d>> boxes;  // per received frame
  // colortrack's state per frame (its element message, else its ROI meta's params); "" for other trackers
  std::vector<std::string> states;
  // colortrack's score per frame (its element message, else its ROI meta's params); 0 for other trackers
  std::vector<double> scores;
  double wallSeconds = 0;
  double elementSeconds = 0;
  int frames() const { return static_cast<int>(boxes.size()); }
  double pipelineFps() const { return wallSeconds > 0 ? frames() / wallSeconds : 0; }
  double elementFps() const { return elementSeconds > 0 ? frames() / elementSeconds : 0; }
};

// One run: `fragment` (a gst-launch fragment whose last element is the tracker) over the sequence's frames,
//   multifilesrc ! jpegdec ! videoconvert [! video/x-raw,format=<format>] ! <fragment> ! appsink
// with no caps filter when `format` is empty. The tracker starts from `initBox` when given, and draws only
// with `keepDrawing` or when the fragment sets drawing itself. `progress` is called about four times a second
// with the number of frames received so far.
struct PipelineRequest {
  std::string fragment;
  std::string format;
  std::optional<cv::Rect> initBox;
  bool keepDrawing = false;
};
RunResult runPipeline(const Sequence &sequence, const PipelineRequest &request,
                      const std::function<void(int)> &progress);

// The factory name of the fragment's tracker (its last element), e.g. "colortrack" or "cvtracker".
std::string trackerFactory(const std::string &fragment);

// "cvtracker algorithm=<nick>" for every value of cvtracker's algorithm enum, as installed.
std::vector<std::string> cvtrackerFragments();

}  // namespace colortrack::eval
