// SPDX-License-Identifier: LGPL-2.1-or-later
// Property stress: stress threads flip properties of colortrack (template and threshold mode; also its
// targets: init-box, bins, and mode, which is refused while started), robotctl and trackpublish between valid
// values while buffers flow. No element may crash, stop producing output, lose the meta it owes a tracked
// frame, or post an error; the only warnings allowed are the ones the docs promise (a read-at-start property,
// mode while started). C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the
// standard library.
#include <chrono>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "balls.hpp"
#include "gst_test_util.hpp"
#include "scene.hpp"

#include <glib/gstdio.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace {

using namespace colortrack::gst_test_util;
using Clock = std::chrono::steady_clock;

// Long enough for thousands of flips across many frames, short enough to keep the binary near 10 s.
constexpr auto kStressTime = std::chrono::milliseconds(1500);
// Pause of each stress thread between two sets: a few hundred flips per property per second.
constexpr gulong kFlipPauseUs = 2000;

struct Flip {
  const char *property;
  std::vector<const char *> values;  // serialized as gst-launch would write them
};

// One stress thread per value of each property: the threads race, so a property flips between its values in
// an order the scheduler picks.
class Flipper {
 public:
  Flipper(GstHarness *h, const std::vector<Flip> &flips) {
    for (const Flip &f : flips) {
      GParamSpec *pspec = g_object_class_find_property(G_OBJECT_GET_CLASS(h->element), f.property);
      fail_unless(pspec != nullptr, "no property %s", f.property);
      for (const char *text : f.values) {
        GValue value = G_VALUE_INIT;
        g_value_init(&value, G_PARAM_SPEC_VALUE_TYPE(pspec));
        fail_unless(gst_value_deserialize(&value, text), "%s=%s does not parse", f.property, text);
        threads_.push_back(gst_harness_stress_property_start_full(h, f.property, &value, kFlipPauseUs));
        g_value_unset(&value);
      }
    }
  }
  ~Flipper() { stop(); }
  Flipper(const Flipper &) = delete;
  Flipper &operator=(const Flipper &) = delete;

  // Stops every thread; returns how many sets they made in all.
  guint stop() {
    for (GstHarnessThread *t : threads_) sets_ += gst_harness_stress_thread_stop(t);
    threads_.clear();
    return sets_;
  }

 private:
  std::vector<GstHarnessThread *> threads_;
  guint sets_ = 0;
};

// Everything the element posted, read without dropping any kind (gst_bus_pop_filtered would discard the
// warnings and errors between two element messages).
struct BusLog {
  std::vector<std::string> errors, warnings;
  std::vector<GstMessage *> elementMessages;  // owned

  ~BusLog() {
    for (GstMessage *m : elementMessages) gst_message_unref(m);
  }
  // Takes what is on `bus` now, or waits up to `timeout` for one message when the bus is empty.
  void read(GstBus *bus, GstClockTime timeout = 0) {
    while (GstMessage *m = gst_bus_timed_pop(bus, timeout)) {
      timeout = 0;
      GError *err = nullptr;
      if (GST_MESSAGE_TYPE(m) == GST_MESSAGE_ERROR) {
        gst_message_parse_error(m, &err, nullptr);
        errors.push_back(err->message);
      } else if (GST_MESSAGE_TYPE(m) == GST_MESSAGE_WARNING) {
        gst_message_parse_warning(m, &err, nullptr);
        warnings.push_back(err->message);
      } else if (GST_MESSAGE_TYPE(m) == GST_MESSAGE_ELEMENT) {
        elementMessages.push_back(gst_message_ref(m));
      }
      if (err) g_error_free(err);
      gst_message_unref(m);
    }
  }
  void expectNoErrors() const {
    fail_unless(errors.empty(), "%zu errors, the first: %s", errors.size(),
                errors.empty() ? "" : errors[0].c_str());
  }
};

// `element` (its properties already set) in a harness, posting on `bus`; the harness starts it.
GstHarness *harnessAround(GstElement *element, GstBus *bus, const char *srcPad, const std::string &caps) {
  gst_element_set_bus(element, bus);
  GstHarness *h = gst_harness_new_with_element(element, "sink", srcPad);
  gst_harness_set_src_caps_str(h, caps.c_str());
  return h;
}

