// SPDX-License-Identifier: LGPL-2.1-or-later
// A tracking mode behind the element: template and threshold mode each own their tracker, bring it up to date
// with a frame's settings and requests (prepare), say whether it can take the frame, and track. They reach
// the element only through an ElementSink (messages, the target's life, the property writes back), never its
// private data.
#pragma once

#include <memory>
#include <string>

#include <opencv2/core.hpp>

#include "colortrack/frame_tracker.hpp"
#include "colortrack/threshold_tracker.hpp"
#include "colortrack-element-sink.h"
#include "colortrack-requests.h"
#include "colortrack-settings.h"
#include "frame-view.h"

namespace colortrack_gst {

// The settings as one frame sees them, with what changed since the frame before.
struct Snapshot : Settings {
  gstglue::ChangeSet<Change> changed;
};

class Mode {
 public:
  virtual ~Mode() = default;
  // The settings of the start, and what is read once then (template mode: the template file); false, with an
  // error posted, when streaming cannot start.
  virtual bool start(const Snapshot &snapshot) = 0;
  // The frame's settings (the parts that changed), a reset, then the init-box and click waiting for it;
  // false, with an error posted, when streaming must stop.
  virtual bool prepare(const Snapshot &snapshot, const Requests &requests, const FrameView &view) = 0;
  // Whether the tracker can take a frame of `frame`'s size: Waiting passes the video through (template mode
  // without a template, told once), Error stops streaming (posted).
  enum class Readiness { Ready, Waiting, Error };
  virtual Readiness readiness(cv::Size frame) = 0;
  virtual colortrack::FrameTracker &tracker() = 0;
  // Whether the mode's reports list every track (threshold) or one target (template).
  virtual bool listsTracks() const = 0;
};

// The mode `mode` (fixed while the element is started), reaching the element through `sink`.
std::unique_ptr<Mode> makeMode(colortrack::TrackingMode mode, std::unique_ptr<ElementSink> sink);
std::unique_ptr<Mode> makeTemplateMode(std::unique_ptr<ElementSink> sink);
std::unique_ptr<Mode> makeThresholdMode(std::unique_ptr<ElementSink> sink);

// --- What both modes do alike (colortrack-targets.cpp) ---

// After new caps or the "reset" signal: the tracks are forgotten (the target stays).
void resetIfRequested(const ElementSink &sink, colortrack::FrameTracker &tracker);
// A right click: no target until a new one is given.
void stopTracking(const ElementSink &sink, colortrack::FrameTracker &tracker);

// The square of side `side` centred on `point`, clipped to the frame; empty when the point lies outside.
cv::Rect boxAround(const cv::Point2d &point, int side, cv::Size frame);
// "the click at x,y (box x,y,w,h)", for messages and the template's origin.
std::string describeClick(const ClickRequest &click, const cv::Rect &box);
// A click on a sink's letterbox border, outside the frame: logged and ignored.
void ignoreClickOutside(const ElementSink &sink, const ClickRequest &click, cv::Size frame);
// An init-box that does not lie inside the frame: an element error before streaming, a warning (and the
// box ignored) when it was set while playing.
enum class InitBoxFit { Fits, Ignored, Error };
InitBoxFit checkInitBox(const ElementSink &sink, const cv::Rect &box, cv::Size frame, bool whileStreaming,
                        const std::string &text);

}  // namespace colortrack_gst
