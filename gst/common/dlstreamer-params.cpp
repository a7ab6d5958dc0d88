// SPDX-License-Identifier: LGPL-2.1-or-later
#include "dlstreamer-params.h"

#include <algorithm>

void colortrack_add_dlstreamer_params(GstVideoRegionOfInterestMeta *roi, gint width, gint height,
                                      gdouble confidence) {
  if (width <= 0 || height <= 0) return;
  const double w = width, h = height;
  const auto unit = [](double v) { return std::clamp(v, 0.0, 1.0); };
  gst_video_region_of_interest_meta_add_param(
      roi, gst_structure_new(COLORTRACK_DLS_DETECTION, "x_min", G_TYPE_DOUBLE, unit(roi->x / w), "y_min",
                             G_TYPE_DOUBLE, unit(roi->y / h), "x_max", G_TYPE_DOUBLE,
                             unit((roi->x + roi->w) / w), "y_max", G_TYPE_DOUBLE, unit((roi->y + roi->h) / h),
                             "confidence", G_TYPE_DOUBLE, unit(confidence), "label_id", G_TYPE_INT, 0,
                             "label", G_TYPE_STRING, g_quark_to_string(roi->roi_type), nullptr));
  gst_video_region_of_interest_meta_add_param(
      roi, gst_structure_new(COLORTRACK_DLS_OBJECT_ID, "id", G_TYPE_INT, roi->id, nullptr));
}
