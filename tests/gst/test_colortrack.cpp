// SPDX-License-Identifier: LGPL-2.1-or-later
// Element tests of colortrack on synthetic scenes with exact ground truth: tracking quality, dynamic scale,
// template files, decoys, re-acquisition, ROI meta and bus messages, meta through videoscale, the reset
// signal. C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard
// library.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "gst_test_util.hpp"
#include "scene.hpp"

#include <glib/gstdio.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace {

using colortrack::scene::iou;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;
using colortrack::scene::SceneFrame;

using namespace colortrack::gst_test_util;

// The colortrack ROI meta of a buffer, read back.
struct TrackMeta {
  bool present = false;
  cv::Rect box;
  int id = 0;
  std::string state;
  double score = 0, scale = 0, vx = 0, vy = 0;
  gboolean verified = FALSE;
  bool paramsComplete = false;  // every params field present with its type
};

TrackMeta readMeta(GstBuffer *buffer) {
  TrackMeta m;
  int found = 0;
  for (GstVideoRegionOfInterestMeta *roi : colortrackRois(buffer)) {
    ++found;
    m.present = true;
    m.box = cv::Rect(roi->x, roi->y, roi->w, roi->h);
    m.id = roi->id;
    // On the meta itself, or (after videoconvert / videoscale, whose ROI transform drops it in
    // GStreamer 1.22) in the documented custom meta under "id-<track id>".
    const GstStructure *p = gst_video_region_of_interest_meta_get_param(roi, "colortrack");
    if (!p) {
      if (GstCustomMeta *custom = gst_buffer_get_custom_meta(buffer, "GstColorTrackParamsMeta")) {
        const GValue *v = gst_structure_get_value(gst_custom_meta_get_structure(custom),
                                                  ("id-" + std::to_string(roi->id)).c_str());
        if (v && GST_VALUE_HOLDS_STRUCTURE(v)) p = gst_value_get_structure(v);
      }
    }
    if (!p) continue;
    m.paramsComplete = gst_structure_has_field_typed(p, "state", G_TYPE_STRING) &&
                       gst_structure_has_field_typed(p, "score", G_TYPE_DOUBLE) &&
                       gst_structure_has_field_typed(p, "verified", G_TYPE_BOOLEAN) &&
                       gst_structure_has_field_typed(p, "scale", G_TYPE_DOUBLE) &&
                       gst_structure_has_field_typed(p, "vx", G_TYPE_DOUBLE) &&
                       gst_structure_has_field_typed(p, "vy", G_TYPE_DOUBLE);
    if (const char *state = gst_structure_get_string(p, "state")) m.state = state;
    gst_structure_get_double(p, "score", &m.score);
    gst_structure_get_double(p, "scale", &m.scale);
    gst_structure_get_double(p, "vx", &m.vx);
    gst_structure_get_double(p, "vy", &m.vy);
    gst_structure_get_boolean(p, "verified", &m.verified);
  }
  fail_unless(found <= 1, "%d colortrack ROI metas on one buffer", found);
  return m;
}

// A harness around a launch line whose colortrack element is named "ct"; BGR frames go in, and its bus
// carries element messages, warnings and errors.
class Harness : public BusHarness {
 public:
  Harness(const std::string &launch, cv::Size size) : BusHarness(launch, videoCaps("BGR", size)) {}

  // Pushes one frame and returns the output buffer (owned by the caller).
  GstBuffer *process(const cv::Mat &bgr, int index) { return BusHarness::process(bgrBuffer(bgr, index)); }
  TrackMeta processMeta(const cv::Mat &bgr, int index) {
    GstBuffer *out = process(bgr, index);
    const TrackMeta m = readMeta(out);
    gst_buffer_unref(out);
    return m;
  }

  GstElement *tracker() const { return element(); }
  // The state field of the next colortrack message ("" when there is none).
  std::string popTrackState() {
    GstMessage *msg = popTrackMessage();
    if (!msg) return "";
    const std::string state = gst_structure_get_string(gst_message_get_structure(msg), "state");
    gst_message_unref(msg);
    return state;
  }
};

std::string trackerLaunch(const std::string &properties) {
  return "colortrack name=ct " + properties;
}

