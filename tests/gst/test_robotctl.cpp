// robotctl on a pseudo-terminal: exact bytes of every protocol and decision, the stops (EOS, flush, pause,
// stop, stalled upstream, lost target), an unplugged port, a slow reader, ROI selection (also from
// cvtracker), bus messages and errors for bad settings.
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
#include <opencv2/imgproc.hpp>

#include "colortrack/mavlink.hpp"
#include "gst_test_util.hpp"
#include "udp_receiver.hpp"

#include <glib/gstdio.h>
#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace {

using Bytes = std::vector<std::uint8_t>;
using Clock = std::chrono::steady_clock;
using colortrack::gst_test_util::waitForCommandOf;
constexpr int kWidth = 320, kHeight = 240, kFps = 30;

struct Pty {
  int master = -1;
  std::string slave;
  Pty() {
    master = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
    fail_unless(master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0);
    slave = ptsname(master);
    // Held open so that the element closing its end does not hang up the pty (the master would read EIO
    // and lose what was written last).
    keepSlave = open(slave.c_str(), O_RDWR | O_NOCTTY);
    fail_unless(keepSlave >= 0);
  }
  ~Pty() {
    close(keepSlave);
    close(master);
  }
  int keepSlave = -1;
  Bytes drain() const {
    Bytes bytes;
    std::uint8_t chunk[4096];
    ssize_t n;
    while ((n = read(master, chunk, sizeof chunk)) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
    return bytes;
  }
  // Reads for `ms` milliseconds.
  Bytes readFor(int ms) const {
    Bytes bytes;
    const auto end = Clock::now() + std::chrono::milliseconds(ms);
    while (Clock::now() < end) {
      const Bytes more = drain();
      bytes.insert(bytes.end(), more.begin(), more.end());
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return bytes;
  }
  // Milliseconds until `byte` arrives (-1 after timeoutMs); the bytes before it are appended to `seen`.
  int waitForByte(std::uint8_t byte, int timeoutMs, Bytes *seen = nullptr) const {
    const auto start = Clock::now();
    while (Clock::now() - start < std::chrono::milliseconds(timeoutMs)) {
      for (std::uint8_t b : drain()) {
        if (b == byte)
          return static_cast<int>(
              std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - start).count());
        if (seen) seen->push_back(b);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return -1;
  }
};

struct Roi {
  const char *type = "colortrack";
  int id = 1;
  cv::Rect box;
  const char *state = "tracking";  // nullptr: no params structure (like other elements' boxes)
  double score = 0.9;
};

GstClockTime ptsOf(int frame) {
  return gst_util_uint64_scale_int(frame, GST_SECOND, kFps);
}

GstBuffer *frameWith(const std::vector<Roi> &rois, int frame) {
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, kWidth * kHeight, nullptr);
  gst_buffer_memset(buffer, 0, 0, kWidth * kHeight);
  for (const Roi &r : rois) {
    GstVideoRegionOfInterestMeta *meta = gst_buffer_add_video_region_of_interest_meta(
        buffer, r.type, r.box.x, r.box.y, r.box.width, r.box.height);
    meta->id = r.id;
    if (r.state)
      gst_video_region_of_interest_meta_add_param(
          meta, gst_structure_new("colortrack", "state", G_TYPE_STRING, r.state, "score", G_TYPE_DOUBLE,
                                  r.score, "verified", G_TYPE_BOOLEAN, TRUE, nullptr));
  }
  GST_BUFFER_PTS(buffer) = ptsOf(frame);
  GST_BUFFER_DURATION(buffer) = ptsOf(1);
  return buffer;
}

// Boxes in a 320x240 frame (set-point 0.3 = 72 px high; deadband 0.1 of the half width = 16 px).
const cv::Rect kRight(216, 100, 48, 48);        // offset +0.5, far
const cv::Rect kLeft(40, 100, 48, 48);          // offset -0.5
const cv::Rect kCentreFar(148, 100, 24, 24);    // size 0.1
const cv::Rect kCentreNear(100, 60, 120, 120);  // size 0.5
const cv::Rect kCentreRight(124, 84, 72, 72);   // at the set-point

Roi roi(const cv::Rect &box, int id = 1) {
  Roi r;
  r.box = box;
  r.id = id;
  return r;
}

// robotctl in a harness, writing to a pty, posting its messages on `bus`.
struct Ctl {
  Pty pty;
  GstHarness *h = nullptr;
  GstBus *bus = nullptr;
  int frame = 0;

  explicit Ctl(const std::string &properties, const std::string &location = "") {
    const std::string launch = "robotctl name=ctl sync=false post-messages=true location=" +
                               (location.empty() ? pty.slave : location) + " " + properties;
    h = gst_harness_new_parse(launch.c_str());
    bus = gst_bus_new();
    gst_element_set_bus(h->element, bus);
    gst_harness_set_src_caps_str(h, "video/x-raw,format=GRAY8,width=320,height=240,framerate=30/1");
  }
  ~Ctl() {
    gst_element_set_bus(h->element, nullptr);
    gst_harness_teardown(h);
    gst_object_unref(bus);
  }
  void push(const std::vector<Roi> &rois) {
    fail_unless_equals_int(gst_harness_push(h, frameWith(rois, frame)), GST_FLOW_OK);
    ++frame;
  }
  // Pushes one frame and returns the bytes on the pty once the command decided on it has been sent.
  Bytes decide(const std::vector<Roi> &rois) {
    push(rois);
    waitForCommandOf(bus, ptsOf(frame - 1));
    return pty.drain();
  }
};

std::string asText(const Bytes &b) {
  return std::string(b.begin(), b.end());
}
std::string lastLine(const Bytes &b) {
  const std::string t = asText(b);
  const std::size_t end = t.rfind('\n');
  fail_unless(end != std::string::npos);
  const std::size_t start = t.rfind('\n', end - 1);
  return t.substr(start == std::string::npos ? 0 : start + 1,
                  end - (start == std::string::npos ? 0 : start + 1) + 1);
}

// The macro keeps a pointer past the statement that made it: the text must outlive it (a temporary's
// c_str() would dangle, as ASan reports).
void expectLastLine(const Bytes &b, const char *expected) {
  const std::string line = lastLine(b);
  fail_unless_equals_string(line.c_str(), expected);
}

std::uint8_t crc8(const std::uint8_t *data, std::size_t size) {
  std::uint8_t crc = 0;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit)
      crc = static_cast<std::uint8_t>(crc & 0x80 ? (crc << 1) ^ 0x07 : crc << 1);
  }
  return crc;
}

