// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl when its port fails: an unplugged adapter behind a symlink, a device link or FIFO that disappears
// and comes back (never replaced by a regular file), a reader that stops reading, frames cut by a slow port.
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

GST_START_TEST(test_unplugged_port_warns_reconnects_and_stops_first) {
  // The element writes to a symlink; "unplugging" closes the pty, "plugging in" points the link at a new one.
  gchar *dir = g_dir_make_tmp("robotctl-XXXXXX", nullptr);
  const std::string link = std::string(dir) + "/robot";
  auto pointLinkAt = [&](const std::string &target) {
    const std::string temp = link + ".new";
    fail_unless(symlink(target.c_str(), temp.c_str()) == 0);
    fail_unless(rename(temp.c_str(), link.c_str()) == 0);
  };
  auto first = std::make_unique<Pty>();
  pointLinkAt(first->slave);
  {
    Ctl ctl("rate=50 lost-timeout=10000", link);
    ctl.push({roi(kRight)});
    waitForCommandOf(ctl.bus, ptsOf(0));
    const Bytes before = first->drain();
    fail_unless(!before.empty() && before.back() == 'R');
    first.reset();  // unplugged

    GstMessage *m = gst_bus_timed_pop_filtered(ctl.bus, 3 * GST_SECOND, GST_MESSAGE_WARNING);
    fail_unless(m != nullptr, "no warning after the port went away");
    GError *error = nullptr;
    gst_message_parse_warning(m, &error, nullptr);
    std::printf("unplugged: warning \"%s\"\n", error->message);
    fail_unless(std::string(error->message).find("Lost the connection") != std::string::npos);
    fail_unless(std::string(error->message).find(link) != std::string::npos);
    g_error_free(error);
    gst_message_unref(m);

    Pty second;
    pointLinkAt(second.slave);
    const auto plugged = Clock::now();
    Bytes got;
    while (got.empty() && Clock::now() - plugged < std::chrono::seconds(4)) got = second.readFor(10);
    fail_if(got.empty(), "no reconnection");
    std::printf("reconnected after %lld ms, first byte '%c'\n",
                static_cast<long long>(
                    std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - plugged).count()),
                got[0]);
    fail_unless_equals_int(got[0], 'S');  // stop first, although the last decision was right
    ctl.push({roi(kLeft)});
    waitForCommandOf(ctl.bus, ptsOf(1));
    const Bytes after = second.drain();
    fail_unless(!after.empty() && after.back() == 'L');
  }
  g_unlink(link.c_str());
  g_rmdir(dir);
  g_free(dir);
}
GST_END_TEST;