double mean(const std::vector<double> &v) {
  double sum = 0;
  for (double x : v) sum += x;
  return v.empty() ? 0 : sum / v.size();
}

double pearson(const std::vector<double> &a, const std::vector<double> &b) {
  const double ma = mean(a), mb = mean(b);
  double sab = 0, saa = 0, sbb = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    sab += (a[i] - ma) * (b[i] - mb);
    saa += (a[i] - ma) * (a[i] - ma);
    sbb += (b[i] - mb) * (b[i] - mb);
  }
  return saa > 0 && sbb > 0 ? sab / std::sqrt(saa * sbb) : 0;
}

}  // namespace

// The scene's object written as a PNG (mask as alpha) in a fresh temporary directory, removed afterwards.
class TemplateFile {
 public:
  explicit TemplateFile(const Scene &scene) {
    cv::Mat bgr, mask, bgra;
    scene.objectTemplate(bgr, mask);
    cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
    cv::insertChannel(mask, bgra, 3);
    dir_ = g_dir_make_tmp("colortrack-XXXXXX", nullptr);
    fail_unless(dir_ != nullptr);
    path_ = std::string(dir_) + "/object.png";
    fail_unless(cv::imwrite(path_, bgra));
  }
  ~TemplateFile() {
    g_unlink(path_.c_str());
    g_rmdir(dir_);
    g_free(dir_);
  }
  TemplateFile(const TemplateFile &) = delete;
  TemplateFile &operator=(const TemplateFile &) = delete;
  const std::string &path() const { return path_; }

 private:
  gchar *dir_ = nullptr;
  std::string path_;
};

// The object moves, turns through 90 degrees, scales 0.7x-1.4x and its lighting changes by +-40%.
GST_START_TEST(test_tracks_through_motion_rotation_scale_and_lighting) {
  SceneConfig config;
  config.frames = 200;
  config.rotationDegrees = 90;
  config.scaleMin = 0.7;
  config.scaleMax = 1.4;
  config.brightness = 0.4;
  const Scene scene(config);
  Harness h(trackerLaunch("init-box=" + boxString(scene.initBox())), config.frameSize);

  std::vector<double> ious, boxWidths, truthWidths;
  int missing = 0;
  for (int i = 0; i < config.frames; ++i) {
    const SceneFrame f = scene.render(i);
    const TrackMeta m = h.processMeta(f.bgr, i);
    ious.push_back(m.present ? iou(m.box, f.box) : 0.0);
    if (!m.present) {
      ++missing;
      continue;
    }
    boxWidths.push_back(m.box.width);
    truthWidths.push_back(f.box.width);
  }
  const double meanIou = mean(ious);
  const double widthCorrelation = pearson(boxWidths, truthWidths);
  GST_INFO("mean IoU %.3f over %d frames, %d without a box, width correlation %.3f", meanIou, config.frames,
           missing, widthCorrelation);
  fail_unless(meanIou >= 0.6, "mean IoU %.3f < 0.6", meanIou);
  fail_unless(missing <= config.frames / 20, "%d frames without a box", missing);

  // Dynamic scale: the box follows the object's size (the object is round, so rotation leaves its width).
  fail_unless(widthCorrelation >= 0.8, "box width / true width correlation %.3f", widthCorrelation);
  const auto [minIt, maxIt] = std::minmax_element(truthWidths.begin(), truthWidths.end());
  const double boxRatio = boxWidths[maxIt - truthWidths.begin()] / boxWidths[minIt - truthWidths.begin()];
  const double truthRatio = *maxIt / *minIt;
  GST_INFO("box width ratio at the largest / smallest object %.2f (truth %.2f)", boxRatio, truthRatio);
  fail_unless(boxRatio >= 1 + 0.6 * (truthRatio - 1), "box width ratio %.2f for a true ratio %.2f", boxRatio,
              truthRatio);
}
GST_END_TEST;