// Ping-pong through a scene of `length` frames, so that the object never jumps back to its start.
int pingPong(int frame, int length) {
  const int phase = frame % (2 * length - 2);
  return phase < length ? phase : 2 * length - 2 - phase;
}

bool paramsComplete(GstVideoRegionOfInterestMeta *roi, bool withArea) {
  const GstStructure *p = gst_video_region_of_interest_meta_get_param(roi, "colortrack");
  return p && gst_structure_has_field_typed(p, "state", G_TYPE_STRING) &&
         gst_structure_has_field_typed(p, "score", G_TYPE_DOUBLE) &&
         gst_structure_has_field_typed(p, "verified", G_TYPE_BOOLEAN) &&
         gst_structure_has_field_typed(p, "scale", G_TYPE_DOUBLE) &&
         gst_structure_has_field_typed(p, "vx", G_TYPE_DOUBLE) &&
         gst_structure_has_field_typed(p, "vy", G_TYPE_DOUBLE) &&
         (!withArea || gst_structure_has_field_typed(p, "area", G_TYPE_DOUBLE));
}

GstElement *makeColortrack(const char *properties) {
  GstElement *e = gst_element_factory_make("colortrack", nullptr);
  fail_unless(e != nullptr);
  gchar **pairs = g_strsplit(properties, " ", -1);
  for (gchar **p = pairs; *p; ++p) {
    gchar **kv = g_strsplit(*p, "=", 2);
    fail_unless(kv[0] && kv[1], "bad property text %s", *p);
    gst_util_set_object_arg(G_OBJECT(e), kv[0], kv[1]);
    g_strfreev(kv);
  }
  g_strfreev(pairs);
  return e;
}

// Settings every mode reads while streaming: the overlay, the trail and the messages' companions.
const std::vector<Flip> kDrawFlips = {
    {"draw", {"0", "box", "box+label+trail", "box+trail+search-window+label+mask"}},
    {"trail-length", {"0", "5", "30"}},
    {"click-to-track", {"true", "false"}},
    {"click-box-size", {"32", "64"}},
};

}  // namespace

// Template mode from an init-box: method, draw flags and the search settings flip while frames flow.
GST_START_TEST(test_colortrack_template_under_property_flips) {
  colortrack::scene::SceneConfig config;
  config.frameSize = cv::Size(320, 240);  // small: many frames within the stress time on a shared machine
  config.objectSize = cv::Size(40, 40);
  const colortrack::scene::Scene scene(config);

  const std::string props = "post-messages=true init-box=" + boxString(scene.initBox());
  GstElement *element = makeColortrack(props.c_str());
  GstBus *bus = gst_bus_new();
  GstHarness *h = harnessAround(element, bus, "src", videoCaps("BGR", config.frameSize));
  gst_object_unref(element);

  std::vector<Flip> flips = kDrawFlips;
  flips.insert(flips.end(), {
                                {"method", {"fused", "discriminative", "indexing"}},
                                {"verify", {"none", "edge-density", "edge-energy", "both"}},
                                {"match-threshold", {"0.1", "0.25"}},
                                {"likelihood-threshold", {"0.2", "0.3"}},
                                {"model-update-rate", {"0", "0.05"}},
                                {"search-margin", {"1.5", "2"}},
                                {"scale-min", {"0.9", "0.94"}},
                                {"scale-max", {"1.06", "1.1"}},
                                {"max-coast-frames", {"5", "10"}},
                                {"adapt-aspect", {"true", "false"}},
                            });
  BusLog log;
  int frames = 0, tracked = 0, lastTracked = -1;
  {
    Flipper flipper(h, flips);
    for (const auto end = Clock::now() + kStressTime; Clock::now() < end || frames < 30; ++frames) {
      const colortrack::scene::SceneFrame f = scene.render(pingPong(frames, config.frames));
      fail_unless_equals_int(gst_harness_push(h, bgrBuffer(f.bgr, frames)), GST_FLOW_OK);
      GstBuffer *out = gst_harness_pull(h);
      fail_unless(out != nullptr, "no output for frame %d", frames);

      // The message of this frame was posted from this thread before the buffer came out.
      log.read(bus);
      fail_unless(!log.elementMessages.empty(), "no message for frame %d", frames);
      const GstStructure *s = gst_message_get_structure(log.elementMessages.back());
      const std::string state = gst_structure_get_string(s, "state");
      const std::vector<GstVideoRegionOfInterestMeta *> rois = colortrackRois(out);
      fail_unless(rois.size() <= 1, "%zu ROI metas on frame %d", rois.size(), frames);
      for (GstVideoRegionOfInterestMeta *roi : rois)
        fail_unless(paramsComplete(roi, false), "incomplete params on frame %d", frames);
      if (state == "tracking") {
        int id = 0;
        fail_unless(gst_structure_get_int(s, "id", &id));
        fail_unless_equals_int(rois.size(), 1);
        fail_unless_equals_int(rois[0]->id, id);
        ++tracked;
        lastTracked = frames;
      }
      gst_buffer_unref(out);
    }
    GST_INFO("template: %u property sets over %d frames, %d tracked", flipper.stop(), frames, tracked);
  }
  log.read(bus);
  log.expectNoErrors();
  fail_unless(log.warnings.empty(), "warning: %s", log.warnings.empty() ? "" : log.warnings[0].c_str());
  // The object never leaves the frame: flips may cost a few frames, not the track.
  fail_unless(tracked >= frames / 2, "tracked %d of %d frames", tracked, frames);
  fail_unless(lastTracked >= frames - 10, "last tracked frame %d of %d", lastTracked, frames);

  gst_element_set_bus(h->element, nullptr);
  gst_harness_teardown(h);
  gst_object_unref(bus);
}
GST_END_TEST;

