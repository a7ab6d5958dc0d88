// SPDX-License-Identifier: LGPL-2.1-or-later
// Property fuzz: random strings into every text property of colortrack, robotctl and trackpublish. Each value
// is set in the NULL state; every so often the element is started (PAUSED) behind a two-frame source. Nothing
// may crash or hang, and a start refused because of a value must name the property in its error.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "gst_test_util.hpp"

#include <glib/gstdio.h>
#include <gst/check/gstcheck.h>

namespace {

using namespace colortrack::gst_test_util;
using Clock = std::chrono::steady_clock;

constexpr int kValuesPerProperty = 10000;
// A start costs a few milliseconds: one value in this many is started with, to keep the binary near 20 s.
constexpr int kStartEvery = 100;

// Pieces the elements' parsers look for, so that random strings reach past the first check.
const char *const kPieces[] = {"0", "1",         "255",      "-1",     ",",      "x",    ":",
                               "/", ".",         "udp://",   "tcp://", "ssl://", "$SYS", "{source}",
                               "#", "+",         "nan",      "inf",    "1e308",  "-0",   "1e-320",
                               " ", "127.0.0.1", "\xc4\x89", "\xff",   "%s",     "@"};

// A random string: pieces, random bytes (any byte but NUL, which a C string cannot carry) or both.
std::string randomText(std::mt19937 &rng) {
  std::string text;
  const int parts = std::uniform_int_distribution<int>(0, 8)(rng);
  for (int i = 0; i < parts; ++i) {
    if (std::uniform_int_distribution<int>(0, 2)(rng) > 0) {
      text += kPieces[std::uniform_int_distribution<std::size_t>(0, G_N_ELEMENTS(kPieces) - 1)(rng)];
    } else {
      const int bytes = std::uniform_int_distribution<int>(1, 12)(rng);
      for (int b = 0; b < bytes; ++b)
        text += static_cast<char>(std::uniform_int_distribution<int>(1, 255)(rng));
    }
  }
  if (std::uniform_int_distribution<int>(0, 500)(rng) == 0) text += std::string(70000, 'a');  // very long
  return text;
}

// A path the elements write to stays in the scratch directory: no '/' (so no other directory, no "..").
std::string confined(const std::string &property, std::string value) {
  if (property != "location") return value;
  std::replace(value.begin(), value.end(), '/', '_');
  return value;
}

// The writable string properties of `element`, less those that would reach outside this test: a serial
// device or a network address could be a real one.
std::vector<std::string> textProperties(GstElement *element, const std::vector<std::string> &skipped) {
  guint count = 0;
  GParamSpec **specs = g_object_class_list_properties(G_OBJECT_GET_CLASS(element), &count);
  std::vector<std::string> names;
  for (guint i = 0; i < count; ++i) {
    const std::string name = specs[i]->name;
    if (G_PARAM_SPEC_VALUE_TYPE(specs[i]) != G_TYPE_STRING || !(specs[i]->flags & G_PARAM_WRITABLE)) continue;
    if (name == "name" || std::find(skipped.begin(), skipped.end(), name) != skipped.end()) continue;
    names.push_back(name);
  }
  g_free(specs);
  return names;
}

// Starts `pipeline` (PAUSED: the two frames reach the element) and back to NULL; fails when a refused start
// does not name `property`, its message is not UTF-8, or the start does not end within 5 s. True when the
// start was refused.
bool startOnce(GstElement *pipeline, const std::string &property, const std::string &value) {
  const auto begin = Clock::now();
  const GstStateChangeReturn ret = gst_element_set_state(pipeline, GST_STATE_PAUSED);
  if (ret == GST_STATE_CHANGE_ASYNC) gst_element_get_state(pipeline, nullptr, nullptr, 5 * GST_SECOND);
  GstBus *bus = gst_element_get_bus(pipeline);
  GstMessage *error = gst_bus_pop_filtered(bus, GST_MESSAGE_ERROR);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  fail_unless(Clock::now() - begin < std::chrono::seconds(5), "%s: a start took over 5 s", property.c_str());
  if (error) {
    GError *e = nullptr;
    gst_message_parse_error(error, &e, nullptr);
    const std::string text = e ? e->message : "";
    g_clear_error(&e);
    gst_message_unref(error);
    // Values of other properties were valid (defaults), so a refusal is this property's.
    fail_unless(contains(text, "'" + property + "'"), "%s='%s': the error does not name it: %s",
                property.c_str(), g_strescape(value.c_str(), nullptr), text.c_str());
    // Whatever bytes the value had, the message is UTF-8 (an application in Python could not read it else).
    fail_unless(g_utf8_validate(text.data(), static_cast<gssize>(text.size()), nullptr),
                "%s='%s': the error is not valid UTF-8", property.c_str(),
                g_strescape(value.c_str(), nullptr));
  }
  gst_bus_set_flushing(bus, TRUE);
  gst_bus_set_flushing(bus, FALSE);
  gst_object_unref(bus);
  return error != nullptr;
}

// Fuzzes the text properties of the element named "e" in `launch`, one property at a time (the others at
// their values in `launch`).
void fuzz(const std::string &launch, const std::vector<std::string> &skipped, unsigned seed) {
  std::mt19937 rng(seed);
  GstElement *probe = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(probe != nullptr, "cannot parse %s", launch.c_str());
  GstElement *element = gst_bin_get_by_name(GST_BIN(probe), "e");
  const std::vector<std::string> properties = textProperties(element, skipped);
  gst_object_unref(element);
  gst_object_unref(probe);
  fail_if(properties.empty());
  int refusedStarts = 0;
  for (const std::string &property : properties) {
    GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
    GstElement *e = gst_bin_get_by_name(GST_BIN(pipeline), "e");
    for (int i = 0; i < kValuesPerProperty; ++i) {
      const std::string value = confined(property, randomText(rng));
      g_object_set(e, property.c_str(), value.c_str(), nullptr);
      gchar *back = nullptr;
      g_object_get(e, property.c_str(), &back, nullptr);  // reading back never crashes either
      g_free(back);
      if (i % kStartEvery == kStartEvery - 1) refusedStarts += startOnce(pipeline, property, value);
    }
    gst_object_unref(e);
    gst_object_unref(pipeline);
  }
  // Random text is mostly refused: a run that saw no refusal did not test what it claims.
  fail_unless(refusedStarts > 0, "no start was refused");
  std::printf("%zu properties, %d values each, %d starts refused\n", properties.size(), kValuesPerProperty,
              refusedStarts);
}

// The whole run in a fresh directory: a random location (confined()) creates its files there, never
// elsewhere.
class ScratchDirectory {
 public:
  ScratchDirectory() : dir_(g_dir_make_tmp("colortrack-fuzz-XXXXXX", nullptr)), before_(g_get_current_dir()) {
    fail_unless(dir_ != nullptr && g_chdir(dir_) == 0);
  }
  ~ScratchDirectory() {
    g_chdir(before_);
    GDir *d = g_dir_open(dir_, 0, nullptr);
    while (const gchar *name = d ? g_dir_read_name(d) : nullptr) {
      gchar *path = g_build_filename(dir_, name, nullptr);
      g_remove(path);
      g_free(path);
    }
    if (d) g_dir_close(d);
    g_rmdir(dir_);
    g_free(dir_);
    g_free(before_);
  }