// A PNG template (mask as alpha) instead of init-box: the element starts by searching the whole frame.
GST_START_TEST(test_template_file_acquires_from_search) {
  SceneConfig config;
  config.frames = 120;
  config.scaleMin = 0.9;
  config.scaleMax = 1.1;
  const Scene scene(config);

  TemplateFile file(scene);
  {
    Harness h(trackerLaunch("post-messages=true template-location=" + file.path()), config.frameSize);
    fail_unless(h.popTrackState().empty());  // nothing before the first frame
    int acquiredAt = -1;
    std::vector<double> ious;
    for (int i = 0; i < 60; ++i) {
      const SceneFrame f = scene.render(i);
      const TrackMeta m = h.processMeta(f.bgr, i);
      const std::string state = h.popTrackState();
      if (i == 0) fail_unless(state == "tracking" || state == "searching", "first state %s", state.c_str());
      if (acquiredAt < 0 && state == "tracking") acquiredAt = i;
      if (acquiredAt >= 0) ious.push_back(m.present ? iou(m.box, f.box) : 0.0);
    }
    GST_INFO("acquired at frame %d, mean IoU after %.3f", acquiredAt, mean(ious));
    fail_unless(acquiredAt >= 0 && acquiredAt <= 3, "acquired at frame %d", acquiredAt);
    fail_unless(mean(ious) >= 0.6, "mean IoU %.3f after acquisition", mean(ious));
  }
}
GST_END_TEST;

// An untextured disc of the object's colour. The object is tracked (verified) and then leaves for good, so
// the search can only find the disc: it must be reported as a colour-only (unverified) match. The disc's
// single colour only partly matches the object's several shades, hence the lower match threshold: this
// test is about the edge check, not the colour match. It runs the colour-only discriminative method: the
// fused default's shape cue does not take the untextured disc for the object at all.
GST_START_TEST(test_decoy_is_unverified) {
  SceneConfig config;
  config.frames = 200;
  config.decoy = true;
  config.leaveFrom = 50;
  config.leaveTo = 100000;  // never comes back within the test
  const Scene scene(config);
  Harness h(trackerLaunch("method=discriminative match-threshold=0.1 init-box=" + boxString(scene.initBox())),
            config.frameSize);

  int objectFrames = 0, objectVerified = 0, decoyFrames = 0, decoyVerified = 0;
  for (int i = 0; i < 100; ++i) {
    const SceneFrame f = scene.render(i);
    const TrackMeta m = h.processMeta(f.bgr, i);
    GST_LOG("frame %d: %s %s box %d,%d %dx%d verified %d decoy IoU %.2f", i, m.present ? "meta" : "no meta",
            m.state.c_str(), m.box.x, m.box.y, m.box.width, m.box.height, m.verified, iou(m.box, f.decoyBox));
    if (!m.present || m.state != "tracking") continue;
    if (f.objectVisible && iou(m.box, f.box) > 0.3) {
      ++objectFrames;
      objectVerified += m.verified ? 1 : 0;
    } else if (iou(m.box, f.decoyBox) > 0.3) {
      ++decoyFrames;
      decoyVerified += m.verified ? 1 : 0;
    }
  }
  GST_INFO("object: %d/%d verified; decoy: %d/%d verified", objectVerified, objectFrames, decoyVerified,
           decoyFrames);
  fail_unless(decoyFrames >= 10, "the decoy was picked up in %d frames only: nothing to check", decoyFrames);
  fail_unless(decoyVerified <= 0.1 * decoyFrames, "decoy verified in %d of %d frames", decoyVerified,
              decoyFrames);
  fail_unless(objectFrames >= 45, "object tracked in %d frames only", objectFrames);
  fail_unless(objectVerified >= 0.8 * objectFrames, "object verified in %d of %d frames", objectVerified,
              objectFrames);
}
GST_END_TEST;

