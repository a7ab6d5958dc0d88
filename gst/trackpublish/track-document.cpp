// SPDX-License-Identifier: LGPL-2.1-or-later
#include "track-document.h"

#include <gst/video/video.h>

#include <algorithm>
#include <set>
#include <vector>
// nlohmann-json rather than json-glib: the same document costs 0.06 ms instead of 0.38 ms with 8 tracks
// (json-glib builds and seals a node tree and formats every double twice), and the budget is 0.2 ms a frame
// (tests/bench/bench_trackpublish.cpp).
#include <nlohmann/json.hpp>

#include "track-params.h"

namespace trackpublish {

namespace {

using Json = nlohmann::ordered_json;  // members in the order written, as gvametaconvert writes them

// The tracker's fields of one object, when the ROI carries colortrack's parameters.
void addTrackFields(Json &object, const GstStructure *params, double &confidence) {
  if (const char *state = gst_structure_get_string(params, COLORTRACK_PARAM_STATE)) object["state"] = state;
  double score = 0;
  if (gst_structure_get_double(params, COLORTRACK_PARAM_SCORE, &score)) {
    object["score"] = score;
    confidence = std::clamp(score, 0.0, 1.0);
  }
  gboolean verified = FALSE;
  if (gst_structure_get_boolean(params, COLORTRACK_PARAM_VERIFIED, &verified))
    object["verified"] = static_cast<bool>(verified);
  for (const char *field : {COLORTRACK_PARAM_VX, COLORTRACK_PARAM_VY, COLORTRACK_PARAM_AREA}) {
    double value = 0;
    if (gst_structure_get_double(params, field, &value)) object[field] = value;
  }
}

Json objectOf(GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi, const FrameFacts &facts) {
  Json object;
  object["id"] = roi->id;
  object["roi_type"] = g_quark_to_string(roi->roi_type);
  object["x"] = roi->x;
  object["y"] = roi->y;
  object["w"] = roi->w;
  object["h"] = roi->h;
  double confidence = 1.0;  // a box from an element that gives no score
  if (const GstStructure *params = colortrack_find_roi_params(buffer, roi))
    addTrackFields(object, params, confidence);
  Json detection;
  if (facts.width > 0 && facts.height > 0) {
    const double w = facts.width, h = facts.height;
    const auto unit = [](double v) { return std::clamp(v, 0.0, 1.0); };
    detection["bounding_box"] = {{"x_min", unit(roi->x / w)},
                                 {"y_min", unit(roi->y / h)},
                                 {"x_max", unit((roi->x + roi->w) / w)},
                                 {"y_max", unit((roi->y + roi->h) / h)}};
  }
  detection["confidence"] = confidence;
  detection["label"] = g_quark_to_string(roi->roi_type);
  detection["label_id"] = 0;  // one class: what roi-type selects
  object["detection"] = std::move(detection);
  return object;
}

}  // namespace

std::string trackDocument(GstBuffer *buffer, GQuark roiType, const FrameFacts &facts) {
  Json objects = Json::array();
  gpointer state = nullptr;
  while (GstMeta *meta =
             gst_buffer_iterate_meta_filtered(buffer, &state, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (roi->roi_type == roiType) objects.push_back(objectOf(buffer, roi, facts));
  }
  if (objects.empty() && !facts.addEmptyResults) return "";
  Json document;
  document["timestamp"] =
      GST_CLOCK_TIME_IS_VALID(facts.timestamp) ? Json(static_cast<guint64>(facts.timestamp)) : Json(nullptr);
  document["source"] = facts.source;
  document["run"] = facts.run;
  document["frame"] = facts.frame;
  document["resolution"] = {{"width", facts.width}, {"height", facts.height}};
  if (!facts.tags.is_null()) document["tags"] = facts.tags;
  // As gvametaconvert: an empty frame's document (add-empty-results) has no "objects" key at all.
  if (!objects.empty()) document["objects"] = std::move(objects);
  // Invalid UTF-8 in a source name is replaced rather than thrown.
  return document.dump(-1, ' ', false, Json::error_handler_t::replace);
}

colortrack::Status checkTags(const std::string &tags) {
  // What JSON allows but a consumer would trip on: a key given twice (which one wins differs between
  // readers) and a NUL character (which C strings cut).
  std::string problem;
  std::vector<std::set<std::string>> keysPerObject;
  const auto check = [&](int, Json::parse_event_t event, Json &value) {
    if (event == Json::parse_event_t::object_start) keysPerObject.emplace_back();
    if (event == Json::parse_event_t::object_end && !keysPerObject.empty()) keysPerObject.pop_back();
    const bool text =
        (event == Json::parse_event_t::key || event == Json::parse_event_t::value) && value.is_string();
    if (text && problem.empty() && value.get_ref<const std::string &>().find('\0') != std::string::npos)
      problem = "it holds a NUL character (\\u0000)";
    if (event == Json::parse_event_t::key && !keysPerObject.empty() && problem.empty() &&
        !keysPerObject.back().insert(value.get<std::string>()).second)
      problem = "the key \"" + value.get<std::string>() + "\" is given twice";
    return true;
  };
  const Json parsed = Json::parse(tags, check, false);
  if (parsed.is_discarded())
    return colortrack::Status::failure("it is not JSON (expected an object such as {\"site\":\"dock-3\"})");
  if (!parsed.is_object())
    return colortrack::Status::failure("it must be a JSON object such as {\"site\":\"dock-3\"}");
  return problem.empty() ? colortrack::Status() : colortrack::Status::failure(problem);
}

}  // namespace trackpublish