GST_START_TEST(test_zone_char_decisions) {
  Ctl ctl("rate=100");
  fail_unless_equals_int(ctl.decide({}).back(), 'S');  // nothing seen yet
  fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
  fail_unless_equals_int(ctl.decide({roi(kLeft)}).back(), 'L');
  fail_unless_equals_int(ctl.decide({roi(kCentreFar)}).back(), 'F');
  fail_unless_equals_int(ctl.decide({roi(kCentreNear)}).back(), 'B');
  fail_unless_equals_int(ctl.decide({roi(kCentreRight)}).back(), 'S');
  // One byte per command and nothing else on the wire.
  for (std::uint8_t b : ctl.pty.readFor(50)) fail_unless_equals_int(b, 'S');

  Ctl custom("rate=100 zone-chars=wsadx");
  fail_unless_equals_int(custom.decide({roi(kRight)}).back(), 'd');
  fail_unless_equals_int(custom.decide({roi(kCentreFar)}).back(), 'w');
}
GST_END_TEST;

GST_START_TEST(test_text_exact_line) {
  // Proportional, no slew limit, first sight (no integral, no rate yet): angular -0.3 (limited), linear
  // 2 * 1/3, limited to 0.5; left 0.8 * 255 = 204, right 0.2 * 255 = 51.
  Ctl ctl("rate=100 protocol=text controller=proportional max-linear-accel=0 max-angular-accel=0");
  expectLastLine(ctl.decide({}), "L=0 R=0\n");
  expectLastLine(ctl.decide({roi(kRight)}), "L=204 R=51\n");
  expectLastLine(ctl.decide({roi(kCentreRight)}), "L=0 R=0\n");
}
GST_END_TEST;