// The object leaves the frame and comes back somewhere else: the track is lost, then found again.
GST_START_TEST(test_reacquires_after_leaving) {
  SceneConfig config;
  config.frames = 200;
  config.leaveFrom = 60;
  config.leaveTo = 90;
  const Scene scene(config);
  Harness h(trackerLaunch("post-messages=true init-box=" + boxString(scene.initBox())), config.frameSize);

  bool lostOrSearching = false;
  int firstIdAfterReturn = 0, idBeforeLeaving = 0, reacquiredAt = -1;
  std::vector<double> laterIous;
  for (int i = 0; i < 140; ++i) {
    const SceneFrame f = scene.render(i);
    const TrackMeta m = h.processMeta(f.bgr, i);
    const std::string state = h.popTrackState();
    if (i == config.leaveFrom - 1) idBeforeLeaving = m.id;
    if (i >= config.leaveFrom && i < config.leaveTo && (state == "lost" || state == "searching"))
      lostOrSearching = true;
    if (i >= config.leaveTo && reacquiredAt < 0 && state == "tracking" && m.present &&
        iou(m.box, f.box) > 0.5) {
      reacquiredAt = i;
      firstIdAfterReturn = m.id;
    }
    if (i >= config.leaveTo + 10) laterIous.push_back(m.present ? iou(m.box, f.box) : 0.0);
  }
  GST_INFO("re-acquired %d frames after returning, then mean IoU %.3f", reacquiredAt - config.leaveTo,
           mean(laterIous));
  fail_unless(lostOrSearching, "never lost or searching while the object was away");
  fail_unless(reacquiredAt >= 0 && reacquiredAt <= config.leaveTo + 5, "re-acquired at frame %d",
              reacquiredAt);
  fail_unless(firstIdAfterReturn > idBeforeLeaving, "track id %d after returning, %d before",
              firstIdAfterReturn, idBeforeLeaving);
  fail_unless(mean(laterIous) >= 0.6, "mean IoU %.3f after re-acquisition", mean(laterIous));
}
GST_END_TEST;

// Meta params and message fields: present, typed, and consistent with each other and with the buffers.
GST_START_TEST(test_meta_and_message_fields) {
  SceneConfig config;
  const Scene scene(config);
  Harness h(trackerLaunch("post-messages=true init-box=" + boxString(scene.initBox())), config.frameSize);

  guint64 expectedFrame = 0;
  for (int i = 0; i < 30; ++i) {
    const SceneFrame f = scene.render(i);
    GstBuffer *out = h.process(f.bgr, i);
    const TrackMeta m = readMeta(out);
    fail_unless(m.present, "no ROI meta on frame %d", i);
    fail_unless(m.paramsComplete, "ROI meta params incomplete on frame %d", i);
    fail_unless(m.id >= 1);
    fail_unless_equals_string(m.state.c_str(), "tracking");
    fail_unless(m.score > 0 && m.score <= 1, "score %f", m.score);
    fail_unless(m.scale > 0.5 && m.scale < 2, "scale %f", m.scale);
    fail_unless(std::isfinite(m.vx) && std::isfinite(m.vy));

    GstMessage *msg = h.popTrackMessage();
    fail_unless(msg != nullptr, "no message for frame %d", i);
    fail_unless(GST_MESSAGE_SRC(msg) == GST_OBJECT(h.tracker()));
    const GstStructure *s = gst_message_get_structure(msg);
    for (const char *field : {"timestamp", "stream-time", "running-time", "duration", "frame"})
      fail_unless(gst_structure_has_field_typed(s, field, G_TYPE_UINT64), "field %s", field);
    for (const char *field : {"x", "y", "width", "height", "score", "scale"})
      fail_unless(gst_structure_has_field_typed(s, field, G_TYPE_DOUBLE), "field %s", field);
    fail_unless(gst_structure_has_field_typed(s, "state", G_TYPE_STRING));
    fail_unless(gst_structure_has_field_typed(s, "verified", G_TYPE_BOOLEAN));

    guint64 timestamp, streamTime, runningTime, duration, frame;
    gst_structure_get_uint64(s, "timestamp", &timestamp);
    gst_structure_get_uint64(s, "stream-time", &streamTime);
    gst_structure_get_uint64(s, "running-time", &runningTime);
    gst_structure_get_uint64(s, "duration", &duration);
    gst_structure_get_uint64(s, "frame", &frame);
    fail_unless_equals_uint64(frame, expectedFrame++);
    fail_unless_equals_uint64(timestamp, GST_BUFFER_PTS(out));
    fail_unless_equals_uint64(duration, GST_BUFFER_DURATION(out));
    // The harness's segment starts at 0 with rate 1: stream and running time equal the timestamp.
    fail_unless_equals_uint64(streamTime, GST_BUFFER_PTS(out));
    fail_unless_equals_uint64(runningTime, GST_BUFFER_PTS(out));

    double x, y, width, height, score, scale;
    gboolean verified;
    gst_structure_get_double(s, "x", &x);
    gst_structure_get_double(s, "y", &y);
    gst_structure_get_double(s, "width", &width);
    gst_structure_get_double(s, "height", &height);
    gst_structure_get_double(s, "score", &score);
    gst_structure_get_double(s, "scale", &scale);
    gst_structure_get_boolean(s, "verified", &verified);
    fail_unless(std::abs(x - m.box.x) <= 1 && std::abs(y - m.box.y) <= 1, "message %.1f,%.1f meta %d,%d", x,
                y, m.box.x, m.box.y);
    fail_unless(std::abs(x + width - m.box.br().x) <= 1 && std::abs(y + height - m.box.br().y) <= 1);
    fail_unless_equals_string(gst_structure_get_string(s, "state"), m.state.c_str());
    fail_unless(score == m.score && scale == m.scale && !verified == !m.verified);
    fail_unless(iou(cv::Rect2d(x, y, width, height), f.box) > 0.5);

    gst_message_unref(msg);
    gst_buffer_unref(out);
  }
}
GST_END_TEST;

