// SPDX-License-Identifier: LGPL-2.1-or-later
#include "track-params.h"

#include <cctype>
#include <cmath>
#include <string>
#include <vector>

namespace {

// The entry of one element's track: "id-<track id>.<element name>", the name reduced to the characters a
// structure field name may hold.
std::string elementEntry(gint id, const char *element) {
  std::string name = element ? element : "";
  for (char &c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') c = '_';
  return "id-" + std::to_string(id) + "." + name;
}

// The entry every reader of the first layout looks for; written by the first element with this id only.
std::string sharedEntry(gint id) {
  return "id-" + std::to_string(id);
}

gboolean copyField(GQuark field, const GValue *value, gpointer destination) {
  gst_structure_id_set_value(static_cast<GstStructure *>(destination), field, value);
  return TRUE;
}

// Copies the parameters on buffer copies and video transforms (scale, convert). The parameters hold no
// coordinates of the frame (vx, vy stay in the tracker's pixels), so nothing is rescaled; the box kept for
// telling entries apart is compared up to scale (see colortrack_find_roi_params).
gboolean transformParams(GstBuffer *destination, GstCustomMeta *meta, GstBuffer * /*source*/, GQuark type,
                         gpointer /*data*/, gpointer /*user_data*/) {
  if (!GST_META_TRANSFORM_IS_COPY(type) && !GST_VIDEO_META_TRANSFORM_IS_SCALE(type)) return FALSE;
  GstCustomMeta *copy = gst_buffer_add_custom_meta(destination, COLORTRACK_PARAMS_META_NAME);
  if (!copy) return FALSE;
  gst_structure_foreach(gst_custom_meta_get_structure(meta), copyField, gst_custom_meta_get_structure(copy));
  return TRUE;
}

struct Candidate {
  const GstStructure *params;
  gint x, y, w, h;
};

gboolean collectCandidates(GQuark field, const GValue *value, gpointer data) {
  auto *found = static_cast<std::pair<std::string, std::vector<Candidate>> *>(data);
  const std::string name = g_quark_to_string(field);
  if (name.compare(0, found->first.size(), found->first) != 0 || !GST_VALUE_HOLDS_STRUCTURE(value))
    return TRUE;
  const GstStructure *params = gst_value_get_structure(value);
  Candidate c{params, 0, 0, 0, 0};
  gst_structure_get(params, "roi-x", G_TYPE_INT, &c.x, "roi-y", G_TYPE_INT, &c.y, "roi-w", G_TYPE_INT, &c.w,
                    "roi-h", G_TYPE_INT, &c.h, nullptr);
  found->second.push_back(c);
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

void colortrack_add_roi_params(GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi, GstStructure *params,
                               const char *element) {
  GstCustomMeta *meta = gst_buffer_get_custom_meta(buffer, COLORTRACK_PARAMS_META_NAME);
  if (!meta) meta = gst_buffer_add_custom_meta(buffer, COLORTRACK_PARAMS_META_NAME);
  if (meta) {
    GstStructure *entries = gst_custom_meta_get_structure(meta);
    // The copy also names its element and box, so that two elements' tracks with one id stay apart.
    GstStructure *entry = gst_structure_copy(params);
    gst_structure_set(entry, "element", G_TYPE_STRING, element ? element : "", "roi-x", G_TYPE_INT,
                      static_cast<gint>(roi->x), "roi-y", G_TYPE_INT, static_cast<gint>(roi->y), "roi-w",
                      G_TYPE_INT, static_cast<gint>(roi->w), "roi-h", G_TYPE_INT, static_cast<gint>(roi->h),
                      nullptr);
    const std::string shared = sharedEntry(roi->id);
    if (!gst_structure_has_field(entries, shared.c_str()))
      gst_structure_set(entries, shared.c_str(), GST_TYPE_STRUCTURE, entry, nullptr);
    gst_structure_set(entries, elementEntry(roi->id, element).c_str(), GST_TYPE_STRUCTURE, entry, nullptr);
    gst_structure_free(entry);
  }
  gst_video_region_of_interest_meta_add_param(roi, params);
}

const GstStructure *colortrack_find_roi_params(GstBuffer *buffer, GstVideoRegionOfInterestMeta *roi) {
  if (const GstStructure *own = gst_video_region_of_interest_meta_get_param(roi, COLORTRACK_PARAMS_NAME))
    return own;
  GstCustomMeta *meta = gst_buffer_get_custom_meta(buffer, COLORTRACK_PARAMS_META_NAME);
  if (!meta) return nullptr;
  std::pair<std::string, std::vector<Candidate>> found{sharedEntry(roi->id) + ".", {}};
  gst_structure_foreach(gst_custom_meta_get_structure(meta), collectCandidates, &found);
  const std::vector<Candidate> &candidates = found.second;
  if (candidates.empty()) return nullptr;
  // One element tracked this id: its entry. Several: the one whose box this ROI still has (copies keep boxes
  // exactly), else the one whose box matches best up to a scale (videoscale scales every box alike).
  if (candidates.size() == 1) return candidates[0].params;
  const Candidate *best = nullptr;
  double bestDistance = 0;
  for (const Candidate &c : candidates) {
    if (c.x == static_cast<gint>(roi->x) && c.y == static_cast<gint>(roi->y) &&
        c.w == static_cast<gint>(roi->w) && c.h == static_cast<gint>(roi->h))
      return c.params;
    if (c.w <= 0 || c.h <= 0 || roi->w == 0 || roi->h == 0) continue;
    const double sx = static_cast<double>(roi->w) / c.w, sy = static_cast<double>(roi->h) / c.h;
    const double distance = std::abs(roi->x - c.x * sx) + std::abs(roi->y - c.y * sy);
    if (!best || distance < bestDistance) {
      best = &c;
      bestDistance = distance;
    }
  }
  return best ? best->params : candidates[0].params;
}
