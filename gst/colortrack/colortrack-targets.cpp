// SPDX-License-Identifier: LGPL-2.1-or-later
// What both modes do alike: where a target comes from (the init-box, the click-to-track square), a reset
// and a stop.
#include <cmath>
#include <cstdio>

#include "colortrack-mode.h"
#include "property-table.h"

namespace colortrack_gst {

void resetIfRequested(const ElementSink &sink, colortrack::FrameTracker &tracker) {
  if (!sink.takeResetRequest()) return;
  tracker.reset();
  sink.tracksReset();
}

void stopTracking(const ElementSink &sink, colortrack::FrameTracker &tracker) {
  tracker.reset();
  sink.stopped();
}

// Clipped rather than moved, so it stays centred on what was clicked, only smaller, near an edge. A click on
// a sink's letterbox border lies outside the frame.
cv::Rect boxAround(const cv::Point2d &point, int side, cv::Size frame) {
  const cv::Rect frameRect(cv::Point(), frame);
  if (!(point.x >= 0 && point.y >= 0 && point.x < frame.width && point.y < frame.height)) return cv::Rect();
  const cv::Point topLeft(static_cast<int>(std::lround(point.x - side / 2.0)),
                          static_cast<int>(std::lround(point.y - side / 2.0)));
  return cv::Rect(topLeft, cv::Size(side, side)) & frameRect;
}

std::string describeClick(const ClickRequest &click, const cv::Rect &box) {
  char text[96];
  std::snprintf(text, sizeof text, "the click at %.0f,%.0f (box %d,%d,%d,%d)", click.point.x, click.point.y,
                box.x, box.y, box.width, box.height);
  return text;
}

void ignoreClickOutside(const ElementSink &sink, const ClickRequest &click, cv::Size frame) {
  char text[128];
  std::snprintf(text, sizeof text, "click at %.1f,%.1f lies outside the %dx%d frame: ignored", click.point.x,
                click.point.y, frame.width, frame.height);
  sink.info(text);
}

InitBoxFit checkInitBox(const ElementSink &sink, const cv::Rect &box, cv::Size frame, bool whileStreaming,
                        const std::string &text) {
  if ((box & cv::Rect(cv::Point(), frame)) == box) return InitBoxFit::Fits;
  const std::string what = "Property 'init-box' '" + gstglue::validUtf8(text) + "' does not fit in the " +
                           std::to_string(frame.width) + "x" + std::to_string(frame.height) + " frame";
  if (whileStreaming) {
    sink.warning(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_SETTINGS, what + ": ignored.");
    return InitBoxFit::Ignored;
  }
  sink.error(GST_RESOURCE_ERROR, GST_RESOURCE_ERROR_SETTINGS, what + ".");
  return InitBoxFit::Error;
}

}  // namespace colortrack_gst