// Issue 10's safety bug: udev removes /dev/serial/by-id/... links when the adapter is unplugged, and a FIFO's
// reader may remove it. A reopen must never create a regular file there (the commands would go into it and
// the robot would never hear from robotctl again); it waits, warns, and the robot hears stop first when the
// device or FIFO comes back.
GST_START_TEST(test_reopen_never_creates_a_file_where_a_device_or_fifo_was) {
  gchar *dir = g_dir_make_tmp("robotctl-XXXXXX", nullptr);
  const std::string link = std::string(dir) + "/robot";
  auto waitForWarning = [](GstBus *bus, const char *text) {
    const auto end = Clock::now() + std::chrono::seconds(4);
    while (Clock::now() < end) {
      GstMessage *m = gst_bus_timed_pop_filtered(bus, 100 * GST_MSECOND, GST_MESSAGE_WARNING);
      if (!m) continue;
      GError *error = nullptr;
      gst_message_parse_warning(m, &error, nullptr);
      const bool found = std::string(error->message).find(text) != std::string::npos;
      if (found) std::printf("warning: \"%s\"\n", error->message);
      g_error_free(error);
      gst_message_unref(m);
      if (found) return true;
    }
    return false;
  };
  auto isNothingThere = [&] {
    struct stat st;
    return lstat(link.c_str(), &st) != 0;
  };

  // A pty behind a symlink: unplugging removes both, as udev does.
  {
    auto first = std::make_unique<Pty>();
    fail_unless(symlink(first->slave.c_str(), link.c_str()) == 0);
    Ctl ctl("rate=50 lost-timeout=10000", link);
    ctl.push({roi(kRight)});
    waitForCommandOf(ctl.bus, ptsOf(0));
    fail_unless(!first->drain().empty());
    first.reset();
    fail_unless(g_unlink(link.c_str()) == 0);
    fail_unless(waitForWarning(ctl.bus, "Cannot reopen"), "no warning while waiting for the device");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));  // several reopen attempts
    fail_unless(isNothingThere(), "a reopen created a file where the device link was");

    Pty second;
    fail_unless(symlink(second.slave.c_str(), link.c_str()) == 0);
    Bytes got;
    const auto plugged = Clock::now();
    while (got.empty() && Clock::now() - plugged < std::chrono::seconds(4)) got = second.readFor(10);
    fail_if(got.empty(), "no reconnection to the replugged device");
    fail_unless_equals_int(got[0], 'S');
    ctl.push({roi(kLeft)});
    waitForCommandOf(ctl.bus, ptsOf(1));
    const Bytes after = second.drain();
    fail_unless(!after.empty() && after.back() == 'L', "commands did not resume");
  }
  g_unlink(link.c_str());

  // A FIFO whose reader closes it and removes it, then makes a new one.
  {
    fail_unless(mkfifo(link.c_str(), 0600) == 0);
    int reader = open(link.c_str(), O_RDONLY | O_NONBLOCK);
    fail_unless(reader >= 0);
    auto readAll = [](int fd) {
      Bytes bytes;
      std::uint8_t chunk[4096];
      ssize_t n;
      while ((n = read(fd, chunk, sizeof chunk)) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
      return bytes;
    };
    Ctl ctl("rate=50 lost-timeout=10000", link);
    ctl.push({roi(kRight)});
    waitForCommandOf(ctl.bus, ptsOf(0));
    fail_unless(!readAll(reader).empty());
    close(reader);
    fail_unless(g_unlink(link.c_str()) == 0);
    ctl.push({roi(kRight)});  // the next write finds no reader
    fail_unless(waitForWarning(ctl.bus, "Cannot reopen"), "no warning while waiting for the FIFO");
    std::this_thread::sleep_for(std::chrono::milliseconds(500));
    fail_unless(isNothingThere(), "a reopen created a file where the FIFO was");

    fail_unless(mkfifo(link.c_str(), 0600) == 0);
    reader = open(link.c_str(), O_RDONLY | O_NONBLOCK);
    fail_unless(reader >= 0);
    Bytes got;
    const auto back = Clock::now();
    while (got.empty() && Clock::now() - back < std::chrono::seconds(4)) {
      got = readAll(reader);
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    fail_if(got.empty(), "no reconnection to the new FIFO");
    fail_unless_equals_int(got[0], 'S');
    ctl.push({roi(kLeft)});
    waitForCommandOf(ctl.bus, ptsOf(2));
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    const Bytes after = readAll(reader);
    fail_unless(!after.empty() && after.back() == 'L', "commands did not resume on the FIFO");
    close(reader);
  }
  g_unlink(link.c_str());
  g_rmdir(dir);
  g_free(dir);
}
GST_END_TEST;

GST_START_TEST(test_slow_reader_never_blocks_streaming) {
  Ctl ctl("rate=1000 protocol=binary lost-timeout=10000");
  ctl.push({roi(kRight)});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));  // nobody reads: the pty buffer fills up
  double slowest = 0;
  for (int i = 0; i < 100; ++i) {
    const auto t0 = Clock::now();
    ctl.push({roi(i % 2 ? kRight : kLeft)});
    slowest = std::max(slowest, std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
  }
  std::printf("slow reader: slowest push %.2f ms\n", slowest);
  fail_unless(slowest < 20, "a push took %.1f ms", slowest);
  // The backlog is whole packets, and once read, new commands flow again.
  const Bytes backlog = ctl.pty.drain();
  fail_unless(backlog.size() >= 10);
  fail_unless(ctl.pty.readFor(100).size() >= 10);
}
GST_END_TEST;

