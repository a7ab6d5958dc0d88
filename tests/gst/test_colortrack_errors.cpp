// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's handling of bad input: every case ends in a clear error (or, for a bad value set while
// playing, a warning and the old value) on the bus naming the property or file; never a crash or a hang.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <sys/stat.h>

#include <cstdio>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "gst_test_util.hpp"
#include "scene.hpp"

#include <glib/gstdio.h>
#include <gst/app/gstappsink.h>
#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>
#include <gst/video/video.h>

namespace {

using colortrack::scene::iou;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;
using namespace colortrack::gst_test_util;

// How a run ended, and the warnings on the way.
using Outcome = BusOutcome;

// appsrc (BGR) ! <middle> ! appsink, with the colortrack element named "ct" somewhere in <middle>.
class Pipeline {
 public:
  explicit Pipeline(const std::string &middle) {
    const std::string launch =
        "appsrc name=src format=time ! " + middle + " ! appsink name=sink sync=false wait-on-eos=false";
    GError *error = nullptr;
    pipeline_ = gst_parse_launch(launch.c_str(), &error);
    fail_unless(pipeline_ != nullptr && error == nullptr, "cannot parse %s", launch.c_str());
    src_ = gst_bin_get_by_name(GST_BIN(pipeline_), "src");
    sink_ = gst_bin_get_by_name(GST_BIN(pipeline_), "sink");
    tracker_ = gst_bin_get_by_name(GST_BIN(pipeline_), "ct");
    fail_unless(src_ && sink_ && tracker_);
    bus_ = gst_element_get_bus(pipeline_);
  }
  ~Pipeline() {
    gst_element_set_state(pipeline_, GST_STATE_NULL);
    gst_object_unref(bus_);
    gst_object_unref(tracker_);
    gst_object_unref(sink_);
    gst_object_unref(src_);
    gst_object_unref(pipeline_);
  }
  Pipeline(const Pipeline &) = delete;
  Pipeline &operator=(const Pipeline &) = delete;

  GstElement *tracker() const { return tracker_; }
  GstStateChangeReturn play() { return gst_element_set_state(pipeline_, GST_STATE_PLAYING); }

  // Pushes a BGR frame, announcing new caps when the size changes. The flow result is ignored: after an
  // error upstream sees it, and that is what is being tested.
  void push(const cv::Mat &bgr, int index) {
    if (bgr.size() != capsSize_) {
      capsSize_ = bgr.size();
      GstCaps *c = gst_caps_from_string(videoCaps("BGR", capsSize_).c_str());
      gst_app_src_set_caps(GST_APP_SRC(src_), c);
      gst_caps_unref(c);
    }
    gst_app_src_push_buffer(GST_APP_SRC(src_), bgrBuffer(bgr, index));
  }

  // Ends the stream and waits for EOS or an error, collecting warnings.
  Outcome finish() {
    gst_app_src_end_of_stream(GST_APP_SRC(src_));
    return waitForEnd();
  }

  Outcome waitForEnd() { return colortrack::gst_test_util::waitForEnd(bus_); }

  // Output buffers so far (new references).
  std::vector<GstBuffer *> outputs() {
    std::vector<GstBuffer *> buffers;
    while (GstSample *sample = gst_app_sink_try_pull_sample(GST_APP_SINK(sink_), 0)) {
      buffers.push_back(gst_buffer_ref(gst_sample_get_buffer(sample)));
      gst_sample_unref(sample);
    }
    return buffers;
  }