GST_START_TEST(test_binary_exact_packets) {
  Ctl ctl("rate=100 protocol=binary controller=proportional max-linear-accel=0 max-angular-accel=0");
  const Bytes bytes = ctl.decide({roi(kRight)});
  fail_unless(bytes.size() >= 10 && bytes.size() % 10 == 0, "%zu bytes", bytes.size());
  const std::uint8_t *p = bytes.data() + bytes.size() - 10;
  const Bytes expected = {0xA5, p[1], 0x06, 0x01, 0x01, 0xCC, 0x00, 0x33, 0x00};  // forward, visible, 204, 51
  fail_unless(Bytes(p, p + 9) == expected);
  fail_unless_equals_int(p[9], crc8(p + 1, 8));
  // Every packet is framed and numbered one after the other.
  for (std::size_t i = 0; i + 10 <= bytes.size(); i += 10) {
    fail_unless_equals_int(bytes[i], 0xA5);
    fail_unless_equals_int(bytes[i + 9], crc8(&bytes[i + 1], 8));
    if (i > 0) fail_unless_equals_int(bytes[i + 1], (bytes[i - 9] + 1) & 0xFF);
  }
}
GST_END_TEST;

GST_START_TEST(test_repeats_at_rate) {
  Ctl ctl("rate=50 lost-timeout=5000");
  fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
  const Bytes bytes = ctl.pty.readFor(400);  // 20 commands at 50 Hz
  std::printf("rate 50 Hz: %zu commands in 400 ms\n", bytes.size());
  fail_unless(bytes.size() >= 15 && bytes.size() <= 25, "%zu commands in 400 ms at 50 Hz", bytes.size());
  for (std::uint8_t b : bytes) fail_unless_equals_int(b, 'R');
}
GST_END_TEST;

// After `event`, the robot hears stop within 100 ms, and nothing but stop after that.
void checkStopsAfter(Ctl &ctl, const char *what, int waitMs) {
  const int ms = ctl.pty.waitForByte('S', waitMs);
  std::printf("%s: stop after %d ms\n", what, ms);
  fail_unless(ms >= 0, "%s: no stop", what);
  for (std::uint8_t b : ctl.pty.readFor(60)) fail_unless_equals_int(b, 'S');
}

GST_START_TEST(test_stop_on_eos_flush_pause_and_ready) {
  {
    Ctl ctl("rate=10 lost-timeout=5000");  // slow rate: the stop must not wait for the next tick
    fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
    fail_unless(gst_harness_push_event(ctl.h, gst_event_new_eos()));
    checkStopsAfter(ctl, "eos", 50);
  }
  {
    Ctl ctl("rate=10 lost-timeout=5000");
    fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
    fail_unless(gst_harness_push_event(ctl.h, gst_event_new_flush_start()));
    checkStopsAfter(ctl, "flush", 50);
    fail_unless(gst_harness_push_event(ctl.h, gst_event_new_flush_stop(TRUE)));
  }
  {
    Ctl ctl("rate=10 lost-timeout=5000");
    fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
    gst_element_set_state(ctl.h->element, GST_STATE_PAUSED);
    checkStopsAfter(ctl, "pause", 50);
  }
  {
    // async=false: the sink does not wait for a preroll buffer, so READY is reached before set_state returns.
    Ctl ctl("rate=10 lost-timeout=5000 async=false");
    fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
    fail_unless_equals_int(gst_element_set_state(ctl.h->element, GST_STATE_READY), GST_STATE_CHANGE_SUCCESS);
    checkStopsAfter(ctl, "ready", 50);
    // The port closes (READY to NULL) with a last stop.
    gst_bus_set_flushing(ctl.bus, TRUE);
    gst_bus_set_flushing(ctl.bus, FALSE);
    fail_unless_equals_int(gst_element_set_state(ctl.h->element, GST_STATE_NULL), GST_STATE_CHANGE_SUCCESS);
    const Bytes last = ctl.pty.drain();
    fail_unless(!last.empty() && last.back() == 'S');
    std::string lastReason, lastCommand;
    while (GstMessage *m = gst_bus_pop_filtered(ctl.bus, GST_MESSAGE_ELEMENT)) {
      lastReason = gst_structure_get_string(gst_message_get_structure(m), "reason");
      lastCommand = gst_structure_get_string(gst_message_get_structure(m), "command");
      gst_message_unref(m);
    }
    fail_unless_equals_string(lastReason.c_str(), "shutdown");
    fail_unless_equals_string(lastCommand.c_str(), "stop");
  }
}
GST_END_TEST;