 private:
  gchar *dir_;
  gchar *before_;
};

}  // namespace

GST_START_TEST(test_colortrack_text_properties) {
  ScratchDirectory scratch;
  fuzz(
      "videotestsrc num-buffers=2 ! video/x-raw,width=160,height=120 ! colortrack name=e "
      "init-box=60,40,32,32 "
      "! fakesink",
      {}, 1);
}
GST_END_TEST;

GST_START_TEST(test_robotctl_text_properties) {
  ScratchDirectory scratch;
  // device: a random string could name a real serial port of this machine.
  fuzz("videotestsrc num-buffers=2 ! video/x-raw,width=160,height=120 ! robotctl name=e location=/dev/null",
       {"device"}, 2);
}
GST_END_TEST;

GST_START_TEST(test_trackpublish_text_properties) {
  ScratchDirectory scratch;
  // address: a random string could name a real broker (and a host name waits on the resolver).
  fuzz(
      "videotestsrc num-buffers=2 ! video/x-raw,width=160,height=120 ! trackpublish name=e "
      "location=out.jsonl "
      "! fakesink",
      {"address"}, 3);
}
GST_END_TEST;

static Suite *property_fuzz_suite(void) {
  preloadPlugins({"colortrack", "videotestsrc", "coreelements"});
  Suite *s = suite_create("property_fuzz");
  TCase *tc = tcase_create("fuzz");
  tcase_set_timeout(tc, 240);
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_colortrack_text_properties);
  tcase_add_test(tc, test_robotctl_text_properties);
  tcase_add_test(tc, test_trackpublish_text_properties);
  return s;
}

GST_CHECK_MAIN(property_fuzz);