 private:
  GstElement *pipeline_ = nullptr, *src_ = nullptr, *sink_ = nullptr, *tracker_ = nullptr;
  GstBus *bus_ = nullptr;
  cv::Size capsSize_;
};

// Plays `middle` on `frames` frames of `scene` and returns how it ended.
Outcome run(const std::string &middle, const Scene &scene, int frames = 5) {
  Pipeline p(middle);
  if (p.play() != GST_STATE_CHANGE_FAILURE) {
    for (int i = 0; i < frames; ++i) p.push(scene.render(i).bgr, i);
    return p.finish();
  }
  return p.waitForEnd();
}

SceneConfig smallScene() {
  SceneConfig config;
  config.frameSize = cv::Size(160, 120);
  config.objectSize = cv::Size(32, 32);
  return config;
}

// A file in a fresh temporary directory, removed afterwards.
class TempFile {
 public:
  explicit TempFile(const char *name) {
    dir_ = g_dir_make_tmp("colortrack-XXXXXX", nullptr);
    fail_unless(dir_ != nullptr);
    path_ = std::string(dir_) + "/" + name;
  }
  ~TempFile() {
    g_unlink(path_.c_str());
    g_rmdir(dir_);
    g_free(dir_);
  }
  TempFile(const TempFile &) = delete;
  TempFile &operator=(const TempFile &) = delete;
  const std::string &path() const { return path_; }

 private:
  gchar *dir_ = nullptr;
  std::string path_;
};

void assertErrorNames(const Outcome &o, const std::string &property, const std::string &value) {
  fail_unless(o.error, "no error for %s '%s'", property.c_str(), value.c_str());
  fail_unless(contains(o.errorText, property), "error does not name %s: %s", property.c_str(),
              o.errorText.c_str());
  fail_unless(contains(o.errorText, value), "error does not name '%s': %s", value.c_str(),
              o.errorText.c_str());
}

// All `frames` buffers came out, and the last one's box is on the scene's object.
void assertStillTracking(Pipeline &p, const Scene &scene, int frames) {
  const std::vector<GstBuffer *> out = p.outputs();
  fail_unless_equals_int(out.size(), frames);
  auto *roi = gst_buffer_get_video_region_of_interest_meta(out.back());
  fail_unless(roi != nullptr);
  fail_unless(iou(cv::Rect2d(roi->x, roi->y, roi->w, roi->h), scene.render(frames - 1).box) > 0.5);
  for (GstBuffer *b : out) gst_buffer_unref(b);
}

}  // namespace

GST_START_TEST(test_missing_template_file) {
  const Scene scene(smallScene());
  const std::string path = "/nonexistent-colortrack-dir/object.png";
  const Outcome o = run("colortrack name=ct template-location=" + path, scene);
  assertErrorNames(o, "template-location", path);
  fail_unless(o.errorDomain == GST_RESOURCE_ERROR && o.errorCode == GST_RESOURCE_ERROR_NOT_FOUND);
}
GST_END_TEST;

// Issue 48: a template file with an init-box, or in threshold mode, was accepted and one of them silently
// unused. Refused at start, naming both.
GST_START_TEST(test_template_file_with_another_definition_is_refused) {
  const Scene scene(smallScene());
  TempFile file("object.png");
  fail_unless(cv::imwrite(file.path(), cv::Mat(16, 16, CV_8UC3, cv::Scalar(0, 0, 255))));
  const std::string box = boxString(scene.initBox());
  for (const auto &[properties, other] : std::vector<std::pair<std::string, std::string>>{
           {"init-box=" + box, "init-box"}, {"mode=threshold", "mode=threshold"}}) {
    const Outcome o = run("colortrack name=ct template-location=" + file.path() + " " + properties, scene);
    assertErrorNames(o, "template-location", other);
  }
}
GST_END_TEST;

GST_START_TEST(test_unreadable_template_file) {
  const Scene scene(smallScene());
  TempFile file("garbage.png");
  FILE *f = std::fopen(file.path().c_str(), "wb");
  fail_unless(f != nullptr);
  cv::Mat noise(1, 4096, CV_8UC1);
  cv::randu(noise, 0, 256);
  std::fwrite(noise.data, 1, noise.total(), f);
  std::fclose(f);
  const Outcome o = run("colortrack name=ct template-location=" + file.path(), scene);
  assertErrorNames(o, "template-location", file.path());
  fail_unless(o.errorDomain == GST_RESOURCE_ERROR && o.errorCode == GST_RESOURCE_ERROR_OPEN_READ);
}
GST_END_TEST;