GST_START_TEST(test_pause_then_play_again_follows_at_once) {
  Ctl ctl("rate=10 lost-timeout=5000");
  fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
  gst_element_set_state(ctl.h->element, GST_STATE_PAUSED);
  checkStopsAfter(ctl, "pause", 50);
  gst_element_set_state(ctl.h->element, GST_STATE_PLAYING);
  // The first buffer of PLAYING is a decision again (decide() waits for its message).
  fail_unless_equals_int(ctl.decide({roi(kLeft)}).back(), 'L');
}
GST_END_TEST;

GST_START_TEST(test_stop_when_upstream_stalls) {
  Ctl ctl("rate=100 lost-timeout=300");
  fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
  const auto pushed = Clock::now();
  Bytes before;
  fail_unless(ctl.pty.waitForByte('S', 2000, &before) >= 0);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - pushed).count();
  std::printf("stalled upstream: stop %lld ms after the last buffer (lost-timeout 300)\n",
              static_cast<long long>(ms));
  fail_unless(ms >= 280 && ms <= 600, "stop after %lld ms", static_cast<long long>(ms));
  for (std::uint8_t b : before) fail_unless_equals_int(b, 'R');
}
GST_END_TEST;

GST_START_TEST(test_lost_timeout_change_reaches_the_stall_watchdog) {
  Ctl ctl("rate=100 lost-timeout=5000");
  fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
  GstElement *element = gst_harness_find_element(ctl.h, "robotctl");
  g_object_set(element, "lost-timeout", 300u, nullptr);
  gst_object_unref(element);
  fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');  // the change applies from this buffer
  const auto pushed = Clock::now();
  fail_unless(ctl.pty.waitForByte('S', 2000) >= 0, "no stop within 2 s");
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - pushed).count();
  std::printf("lost-timeout 5000 -> 300 while playing: stop %lld ms after the last buffer\n",
              static_cast<long long>(ms));
  fail_unless(ms >= 250 && ms <= 600, "stop after %lld ms", static_cast<long long>(ms));
}
GST_END_TEST;

GST_START_TEST(test_stop_after_lost_timeout_of_stream_time) {
  // Frames 0-2 see the target; stop on the first frame at least 190 ms (stream time) after frame 2: frame 8.
  Ctl ctl("rate=200 lost-timeout=190");
  for (int i = 0; i < 3; ++i) fail_unless_equals_int(ctl.decide({roi(kRight)}).back(), 'R');
  Roi coasting = roi(kRight);
  coasting.state = "coasting";
  for (int i = 3; i < 8; ++i) fail_unless_equals_int(ctl.decide({coasting}).back(), 'R');  // held
  fail_unless_equals_int(ctl.decide({coasting}).back(), 'S');
  fail_unless_equals_int(ctl.decide({}).back(), 'S');
}
GST_END_TEST;

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
  for (const char *bad : {"/nonexistent/x", "udp://127.0.0.1:0", "/tmp"}) {
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
  gst_object_unref(element);
}
GST_END_TEST;

GST_START_TEST(test_roi_selection) {
  {
    Ctl ctl("rate=100");  // the lowest colortrack id by default
    fail_unless_equals_int(ctl.decide({roi(kRight, 2), roi(kLeft, 1)}).back(), 'L');
    Roi object = roi(kRight, 0);
    object.type = "object";
    object.state = nullptr;
    fail_unless_equals_int(ctl.decide({object}).back(), 'L');  // another type is ignored: held
  }
  {
    Ctl ctl("rate=100 target-id=2");
    fail_unless_equals_int(ctl.decide({roi(kLeft, 1), roi(kRight, 2)}).back(), 'R');
  }
  {
    Ctl ctl("rate=100 roi-type=object");
    Roi object = roi(kLeft, 0);
    object.type = "object";
    object.state = nullptr;  // no state or score: counts as tracking
    fail_unless_equals_int(ctl.decide({roi(kRight, 1), object}).back(), 'L');
  }
  {
    Ctl ctl("rate=100 min-score=0.5");
    Roi weak = roi(kRight);
    weak.score = 0.4;
    fail_unless_equals_int(ctl.decide({weak}).back(), 'S');
    weak.score = 0.6;
    fail_unless_equals_int(ctl.decide({weak}).back(), 'R');
  }
}
GST_END_TEST;

