// SPDX-License-Identifier: LGPL-2.1-or-later
// The one entry point the element uses: settings in, frame in, track out.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/edges.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/histogram.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/kalman.hpp"
#include "colortrack/scale.hpp"
#include "colortrack/search.hpp"
#include "colortrack/track.hpp"
#include "colortrack/track_output.hpp"
#include "colortrack/status.hpp"
#include "colortrack/tracker_settings.hpp"

namespace colortrack {

// The smallest template side: smaller boxes hold too few pixels for a histogram or a shape filter.
constexpr int kMinTemplateSide = 8;
// Whether a template (or init box) of `size` can be used, or why not.
Status checkTemplateSize(cv::Size size);

// Thrown for unusable input (a template larger than the frame, an empty box ...). The text names the problem.
class TrackerError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Tracker : public FrameTracker {
 public:
  explicit Tracker(const TrackerSettings &settings = TrackerSettings());
  ~Tracker() override;

  // Settings may change at any time; the template model is rebuilt if the colour space or bins change.
  void setSettings(const TrackerSettings &settings);
  const TrackerSettings &settings() const { return settings_; }

  // Template from an image (CV_8UC3 BGR); a non-empty mask (CV_8UC1) selects the object's pixels.
  void setTemplate(const cv::Mat &bgr, const cv::Mat &mask = cv::Mat());
  // Template from a box of a frame; tracking starts there (the first output is `tracking` at that box).
  void setTemplateFromBox(const ImageSource &frame, const cv::Rect &box);
  bool hasTemplate() const;
  cv::Size templateSize() const;

  // Processes one frame. dt: time since the previous frame in frames (1 unless timestamps say otherwise).
  // A frame that cuts to another scene (SceneCut) loses the track at once: it is reported `lost`, and the
  // frames after it search the whole frame. Throws TrackerError when the template does not fit in the frame.
  TrackOutput process(const ImageSource &frame, double dt = 1.0);
  // process() as the element sees it: the track (if any) as the primary and only report.
  FrameReport track(const ImageSource &frame, double dt) override;

  // Forget the track (keeps the template): the next frame searches the whole frame.
  void reset() override;

 private:
  struct Impl;
  TrackerSettings settings_;
  std::unique_ptr<Impl> impl_;
};

// Loads a template image (PNG or JPEG). A PNG alpha channel becomes the mask (alpha > 127 counts).
// Throws TrackerError naming the file when it cannot be read.
void loadTemplate(const std::string &path, cv::Mat &bgr, cv::Mat &mask);

// Starts OpenCV's worker threads now. The first parallel loop of a process starts them, which costs a few
// milliseconds: called before streaming, that cost is not paid on the first frame.
void startWorkerThreads();

}  // namespace colortrack