// A template image under the minimum side (8 px) is refused at start, naming the file.
GST_START_TEST(test_tiny_template_file) {
  const Scene scene(smallScene());
  TempFile file("tiny.png");
  fail_unless(cv::imwrite(file.path(), cv::Mat(1, 1, CV_8UC3, cv::Scalar(0, 0, 255))));
  const Outcome o = run("colortrack name=ct template-location=" + file.path(), scene);
  assertErrorNames(o, "template-location", file.path());
  fail_unless(contains(o.errorText, "at least 8x8"), "%s", o.errorText.c_str());
}
GST_END_TEST;

// Interlaced video is refused with a message that says what to do.
GST_START_TEST(test_interlaced_caps_are_refused) {
  GstHarness *h = gst_harness_new_parse("colortrack init-box=10,10,20,20");
  gst_harness_set_src_caps_str(
      h, "video/x-raw,format=BGR,width=160,height=120,framerate=30/1,interlace-mode=interleaved");
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, 160 * 120 * 3, nullptr);
  fail_if(gst_harness_push(h, buffer) == GST_FLOW_OK, "interlaced frames were processed");
  gst_harness_teardown(h);
}
GST_END_TEST;

GST_START_TEST(test_template_larger_than_frame) {
  const Scene scene(smallScene());  // 160x120 frames
  TempFile file("big.png");
  fail_unless(cv::imwrite(file.path(), cv::Mat(200, 100, CV_8UC3, cv::Scalar(30, 60, 200))));
  const Outcome o = run("colortrack name=ct template-location=" + file.path(), scene);
  assertErrorNames(o, "template-location", file.path());
  fail_unless(contains(o.errorText, "100x200") && contains(o.errorText, "160x120"), "%s",
              o.errorText.c_str());
}
GST_END_TEST;

GST_START_TEST(test_init_box_outside_or_larger_than_frame) {
  const Scene scene(smallScene());
  for (const char *box : {"150,100,32,32", "0,0,161,100", "0,0,400,300"}) {
    const Outcome o = run(std::string("colortrack name=ct init-box=") + box, scene);
    assertErrorNames(o, "init-box", box);
  }
}
GST_END_TEST;

GST_START_TEST(test_malformed_strings) {
  const Scene scene(smallScene());
  const std::string box = "init-box=" + boxString(scene.initBox());
  struct Case {
    const char *property, *value;
  };
  const Case cases[] = {
      {"bins", "16,16"},
      {"bins", "a,b,c"},
      {"bins", "0,16,8"},
      {"bins", "16,16,300"},
      {"channel-weights", "1,1"},
      {"channel-weights", "2,1,1"},
      {"channel-weights", "x"},
      {"init-box", "1,2,3"},
      {"init-box", "10,10,0,20"},
      {"init-box", "-5,0,10,10"},
      // Accepted silently before (issue 10): all weights zero makes every window a perfect match; a box under
      // the minimum template side never tracks.
      {"channel-weights", "0,0,0"},
      {"init-box", "10,10,1,1"},
      {"init-box", "0,0,7,20"},
  };
  for (const Case &c : cases) {
    // Quoted: some values hold characters the launch syntax would otherwise split on.
    const std::string setting = std::string(c.property) + "=\"" + c.value + "\"";
    const bool boxCase = std::string(c.property) == "init-box";
    const Outcome o = run("colortrack name=ct " + setting + (boxCase ? "" : " " + box), scene);
    assertErrorNames(o, c.property, c.value);
    fail_unless(o.errorDomain == GST_RESOURCE_ERROR && o.errorCode == GST_RESOURCE_ERROR_SETTINGS);
  }
}
GST_END_TEST;

