// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's presets (GstPreset, colortrack-preset.cpp): a preset saved from one colortrack with
// non-default hsv-lower/hsv-upper/min-area/morph-size loads into a fresh element with the same values, the
// commas of the HSV strings intact; the element keeps its own name; 'init-box' and 'template-location' are
// not in a preset; robotctl has no presets (its 'device' and 'location' would be saved). Presets go to a
// temporary XDG_DATA_HOME (where GStreamer's default implementation saves) that is also GST_PRESET_PATH.
#include <cstdlib>
#include <string>

#include "gst_test_util.hpp"

#include <glib/gstdio.h>
#include <gst/check/gstcheck.h>

namespace {

using namespace colortrack::gst_test_util;

std::string presetDir;

std::string readString(GstElement *e, const char *property) {
  gchar *value = nullptr;
  g_object_get(e, property, &value, nullptr);
  std::string out = value != nullptr ? value : "";
  g_free(value);
  return out;
}

int readInt(GstElement *e, const char *property) {
  gint value = 0;
  g_object_get(e, property, &value, nullptr);
  return value;
}

}  // namespace

GST_START_TEST(test_preset_round_trip) {
  GstElement *saved = gst_element_factory_make("colortrack", "saved");
  fail_unless(saved != nullptr && GST_IS_PRESET(saved));
  g_object_set(saved, "hsv-lower", "10,0.5,0.6", "hsv-upper", "40,0.9,0.95", "min-area", 321, "morph-size", 7,
               nullptr);
  fail_unless(gst_preset_save_preset(GST_PRESET(saved), "studio-test"));
  const std::string file = presetDir + "/gstreamer-1.0/presets/GstColorTrack.prs";
  fail_unless(g_file_test(file.c_str(), G_FILE_TEST_EXISTS), "no preset file at %s", file.c_str());

  GstElement *fresh = gst_element_factory_make("colortrack", "fresh");
  fail_unless(readInt(fresh, "min-area") != 321);
  fail_unless(gst_preset_load_preset(GST_PRESET(fresh), "studio-test"));
  // Kept in variables: the macro reads the text after the statement that made it (a temporary's would dangle).
  const std::string lower = readString(fresh, "hsv-lower"), upper = readString(fresh, "hsv-upper");
  fail_unless_equals_string(lower.c_str(), "10,0.5,0.6");
  fail_unless_equals_string(upper.c_str(), "40,0.9,0.95");
  fail_unless_equals_int(readInt(fresh, "min-area"), 321);
  fail_unless_equals_int(readInt(fresh, "morph-size"), 7);
  fail_unless_equals_string(GST_OBJECT_NAME(fresh), "fresh");
  fail_if(gst_preset_load_preset(GST_PRESET(fresh), "no-such-preset"));
  gst_object_unref(saved);
  gst_object_unref(fresh);
}
GST_END_TEST;

GST_START_TEST(test_preset_property_list) {
  GstElement *e = gst_element_factory_make("colortrack", nullptr);
  gchar **names = gst_preset_get_property_names(GST_PRESET(e));
  fail_unless(names != nullptr);
  for (const char *kept : {"hsv-lower", "hsv-upper", "min-area", "morph-size", "mode", "max-objects"})
    fail_unless(g_strv_contains(names, kept), "'%s' not in a preset", kept);
  for (const char *left : {"name", "parent", "qos", "init-box", "template-location"})
    fail_if(g_strv_contains(names, left), "'%s' in a preset", left);
  g_strfreev(names);
  gst_object_unref(e);

  GstElement *robot = gst_element_factory_make("robotctl", nullptr);
  fail_unless(robot != nullptr);
  fail_if(GST_IS_PRESET(robot));
  gst_object_unref(robot);
}
GST_END_TEST;

static Suite *colortrack_preset_suite(void) {
  preloadPlugins({"colortrack"});
  Suite *s = suite_create("colortrack_preset");
  TCase *tc = tcase_create("preset");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_preset_round_trip);
  tcase_add_test(tc, test_preset_property_list);
  return s;
}

// GST_CHECK_MAIN with the preset folders set first (GLib reads XDG_DATA_HOME once) and removed after.
int main(int argc, char **argv) {
  gchar *dir = g_dir_make_tmp("colortrack-preset-XXXXXX", nullptr);
  if (dir == nullptr) return 1;
  presetDir = dir;
  g_setenv("XDG_DATA_HOME", dir, TRUE);
  g_setenv("GST_PRESET_PATH", (presetDir + "/gstreamer-1.0/presets").c_str(), TRUE);
  gst_check_init(&argc, &argv);
  SRunner *runner = srunner_create(colortrack_preset_suite());
  srunner_run_all(runner, CK_NORMAL);
  const int failed = srunner_ntests_failed(runner);
  srunner_free(runner);
  const std::string presets = presetDir + "/gstreamer-1.0/presets";
  g_unlink((presets + "/GstColorTrack.prs").c_str());
  g_unlink((presets + "/GstColorTrack.prs.bak").c_str());
  g_rmdir(presets.c_str());
  g_rmdir((presetDir + "/gstreamer-1.0").c_str());
  g_rmdir(dir);
  g_free(dir);
  return failed == 0 ? 0 : 1;
}
