// What each mode does to a frame before it is tracked: the settings, the template or colour range, and the
// init-box and clicks waiting in the mailbox, applied to that mode's tracker. Errors are posted on the
// element; a false return means streaming must stop.
#pragma once

#include <string>

#include <opencv2/core.hpp>

#include "colortrack-requests.h"
#include "colortrack-state.h"
#include "frame-view.h"

namespace colortrack_gst {

// Template mode: tracker settings, a new template file, a reset, then init-box and clicks.
bool prepareTemplateFrame(GstColorTrack *self, const Snapshot &snapshot, const Requests &requests,
                          const colortrack_gst::FrameView &view);

// Whether the template tracker can take this frame: it has a template (else a warning, once) that fits in
// the frame (else an error).
enum class TemplateReadiness { Ready, NoTemplate, Error };
TemplateReadiness templateReadiness(GstColorTrack *self, cv::Size frame);

// Threshold mode: blob and track settings, a reset, then a colour range learnt from an init-box or a click.
bool prepareThresholdFrame(GstColorTrack *self, const Snapshot &snapshot, const Requests &requests,
                           const colortrack_gst::FrameView &view);

// Reads a template file; on failure fills `why` and says whether the file exists at all.
bool loadTemplateFile(const std::string &path, cv::Mat &bgr, cv::Mat &mask, std::string &why, bool &missing);

// --- Shared by both modes (colortrack-targets.cpp) ---

// After new caps or the "reset" signal: the tracks and their trails are forgotten (the target stays).
void resetIfRequested(GstColorTrack *self, colortrack::FrameTracker &tracker);
// A right click: no target until a new one is given.
void stopTracking(State &state, colortrack::FrameTracker &tracker);

// The square of side `side` centred on `point`, clipped to the frame; empty when the point lies outside.
cv::Rect boxAround(const cv::Point2d &point, int side, cv::Size frame);
// "the click at x,y (box x,y,w,h)", for messages and the template's origin.
std::string describeClick(const ClickRequest &click, const cv::Rect &box);
// An init-box that does not lie inside the frame: an element error before streaming, a warning (and the
// box ignored) when it was set while playing.
enum class InitBoxFit { Fits, Ignored, Error };
InitBoxFit checkInitBox(GstColorTrack *self, const cv::Rect &box, cv::Size frame, bool whileStreaming,
                        const std::string &text);

}  // namespace colortrack_gst