// The lock: the followed track is kept while it lives, whatever else appears; a new one is chosen by lock-on
// only when it is lost or gone.
GST_START_TEST(test_lock_on_keeps_the_target_until_its_track_ends) {
  {
    Ctl ctl("rate=100");  // first-confirmed
    fail_unless_equals_int(ctl.decide({roi(kRight, 5)}).back(), 'R');
    // A newer object with a lower id (a restarted tracker) does not steal the robot.
    fail_unless_equals_int(ctl.decide({roi(kLeft, 3), roi(kRight, 5)}).back(), 'R');
    // While the followed track coasts (an object passes in front), its id is kept: the last command is held.
    Roi coasting = roi(kRight, 5);
    coasting.state = "coasting";
    fail_unless_equals_int(ctl.decide({roi(kLeft, 3), coasting}).back(), 'R');
    fail_unless_equals_int(ctl.decide({roi(kLeft, 3), roi(kRight, 5)}).back(), 'R');
    // Lost: the lock moves on, to the oldest of the others.
    Roi lost = roi(kRight, 5);
    lost.state = "lost";
    fail_unless_equals_int(ctl.decide({roi(kLeft, 3), lost, roi(kRight, 7)}).back(), 'L');
    // Gone, then back under its old id: the lock stays on the new choice.
    fail_unless_equals_int(ctl.decide({roi(kRight, 5), roi(kLeft, 3)}).back(), 'L');
  }
  {
    Ctl ctl("rate=100 lock-on=largest");
    fail_unless_equals_int(ctl.decide({roi(kLeft, 1), roi(kCentreNear, 2)}).back(), 'B');
    fail_unless_equals_int(ctl.decide({roi(cv::Rect(0, 0, 200, 200), 1), roi(kCentreNear, 2)}).back(), 'B');
  }
  {
    Ctl ctl("rate=100 lock-on=nearest-centre");
    fail_unless_equals_int(ctl.decide({roi(kLeft, 1), roi(kCentreFar, 2)}).back(), 'F');
    // A flush starts again: the choice is made afresh (id 2 is no longer the nearest).
    fail_unless(gst_harness_push_event(ctl.h, gst_event_new_flush_start()));
    fail_unless(gst_harness_push_event(ctl.h, gst_event_new_flush_stop(TRUE)));
    GstSegment segment;
    gst_segment_init(&segment, GST_FORMAT_TIME);
    fail_unless(gst_harness_push_event(ctl.h, gst_event_new_segment(&segment)));
    fail_unless_equals_int(ctl.decide({roi(kCentreNear, 1), roi(kRight, 2)}).back(), 'B');
  }
  {
    Ctl ctl("rate=100 target-id=2 lock-on=largest");  // a fixed id wins over the policy
    fail_unless_equals_int(ctl.decide({roi(kCentreNear, 1), roi(kLeft, 2)}).back(), 'L');
    fail_unless_equals_int(ctl.decide({roi(kCentreNear, 1)}).back(), 'L');  // held, never switched
  }
}
GST_END_TEST;

