// SPDX-License-Identifier: LGPL-2.1-or-later
// The types of colortrack's enum and flags properties: what the settings need of the element, without the
// element.
#pragma once

#include <glib-object.h>

G_BEGIN_DECLS

/* The enum types of mode, color-space, method and verify are generated from the core tables that declare
 * their values (kTrackingModes in colortrack/frame_tracker.hpp, kColorSpaces in color.hpp, the method
 * registry's methodDescriptors() in detection_method.hpp, kVerifyModes in edges.hpp); the values are those
 * enums', in their order. */

/**
 * GstColorTrackDraw:
 * @GST_COLOR_TRACK_DRAW_NONE: no overlay: frames are only read, never written (no copy behind a tee)
 * @GST_COLOR_TRACK_DRAW_BOX: the tracked box (red: colour match, green: verified, orange: coasting)
 * @GST_COLOR_TRACK_DRAW_TRAIL: the path of the box centre (yellow)
 * @GST_COLOR_TRACK_DRAW_SEARCH_WINDOW: the region searched in this frame (blue)
 * @GST_COLOR_TRACK_DRAW_LABEL: "id score state" above the box
 * @GST_COLOR_TRACK_DRAW_MASK: mode=threshold: the pixels inside the HSV range, tinted magenta (for tuning)
 */
typedef enum {
  GST_COLOR_TRACK_DRAW_NONE = 0,
  GST_COLOR_TRACK_DRAW_BOX = (1 << 0),
  GST_COLOR_TRACK_DRAW_TRAIL = (1 << 1),
  GST_COLOR_TRACK_DRAW_SEARCH_WINDOW = (1 << 2),
  GST_COLOR_TRACK_DRAW_LABEL = (1 << 3),
  GST_COLOR_TRACK_DRAW_MASK = (1 << 4),
} GstColorTrackDraw;

#define GST_TYPE_COLOR_TRACK_MODE (gst_color_track_mode_get_type())
#define GST_TYPE_COLOR_TRACK_COLOR_SPACE (gst_color_track_color_space_get_type())
#define GST_TYPE_COLOR_TRACK_VERIFY (gst_color_track_verify_get_type())
#define GST_TYPE_COLOR_TRACK_DRAW (gst_color_track_draw_get_type())
GType gst_color_track_mode_get_type(void);
GType gst_color_track_color_space_get_type(void);
GType gst_color_track_verify_get_type(void);
#define GST_TYPE_COLOR_TRACK_METHOD (gst_color_track_method_get_type())
GType gst_color_track_method_get_type(void);
GType gst_color_track_draw_get_type(void);

G_END_DECLS
