// SPDX-License-Identifier: LGPL-2.1-or-later
// DL Streamer's view of a box: the parameter structures its elements (gvametaconvert, gvawatermark,
// gvapython, through gva_utils) read on each GstVideoRegionOfInterestMeta, beside colortrack's own:
//   "detection": x_min, y_min, x_max, y_max (double, the box normalised to the frame), confidence (double
//                0-1), label_id (int, 0: one class), label (string, the ROI type);
//   "object_id": id (int, the track id).
// Written from DL Streamer's documented meta layout; DL Streamer is not in Debian, so its tests read them
// back the way its code does (tests/gst/test_dlstreamer_params.cpp).
#pragma once

#include <gst/video/video.h>

G_BEGIN_DECLS

#define COLORTRACK_DLS_DETECTION "detection"
#define COLORTRACK_DLS_OBJECT_ID "object_id"

// Adds both structures to `roi` for a frame of width x height; `confidence` is clamped to 0..1.
void colortrack_add_dlstreamer_params(GstVideoRegionOfInterestMeta *roi, gint width, gint height,
                                      gdouble confidence);

G_END_DECLS
