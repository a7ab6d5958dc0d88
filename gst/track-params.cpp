#include "track-params.h"

#include <string>

namespace {

std::string fieldFor(gint id) {
  return "id-" + std::to_string(id);
}

gboolean copyField(GQuark field, const GValue *value, gpointer destination) {
  gst_structure_id_set_value(static_cast<GstStructure *>(destination), field, value);
  return TRUE;
}

// Copies the parameters on buffer copies and video transforms (scale, convert). The parameters hold no
// coordinates of the frame (vx, vy stay in the tracker's pixels), so nothing is rescaled.
gboolean transformParams(GstBuffer *destination, GstCustomMeta *meta, GstBuffer * /*source*/, GQuark type,
                         gpointer /*data*/, gpointer /*user_data*/) {
  if (!GST_META_TRANSFORM_IS_COPY(type) && !GST_VIDEO_META_TRANSFORM_IS_SCALE(type)) return FALSE;
  GstCustomMeta *copy = gst_buffer_add_custom_meta(destination, COLORTRACK_PARAMS_META_NAME);
  if (!copy) return FALSE;
  gst_structure_foreach(gst_custom_meta_get_structure(meta), copyField, gst_custom_meta_get_structure(copy));
  return TRUE;
}

}  // namespace

void colortrack_params_meta_register(void) {
  // The same tags as the ROI meta, so every element that keeps the boxes keeps their parameters too.
  static const gchar *tags[] = {GST_META_TAG_VIDEO_STR, GST_META_TAG_VIDEO_ORIENTATION_STR,
                                GST_META_TAG_VIDEO_SIZE_STR, nullptr};
  if (!gst_meta_get_info(COLORTRACK_PARAMS_META_NAME))
    gst_meta_register_custom(COLORTRACK_PARAMS_META_NAME, tags, transformParams, nullptr, nullptr);
}

void colortrack_add_roi_params(GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi, GstStructure *params) {
  GstCustomMeta *meta = gst_buffer_get_custom_meta(buffer, COLORTRACK_PARAMS_META_NAME);
  if (!meta) meta = gst_buffer_add_custom_meta(buffer, COLORTRACK_PARAMS_META_NAME);
  if (meta)
    gst_structure_set(gst_custom_meta_get_structure(meta), fieldFor(roi->id).c_str(), GST_TYPE_STRUCTURE,
                      params, nullptr);
  gst_video_region_of_interest_meta_add_param(roi, params);
}

const GstStructure *colortrack_find_roi_params(GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi) {
  if (const GstStructure *own = gst_video_region_of_interest_meta_get_param(roi, COLORTRACK_PARAMS_NAME))
    return own;
  GstCustomMeta *meta = gst_buffer_get_custom_meta(buffer, COLORTRACK_PARAMS_META_NAME);
  if (!meta) return nullptr;
  const GValue *value =
      gst_structure_get_value(gst_custom_meta_get_structure(meta), fieldFor(roi->id).c_str());
  return value && GST_VALUE_HOLDS_STRUCTURE(value) ? gst_value_get_structure(value) : nullptr;
}