// Threshold mode on a red ball: the HSV range, morphology, blob limits and draw flags flip while frames flow.
GST_START_TEST(test_colortrack_threshold_under_property_flips) {
  colortrack::balls::Ball ball;
  ball.hue = 358;
  ball.radius = 20;
  ball.path = {{0, {60, 60}}, {60, {260, 180}}};
  const colortrack::balls::BallScene scene(colortrack::balls::BallSceneConfig{}, {ball});
  const cv::Size size = scene.render(0).size();

  GstElement *element = makeColortrack(
      "mode=threshold post-messages=true hsv-lower=345,0.5,0.25 "
      "hsv-upper=15,1,1");
  GstBus *bus = gst_bus_new();
  GstHarness *h = harnessAround(element, bus, "src", videoCaps("BGR", size));
  gst_object_unref(element);

  std::vector<Flip> flips = kDrawFlips;
  flips.insert(flips.end(), {
                                {"hsv-lower", {"345,0.5,0.25", "340,0.45,0.2"}},
                                {"hsv-upper", {"15,1,1", "20,1,1"}},
                                {"morph-size", {"3", "5"}},
                                {"min-area", {"50", "200"}},
                                {"max-objects", {"1", "8"}},
                                {"max-coast-frames", {"5", "10"}},
                            });
  BusLog log;
  int frames = 0, withMeta = 0;
  {
    Flipper flipper(h, flips);
    for (const auto end = Clock::now() + kStressTime; Clock::now() < end || frames < 30; ++frames) {
      const cv::Mat bgr = scene.render(pingPong(frames, 61));
      fail_unless_equals_int(gst_harness_push(h, bgrBuffer(bgr, frames)), GST_FLOW_OK);
      GstBuffer *out = gst_harness_pull(h);
      fail_unless(out != nullptr, "no output for frame %d", frames);
      const std::vector<GstVideoRegionOfInterestMeta *> rois = colortrackRois(out);
      for (GstVideoRegionOfInterestMeta *roi : rois)
        fail_unless(paramsComplete(roi, true), "incomplete params on frame %d", frames);
      if (!rois.empty()) ++withMeta;
      gst_buffer_unref(out);
      log.read(bus);
      fail_unless(!log.elementMessages.empty(), "no message for frame %d", frames);
    }
    GST_INFO("threshold: %u property sets over %d frames, %d with a meta", flipper.stop(), frames, withMeta);
  }
  log.read(bus);
  log.expectNoErrors();
  fail_unless(log.warnings.empty(), "warning: %s", log.warnings.empty() ? "" : log.warnings[0].c_str());
  // Every range flipped to still holds the ball; only a new range's first (tentative) frames lack a meta.
  fail_unless(withMeta >= frames * 3 / 4, "a meta on %d of %d frames", withMeta, frames);

  gst_element_set_bus(h->element, nullptr);
  gst_harness_teardown(h);
  gst_object_unref(bus);
}
GST_END_TEST;

