// SPDX-License-Identifier: LGPL-2.1-or-later
// Every writable property each element declares (its base classes' own, such as basesink's sync, are not
// ours) flipped while buffers flow, the list taken from g_object_class_list_properties, so that "every
// property" stays true when one is added; colortrack in both modes. Values come from
// the GParamSpec (booleans, each enum value, flags, a number beside the default within the range); a text
// property needs values written here, and the test fails naming one that has none. What a change may cause
// (a warning that keeps the old value, a start-time setting for the next start) is allowed; an error, a
// crash or a frame that does not come out is not. tests/gst/test_property_stress.cpp checks what each
// element's own flips must not change (the track, the documents).
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "gst_test_util.hpp"
#include "scene.hpp"

#include <glib/gstdio.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>

namespace {

using namespace colortrack::gst_test_util;
using Clock = std::chrono::steady_clock;

constexpr auto kFlipTime = std::chrono::milliseconds(1200);
constexpr gulong kFlipPauseUs = 3000;

std::string number(double value) {
  gchar text[G_ASCII_DTOSTR_BUF_SIZE];
  return g_ascii_dtostr(text, sizeof text, value);
}

// A value beside the default, inside [min, max].
template <typename T>
std::vector<std::string> besideDefault(T value, T min, T max, T step) {
  const T other = value <= max - step ? value + step : value - step;
  return {number(static_cast<double>(value)), number(static_cast<double>(std::max(min, other)))};
}

// Values a GParamSpec itself tells: empty for a type it cannot (text).
std::vector<std::string> valuesOf(GParamSpec *p) {
  const GType type = G_PARAM_SPEC_VALUE_TYPE(p);
  if (type == G_TYPE_BOOLEAN) return {"true", "false"};
  if (G_TYPE_IS_ENUM(type)) {
    std::vector<std::string> nicks;
    const GEnumClass *e = G_PARAM_SPEC_ENUM(p)->enum_class;
    for (guint i = 0; i < e->n_values; ++i) nicks.push_back(e->values[i].value_nick);
    return nicks;
  }
  if (G_TYPE_IS_FLAGS(type)) {
    std::vector<std::string> nicks = {"0"};
    const GFlagsClass *f = G_PARAM_SPEC_FLAGS(p)->flags_class;
    for (guint i = 0; i < f->n_values; ++i) nicks.push_back(f->values[i].value_nick);
    return nicks;
  }
  if (type == G_TYPE_INT) {
    const GParamSpecInt *s = G_PARAM_SPEC_INT(p);
    return besideDefault<gint>(s->default_value, s->minimum, s->maximum, 1);
  }
  if (type == G_TYPE_UINT) {
    const GParamSpecUInt *s = G_PARAM_SPEC_UINT(p);
    return besideDefault<guint>(s->default_value, s->minimum, s->maximum, 1);
  }
  if (type == G_TYPE_INT64) {
    const GParamSpecInt64 *s = G_PARAM_SPEC_INT64(p);
    return besideDefault<gint64>(s->default_value, s->minimum, s->maximum, 1);
  }
  if (type == G_TYPE_UINT64) {
    const GParamSpecUInt64 *s = G_PARAM_SPEC_UINT64(p);
    return besideDefault<guint64>(s->default_value, s->minimum, s->maximum, 1);
  }
  if (type == G_TYPE_DOUBLE) {
    const GParamSpecDouble *s = G_PARAM_SPEC_DOUBLE(p);
    const double room = std::max(s->maximum - s->default_value, s->default_value - s->minimum);
    return besideDefault<double>(s->default_value, s->minimum, s->maximum, std::min(1.0, room / 4));
  }
  if (type == G_TYPE_FLOAT) {
    const GParamSpecFloat *s = G_PARAM_SPEC_FLOAT(p);
    const float room = std::max(s->maximum - s->default_value, s->default_value - s->minimum);
    return besideDefault<float>(s->default_value, s->minimum, s->maximum, std::min(1.0f, room / 4));
  }
  return {};
}

using TextValues = std::map<std::string, std::vector<std::string>>;

// One stress thread per value of each of the element's own writable properties; fails naming a property
// with no values.
struct AllFlips {
  std::vector<GstHarnessThread *> threads;
  int properties = 0, flipped = 0;