// While playing, a bad value is refused with a warning and the element goes on with the old one (for a
// template file that cannot be read: the old template).
GST_START_TEST(test_bad_value_while_playing_keeps_old) {
  SceneConfig config = smallScene();
  const Scene scene(config);
  Pipeline p("colortrack name=ct init-box=" + boxString(scene.initBox()));
  fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
  for (int i = 0; i < 5; ++i) p.push(scene.render(i).bgr, i);
  g_object_set(p.tracker(), "bins", "16,x,8", "channel-weights", "1,1,7", "init-box", "1,1,1",
               "template-location", "/nonexistent-colortrack-dir/other.png", nullptr);
  // mode decides what the element's state holds: fixed while started.
  gst_util_set_object_arg(G_OBJECT(p.tracker()), "mode", "threshold");
  for (int i = 5; i < 20; ++i) p.push(scene.render(i).bgr, i);
  const Outcome o = p.finish();

  fail_unless(o.eos && !o.error, "%s", o.errorText.c_str());
  fail_unless(o.warned("bins") && o.warned("16,x,8"), "no warning naming bins");
  fail_unless(o.warned("channel-weights") && o.warned("1,1,7"), "no warning naming channel-weights");
  fail_unless(o.warned("init-box") && o.warned("1,1,1"), "no warning naming init-box");
  fail_unless(o.warned("template-location") && o.warned("/nonexistent-colortrack-dir/other.png"),
              "no warning naming the template file");
  fail_unless(o.warned("mode"), "no warning naming mode");
  gchar *bins = nullptr, *weights = nullptr, *location = nullptr;
  g_object_get(p.tracker(), "bins", &bins, "channel-weights", &weights, "template-location", &location,
               nullptr);
  fail_unless_equals_string(bins, "16,16,8");
  fail_unless_equals_string(weights, "1,1,0.3");
  fail_unless(location == nullptr, "template-location reads back as %s", location);
  gint mode = -1;
  g_object_get(p.tracker(), "mode", &mode, nullptr);
  GParamSpec *modeSpec = g_object_class_find_property(G_OBJECT_GET_CLASS(p.tracker()), "mode");
  GEnumClass *modes = G_ENUM_CLASS(g_type_class_ref(G_PARAM_SPEC_VALUE_TYPE(modeSpec)));
  fail_unless_equals_string(g_enum_get_value(modes, mode)->value_nick, "template");
  g_type_class_unref(modes);
  g_free(bins);
  g_free(weights);
  g_free(location);

  // Still tracking with the old values.
  assertStillTracking(p, scene, 20);
}
GST_END_TEST;

// Neither template-location nor init-box: one warning, buffers untouched.
GST_START_TEST(test_no_template_passes_through) {
  const Scene scene(smallScene());
  Pipeline p("colortrack name=ct");
  fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
  std::vector<cv::Mat> inputs;
  for (int i = 0; i < 6; ++i) {
    inputs.push_back(scene.render(i).bgr);
    p.push(inputs.back(), i);
  }
  const Outcome o = p.finish();
  fail_unless(o.eos && !o.error);
  fail_unless_equals_int(o.warnings.size(), 1);
  fail_unless(o.warned("template-location") && o.warned("init-box"), "%s", o.warnings[0].c_str());

  const std::vector<GstBuffer *> out = p.outputs();
  fail_unless_equals_int(out.size(), inputs.size());
  for (size_t i = 0; i < out.size(); ++i) {
    fail_unless(gst_buffer_get_video_region_of_interest_meta(out[i]) == nullptr);
    GstBuffer *expected = bgrBuffer(inputs[i], static_cast<int>(i));
    GstMapInfo a, b;
    fail_unless(gst_buffer_map(out[i], &a, GST_MAP_READ) && gst_buffer_map(expected, &b, GST_MAP_READ));
    fail_unless(a.size == b.size && memcmp(a.data, b.data, a.size) == 0, "frame %zu modified", i);
    gst_buffer_unmap(out[i], &a);
    gst_buffer_unmap(expected, &b);
    gst_buffer_unref(expected);
    gst_buffer_unref(out[i]);
  }
}
GST_END_TEST;

