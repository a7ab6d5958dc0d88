// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's settings: start-time settings changed while running, clear errors naming the property for bad
// values, URL-like locations that are never files, a bad field of view while running.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <fcntl.h>
#include <sys/stat.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "gst_test_util.hpp"

#include <glib/gstdio.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

#include "robotctl_rig.hpp"

namespace {

using namespace robotctl_rig;

GST_START_TEST(test_start_settings_warn_when_changed) {
  Ctl ctl("rate=100");
  fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
  GstElement *element = gst_harness_find_element(ctl.h, "robotctl");
  // A live setting and a start setting set to its current value: no warning.
  g_object_set(element, "turn-gain", 2.0, "rate", 100.0, nullptr);
  g_object_set(element, "rate", 25.0, nullptr);
  GstMessage *m = gst_bus_pop_filtered(ctl.bus, GST_MESSAGE_WARNING);
  fail_unless(m != nullptr, "no warning for a change of 'rate' while started");
  GError *error = nullptr;
  gst_message_parse_warning(m, &error, nullptr);
  std::printf("rate changed while playing: warning \"%s\"\n", error->message);
  fail_unless(std::string(error->message).find("'rate'") != std::string::npos);
  fail_unless(std::string(error->message).find("next start") != std::string::npos);
  g_error_free(error);
  gst_message_unref(m);
  fail_unless(gst_bus_pop_filtered(ctl.bus, GST_MESSAGE_WARNING) == nullptr, "more than one warning");
  // A location that could never be opened is refused when set, not at the next start: the old one stays.
  gchar *before = nullptr;
  g_object_get(element, "location", &before, nullptr);
  for (const char *bad : {"/nonexistent/x", "udp://127.0.0.1:0", "/tmp", "C:robot.txt"}) {
    g_object_set(element, "location", bad, nullptr);
    gchar *now = nullptr;
    g_object_get(element, "location", &now, nullptr);
    fail_unless_equals_string(now, before);
    g_free(now);
    m = gst_bus_pop_filtered(ctl.bus, GST_MESSAGE_WARNING);
    fail_unless(m != nullptr, "no warning for location=%s", bad);
    gst_message_parse_warning(m, &error, nullptr);
    std::printf("location=%s while playing: warning \"%s\"\n", bad, error->message);
    fail_unless(std::string(error->message).find("'location'") != std::string::npos);
    g_error_free(error);
    gst_message_unref(m);
  }
  g_free(before);
  // zone-chars that could never be used (four characters): refused when set too, the old ones kept.
  g_object_set(element, "zone-chars", "FBLR", nullptr);
  gchar *chars = nullptr;
  g_object_get(element, "zone-chars", &chars, nullptr);
  fail_unless_equals_string(chars, "FBLRS");
  g_free(chars);
  m = gst_bus_pop_filtered(ctl.bus, GST_MESSAGE_WARNING);
  fail_unless(m != nullptr, "no warning for zone-chars=FBLR");
  gst_message_parse_warning(m, &error, nullptr);
  fail_unless(std::string(error->message).find("'zone-chars'") != std::string::npos, "%s", error->message);
  g_error_free(error);
  gst_message_unref(m);
  gst_object_unref(element);
}
GST_END_TEST;

// The error posted when `launch` goes to PAUSED.
std::string startError(const std::string &launch) {
  GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(pipeline != nullptr);
  fail_unless_equals_int(gst_element_set_state(pipeline, GST_STATE_PAUSED), GST_STATE_CHANGE_FAILURE);
  GstBus *bus = gst_element_get_bus(pipeline);
  GstMessage *m = gst_bus_timed_pop_filtered(bus, 0, GST_MESSAGE_ERROR);
  fail_unless(m != nullptr, "no error for %s", launch.c_str());
  GError *error = nullptr;
  gst_message_parse_error(m, &error, nullptr);
  std::string text = error->message;
  g_error_free(error);
  gst_message_unref(m);
  gst_object_unref(bus);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(pipeline);
  std::printf("error: %s\n", text.c_str());
  return text;
}

GST_START_TEST(test_bad_settings_give_clear_errors) {
  const std::string src = "videotestsrc num-buffers=1 ! ";
  fail_unless(startError(src + "robotctl device=/dev/ttyNOSUCHPORT").find("/dev/ttyNOSUCHPORT") !=
              std::string::npos);
  fail_unless(startError(src + "robotctl device=/dev/ttyNOSUCHPORT baud-rate=12345").find("12345") !=
              std::string::npos);
  fail_unless(startError(src + "robotctl location=/dev/null zone-chars=FBL").find("zone-chars") !=
              std::string::npos);
  fail_unless(startError(src + "robotctl").find("'location'") != std::string::npos);
  fail_unless(startError(src + "robotctl location=/dev/null roi-type=\"\"").find("roi-type") !=
              std::string::npos);
  fail_unless(startError(src + "robotctl location=/nonexistent-dir/x").find("/nonexistent-dir/x") !=
              std::string::npos);
  // MAVLink and UDP: each error names the property (and says what is wrong); none waits.
  const std::string mavlink = src + "robotctl protocol=mavlink ";
  for (const char *bad : {"udp://127.0.0.1", "udp://127.0.0.1:70000", "udp://127.0.0.1:0", "udp://:14550",
                          "udp://::1:14550", "udp://nonexistent.invalid:14550"}) {
    const std::string text = startError(mavlink + "location=" + bad);
    fail_unless(text.find("'location'") != std::string::npos && text.find(bad) != std::string::npos, "%s",
                text.c_str());
  }
  // Ids, lenses and bounds outside their declared ranges (a lens that makes the rates explode or vanish,
  // bounds that bound nothing, negative gains) are GLib's to refuse: test_property_ranges.
}
GST_END_TEST;

// A location that starts like a URL but is not a valid udp:// one is an error, never a file of that name in
// the working directory (where the commands would quietly go); "./NAME" names such a file on purpose.
GST_START_TEST(test_url_typos_are_never_files) {
  gchar *dir = g_dir_make_tmp("robotctl-XXXXXX", nullptr);
  fail_unless(dir != nullptr);
  gchar *before = g_get_current_dir();
  fail_unless(g_chdir(dir) == 0);
  const std::string src = "videotestsrc num-buffers=1 ! ";
  for (const char *typo : {"udp:127.0.0.1:14550", "udp:/127.0.0.1:14550", "tcp://127.0.0.1:5760",
                           "serial:/dev/ttyUSB0", "C:robot.txt"}) {
    const std::string text = startError(src + "robotctl location=" + typo);
    fail_unless(text.find("'location'") != std::string::npos && text.find(typo) != std::string::npos, "%s",
                text.c_str());
    fail_unless(!g_file_test(typo, G_FILE_TEST_EXISTS), "'%s' was created", typo);
  }
  GstElement *pipeline = gst_parse_launch((src + "robotctl location=./udp:x").c_str(), nullptr);
  fail_unless(pipeline != nullptr);
  fail_unless(gst_element_set_state(pipeline, GST_STATE_PAUSED) != GST_STATE_CHANGE_FAILURE);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(pipeline);
  fail_unless(g_file_test("udp:x", G_FILE_TEST_IS_REGULAR), "./udp:x was not written");
  g_unlink("udp:x");
  fail_unless(g_chdir(before) == 0);
  g_rmdir(dir);
  g_free(dir);
  g_free(before);
}
GST_END_TEST;

// The next warning on the bus names 'hfov'.
void expectFieldOfViewWarning(GstBus *bus, const char *what) {
  GstMessage *m = gst_bus_pop_filtered(bus, GST_MESSAGE_WARNING);
  fail_unless(m != nullptr, "no warning for %s", what);
  GError *error = nullptr;
  gst_message_parse_warning(m, &error, nullptr);
  std::printf("%s while playing: warning \"%s\"\n", what, error->message);
  fail_unless(std::string(error->message).find("'hfov'") != std::string::npos);
  g_error_free(error);
  gst_message_unref(m);
}

// hfov NaN and 0 while running are refused, keeping the old value. 0 is outside the declared range: GLib
// refuses it with its own warning naming the property. Which check refuses NaN depends on GLib: its range
// check may refuse it (Debian 12) before robotctl sees it; if it lets NaN through, robotctl refuses it with a
// warning naming 'hfov'.
GST_START_TEST(test_bad_field_of_view_while_running) {
  Ctl ctl("protocol=mavlink rate=100 hfov=70");
  ctl.decide({roi(kRight)});
  GstElement *element = gst_harness_find_element(ctl.h, "robotctl");
  for (const double bad : {std::nan(""), 0.0}) {
    _gst_check_expecting_log = TRUE;
    _gst_check_raised_warning = _gst_check_raised_critical = FALSE;
    g_object_set(element, "hfov", bad, nullptr);
    const bool glibRefused = _gst_check_raised_warning || _gst_check_raised_critical;
    _gst_check_expecting_log = FALSE;
    _gst_check_raised_warning = _gst_check_raised_critical = FALSE;
    gdouble hfov = 0;
    g_object_get(element, "hfov", &hfov, nullptr);
    fail_unless_equals_float(hfov, 70.0);
    if (!glibRefused) expectFieldOfViewWarning(ctl.bus, std::isnan(bad) ? "hfov=nan" : "hfov=0");
  }
  gst_object_unref(element);
}
GST_END_TEST;

// The zone law cannot drive a gimbal (issue 25): an error at start that names the fix, whichever order the
// properties come in; auto, the default, drives it (proportionally: test_gimbal_sim); zone set while running
// is refused with a warning that keeps the value; a MAVLink follow (a drone) takes the zone law.
GST_START_TEST(test_zone_law_refused_for_a_gimbal) {
  const std::string src = "videotestsrc num-buffers=1 ! robotctl location=/dev/null ";
  for (const char *props :
       {"protocol=mavlink controller=zone", "controller=zone protocol=mavlink mavlink-mode=gimbal"}) {
    const std::string text = startError(src + props);
    std::printf("%s: \"%s\"\n", props, text.c_str());
    fail_unless(text.find("controller=zone") != std::string::npos &&
                    text.find("controller=auto") != std::string::npos,
                "%s", text.c_str());
  }
  {
    Ctl follow("protocol=mavlink mavlink-mode=follow controller=zone rate=100");
    fail_if(follow.decide({roi(kRight)}).empty());
  }
  Ctl ctl("protocol=mavlink rate=100");
  fail_if(ctl.decide({roi(kRight)}).empty());
  GstElement *element = gst_harness_find_element(ctl.h, "robotctl");
  gst_util_set_object_arg(G_OBJECT(element), "controller", "zone");
  GstMessage *m = gst_bus_pop_filtered(ctl.bus, GST_MESSAGE_WARNING);
  fail_unless(m != nullptr, "no warning for controller=zone while driving a gimbal");
  GError *error = nullptr;
  gst_message_parse_warning(m, &error, nullptr);
  std::printf("controller=zone while playing: warning \"%s\"\n", error->message);
  fail_unless(std::string(error->message).find("gimbal") != std::string::npos, "%s", error->message);
  g_error_free(error);
  gst_message_unref(m);
  GValue value = G_VALUE_INIT;
  g_object_get_property(G_OBJECT(element), "controller", &value);
  gchar *nick = gst_value_serialize(&value);
  fail_unless_equals_string(nick, "auto");
  g_free(nick);
  g_value_unset(&value);
  gst_object_unref(element);
}
GST_END_TEST;

// A location refused when set (its folder did not exist yet) is judged again at start: an application that
// creates the folder in between starts fine.
GST_START_TEST(test_location_refused_when_set_is_judged_again_at_start) {
  gchar *dir = g_dir_make_tmp("robotctl-XXXXXX", nullptr);
  const std::string folder = std::string(dir) + "/later", file = folder + "/commands.txt";
  GstElement *pipeline = gst_parse_launch("videotestsrc num-buffers=2 ! robotctl name=r", nullptr);
  GstElement *robot = gst_bin_get_by_name(GST_BIN(pipeline), "r");
  g_object_set(robot, "location", file.c_str(), nullptr);  // refused: the folder is missing
  fail_unless(g_mkdir(folder.c_str(), 0700) == 0);
  fail_unless(gst_element_set_state(pipeline, GST_STATE_PAUSED) != GST_STATE_CHANGE_FAILURE,
              "the start failed although the folder exists now");
  gst_element_set_state(pipeline, GST_STATE_NULL);
  fail_unless(g_file_test(file.c_str(), G_FILE_TEST_IS_REGULAR));
  g_unlink(file.c_str());
  g_rmdir(folder.c_str());
  g_rmdir(dir);
  g_free(dir);
  gst_object_unref(robot);
  gst_object_unref(pipeline);
}
GST_END_TEST;

// The warnings of a pipeline run to its end, one per line.
std::string warningsOf(const std::string &launch) {
  GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(pipeline != nullptr, "%s", launch.c_str());
  GstBus *bus = gst_element_get_bus(pipeline);
  gst_element_set_state(pipeline, GST_STATE_PLAYING);
  std::string warnings;
  bool ended = false;
  while (GstMessage *m = gst_bus_timed_pop_filtered(
             bus, 10 * GST_SECOND,
             static_cast<GstMessageType>(GST_MESSAGE_WARNING | GST_MESSAGE_ERROR | GST_MESSAGE_EOS))) {
    const bool warning = GST_MESSAGE_TYPE(m) == GST_MESSAGE_WARNING;
    ended = GST_MESSAGE_TYPE(m) == GST_MESSAGE_EOS;
    if (warning) {
      GError *error = nullptr;
      gst_message_parse_warning(m, &error, nullptr);
      warnings += std::string(error->message) + "\n";
      g_error_free(error);
    }
    gst_message_unref(m);
    if (!warning) break;
  }
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(pipeline);
  fail_unless(ended, "%s did not run to its end", launch.c_str());
  return warnings;
}

// Serial settings mean nothing to a 'location' (a file, a pty...): said at start, naming each one set.
GST_START_TEST(test_serial_settings_with_a_location_are_said_to_be_ignored) {
  const std::string src = "videotestsrc num-buffers=2 ! robotctl location=/dev/null ";
  const std::string warnings = warningsOf(src + "baud-rate=115200 parity=even");
  std::printf("baud-rate and parity with a location: \"%s\"\n", warnings.c_str());
  fail_unless(warnings.find("Serial settings") != std::string::npos, "no warning: \"%s\"", warnings.c_str());
  for (const char *named : {"'baud-rate'", "'parity'", "'device'", "'location'"})
    fail_unless(warnings.find(named) != std::string::npos, "%s not named: \"%s\"", named, warnings.c_str());
  fail_unless(warnings.find("data-bits") == std::string::npos, "a default setting named: %s",
              warnings.c_str());
  const std::string plain = warningsOf(src + "baud-rate=9600");
  fail_unless(plain.find("Serial settings") == std::string::npos, "warned with defaults: %s", plain.c_str());
}
GST_END_TEST;

}  // namespace

static Suite *robotctl_settings_suite(void) {
  Suite *s = suite_create("robotctl_settings");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_start_settings_warn_when_changed);
  tcase_add_test(tc, test_bad_settings_give_clear_errors);
  tcase_add_test(tc, test_url_typos_are_never_files);
  tcase_add_test(tc, test_bad_field_of_view_while_running);
  tcase_add_test(tc, test_zone_law_refused_for_a_gimbal);
  tcase_add_test(tc, test_location_refused_when_set_is_judged_again_at_start);
  tcase_add_test(tc, test_serial_settings_with_a_location_are_said_to_be_ignored);
  return s;
}

GST_CHECK_MAIN(robotctl_settings);
