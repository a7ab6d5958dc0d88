// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl over UDP when the peer goes away and comes back (a flight controller or robot restarting): the
// connected socket sees the ICMP "port unreachable", robotctl warns once (not at every retry), and the first
// datagram the peer hears when it is back is stop, as over a serial link. With MAVLink, a vehicle whose
// heartbeats stop (its radio link drops, its port stays open) is sent only stop until they are back.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <thread>

#include "colortrack/mavlink.hpp"
#include "gst_test_util.hpp"
#include "udp_receiver.hpp"

#include <gst/check/gstcheck.h>

namespace {

using colortrack::gst_test_util::UdpReceiver;
using Clock = std::chrono::steady_clock;

// The first datagram within `seconds`, or "".
std::string firstDatagram(UdpReceiver &receiver, double seconds) {
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

// A flight controller on loopback: answers robotctl with its heartbeat (system 1) while `beating`, and
// keeps the yaw rates of the gimbal commands it hears, with the time each came.
struct Vehicle {
  UdpReceiver socket;
  bool beating = true;
  struct Heard {
    double time;
    float yawRate;
  };
  std::vector<Heard> heard;
  std::vector<std::string> warnings, infos;

  // Runs for `seconds`: every 50 ms takes what came, answers, and reads `bus`.
  void run(GstBus *bus, double seconds) {
    const auto until = Clock::now() + std::chrono::duration<double>(seconds);
    colortrack::mavlink::Sender self{1, 1, 0};
    while (Clock::now() < until) {
      for (const auto &d : socket.drain())
        for (const auto &f : colortrack::mavlink::parseFrames(d.bytes.data(), d.bytes.size()))
          if (f.messageId == colortrack::mavlink::kGimbalManagerSetPitchyaw.id)
            heard.push_back({d.time, colortrack::mavlink::payloadFloat(f.payload, 16)});
      if (beating) socket.reply(colortrack::mavlink::encode(colortrack::mavlink::Heartbeat(), self));
      while (GstMessage *m =
                 gst_bus_pop_filtered(bus, GstMessageType(GST_MESSAGE_WARNING | GST_MESSAGE_INFO))) {
        GError *error = nullptr;
        if (GST_MESSAGE_TYPE(m) == GST_MESSAGE_WARNING)
          gst_message_parse_warning(m, &error, nullptr);
        else
          gst_message_parse_info(m, &error, nullptr);
        std::printf("%s: %s\n", GST_MESSAGE_TYPE_NAME(m), error->message);
        (GST_MESSAGE_TYPE(m) == GST_MESSAGE_WARNING ? warnings : infos).push_back(error->message);
        g_error_free(error);
        gst_message_unref(m);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  // The moving commands heard after `from` (s, steady clock).
  int turnsAfter(double from) const {
    int count = 0;
    for (const Heard &h : heard) count += h.time > from && h.yawRate != 0;
    return count;
  }
};

}  // namespace

// The vehicle's heartbeats stop for 1.5 s with its port open: one warning naming the heartbeat, nothing
// but stop from link-timeout on, then "Reconnected" and the turn again once they are back.
GST_START_TEST(test_mavlink_vehicle_silent_hears_only_stop) {
  Vehicle vehicle;
  fail_unless(vehicle.socket.port() > 0);
  const std::string launch =
      "videotestsrc is-live=true ! video/x-raw,width=320,height=240,framerate=30/1 ! "
      "colortrack init-box=250,20,30,60 draw=0 ! robotctl protocol=mavlink rate=20 lost-timeout=10000 "
      "link-timeout=400 location=" +
      vehicle.socket.location();
  GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(pipeline != nullptr);
  GstBus *bus = gst_element_get_bus(pipeline);
  fail_unless(gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE);
  vehicle.run(bus, 1.5);
  fail_unless(vehicle.turnsAfter(0) > 0, "the gimbal was never turned");

  vehicle.beating = false;
  const double silentFrom = UdpReceiver::now();
  vehicle.run(bus, 1.5);
  fail_unless_equals_int(static_cast<int>(vehicle.warnings.size()), 1);
  fail_unless(vehicle.warnings[0].find("no HEARTBEAT from system 1") != std::string::npos);
  // Its last heartbeat may be 50 ms older than the silence; a turn already on its way may land 100 ms late.
  fail_unless_equals_int(vehicle.turnsAfter(silentFrom + 0.4 + 0.15), 0);

  vehicle.beating = true;
  const double backFrom = UdpReceiver::now();
  vehicle.run(bus, 1.0);
  fail_unless(vehicle.turnsAfter(backFrom) > 0, "the turn did not come back with the heartbeats");
  fail_unless_equals_int(static_cast<int>(vehicle.warnings.size()), 1);
  int reconnected = 0;
  for (const std::string &info : vehicle.infos) reconnected += info.rfind("Reconnected", 0) == 0;
  fail_unless_equals_int(reconnected, 1);

  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(pipeline);
}
GST_END_TEST;

// A receiver on a port below the kernel's ephemeral range (32768 and up by default): the other tests'
// sockets, bound to port 0, never take it, so the peer finds it free when it comes back (with an ephemeral
// port, a test running beside this one took it in between once).
std::unique_ptr<UdpReceiver> receiverBelowEphemeralPorts() {
  std::mt19937 rng(std::random_device{}());
  for (int attempt = 0; attempt < 50; ++attempt) {
    auto receiver = std::make_unique<UdpReceiver>(20000 + static_cast<int>(rng() % 10000));
    if (receiver->port() > 0) return receiver;
  }
  return std::make_unique<UdpReceiver>();
}

GST_START_TEST(test_udp_peer_back_hears_stop_first) {
  auto peer = receiverBelowEphemeralPorts();
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
  tcase_add_test(tc, test_mavlink_vehicle_silent_hears_only_stop);
  return s;
}

GST_CHECK_MAIN(robotctl_udp_link);
