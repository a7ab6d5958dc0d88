// robotctl over UDP when the peer goes away and comes back (a flight controller or robot restarting): the
// connected socket sees the ICMP "port unreachable", robotctl warns once (not at every retry), and the first
// datagram the peer hears when it is back is stop, as over a serial link.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>

#include "gst_test_util.hpp"
#include "udp_receiver.hpp"

#include <gst/check/gstcheck.h>

namespace {

using colortrack::gst_test_util::UdpReceiver;
using Clock = std::chrono::steady_clock;

// The first datagram within `seconds`, or "".
std::string firstDatagram(const UdpReceiver &receiver, double seconds) {
  const auto until = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < until) {
    const auto datagrams = receiver.drain();
    if (!datagrams.empty()) return std::string(datagrams[0].bytes.begin(), datagrams[0].bytes.end());
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  return "";
}

// Warnings on `bus` within `seconds` whose text holds `part`.
int warningsWith(GstBus *bus, const std::string &part, double seconds) {
  int count = 0;
  const auto until = Clock::now() + std::chrono::duration<double>(seconds);
  while (Clock::now() < until) {
    GstMessage *m = gst_bus_timed_pop_filtered(bus, GST_MSECOND * 20, GST_MESSAGE_WARNING);
    if (!m) continue;
    GError *error = nullptr;
    gst_message_parse_warning(m, &error, nullptr);
    std::printf("warning: %s\n", error->message);
    count += std::string(error->message).find(part) != std::string::npos;
    g_error_free(error);
    gst_message_unref(m);
  }
  return count;
}

}  // namespace

GST_START_TEST(test_udp_peer_back_hears_stop_first) {
  auto peer = std::make_unique<UdpReceiver>();
  const int port = peer->port();
  fail_unless(port > 0);
  // A still colour-bar frame with the target box right of centre: the zone controller turns right ('R').
  const std::string launch =
      "videotestsrc is-live=true ! video/x-raw,width=320,height=240,framerate=30/1 ! "
      "colortrack init-box=250,20,30,60 draw=0 ! robotctl protocol=zone-char rate=50 lost-timeout=10000 "
      "location=" +
      peer->location();
  GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(pipeline != nullptr);
  GstBus *bus = gst_element_get_bus(pipeline);
  fail_unless(gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE);
  std::string command;
  for (auto until = Clock::now() + std::chrono::seconds(5); command != "R" && Clock::now() < until;)
    command = firstDatagram(*peer, 0.1);
  fail_unless_equals_string(command.c_str(), "R");

  peer.reset();  // the peer goes away: its port answers with ICMP port unreachable
  fail_unless(warningsWith(bus, "Lost the connection", 1.5) == 1, "not one warning when the peer went away");
  fail_unless(warningsWith(bus, "Lost the connection", 1.0) == 0, "a warning at every retry");

  peer = std::make_unique<UdpReceiver>(port);  // back on the same port
  fail_unless(peer->port() == port);
  const std::string heard = firstDatagram(*peer, 4.0);
  std::printf("back: first datagram %s\n", heard.c_str());
  fail_unless_equals_string(heard.c_str(), "S");  // stop first, although the decision is right
  command.clear();
  for (auto until = Clock::now() + std::chrono::seconds(2); command != "R" && Clock::now() < until;)
    command = firstDatagram(*peer, 0.1);
  fail_unless_equals_string(command.c_str(), "R");

  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(pipeline);
}
GST_END_TEST;

static Suite *robotctl_udp_link_suite(void) {
  colortrack::gst_test_util::preloadPlugins({"colortrack", "videotestsrc"});
  Suite *s = suite_create("robotctl_udp_link");
  TCase *tc = tcase_create("link");
  tcase_set_timeout(tc, 60);
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_udp_peer_back_hears_stop_first);
  return s;
}

GST_CHECK_MAIN(robotctl_udp_link);