// New caps mid-stream: the template stays and the object is found again at the new size; a frame smaller
// than the template is an error naming where the template came from.
GST_START_TEST(test_caps_change_mid_stream) {
  SceneConfig first = smallScene();
  SceneConfig second = first;
  second.frameSize = cv::Size(240, 180);  // same seed: the same object (the template's) on a larger frame
  const Scene a(first), b(second);
  {
    Pipeline p("colortrack name=ct init-box=" + boxString(a.initBox()));
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 10; ++i) p.push(a.render(i).bgr, i);
    for (int i = 10; i < 30; ++i) p.push(b.render(i).bgr, i);
    const Outcome o = p.finish();
    fail_unless(o.eos && !o.error, "%s", o.errorText.c_str());
    const std::vector<GstBuffer *> out = p.outputs();
    fail_unless_equals_int(out.size(), 30);
    int found = 0;
    for (int i = 15; i < 30; ++i) {
      auto *roi = gst_buffer_get_video_region_of_interest_meta(out[i]);
      if (roi && iou(cv::Rect2d(roi->x, roi->y, roi->w, roi->h), b.render(i).box) > 0.5) ++found;
    }
    fail_unless(found >= 13, "object found in %d of the 15 frames after the caps change", found);
    for (GstBuffer *buf : out) gst_buffer_unref(buf);
  }
  {
    SceneConfig tiny = first;
    tiny.frameSize = cv::Size(24, 20);  // smaller than the 33x33 init-box template
    const Scene c(tiny);
    const std::string box = boxString(a.initBox());
    Pipeline p("colortrack name=ct init-box=" + box);
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 5; ++i) p.push(a.render(i).bgr, i);
    for (int i = 5; i < 10; ++i) p.push(c.render(i).bgr, i);
    const Outcome o = p.finish();
    assertErrorNames(o, "init-box", box);
  }
}
GST_END_TEST;

// A template-location that is a FIFO with no writer is refused at once, at start and while playing: reading
// it would wait in open() for a writer that never comes (and then set_state(NULL) could never return).
GST_START_TEST(test_template_fifo_never_blocks) {
  const Scene scene(smallScene());
  TempFile fifo("object.png");
  fail_unless(mkfifo(fifo.path().c_str(), 0600) == 0);
  gint64 started = g_get_monotonic_time();
  const Outcome o = run("colortrack name=ct template-location=" + fifo.path(), scene);
  assertErrorNames(o, "template-location", fifo.path());
  fail_unless(contains(o.errorText, "FIFO"), "the error does not say why: %s", o.errorText.c_str());
  fail_unless(g_get_monotonic_time() - started < G_USEC_PER_SEC, "the refusal took over a second");

  Pipeline p("colortrack name=ct init-box=" + boxString(scene.initBox()));
  fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
  for (int i = 0; i < 3; ++i) p.push(scene.render(i).bgr, i);
  started = g_get_monotonic_time();
  g_object_set(p.tracker(), "template-location", fifo.path().c_str(), nullptr);
  for (int i = 3; i < 8; ++i) p.push(scene.render(i).bgr, i);
  const Outcome playing = p.finish();
  fail_unless(playing.eos && !playing.error, "%s", playing.errorText.c_str());
  fail_unless(playing.warned("template-location") && playing.warned(fifo.path()),
              "no warning naming the FIFO");
  fail_unless_equals_int(p.outputs().size(), 8);
  fail_unless(g_get_monotonic_time() - started < G_USEC_PER_SEC, "the stream waited over a second");
}
GST_END_TEST;

// A template image that cannot serve this video (under the minimum side, larger than the frame), set while
// playing: a warning naming it, the old template kept, and the property reads back as before.
GST_START_TEST(test_unusable_template_while_playing_keeps_old) {
  const Scene scene(smallScene());
  TempFile tiny("tiny.png"), huge("huge.png");
  fail_unless(cv::imwrite(tiny.path(), cv::Mat(1, 1, CV_8UC3, cv::Scalar(0, 0, 255))));
  fail_unless(cv::imwrite(huge.path(), cv::Mat(400, 400, CV_8UC3, cv::Scalar(0, 0, 255))));
  for (const TempFile *file : {&tiny, &huge}) {
    Pipeline p("colortrack name=ct init-box=" + boxString(scene.initBox()));
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 5; ++i) p.push(scene.render(i).bgr, i);
    g_object_set(p.tracker(), "template-location", file->path().c_str(), nullptr);
    for (int i = 5; i < 20; ++i) p.push(scene.render(i).bgr, i);
    const Outcome o = p.finish();
    fail_unless(o.eos && !o.error, "%s", o.errorText.c_str());
    fail_unless(o.warned("template-location") && o.warned(file->path()), "no warning naming %s",
                file->path().c_str());
    gchar *location = nullptr;
    g_object_get(p.tracker(), "template-location", &location, nullptr);
    fail_unless(location == nullptr, "template-location reads back as %s", location);
    g_free(location);
    assertStillTracking(p, scene, 20);
  }
}
GST_END_TEST;

