// What both modes do alike: where a target comes from (the init-box, the click-to-track square), a reset
// and a stop.
#include <cmath>
#include <cstdio>

#include "colortrack-modes.h"
#include "property-table.h"

#define GST_CAT_DEFAULT gst_color_track_debug

namespace colortrack_gst {

void resetIfRequested(GstColorTrack *self, colortrack::FrameTracker &tracker) {
  State &state = self->priv->state;
  if (!state.capsChanged && !self->priv->resetRequested.exchange(false)) return;
  state.capsChanged = false;
  tracker.reset();
  state.trails.clear();
}

void stopTracking(State &state, colortrack::FrameTracker &tracker) {
  tracker.reset();
  state.trails.clear();
  state.idle = true;
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

InitBoxFit checkInitBox(GstColorTrack *self, const cv::Rect &box, cv::Size frame, bool whileStreaming,
                        const std::string &text) {
  if ((box & cv::Rect(cv::Point(), frame)) == box) return InitBoxFit::Fits;
  if (whileStreaming) {
    GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS,
                        ("Property 'init-box' '%s' does not fit in the %dx%d frame: ignored.", text.c_str(),
                         frame.width, frame.height),
                        (nullptr));
    return InitBoxFit::Ignored;
  }
  GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                    ("Property 'init-box' '%s' does not fit in the %dx%d frame.",
                     gstglue::validUtf8(text).c_str(), frame.width, frame.height),
                    (nullptr));
  return InitBoxFit::Error;
}

}  // namespace colortrack_gst
