// SPDX-License-Identifier: LGPL-2.1-or-later
#include "track-report.h"

#include <cmath>

#include "colortrack-meta.h"
#include "dlstreamer-params.h"
#include "track-params.h"

namespace colortrack_gst {

cv::Rect frameBox(const cv::Rect2d &box, cv::Size frame) {
  const int x0 = static_cast<int>(std::lround(box.x)), y0 = static_cast<int>(std::lround(box.y));
  const int x1 = static_cast<int>(std::lround(box.x + box.width));
  const int y1 = static_cast<int>(std::lround(box.y + box.height));
  return cv::Rect(cv::Point(x0, y0), cv::Point(x1, y1)) & cv::Rect(cv::Point(), frame);
}

void attachTrackMeta(GstElement *element, GstBuffer *buffer, const colortrack::TrackReport &track,
                     cv::Size frame) {
  const cv::Rect box = frameBox(track.box, frame);
  if (box.empty()) return;
  GstVideoRegionOfInterestMeta *meta = gst_buffer_add_video_region_of_interest_meta(
      buffer, COLORTRACK_ROI_TYPE, static_cast<guint>(box.x), static_cast<guint>(box.y),
      static_cast<guint>(box.width), static_cast<guint>(box.height));
  meta->id = track.id;
  GstStructure *params = gst_structure_new(
      COLORTRACK_PARAMS_NAME, COLORTRACK_PARAM_STATE, G_TYPE_STRING, colortrack::toString(track.state),
      COLORTRACK_PARAM_SCORE, G_TYPE_DOUBLE, track.score, COLORTRACK_PARAM_VERIFIED, G_TYPE_BOOLEAN,
      static_cast<gboolean>(track.verified), COLORTRACK_PARAM_SCALE, G_TYPE_DOUBLE, track.scale,
      COLORTRACK_PARAM_VX, G_TYPE_DOUBLE, track.vx, COLORTRACK_PARAM_VY, G_TYPE_DOUBLE, track.vy, nullptr);
  if (track.area) gst_structure_set(params, COLORTRACK_PARAM_AREA, G_TYPE_DOUBLE, *track.area, nullptr);
  colortrack_add_roi_params(buffer, meta, params, GST_ELEMENT_NAME(element));
  colortrack_add_dlstreamer_params(meta, frame.width, frame.height, track.score);
}

namespace {

GstStructure *objectStructure(const colortrack::TrackReport &o) {
  return gst_structure_new(
      COLORTRACK_OBJECT_NAME, COLORTRACK_OBJECT_ID, G_TYPE_INT, o.id, COLORTRACK_OBJECT_X, G_TYPE_DOUBLE,
      o.box.x, COLORTRACK_OBJECT_Y, G_TYPE_DOUBLE, o.box.y, COLORTRACK_OBJECT_WIDTH, G_TYPE_DOUBLE,
      o.box.width, COLORTRACK_OBJECT_HEIGHT, G_TYPE_DOUBLE, o.box.height, COLORTRACK_OBJECT_CX, G_TYPE_DOUBLE,
      o.centre.x, COLORTRACK_OBJECT_CY, G_TYPE_DOUBLE, o.centre.y, COLORTRACK_OBJECT_AREA, G_TYPE_DOUBLE,
      o.area.value_or(0.0), COLORTRACK_OBJECT_STATE, G_TYPE_STRING, colortrack::toString(o.state),
      COLORTRACK_OBJECT_SCORE, G_TYPE_DOUBLE, o.score, nullptr);
}

}  // namespace

void postTrackMessage(GstElement *element, const GstSegment &segment, GstBuffer *buffer, guint64 frame,
                      const colortrack::FrameReport &report, const char *stateName) {
  const GstClockTime pts = GST_BUFFER_PTS(buffer);
  GstClockTime streamTime = GST_CLOCK_TIME_NONE, runningTime = GST_CLOCK_TIME_NONE;
  if (GST_CLOCK_TIME_IS_VALID(pts) && segment.format == GST_FORMAT_TIME) {
    streamTime = gst_segment_to_stream_time(&segment, GST_FORMAT_TIME, pts);
    runningTime = gst_segment_to_running_time(&segment, GST_FORMAT_TIME, pts);
  }
  const colortrack::TrackReport &p = report.primary;
  GstStructure *s = gst_structure_new(
      COLORTRACK_MESSAGE_NAME, COLORTRACK_MESSAGE_TIMESTAMP, G_TYPE_UINT64, static_cast<guint64>(pts),
      COLORTRACK_MESSAGE_STREAM_TIME, G_TYPE_UINT64, static_cast<guint64>(streamTime),
      COLORTRACK_MESSAGE_RUNNING_TIME, G_TYPE_UINT64, static_cast<guint64>(runningTime),
      COLORTRACK_MESSAGE_DURATION, G_TYPE_UINT64, static_cast<guint64>(GST_BUFFER_DURATION(buffer)),
      COLORTRACK_MESSAGE_FRAME, G_TYPE_UINT64, frame, COLORTRACK_MESSAGE_ID, G_TYPE_INT, p.id,
      COLORTRACK_MESSAGE_STATE, G_TYPE_STRING, stateName ? stateName : colortrack::toString(p.state),
      COLORTRACK_MESSAGE_X, G_TYPE_DOUBLE, p.box.x, COLORTRACK_MESSAGE_Y, G_TYPE_DOUBLE, p.box.y,
      COLORTRACK_MESSAGE_WIDTH, G_TYPE_DOUBLE, p.box.width, COLORTRACK_MESSAGE_HEIGHT, G_TYPE_DOUBLE,
      p.box.height, COLORTRACK_MESSAGE_SCORE, G_TYPE_DOUBLE, p.score, COLORTRACK_MESSAGE_VERIFIED,
      G_TYPE_BOOLEAN, static_cast<gboolean>(p.verified), COLORTRACK_MESSAGE_SCALE, G_TYPE_DOUBLE, p.scale,
      nullptr);
  if (report.listsTracks) {
    GValue list = G_VALUE_INIT;
    g_value_init(&list, GST_TYPE_LIST);
    for (const colortrack::TrackReport &o : report.tracks) {
      GValue item = G_VALUE_INIT;
      g_value_init(&item, GST_TYPE_STRUCTURE);
      GstStructure *object = objectStructure(o);
      gst_value_set_structure(&item, object);
      gst_structure_free(object);
      gst_value_list_append_and_take_value(&list, &item);
    }
    gst_structure_take_value(s, COLORTRACK_MESSAGE_OBJECTS, &list);
  }
  gst_element_post_message(element, gst_message_new_element(GST_OBJECT(element), s));
}

}  // namespace colortrack_gst
