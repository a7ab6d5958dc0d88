// SPDX-License-Identifier: LGPL-2.1-or-later
#include "analytics-meta.h"

#include <algorithm>
#include <cstddef>
#include <iterator>

#include <gst/analytics/analytics.h>

#include "colortrack-meta.h"
#include "track-report.h"

namespace colortrack_gst {

namespace {

GstAnalyticsRelationMeta *relationMetaOf(GstBuffer *buffer) {
  GstAnalyticsRelationMeta *meta = gst_buffer_get_analytics_relation_meta(buffer);
  return meta ? meta : gst_buffer_add_analytics_relation_meta(buffer);
}

}  // namespace

GstClockTime AnalyticsTracks::firstSeen(int id, GstClockTime now) {
  const auto live = live_.find(id);
  if (live != live_.end()) return live->second.first;
  const auto back = std::find_if(gone_.rbegin(), gone_.rend(), [id](const auto &g) { return g.first == id; });
  if (back == gone_.rend()) return now;
  const GstClockTime first = back->second;
  gone_.erase(std::next(back).base());
  return first;
}

void AnalyticsTracks::attach(GstBuffer *buffer, const colortrack::FrameReport &report, cv::Size frame) {
  const GstClockTime now = GST_BUFFER_PTS(buffer);
  const GQuark type = g_quark_from_static_string(COLORTRACK_ROI_TYPE);
  std::map<int, Seen> seen;
  GstAnalyticsRelationMeta *meta = nullptr;
  for (const colortrack::TrackReport &track : report.tracks) {
    const cv::Rect box = frameBox(track.box, frame);
    if (box.empty() || track.id <= 0) continue;
    const Seen s{firstSeen(track.id, now), now};
    const bool lost = track.state == colortrack::TrackState::Lost;
    if (lost)
      gone_.emplace_back(track.id, s.first);  // said lost now, and not again on the next frame
    else
      seen[track.id] = s;
    if (!meta) meta = relationMetaOf(buffer);
    GstAnalyticsODMtd od;
    GstAnalyticsTrackingMtd tracking;
    const auto confidence = static_cast<gfloat>(std::clamp(track.score, 0.0, 1.0));
    if (!gst_analytics_relation_meta_add_od_mtd(meta, type, box.x, box.y, box.width, box.height, confidence,
                                                &od) ||
        !gst_analytics_relation_meta_add_tracking_mtd(meta, static_cast<guint64>(track.id), s.first,
                                                      &tracking)) {
      GST_WARNING("could not add the analytics meta of track %d", track.id);
      continue;
    }
    gst_analytics_tracking_mtd_update_last_seen(&tracking, now);
    if (lost) gst_analytics_tracking_mtd_set_lost(&tracking);
    gst_analytics_relation_meta_set_relation(meta, GST_ANALYTICS_REL_TYPE_RELATE_TO, od.id, tracking.id);
  }
  // Gone since the previous frame: said once, as lost.
  for (const auto &[id, s] : live_) {
    if (seen.count(id)) continue;
    if (!meta) meta = relationMetaOf(buffer);
    GstAnalyticsTrackingMtd tracking;
    if (!gst_analytics_relation_meta_add_tracking_mtd(meta, static_cast<guint64>(id), s.first, &tracking)) {
      GST_WARNING("could not add the analytics meta of lost track %d", id);
      continue;
    }
    gst_analytics_tracking_mtd_update_last_seen(&tracking, s.last);
    gst_analytics_tracking_mtd_set_lost(&tracking);
    gone_.emplace_back(id, s.first);
  }
  if (gone_.size() > kRememberedGone)
    gone_.erase(gone_.begin(), gone_.end() - static_cast<std::ptrdiff_t>(kRememberedGone));
  live_ = std::move(seen);
}

}  // namespace colortrack_gst