// robotctl writing to a file, fed frames with a moving colortrack ROI: controller settings flip, and so does
// a read-at-start property (rate), whose only effect must be its warning.
GST_START_TEST(test_robotctl_under_property_flips) {
  gchar *path = nullptr;
  const gint fd = g_file_open_tmp("robotctl-stress-XXXXXX", &path, nullptr);
  fail_unless(fd >= 0);
  g_close(fd, nullptr);

  GstElement *element = gst_element_factory_make("robotctl", nullptr);
  fail_unless(element != nullptr);
  g_object_set(element, "location", path, "sync", FALSE, "post-messages", TRUE, "rate", 100.0, nullptr);
  GstBus *bus = gst_bus_new();
  GstHarness *h = harnessAround(element, bus, nullptr, videoCaps("GRAY8", {320, 240}));
  gst_object_unref(element);

  const std::vector<Flip> flips = {
      {"controller", {"zone", "proportional", "auto"}},
      {"distance-cue", {"size", "position"}},
      {"set-point", {"0.2", "0.4"}},
      {"turn-deadband", {"0.05", "0.2"}},
      {"distance-deadband", {"0.05", "0.2"}},
      {"hysteresis", {"0", "0.05"}},
      {"turn-gain", {"0.5", "2"}},
      {"drive-gain", {"0.5", "2"}},
      {"turn-integral-gain", {"0", "1"}},
      {"drive-integral-gain", {"0", "1"}},
      {"turn-rate-gain", {"0", "0.1"}},
      {"drive-rate-gain", {"0", "0.5"}},
      {"latency", {"0", "0.1"}},
      {"max-linear", {"0.3", "0.8"}},
      {"max-angular", {"0.2", "0.5"}},
      {"max-linear-accel", {"0", "2"}},
      {"max-angular-accel", {"0", "4"}},
      {"min-score", {"0", "0.5"}},
      {"target-id", {"-1", "1"}},
      {"search-turn", {"true", "false"}},
      {"lost-timeout", {"200", "500"}},
      {"rate", {"50", "100"}},  // read at start
  };
  BusLog log;
  int frames = 0;
  GstClockTime lastPts = 0;
  {
    Flipper flipper(h, flips);
    for (const auto end = Clock::now() + kStressTime; Clock::now() < end || frames < 30; ++frames) {
      GstVideoInfo info;
      gst_video_info_set_format(&info, GST_VIDEO_FORMAT_GRAY8, 320, 240);
      GstBuffer *buffer = gst_buffer_new_allocate(nullptr, info.size, nullptr);
      gst_buffer_memset(buffer, 0, 0, info.size);
      // The box sweeps left to right and grows, so every command kind comes up.
      const int step = pingPong(frames, 40);
      GstVideoRegionOfInterestMeta *roi = gst_buffer_add_video_region_of_interest_meta(
          buffer, "colortrack", 20 + 6 * step, 80, 24 + step, 24 + step);
      roi->id = 1;
      gst_video_region_of_interest_meta_add_param(
          roi, gst_structure_new("colortrack", "state", G_TYPE_STRING, "tracking", "score", G_TYPE_DOUBLE,
                                 0.9, "verified", G_TYPE_BOOLEAN, TRUE, nullptr));
      lastPts = gst_util_uint64_scale_int(frames, GST_SECOND, kFps);
      GST_BUFFER_PTS(buffer) = lastPts;
      GST_BUFFER_DURATION(buffer) = gst_util_uint64_scale_int(1, GST_SECOND, kFps);
      fail_unless_equals_int(gst_harness_push(h, buffer), GST_FLOW_OK);
      log.read(bus);
      g_usleep(2000);  // about 500 frames a second: the writer thread sends between them
    }
    GST_INFO("robotctl: %u property sets over %d frames", flipper.stop(), frames);
  }
  // Still sending: a command decided on the last frame arrives.
  bool lastSent = false;
  for (const auto end = Clock::now() + std::chrono::seconds(5); !lastSent && Clock::now() < end;) {
    log.read(bus, 100 * GST_MSECOND);
    for (GstMessage *m : log.elementMessages) {
      guint64 timestamp = GST_CLOCK_TIME_NONE;
      const GstStructure *s = gst_message_get_structure(m);
      if (gst_structure_has_name(s, "robotctl") && gst_structure_get_uint64(s, "timestamp", &timestamp) &&
          GST_CLOCK_TIME_IS_VALID(timestamp) && timestamp >= lastPts)
        lastSent = true;
    }
  }
  log.read(bus);
  log.expectNoErrors();
  fail_unless(lastSent, "no command for the last frame");
  GST_INFO("robotctl: %zu messages, %zu warnings", log.elementMessages.size(), log.warnings.size());
  fail_unless(log.elementMessages.size() >= 20, "only %zu commands sent", log.elementMessages.size());
  for (const std::string &w : log.warnings)
    fail_unless(contains(w, "'rate' is read at start"), "unexpected warning: %s", w.c_str());

  GStatBuf st;
  fail_unless(g_stat(path, &st) == 0 && st.st_size > 0, "nothing written to %s", path);
  gst_element_set_bus(h->element, nullptr);
  gst_harness_teardown(h);
  gst_object_unref(bus);
  g_unlink(path);
  g_free(path);
}
GST_END_TEST;

