// SPDX-License-Identifier: LGPL-2.1-or-later
// Track parameters that survive videoconvert and videoscale.
//
// GStreamer 1.22's transform of GstVideoRegionOfInterestMeta (run by videoconvert, videoscale and buffer
// copies) keeps the type, id and box but drops the parameter structures; later GStreamer versions copy them.
// So every buffer with tracks also carries one custom meta, COLORTRACK_PARAMS_META_NAME, whose structure
// holds each track's "colortrack" parameters by element and id, and whose transform copies them. Write with
// colortrack_add_roi_params() and read with colortrack_find_roi_params(), which look in both places.
#pragma once

#include <gst/gst.h>
#include <gst/video/video.h>

#include "colortrack-meta.h"

G_BEGIN_DECLS

// Registers the custom meta; call once, from plugin_init.
void colortrack_params_meta_register(void);

// Adds `params` (taken) to `roi`, and a copy of it to the buffer's custom meta under
// "id-<roi id>.<element>" (and under "id-<roi id>" when no element has used that id on this buffer yet: the
// first layout, which applications read). Two colortrack elements in series thus keep both their entries.
void colortrack_add_roi_params(GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi, GstStructure *params,
                               const char *element);

// The "colortrack" parameters of `roi`: from the meta itself, else from the custom meta by the roi's id and,
// when several elements used that id, by its box. NULL when there are none (a box from another element).
// Owned by the buffer.
const GstStructure *colortrack_find_roi_params(GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi);

G_END_DECLS
