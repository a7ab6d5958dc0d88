// SPDX-License-Identifier: LGPL-2.1-or-later
// GStreamer's analytics meta (1.24 and newer; built only when meson finds gstreamer-analytics-1.0):
// colortrack mode=threshold on balls crossing, leaving and coming into the frame, followed by
// objectdetectionoverlay (gst-plugins-bad), which draws the od mtds. Downstream of both, on every buffer: one
// od mtd per ROI meta with the same box, type "colortrack" and a confidence in 0..1, each related (RELATE_TO)
// to a tracking mtd whose id is the ROI meta's, first seen when that id was first reported, last seen now,
// not lost; a tracking mtd without an od mtd only for a track reported on the previous frame and gone now,
// lost. C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard
// library.
#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "balls.hpp"
#include "gst_test_util.hpp"

#include <gst/analytics/analytics.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/navigation.h>
#include <gst/video/video.h>

namespace {

using colortrack::balls::Ball;
using colortrack::balls::BallScene;
using colortrack::balls::BallSceneConfig;
using namespace colortrack::gst_test_util;

struct Od {
  guint mtdId = 0;
  cv::Rect box;
  float confidence = 0;
  GQuark type = 0;
  bool hasTracking = false;
  guint64 trackId = 0;
  GstClockTime firstSeen = GST_CLOCK_TIME_NONE, lastSeen = GST_CLOCK_TIME_NONE;
  gboolean lost = FALSE;
};

struct Tracking {
  guint mtdId = 0;
  guint64 trackId = 0;
  GstClockTime firstSeen = GST_CLOCK_TIME_NONE, lastSeen = GST_CLOCK_TIME_NONE;
  gboolean lost = FALSE;
  bool relatedToOd = false;
};

struct Analytics {
  std::vector<Od> ods;
  std::vector<Tracking> trackings;
};

Analytics readAnalytics(GstBuffer *buffer) {
  Analytics a;
  GstAnalyticsRelationMeta *meta = gst_buffer_get_analytics_relation_meta(buffer);
  if (!meta) return a;
  gpointer state = nullptr;
  GstAnalyticsODMtd od;
  while (gst_analytics_relation_meta_iterate(meta, &state, gst_analytics_od_mtd_get_mtd_type(), &od)) {
    Od o;
    o.mtdId = od.id;
    gint x = 0, y = 0, w = 0, h = 0;
    fail_unless(gst_analytics_od_mtd_get_location(&od, &x, &y, &w, &h, &o.confidence));
    o.box = cv::Rect(x, y, w, h);
    o.type = gst_analytics_od_mtd_get_obj_type(&od);
    gpointer related = nullptr;
    GstAnalyticsTrackingMtd tracking;
    if (gst_analytics_relation_meta_get_direct_related(meta, od.id, GST_ANALYTICS_REL_TYPE_RELATE_TO,
                                                       gst_analytics_tracking_mtd_get_mtd_type(), &related,
                                                       &tracking)) {
      o.hasTracking = true;
      fail_unless(
          gst_analytics_tracking_mtd_get_info(&tracking, &o.trackId, &o.firstSeen, &o.lastSeen, &o.lost));
    }
    a.ods.push_back(o);
  }
  state = nullptr;
  GstAnalyticsTrackingMtd tracking;
  while (gst_analytics_relation_meta_iterate(meta, &state, gst_analytics_tracking_mtd_get_mtd_type(),
                                             &tracking)) {
    Tracking t;
    t.mtdId = tracking.id;
    fail_unless(
        gst_analytics_tracking_mtd_get_info(&tracking, &t.trackId, &t.firstSeen, &t.lastSeen, &t.lost));
    for (const Od &o : a.ods)
      if (gst_analytics_relation_meta_get_relation(meta, o.mtdId, tracking.id) ==
          GST_ANALYTICS_REL_TYPE_RELATE_TO)
        t.relatedToOd = true;
    a.trackings.push_back(t);
  }
  return a;
}

// Four balls: crossing, leaving at the right and coming back, leaving left, entering at the top and leaving
// at the bottom (the scene of test_colortrack_threshold's meta-and-message test).
BallScene exitsScene() {
  BallSceneConfig config;
  config.clutterHueClearance = 0;
  config.clutterSaturation = 0.35;
  std::vector<Ball> balls(4);
  balls[0].path = {{0, {40, 240}}, {60, {700, 240}}, {120, {300, 240}}};
  balls[1].hue = 20;
  balls[1].radius = 14;
  balls[1].path = {{0, {600, 230}}, {120, {-40, 250}}};
  balls[2].path = {{0, {320, -30}}, {120, {320, 520}}};
  balls[3].radius = 30;
  balls[3].path = {{0, {100, 400}}, {120, {560, 80}}};
  return BallScene(config, balls);
}

}  // namespace