// videoscale transforms the ROI meta to the new size; videoconvert keeps it. GStreamer 1.22's ROI meta
// transform, which both use, keeps the type, id and box but drops the params structures: the element's
// custom params meta must carry them through, so they are compared on every frame.
GST_START_TEST(test_meta_survives_videoscale_and_videoconvert) {
  SceneConfig config;
  const Scene scene(config);
  const std::string props = "init-box=" + boxString(scene.initBox());
  Harness direct(trackerLaunch(props), config.frameSize);
  Harness scaled(trackerLaunch(props) +
                     " ! videoscale ! capsfilter caps=video/x-raw,width=320,height=240 ! videoconvert ! "
                     "capsfilter caps=video/x-raw,format=I420",
                 config.frameSize);
  Harness converted(trackerLaunch(props) + " ! videoconvert ! capsfilter caps=video/x-raw,format=NV12",
                    config.frameSize);

  for (int i = 0; i < 15; ++i) {
    const SceneFrame f = scene.render(i);
    const TrackMeta full = direct.processMeta(f.bgr, i);
    const TrackMeta half = scaled.processMeta(f.bgr, i);
    const TrackMeta same = converted.processMeta(f.bgr, i);
    fail_unless(full.present && half.present && same.present, "meta missing on frame %d", i);
    fail_unless_equals_int(half.id, full.id);
    const cv::Rect expected(full.box.x / 2, full.box.y / 2, full.box.width / 2, full.box.height / 2);
    fail_unless(std::abs(half.box.x - expected.x) <= 1 && std::abs(half.box.y - expected.y) <= 1 &&
                    std::abs(half.box.width - expected.width) <= 1 &&
                    std::abs(half.box.height - expected.height) <= 1,
                "frame %d: scaled box %d,%d %dx%d, full box %d,%d %dx%d", i, half.box.x, half.box.y,
                half.box.width, half.box.height, full.box.x, full.box.y, full.box.width, full.box.height);

    fail_unless(same.box == full.box && same.id == full.id, "videoconvert changed the meta on frame %d", i);
    for (const TrackMeta *downstream : {&half, &same}) {
      fail_unless(downstream->paramsComplete, "frame %d: params lost downstream", i);
      fail_unless(downstream->state == full.state && downstream->score == full.score &&
                  downstream->scale == full.scale && downstream->vx == full.vx && downstream->vy == full.vy &&
                  !downstream->verified == !full.verified);
    }
  }
}
GST_END_TEST;

