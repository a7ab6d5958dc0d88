#include "track-document.h"

#include <gst/video/video.h>
#include <json-glib/json-glib.h>

#include <algorithm>

#include "track-params.h"

namespace trackpublish {

namespace {

// The tracker's fields of one object, when the ROI carries colortrack's parameters.
void addTrackFields(JsonBuilder *b, const GstStructure *params, double &confidence) {
  if (const char *state = gst_structure_get_string(params, COLORTRACK_PARAM_STATE)) {
    json_builder_set_member_name(b, "state");
    json_builder_add_string_value(b, state);
  }
  double score = 0;
  if (gst_structure_get_double(params, COLORTRACK_PARAM_SCORE, &score)) {
    json_builder_set_member_name(b, "score");
    json_builder_add_double_value(b, score);
    confidence = std::clamp(score, 0.0, 1.0);
  }
  gboolean verified = FALSE;
  if (gst_structure_get_boolean(params, COLORTRACK_PARAM_VERIFIED, &verified)) {
    json_builder_set_member_name(b, "verified");
    json_builder_add_boolean_value(b, verified);
  }
  for (const char *field : {COLORTRACK_PARAM_VX, COLORTRACK_PARAM_VY}) {
    double value = 0;
    if (!gst_structure_get_double(params, field, &value)) continue;
    json_builder_set_member_name(b, field);
    json_builder_add_double_value(b, value);
  }
}

void addObject(JsonBuilder *b, GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi,
               const FrameFacts &facts) {
  json_builder_begin_object(b);
  json_builder_set_member_name(b, "id");
  json_builder_add_int_value(b, roi->id);
  const struct {
    const char *name;
    guint value;
  } box[] = {{"x", roi->x}, {"y", roi->y}, {"w", roi->w}, {"h", roi->h}};
  for (const auto &field : box) {
    json_builder_set_member_name(b, field.name);
    json_builder_add_int_value(b, field.value);
  }
  double confidence = 1.0;  // a box from an element that gives no score
  if (const GstStructure *params = colortrack_find_roi_params(buffer, roi))
    addTrackFields(b, params, confidence);

  json_builder_set_member_name(b, "detection");
  json_builder_begin_object(b);
  if (facts.width > 0 && facts.height > 0) {
    json_builder_set_member_name(b, "bounding_box");
    json_builder_begin_object(b);
    const double w = facts.width, h = facts.height;
    const struct {
      const char *name;
      double value;
    } corners[] = {{"x_min", roi->x / w},
                   {"y_min", roi->y / h},
                   {"x_max", (roi->x + roi->w) / w},
                   {"y_max", (roi->y + roi->h) / h}};
    for (const auto &corner : corners) {
      json_builder_set_member_name(b, corner.name);
      json_builder_add_double_value(b, std::clamp(corner.value, 0.0, 1.0));
    }
    json_builder_end_object(b);
  }
  json_builder_set_member_name(b, "confidence");
  json_builder_add_double_value(b, confidence);
  json_builder_set_member_name(b, "label");
  json_builder_add_string_value(b, g_quark_to_string(roi->roi_type));
  json_builder_end_object(b);

  json_builder_end_object(b);
}

}  // namespace

std::string trackDocument(GstBuffer *buffer, GQuark roiType, const FrameFacts &facts) {
  JsonBuilder *b = json_builder_new_immutable();
  json_builder_begin_object(b);
  json_builder_set_member_name(b, "timestamp");
  if (GST_CLOCK_TIME_IS_VALID(facts.timestamp))
    json_builder_add_int_value(b, static_cast<gint64>(facts.timestamp));
  else
    json_builder_add_null_value(b);
  json_builder_set_member_name(b, "source");
  json_builder_add_string_value(b, facts.source.c_str());
  json_builder_set_member_name(b, "frame");
  json_builder_add_int_value(b, static_cast<gint64>(facts.frame));
  json_builder_set_member_name(b, "resolution");
  json_builder_begin_object(b);
  json_builder_set_member_name(b, "width");
  json_builder_add_int_value(b, facts.width);
  json_builder_set_member_name(b, "height");
  json_builder_add_int_value(b, facts.height);
  json_builder_end_object(b);

  json_builder_set_member_name(b, "objects");
  json_builder_begin_array(b);
  gpointer state = nullptr;
  while (GstMeta *meta =
             gst_buffer_iterate_meta_filtered(buffer, &state, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (roi->roi_type == roiType) addObject(b, buffer, roi, facts);
  }
  json_builder_end_array(b);
  json_builder_end_object(b);

  JsonNode *root = json_builder_get_root(b);
  JsonGenerator *generator = json_generator_new();
  json_generator_set_root(generator, root);
  gchar *text = json_generator_to_data(generator, nullptr);
  std::string document(text);
  g_free(text);
  g_object_unref(generator);
  json_node_unref(root);
  g_object_unref(b);
  return document;
}

}  // namespace trackpublish