GST_START_TEST(test_analytics_meta_matches_roi_meta) {
  const BallScene scene = exitsScene();
  const cv::Size size = scene.config().frameSize;
  std::string launch = "colortrack name=ct mode=threshold hsv-lower=345,0.5,0.25 hsv-upper=30,1,1 draw=0";
  GstElementFactory *overlay = gst_element_factory_find("objectdetectionoverlay");
  if (overlay) {
    launch += " ! objectdetectionoverlay";
    gst_object_unref(overlay);
  } else {
    g_printerr(
        "objectdetectionoverlay (gst-plugins-bad >= 1.24) is not installed: "
        "reading the analytics meta straight after colortrack\n");
  }
  BusHarness h(launch, videoCaps("BGR", size));
  std::map<guint64, GstClockTime> firstReported;  // track id -> PTS of its first ROI meta
  std::set<int> previousIds;
  int compared = 0, lostSeen = 0;
  for (int i = 0; i < 120; ++i) {
    GstBuffer *out = h.process(bgrBuffer(scene.render(i), i));
    const GstClockTime pts = GST_BUFFER_PTS(out);
    const Analytics a = readAnalytics(out);
    std::set<int> ids;
    const std::vector<GstVideoRegionOfInterestMeta *> rois = colortrackRois(out);
    fail_unless_equals_int(a.ods.size(), rois.size());
    for (GstVideoRegionOfInterestMeta *roi : rois) {
      ids.insert(roi->id);
      firstReported.emplace(static_cast<guint64>(roi->id), pts);
      const cv::Rect box(roi->x, roi->y, roi->w, roi->h);
      const auto od = std::find_if(a.ods.begin(), a.ods.end(), [&](const Od &o) {
        return o.hasTracking && o.trackId == static_cast<guint64>(roi->id);
      });
      fail_unless(od != a.ods.end(), "frame %d: track %d has no od mtd with a tracking mtd", i, roi->id);
      fail_unless(od->box == box, "frame %d: track %d: od %d,%d %dx%d, ROI %d,%d %dx%d", i, roi->id,
                  od->box.x, od->box.y, od->box.width, od->box.height, box.x, box.y, box.width, box.height);
      fail_unless(od->type == g_quark_from_static_string("colortrack"));
      fail_unless(od->confidence >= 0.0f && od->confidence <= 1.0f, "confidence %f", od->confidence);
      fail_unless_equals_uint64(od->firstSeen, firstReported[od->trackId]);
      fail_unless_equals_uint64(od->lastSeen, pts);
      fail_unless(!od->lost, "frame %d: track %d reported and lost", i, roi->id);
      ++compared;
    }
    for (const Od &o : a.ods) fail_unless(o.hasTracking, "frame %d: an od mtd without a tracking mtd", i);
    for (const Tracking &t : a.trackings) {
      if (t.relatedToOd) continue;
      // Alone: a track gone since the previous frame.
      fail_unless(t.lost, "frame %d: tracking mtd %" G_GUINT64_FORMAT " alone and not lost", i, t.trackId);
      fail_unless(previousIds.count(static_cast<int>(t.trackId)) && !ids.count(static_cast<int>(t.trackId)),
                  "frame %d: track %" G_GUINT64_FORMAT " said lost", i, t.trackId);
      fail_unless_equals_uint64(t.firstSeen, firstReported[t.trackId]);
      fail_unless(t.lastSeen < pts);
      ++lostSeen;
    }
    const auto alone = std::count_if(a.trackings.begin(), a.trackings.end(),
                                     [](const Tracking &t) { return !t.relatedToOd; });
    std::set<int> gone;
    std::set_difference(previousIds.begin(), previousIds.end(), ids.begin(), ids.end(),
                        std::inserter(gone, gone.begin()));
    fail_unless_equals_int(alone, gone.size());
    gst_buffer_unref(out);
    previousIds = ids;
  }
  GST_INFO("%d tracks compared, %d lost", compared, lostSeen);
  fail_unless(compared > 200, "only %d tracks compared", compared);
  fail_unless(lostSeen >= 2, "only %d tracks said lost (balls leave the frame)", lostSeen);
}
GST_END_TEST;