  AllFlips(GstHarness *h, const TextValues &texts) {
    guint n = 0;
    GParamSpec **specs = g_object_class_list_properties(G_OBJECT_GET_CLASS(h->element), &n);
    for (guint i = 0; i < n; ++i) {
      GParamSpec *p = specs[i];
      if (p->owner_type != G_OBJECT_TYPE(h->element) || !(p->flags & G_PARAM_WRITABLE)) continue;
      ++properties;
      std::vector<std::string> values = valuesOf(p);
      if (const auto found = texts.find(p->name); found != texts.end()) values = found->second;
      fail_unless(values.size() >= 2, "property '%s' has no values to flip between: add them here", p->name);
      for (const std::string &text : values) {
        GValue value = G_VALUE_INIT;
        g_value_init(&value, G_PARAM_SPEC_VALUE_TYPE(p));
        fail_unless(gst_value_deserialize(&value, text.c_str()), "%s=%s does not parse", p->name,
                    text.c_str());
        threads.push_back(gst_harness_stress_property_start_full(h, p->name, &value, kFlipPauseUs));
        g_value_unset(&value);
      }
      ++flipped;
    }
    g_free(specs);
  }
  guint stop() {
    guint sets = 0;
    for (GstHarnessThread *t : threads) sets += gst_harness_stress_thread_stop(t);
    threads.clear();
    return sets;
  }
};

// Errors posted on `bus` so far (warnings are dropped: flips may cause them).
std::vector<std::string> errorsOn(GstBus *bus) {
  std::vector<std::string> errors;
  while (GstMessage *m = gst_bus_pop_filtered(bus, GST_MESSAGE_ERROR)) {
    GError *err = nullptr;
    gst_message_parse_error(m, &err, nullptr);
    errors.push_back(err->message);
    g_error_free(err);
    gst_message_unref(m);
  }
  return errors;
}

// `factory` with `properties` in a harness (a filter when `hasSrc`), fed the scene's frames while every
// property flips.
void flipEverything(const char *factory, const char *properties, bool hasSrc, const TextValues &texts) {
  colortrack::scene::SceneConfig config;
  config.frameSize = cv::Size(320, 240);
  config.objectSize = cv::Size(40, 40);
  const colortrack::scene::Scene scene(config);
  GstElement *element = gst_element_factory_make(factory, nullptr);
  fail_unless(element != nullptr);
  gst_util_set_object_arg(G_OBJECT(element), "name", factory);
  gchar **pairs = g_strsplit(properties, " ", -1);
  for (gchar **p = pairs; *p && **p; ++p) {
    gchar **kv = g_strsplit(*p, "=", 2);
    gst_util_set_object_arg(G_OBJECT(element), kv[0], kv[1]);
    g_strfreev(kv);
  }
  g_strfreev(pairs);
  GstBus *bus = gst_bus_new();
  gst_element_set_bus(element, bus);
  GstHarness *h = gst_harness_new_with_element(element, "sink", hasSrc ? "src" : nullptr);
  gst_object_unref(element);
  gst_harness_set_src_caps_str(h, videoCaps("BGR", config.frameSize).c_str());
  std::vector<std::string> errors;
  int frames = 0;
  AllFlips flips(h, texts);
  for (const auto end = Clock::now() + kFlipTime; Clock::now() < end || frames < 20; ++frames) {
    const GstFlowReturn flow =
        gst_harness_push(h, bgrBuffer(scene.render(frames % config.frames).bgr, frames));
    fail_unless_equals_int(flow, GST_FLOW_OK);
    if (hasSrc) {
      GstBuffer *out = gst_harness_pull(h);
      fail_unless(out != nullptr, "%s: no output for frame %d", factory, frames);
      gst_buffer_unref(out);
    }
    for (const std::string &e : errorsOn(bus)) errors.push_back(e);
  }
  const guint sets = flips.stop();
  std::printf("%s: %d of %d writable properties flipped (%u sets over %d frames)\n", factory, flips.flipped,
              flips.properties, sets, frames);
  fail_unless_equals_int(flips.flipped, flips.properties);
  fail_unless(flips.properties >= 10, "%s: only %d properties found", factory, flips.properties);
  fail_unless(errors.empty(), "%s: %zu errors, the first: %s", factory, errors.size(),
              errors.empty() ? "" : errors[0].c_str());
  gst_element_set_bus(h->element, nullptr);
  gst_harness_teardown(h);
  gst_object_unref(bus);
}

// A file in a fresh temporary folder (removed by the caller with its folder).
std::string tempPath(const std::string &folder, const char *name) {
  return folder + "/" + name;
}

// colortrack in `mode` (fixed while started: each mode runs its own code for the flips).
void flipColortrack(const char *mode) {
  gchar *dir = g_dir_make_tmp("flip-all-XXXXXX", nullptr);
  const std::string templateFile = tempPath(dir, "template.png");
  fail_unless(cv::imwrite(templateFile, cv::Mat(40, 40, CV_8UC3, cv::Scalar(30, 30, 220))));
  const TextValues texts = {
      {"bins", {"16,16,8", "8,8,4"}},
      {"channel-weights", {"1,1,0.3", "1,1,1"}},
      {"hsv-lower", {"340,0.5,0.25", "330,0.4,0.2"}},
      {"hsv-upper", {"20,1,1", "25,1,1"}},
      {"init-box", {"140,100,40,40", "20,20,40,40"}},
      {"template-location", {templateFile, ""}},
  };
  const std::string properties = std::string("post-messages=true init-box=140,100,40,40 mode=") + mode;
  flipEverything("colortrack", properties.c_str(), true, texts);
  g_unlink(templateFile.c_str());
  g_rmdir(dir);
  g_free(dir);
}

GST_START_TEST(test_colortrack_every_property_flipped) {
  flipColortrack("template");
}
GST_END_TEST;

GST_START_TEST(test_colortrack_threshold_every_property_flipped) {
  flipColortrack("threshold");
}
GST_END_TEST;

GST_START_TEST(test_robotctl_every_property_flipped) {
  gchar *dir = g_dir_make_tmp("flip-all-XXXXXX", nullptr);
  const std::string a = tempPath(dir, "a.txt"), b = tempPath(dir, "b.txt");
  // device and location are read at start: a flip only warns, and nothing is opened but the start's file.
  const TextValues texts = {
      {"device", {"", "/dev/colortrack-no-such-port"}},
      {"location", {a, b}},
      {"roi-type", {"colortrack", "object"}},
      {"zone-chars", {"FBLRS", "fblrs"}},
  };
  flipEverything("robotctl", ("location=" + a + " sync=false").c_str(), false, texts);
  fail_if(g_file_test(b.c_str(), G_FILE_TEST_EXISTS), "a location flipped while playing was opened");
  g_unlink(a.c_str());
  g_rmdir(dir);
  g_free(dir);
}
GST_END_TEST;

GST_START_TEST(test_trackpublish_every_property_flipped) {
  gchar *dir = g_dir_make_tmp("flip-all-XXXXXX", nullptr);
  const std::string a = tempPath(dir, "a.jsonl"), b = tempPath(dir, "b.jsonl");
  // All read at start: the flips only warn; the outputs of the start stay.
  const TextValues texts = {
      {"address", {"", "tcp://127.0.0.1:1"}},
      {"client-id", {"one", "two"}},
      {"location", {a, b}},
      {"username", {"", "alice"}},
      {"password", {"", "secret"}},
      {"roi-type", {"colortrack", "object"}},
      {"source", {"cam1", "cam2"}},
      {"tags", {"{\"a\":1}", "{}"}},
      {"tls-ca-file", {"", a}},
      {"tls-cert-file", {"", a}},
      {"tls-key-file", {"", a}},
      {"topic", {"x/{source}", "y/{source}"}},
  };
  flipEverything("trackpublish", ("location=" + a).c_str(), true, texts);
  fail_if(g_file_test(b.c_str(), G_FILE_TEST_EXISTS), "a location flipped while playing was opened");
  g_unlink(a.c_str());
  g_rmdir(dir);
  g_free(dir);
}
GST_END_TEST;

}  // namespace

static Suite *property_flip_all_suite(void) {
  preloadPlugins({"colortrack"});
  Suite *s = suite_create("property_flip_all");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_colortrack_every_property_flipped);
  tcase_add_test(tc, test_colortrack_threshold_every_property_flipped);
  tcase_add_test(tc, test_robotctl_every_property_flipped);
  tcase_add_test(tc, test_trackpublish_every_property_flipped);
  return s;
}

GST_CHECK_MAIN(property_flip_all);