// A frame too small for the settings ends the pipeline every time, from a source that pushes at once (the
// issue-48 report's pipelines, 25 runs each so that a race would show): colortrack's error naming the
// property comes first, and the pipeline then goes to NULL. (gst-launch-1.0 1.22 itself sometimes keeps
// running after such an early error, with any element: docs/colortrack.md, "Errors and warnings".)
GST_START_TEST(test_too_small_frame_ends_the_pipeline_every_time) {
  struct Case {
    const char *launch, *property;
  };
  const Case cases[] = {
      {"videotestsrc ! video/x-raw,width=1,height=1 ! colortrack init-box=144,104,32,32 ! fakesink",
       "init-box"},
      {"videotestsrc ! video/x-raw,format=BGR,width=2,height=2 ! colortrack mode=threshold ! fakesink",
       "min-area"}};
  for (const Case &c : cases)
    for (int run = 0; run < 25; ++run) {
      GstElement *pipeline = gst_parse_launch(c.launch, nullptr);
      fail_unless(pipeline != nullptr, "cannot parse %s", c.launch);
      GstBus *bus = gst_element_get_bus(pipeline);
      gst_element_set_state(pipeline, GST_STATE_PLAYING);
      GstMessage *message = gst_bus_timed_pop_filtered(
          bus, 5 * GST_SECOND, static_cast<GstMessageType>(GST_MESSAGE_ERROR | GST_MESSAGE_EOS));
      fail_unless(message && GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR,
                  "run %d: no error within 5 s: %s", run, c.launch);
      GError *error = nullptr;
      gst_message_parse_error(message, &error, nullptr);
      const std::string text = error->message, from = GST_OBJECT_NAME(GST_MESSAGE_SRC(message));
      g_error_free(error);
      gst_message_unref(message);
      fail_unless(from.rfind("colortrack", 0) == 0 && text.find(c.property) != std::string::npos,
                  "run %d: the first error is from %s and does not name %s: %s", run, from.c_str(),
                  c.property, text.c_str());
      fail_unless_equals_int(gst_element_set_state(pipeline, GST_STATE_NULL), GST_STATE_CHANGE_SUCCESS);
      gst_object_unref(bus);
      gst_object_unref(pipeline);
    }
}
GST_END_TEST;

static Suite *colortrack_errors_suite(void) {
  preloadPlugins({"colortrack", "app", "videoconvertscale", "videotestsrc", "coreelements"});
  Suite *s = suite_create("colortrack_errors");
  TCase *tc = tcase_create("errors");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_missing_template_file);
  tcase_add_test(tc, test_unreadable_template_file);
  tcase_add_test(tc, test_template_file_with_another_definition_is_refused);
  tcase_add_test(tc, test_template_larger_than_frame);
  tcase_add_test(tc, test_tiny_template_file);
  tcase_add_test(tc, test_interlaced_caps_are_refused);
  tcase_add_test(tc, test_init_box_outside_or_larger_than_frame);
  tcase_add_test(tc, test_malformed_strings);
  tcase_add_test(tc, test_bad_value_while_playing_keeps_old);
  tcase_add_test(tc, test_no_template_passes_through);
  tcase_add_test(tc, test_caps_change_mid_stream);
  tcase_add_test(tc, test_template_fifo_never_blocks);
  tcase_add_test(tc, test_unusable_template_while_playing_keeps_old);
  tcase_add_test(tc, test_too_small_frame_ends_the_pipeline_every_time);
  return s;
}

GST_CHECK_MAIN(colortrack_errors);
