// SPDX-License-Identifier: LGPL-2.1-or-later
// The GTypes of colortrack's enum and flags properties, generated from the core tables that declare the
// values.

#include "colortrack-enums.h"

#include "colortrack/detection_method.hpp"
#include "colortrack/edges.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/color.hpp"
#include "enum-types.h"

COLORTRACK_DEFINE_CHOICE_TYPE(gst_color_track_mode_get_type, "GstColorTrackMode", colortrack::kTrackingModes)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_color_track_color_space_get_type, "GstColorTrackColorSpace",
                              colortrack::kColorSpaces)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_color_track_verify_get_type, "GstColorTrackVerify",
                              colortrack::kVerifyModes)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_color_track_method_get_type, "GstColorTrackMethod",
                              colortrack::methodDescriptors())
COLORTRACK_DEFINE_FLAGS_TYPE(
    gst_color_track_draw_get_type, "GstColorTrackDraw",
    {GST_COLOR_TRACK_DRAW_NONE, "No overlay: frames are only read (no copy behind a tee)", "none"},
    {GST_COLOR_TRACK_DRAW_BOX, "Box (red: colour match, green: verified, orange: coasting)", "box"},
    {GST_COLOR_TRACK_DRAW_TRAIL, "Trail of the box centre (yellow)", "trail"},
    {GST_COLOR_TRACK_DRAW_SEARCH_WINDOW, "Region searched this frame (blue)", "search-window"},
    {GST_COLOR_TRACK_DRAW_LABEL, "Label \"id score state\" (threshold: \"id area state\")", "label"},
    {GST_COLOR_TRACK_DRAW_MASK, "mode=threshold: pixels inside the HSV range, tinted magenta", "mask"})