// Two colortrack elements in series ("first", then "ct"), each with its own track of id 1: the params meta
// keeps both (keyed by element and id), also after videoscale drops the ROI metas' own params, and the first
// layout's "id-1" entry stays the first element's.
GST_START_TEST(test_params_meta_keeps_two_elements_apart) {
  SceneConfig config;
  const Scene scene(config);
  const cv::Rect object = scene.initBox();
  const cv::Rect background(20, 20, 60, 60);
  fail_unless((object & background).empty());
  Harness pipeline("colortrack name=first init-box=" + boxString(object) +
                       " ! colortrack name=ct init-box=" + boxString(background) +
                       " ! videoscale ! capsfilter caps=video/x-raw,width=320,height=240",
                   config.frameSize);
  for (int i = 0; i < 5; ++i) {
    const SceneFrame frame = scene.render(i);
    GstBuffer *out = pipeline.process(frame.bgr, i);
    GstCustomMeta *custom = gst_buffer_get_custom_meta(out, "GstColorTrackParamsMeta");
    fail_unless(custom != nullptr, "frame %d: no params meta", i);
    const GstStructure *entries = gst_custom_meta_get_structure(custom);
    const GstStructure *firstEntry = nullptr, *secondEntry = nullptr, *sharedEntry = nullptr;
    for (auto [name, target] : {std::pair{"id-1.first", &firstEntry}, std::pair{"id-1.ct", &secondEntry},
                                std::pair{"id-1", &sharedEntry}}) {
      const GValue *v = gst_structure_get_value(entries, name);
      fail_unless(v && GST_VALUE_HOLDS_STRUCTURE(v), "frame %d: no entry %s", i, name);
      *target = gst_value_get_structure(v);
    }
    fail_unless_equals_string(gst_structure_get_string(firstEntry, "element"), "first");
    fail_unless_equals_string(gst_structure_get_string(secondEntry, "element"), "ct");
    fail_unless_equals_string(gst_structure_get_string(sharedEntry, "element"), "first");
    // Each entry holds its own element's box: the object for the firstEntry, the background patch for the
    // secondEntry.
    int x = 0, y = 0;
    fail_unless(gst_structure_get_int(firstEntry, "roi-x", &x) &&
                gst_structure_get_int(firstEntry, "roi-y", &y));
    fail_unless(std::abs(x - frame.box.x) <= 12 && std::abs(y - frame.box.y) <= 12,
                "frame %d: first element at %d,%d", i, x, y);
    fail_unless(gst_structure_get_int(secondEntry, "roi-x", &x) &&
                gst_structure_get_int(secondEntry, "roi-y", &y));
    fail_unless(std::abs(x - background.x) <= 12 && std::abs(y - background.y) <= 12,
                "frame %d: second element at %d,%d", i, x, y);
    gst_buffer_unref(out);
  }
}
GST_END_TEST;

// "reset" restarts the search: a visible object is found again as a new track; a gone one is searched for.
GST_START_TEST(test_reset_signal) {
  SceneConfig config;
  config.leaveFrom = 40;
  config.leaveTo = 100000;
  const Scene scene(config);
  Harness h(trackerLaunch("post-messages=true init-box=" + boxString(scene.initBox())), config.frameSize);

  int id = 0;
  for (int i = 0; i < 30; ++i) {
    id = h.processMeta(scene.render(i).bgr, i).id;
    const std::string state = h.popTrackState();
    fail_unless_equals_string(state.c_str(), "tracking");
  }
  g_signal_emit_by_name(h.tracker(), "reset");
  const SceneFrame f30 = scene.render(30);
  const TrackMeta again = h.processMeta(f30.bgr, 30);
  h.popTrackState();
  fail_unless(again.present && again.id == id + 1, "after reset: id %d, before %d", again.id, id);
  fail_unless(iou(again.box, f30.box) > 0.5);

  // The object leaves at frame 40; while the track coasts, a reset sends it straight back to searching.
  for (int i = 31; i < 42; ++i) {
    h.processMeta(scene.render(i).bgr, i);
    h.popTrackState();
  }
  g_signal_emit_by_name(h.tracker(), "reset");
  const TrackMeta gone = h.processMeta(scene.render(42).bgr, 42);
  const std::string state = h.popTrackState();
  fail_unless_equals_string(state.c_str(), "searching");
  fail_unless(!gone.present);
}
GST_END_TEST;