// A right click stops tracking: on the next buffer no od mtd, and each track of the buffer before gets a lost
// tracking mtd alone (with its first- and last-seen times); on the one after, nothing.
GST_START_TEST(test_right_click_reports_tracks_lost) {
  const BallScene scene = exitsScene();
  const cv::Size size = scene.config().frameSize;
  BusHarness h("colortrack name=ct mode=threshold hsv-lower=345,0.5,0.25 hsv-upper=30,1,1 draw=0",
               videoCaps("BGR", size));
  std::map<guint64, GstClockTime> firstReported, lastReported;
  std::set<guint64> before;
  for (int i = 0; i < 20; ++i) {
    GstBuffer *out = h.process(bgrBuffer(scene.render(i), i));
    before.clear();
    for (GstVideoRegionOfInterestMeta *roi : colortrackRois(out)) {
      const auto id = static_cast<guint64>(roi->id);
      firstReported.emplace(id, GST_BUFFER_PTS(out));
      lastReported[id] = GST_BUFFER_PTS(out);
      before.insert(id);
    }
    gst_buffer_unref(out);
  }
  fail_unless(before.size() >= 2, "only %d tracks before the click", static_cast<int>(before.size()));
  fail_unless(gst_harness_push_upstream_event(
      h.harness(), gst_navigation_event_new_mouse_button_press(3, 320, 240, GST_NAVIGATION_MODIFIER_NONE)));
  GstBuffer *out = h.process(bgrBuffer(scene.render(20), 20));
  fail_unless_equals_int(colortrackRois(out).size(), 0);
  const Analytics a = readAnalytics(out);
  gst_buffer_unref(out);
  fail_unless_equals_int(a.ods.size(), 0);
  std::set<guint64> lost;
  for (const Tracking &t : a.trackings) {
    fail_unless(t.lost && !t.relatedToOd);
    fail_unless_equals_uint64(t.firstSeen, firstReported[t.trackId]);
    fail_unless_equals_uint64(t.lastSeen, lastReported[t.trackId]);
    lost.insert(t.trackId);
  }
  fail_unless(lost == before, "the lost tracking mtds are not the tracks before the click");
  out = h.process(bgrBuffer(scene.render(21), 21));
  fail_unless(gst_buffer_get_analytics_relation_meta(out) == nullptr, "analytics meta while stopped");
  gst_buffer_unref(out);
}
GST_END_TEST;

static Suite *analytics_meta_suite(void) {
  Suite *s = suite_create("analytics_meta");
  TCase *tc = tcase_create("analytics");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_analytics_meta_matches_roi_meta);
  tcase_add_test(tc, test_right_click_reports_tracks_lost);
  return s;
}

GST_CHECK_MAIN(analytics_meta)