// A new target every few milliseconds (init-box, two boxes of the object), the histogram bins and mode (fixed
// while started: each change refused with a warning, the mode kept) flip while frames flow: every frame comes
// out with at most one track, and nothing but mode's refusal is said.
GST_START_TEST(test_colortrack_targets_under_property_flips) {
  colortrack::scene::SceneConfig config;
  config.frameSize = cv::Size(320, 240);
  config.objectSize = cv::Size(40, 40);
  const colortrack::scene::Scene scene(config);
  const std::string props = "post-messages=true init-box=" + boxString(scene.initBox());
  GstElement *element = makeColortrack(props.c_str());
  GstBus *bus = gst_bus_new();
  GstHarness *h = harnessAround(element, bus, "src", videoCaps("BGR", config.frameSize));
  gst_object_unref(element);
  const std::string box = boxString(scene.initBox());
  const std::vector<Flip> flips = {
      {"init-box", {box.c_str(), "10,10,30,30"}},
      {"bins", {"16,16,8", "8,8,4"}},
      {"mode", {"threshold", "template"}},
  };
  BusLog log;
  int frames = 0, tracked = 0;
  {
    Flipper flipper(h, flips);
    for (const auto end = Clock::now() + kStressTime; Clock::now() < end || frames < 30; ++frames) {
      const colortrack::scene::SceneFrame f = scene.render(pingPong(frames, config.frames));
      fail_unless_equals_int(gst_harness_push(h, bgrBuffer(f.bgr, frames)), GST_FLOW_OK);
      GstBuffer *out = gst_harness_pull(h);
      fail_unless(out != nullptr, "no output for frame %d", frames);
      const std::vector<GstVideoRegionOfInterestMeta *> rois = colortrackRois(out);
      fail_unless(rois.size() <= 1, "%zu ROI metas on frame %d", rois.size(), frames);
      tracked += !rois.empty();
      gst_buffer_unref(out);
      log.read(bus);
    }
    GST_INFO("targets: %u property sets over %d frames, %d with a track", flipper.stop(), frames, tracked);
  }
  log.read(bus);
  log.expectNoErrors();
  for (const std::string &w : log.warnings)
    fail_unless(contains(w, "'mode'"), "unexpected warning: %s", w.c_str());
  fail_unless(!log.warnings.empty(), "mode changed while started without a warning");
  fail_unless(tracked > 0, "no frame with a track");
  // Refused every time while started: the mode it started in.
  GValue mode = G_VALUE_INIT;
  g_object_get_property(G_OBJECT(h->element), "mode", &mode);
  gchar *modeText = gst_value_serialize(&mode);
  fail_unless_equals_string(modeText, "template");
  g_free(modeText);
  g_value_unset(&mode);
  gst_element_set_bus(h->element, nullptr);
  gst_harness_teardown(h);
  gst_object_unref(bus);
}
GST_END_TEST;