GST_START_TEST(test_follows_cvtracker) {
  GstElementFactory *factory = gst_element_factory_find("cvtracker");
  if (!factory) {
    std::printf("cvtracker not installed: skipped\n");
    return;
  }
  gst_object_unref(factory);
  // A textured square on the right of the frame (RGB: cvtracker's only format); cvtracker starts on it and
  // attaches "object" ROI meta.
  cv::Mat image(kHeight, kWidth, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::RNG rng(7);
  cv::Mat patch(48, 48, CV_8UC3);
  rng.fill(patch, cv::RNG::UNIFORM, 0, 255);
  patch.copyTo(image(kRight));
  Pty pty;
  const std::string launch =
      "appsrc name=src format=time caps=video/x-raw,format=RGB,width=320,height=240,framerate=30/1 ! "
      "cvtracker object-initial-x=216 object-initial-y=100 object-initial-width=48 object-initial-height=48 "
      "! "
      "robotctl roi-type=object sync=false post-messages=true rate=100 location=" +
      pty.slave;
  GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(pipeline != nullptr);
  GstElement *src = gst_bin_get_by_name(GST_BIN(pipeline), "src");
  GstBus *bus = gst_element_get_bus(pipeline);
  gst_element_set_state(pipeline, GST_STATE_PLAYING);
  for (int i = 0; i < 5; ++i) {
    GstBuffer *buffer = gst_buffer_new_allocate(nullptr, image.total() * 3, nullptr);
    gst_buffer_fill(buffer, 0, image.data, image.total() * 3);  // 320 * 3 is a multiple of 4: no row padding
    GST_BUFFER_PTS(buffer) = ptsOf(i);
    GST_BUFFER_DURATION(buffer) = ptsOf(1);
    gst_app_src_push_buffer(GST_APP_SRC(src), buffer);
  }
  waitForCommandOf(bus, ptsOf(4));
  const Bytes bytes = pty.drain();
  fail_unless(!bytes.empty());
  fail_unless_equals_int(bytes.back(), 'R');
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(src);
  gst_object_unref(pipeline);
}
GST_END_TEST;

GST_START_TEST(test_message_fields) {
  Ctl ctl("rate=100");
  ctl.push({roi(kRight)});
  while (true) {
    GstMessage *m = gst_bus_timed_pop_filtered(ctl.bus, 5 * GST_SECOND, GST_MESSAGE_ELEMENT);
    fail_unless(m != nullptr);
    const GstStructure *s = gst_message_get_structure(m);
    guint64 timestamp = 0;
    fail_unless(gst_structure_has_name(s, "robotctl"));
    fail_unless(gst_structure_get_uint64(s, "timestamp", &timestamp));
    if (timestamp != ptsOf(0)) {
      gst_message_unref(m);
      continue;
    }
    gint left = 0, right = 0;
    gboolean visible = FALSE;
    fail_unless_equals_string(gst_structure_get_string(s, "command"), "right");
    fail_unless(gst_structure_get_int(s, "left", &left) && gst_structure_get_int(s, "right", &right));
    fail_unless_equals_int(left, 77);  // max-angular 0.3 * 255 = 76.5
    fail_unless_equals_int(right, -77);
    fail_unless(gst_structure_get_boolean(s, "target-visible", &visible) && visible);
    fail_unless_equals_string(gst_structure_get_string(s, "reason"), "target");
    gst_message_unref(m);
    break;
  }
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
  for (const char *typo :
       {"udp:127.0.0.1:14550", "udp:/127.0.0.1:14550", "tcp://127.0.0.1:5760", "serial:/dev/ttyUSB0"}) {
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

// The MAVLink commands in `bytes` (a pty carries them like a serial link), heartbeats left out.
std::vector<colortrack::mavlink::Frame> mavlinkCommands(const Bytes &bytes) {
  std::vector<colortrack::mavlink::Frame> frames;
  std::size_t at = 0, used = 0;
  while (at < bytes.size()) {
    const auto frame = colortrack::mavlink::parseFrame(bytes.data() + at, bytes.size() - at, &used);
    fail_unless(frame.has_value(), "not a MAVLink frame at byte %zu", at);
    if (frame->messageId != colortrack::mavlink::kHeartbeat.id) frames.push_back(*frame);
    at += used;
  }
  return frames;
}

// Yaw rate and forward velocity (follow) or pitch rate (gimbal) of the last command in `bytes`.
std::pair<float, float> lastRates(const Bytes &bytes) {
  const std::vector<colortrack::mavlink::Frame> frames = mavlinkCommands(bytes);
  fail_if(frames.empty(), "no MAVLink command");
  const colortrack::mavlink::Frame &f = frames.back();
  if (f.messageId == colortrack::mavlink::kGimbalManagerSetPitchyaw.id)
    return {colortrack::mavlink::payloadFloat(f.payload, 16),
            colortrack::mavlink::payloadFloat(f.payload, 12)};
  return {colortrack::mavlink::payloadFloat(f.payload, 44), colortrack::mavlink::payloadFloat(f.payload, 16)};
}

// Every failsafe sends MAVLink's stop form (zero rates, zero velocity), over a serial-like link (a pty).
GST_START_TEST(test_mavlink_stop_form_on_every_failsafe) {
  for (const char *mode : {"gimbal", "follow"}) {
    for (const char *failsafe : {"eos", "pause", "stalled", "lost"}) {
      Ctl ctl(std::string("protocol=mavlink controller=proportional rate=50 lost-timeout=300 mavlink-mode=") +
              mode);
      Bytes bytes;
      for (int i = 0; i < 4; ++i) bytes = ctl.decide({roi(kRight)});  // the slew limit ramps up
      const auto moving = lastRates(bytes);
      fail_unless(moving.first > 0, "%s: target right, yaw rate %g", mode, moving.first);
      if (std::string(failsafe) == "eos")
        fail_unless(gst_harness_push_event(ctl.h, gst_event_new_eos()));
      else if (std::string(failsafe) == "pause")
        gst_element_set_state(ctl.h->element, GST_STATE_PAUSED);
      else if (std::string(failsafe) == "lost")
        for (int i = 0; i < 12; ++i) ctl.decide({});  // 400 ms of stream time without a target
      const auto stopped = lastRates(ctl.pty.readFor(std::string(failsafe) == "stalled" ? 500 : 100));
      std::printf("mavlink %s, %s: yaw rate %g -> %g, %s %g -> %g\n", mode, failsafe, moving.first,
                  stopped.first, std::string(mode) == "gimbal" ? "pitch rate" : "vx", moving.second,
                  stopped.second);
      fail_unless(stopped.first == 0 && stopped.second == 0, "%s, %s: not the stop form", mode, failsafe);
    }
  }
}
GST_END_TEST;

// location=udp://HOST:PORT carries any protocol: here the text protocol, one datagram per command.
GST_START_TEST(test_text_protocol_over_udp) {
  colortrack::gst_test_util::UdpReceiver receiver;
  fail_unless(receiver.port() > 0);
  Ctl ctl("protocol=text rate=100 lost-timeout=5000", receiver.location());
  ctl.decide({roi(kRight)});
  const auto datagrams = receiver.drain();
  fail_if(datagrams.empty(), "nothing received on %s", receiver.location().c_str());
  for (const auto &d : datagrams) {
    const std::string line(d.bytes.begin(), d.bytes.end());
    fail_unless(line == "L=0 R=0\n" || line == "L=77 R=-77\n", "datagram \"%s\"", line.c_str());
  }
  const std::string last(datagrams.back().bytes.begin(), datagrams.back().bytes.end());
  fail_unless_equals_string(last.c_str(), "L=77 R=-77\n");  // zone controller: right at max-angular 0.3
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

Suite *robotctl_suite(void) {
  Suite *s = suite_create("robotctl");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_zone_char_decisions);
  tcase_add_test(tc, test_text_exact_line);
  tcase_add_test(tc, test_binary_exact_packets);
  tcase_add_test(tc, test_repeats_at_rate);
  tcase_add_test(tc, test_stop_on_eos_flush_pause_and_ready);
  tcase_add_test(tc, test_pause_then_play_again_follows_at_once);
  tcase_add_test(tc, test_stop_when_upstream_stalls);
  tcase_add_test(tc, test_lost_timeout_change_reaches_the_stall_watchdog);
  tcase_add_test(tc, test_stop_after_lost_timeout_of_stream_time);
  tcase_add_test(tc, test_unplugged_port_warns_reconnects_and_stops_first);
  tcase_add_test(tc, test_reopen_never_creates_a_file_where_a_device_or_fifo_was);
  tcase_add_test(tc, test_slow_reader_never_blocks_streaming);
  tcase_add_test(tc, test_cut_frames_are_completed_before_the_next);
  tcase_add_test(tc, test_start_settings_warn_when_changed);
  tcase_add_test(tc, test_roi_selection);
  tcase_add_test(tc, test_lock_on_keeps_the_target_until_its_track_ends);
  tcase_add_test(tc, test_follows_cvtracker);
  tcase_add_test(tc, test_message_fields);
  tcase_add_test(tc, test_bad_settings_give_clear_errors);
  tcase_add_test(tc, test_url_typos_are_never_files);
  tcase_add_test(tc, test_bad_field_of_view_while_running);
  tcase_add_test(tc, test_mavlink_stop_form_on_every_failsafe);
  tcase_add_test(tc, test_text_protocol_over_udp);
  return s;
}

}  // namespace

GST_CHECK_MAIN(robotctl);