// QoS (on, as in every GstVideoFilter) drops a late frame before the tracker sees it: the next frame's
// timestamp says how much time passed, and the prediction covers it. Every other frame of 80 dropped, as a
// loaded machine would: the object is still held in every frame that is tracked.
GST_START_TEST(test_dropped_frames_are_a_gap_in_time) {
  SceneConfig config;
  config.frames = 160;
  const Scene scene(config);
  Harness h(trackerLaunch("init-box=" + boxString(scene.initBox())), config.frameSize);
  std::vector<double> ious;
  int missing = 0, tracked = 0;
  for (int i = 0; i < config.frames; ++i) {
    if (i >= 40 && i < 120 && i % 2 == 1) continue;  // dropped upstream of the tracker
    const SceneFrame f = scene.render(i);
    const TrackMeta m = h.processMeta(f.bgr, i);  // the PTS of frame i
    ++tracked;
    missing += !m.present;
    ious.push_back(m.present ? iou(m.box, f.box) : 0.0);
  }
  std::printf("every other frame dropped in 40-120: %d frames tracked, mean IoU %.3f, %d without a box\n",
              tracked, mean(ious), missing);
  fail_unless(mean(ious) >= 0.6, "mean IoU %.3f", mean(ious));
  fail_unless_equals_int(missing, 0);
}
GST_END_TEST;

// A BGRx frame of `size`, dark, with an orange square at `box`.
GstBuffer *squareFrame(cv::Size size, cv::Rect box, int index) {
  cv::Mat bgrx(size, CV_8UC4, cv::Scalar(30, 30, 30, 255));
  bgrx(box).setTo(cv::Scalar(0, 128, 255, 255));
  GstBuffer *buffer = gst_buffer_new_memdup(bgrx.data, bgrx.total() * bgrx.elemSize());
  GST_BUFFER_PTS(buffer) = static_cast<GstClockTime>(index) * GST_SECOND / 30;
  GST_BUFFER_DURATION(buffer) = GST_SECOND / 30;
  return buffer;
}

// draw=none only reads the frame: a buffer still held elsewhere (as behind a tee) comes out with the same
// memory, not a copy, and with its meta. With the overlay the shared memory is copied before it is drawn on.
GST_START_TEST(test_no_overlay_no_copy) {
  const cv::Size size(160, 120);
  const cv::Rect box(40, 40, 32, 32);
  for (const std::string draw : {"none", "box"}) {
    GstHarness *h = gst_harness_new_parse(("colortrack init-box=40,40,32,32 draw=" + draw).c_str());
    gst_harness_set_src_caps_str(h, "video/x-raw,format=BGRx,width=160,height=120,framerate=30/1");
    int copies = 0, withMeta = 0;
    for (int i = 0; i < 5; ++i) {
      GstBuffer *in = squareFrame(size, box, i);
      GstMemory *memory = gst_buffer_peek_memory(in, 0);
      gst_buffer_ref(in);  // the other branch of a tee
      GstBuffer *out = gst_harness_push_and_pull(h, in);
      fail_unless(out != nullptr);
      copies += gst_buffer_peek_memory(out, 0) != memory;
      withMeta += !colortrackRois(out).empty();
      gst_buffer_unref(out);
      gst_buffer_unref(in);
    }
    std::printf("draw=%s: %d of 5 frames copied, %d with meta\n", draw.c_str(), copies, withMeta);
    fail_unless_equals_int(withMeta, 5);
    fail_unless_equals_int(copies, draw == "none" ? 0 : 5);
    gst_harness_teardown(h);
  }
}
GST_END_TEST;

static Suite *colortrack_suite(void) {
  preloadPlugins({"colortrack", "videoconvertscale"});
  Suite *s = suite_create("colortrack");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_tracks_through_motion_rotation_scale_and_lighting);
  tcase_add_test(tc, test_template_file_acquires_from_search);
  tcase_add_test(tc, test_decoy_is_unverified);
  tcase_add_test(tc, test_reacquires_after_leaving);
  tcase_add_test(tc, test_meta_and_message_fields);
  tcase_add_test(tc, test_meta_survives_videoscale_and_videoconvert);
  tcase_add_test(tc, test_reset_signal);
  tcase_add_test(tc, test_no_overlay_no_copy);
  tcase_add_test(tc, test_dropped_frames_are_a_gap_in_time);
  tcase_add_test(tc, test_params_meta_keeps_two_elements_apart);
  return s;
}

GST_CHECK_MAIN(colortrack);