// trackpublish writing to a file: its properties (all read at start) flip while buffers pass; each change
// only warns, every buffer passes through, and a document is written for every frame.
GST_START_TEST(test_trackpublish_under_property_flips) {
  gchar *path = nullptr;
  const gint fd = g_file_open_tmp("trackpublish-stress-XXXXXX", &path, nullptr);
  fail_unless(fd >= 0);
  g_close(fd, nullptr);
  GstElement *element = gst_element_factory_make("trackpublish", nullptr);
  fail_unless(element != nullptr);
  // Frames come as fast as the harness can push them, and the flipper holds the object lock often: on a
  // loaded machine the file's writer thread falls behind (a "does not keep up" drop failed CI once). This
  // test is about property flips, so the queue holds every document and the stop waits for all of them.
  g_object_set(element, "location", path, "add-empty-results", TRUE, "max-queued", 10000000u, "drain-timeout",
               60000u, nullptr);
  GstBus *bus = gst_bus_new();
  GstHarness *h = harnessAround(element, bus, "src", videoCaps("GRAY8", {320, 240}));
  gst_object_unref(element);
  const std::vector<Flip> flips = {
      {"roi-type", {"colortrack", "object"}},  {"source", {"cam1", "cam2"}},
      {"tags", {"{\"a\":1}", "{}"}},           {"add-empty-results", {"true", "false"}},
      {"topic", {"x/{source}", "y/{source}"}},
  };
  BusLog log;
  int frames = 0;
  {
    Flipper flipper(h, flips);
    for (const auto end = Clock::now() + kStressTime; Clock::now() < end || frames < 30; ++frames) {
      GstBuffer *buffer = gst_buffer_new_allocate(nullptr, 320 * 240, nullptr);
      gst_buffer_memset(buffer, 0, 0, 320 * 240);
      GST_BUFFER_PTS(buffer) = gst_util_uint64_scale_int(frames, GST_SECOND, kFps);
      fail_unless_equals_int(gst_harness_push(h, buffer), GST_FLOW_OK);
      GstBuffer *out = gst_harness_pull(h);
      fail_unless(out != nullptr, "no output for frame %d", frames);
      gst_buffer_unref(out);
      log.read(bus);
    }
    GST_INFO("trackpublish: %u property sets over %d frames", flipper.stop(), frames);
  }
  log.read(bus);
  log.expectNoErrors();
  for (const std::string &w : log.warnings)
    fail_unless(contains(w, "is read at start"), "unexpected warning: %s", w.c_str());
  gst_element_set_bus(h->element, nullptr);
  gst_harness_teardown(h);
  gst_object_unref(bus);
  gchar *text = nullptr;
  gsize length = 0;
  fail_unless(g_file_get_contents(path, &text, &length, nullptr));
  int lines = 0;
  for (gsize i = 0; i < length; ++i) lines += text[i] == '\n';
  g_free(text);
  fail_unless_equals_int(lines, frames);  // the settings of the start hold: a document per frame
  g_unlink(path);
  g_free(path);
}
GST_END_TEST;

static Suite *property_stress_suite(void) {
  preloadPlugins({"colortrack"});
  Suite *s = suite_create("property_stress");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_colortrack_template_under_property_flips);
  tcase_add_test(tc, test_colortrack_threshold_under_property_flips);
  tcase_add_test(tc, test_robotctl_under_property_flips);
  tcase_add_test(tc, test_colortrack_targets_under_property_flips);
  tcase_add_test(tc, test_trackpublish_under_property_flips);
  return s;
}

GST_CHECK_MAIN(property_stress);