// A congested pty: filled up before the element writes anything, then read more slowly than the element
// writes, so its writes keep timing out, often part-way through a line (the pty frees room in blocks, and the
// last write into a block is cut). Every line read must be whole and one of the commands the element reports
// as sent. Text only: its lines have different lengths; the other protocols take the same path.
GST_START_TEST(test_cut_frames_are_completed_before_the_next) {
  Pty pty;
  // Filled with '#' one byte at a time (no write can be cut).
  std::size_t filler = 0;
  const int fillFd = open(pty.slave.c_str(), O_WRONLY | O_NOCTTY | O_NONBLOCK);
  fail_unless(fillFd >= 0);
  while (write(fillFd, "#", 1) == 1) ++filler;
  close(fillFd);

  Bytes bytes;
  std::vector<std::pair<int, int>> sent;
  {
    // 1000 lines of up to 18 bytes a second; read at about 13 bytes a millisecond.
    Ctl ctl(
        "rate=1000 lost-timeout=10000 controller=proportional max-linear-accel=0 max-angular-accel=0 "
        "protocol=text output-scale=32767",
        pty.slave);
    const std::vector<cv::Rect> boxes = {kRight, kLeft, kCentreFar, kCentreNear, kCentreRight};
    const auto end = Clock::now() + std::chrono::seconds(4);
    std::uint8_t chunk[13];
    for (int i = 0; bytes.size() < filler + 3000 && Clock::now() < end; ++i) {
      if (i % 5 == 0) ctl.push({roi(boxes[(i / 5) % boxes.size()])});  // lines of different lengths
      const ssize_t n = read(pty.master, chunk, sizeof chunk);
      if (n > 0) bytes.insert(bytes.end(), chunk, chunk + n);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    while (GstMessage *m = gst_bus_pop_filtered(ctl.bus, GST_MESSAGE_ELEMENT)) {
      const GstStructure *st = gst_message_get_structure(m);
      int left = 0, right = 0;
      if (gst_structure_get_int(st, "left", &left) && gst_structure_get_int(st, "right", &right))
        sent.emplace_back(left, right);
      gst_message_unref(m);
    }
  }
  // The filler first, untouched, then the element's lines.
  std::size_t begin = 0;
  while (begin < bytes.size() && bytes[begin] == '#') ++begin;
  fail_unless_equals_int(begin, filler);
  const std::string text = asText(bytes);
  int lines = 0;
  for (std::size_t end; (end = text.find('\n', begin)) != std::string::npos; begin = end + 1, ++lines) {
    const std::string line = text.substr(begin, end - begin);
    int left = 0, right = 0;
    const bool whole = std::sscanf(line.c_str(), "L=%d R=%d", &left, &right) == 2 &&
                       line == "L=" + std::to_string(left) + " R=" + std::to_string(right);
    const bool wasSent = std::find(sent.begin(), sent.end(), std::make_pair(left, right)) != sent.end();
    fail_unless(whole && wasSent, "line %d \"%s\" is not a command sent", lines, line.c_str());
  }
  std::printf("congested pty: %zu filler bytes, then %d whole lines (%zu commands posted)\n", filler, lines,
              sent.size());
  fail_unless(lines >= 100, "%d lines", lines);
}
GST_END_TEST;

}  // namespace

static Suite *robotctl_port_suite(void) {
  Suite *s = suite_create("robotctl_port");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_unplugged_port_warns_reconnects_and_stops_first);
  tcase_add_test(tc, test_reopen_never_creates_a_file_where_a_device_or_fifo_was);
  tcase_add_test(tc, test_slow_reader_never_blocks_streaming);
  tcase_add_test(tc, test_cut_frames_are_completed_before_the_next);
  return s;
}

GST_CHECK_MAIN(robotctl_port);
