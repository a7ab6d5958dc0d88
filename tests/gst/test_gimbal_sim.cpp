// SPDX-License-Identifier: LGPL-2.1-or-later
// Closed loop through MAVLink: a simulated camera on a rate-limited two-axis gimbal (tests/support/
// gimbal_sim.hpp) renders its view, appsrc ! colortrack ! robotctl protocol=mavlink mavlink-mode=gimbal
// sends GIMBAL_MANAGER_SET_PITCHYAW to a UDP socket on loopback, and the test turns the gimbal at the rates
// it reads (decoded with core's parser: the frames' bytes are checked against node-mavlink elsewhere).
//
// Centring: the ball starts 15 degrees off the camera's axis (12 right, 9 up) and must be within 1 degree by
// frame 60 at 30 fps, without latency and with 100 ms of it; vanishing: zero rates soon after the ball
// disappears. The figures are printed (`meson test -C build gst-gimbal-sim -v`).
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/mavlink.hpp"
#include "gimbal_sim.hpp"
#include "gst_test_util.hpp"
#include "udp_receiver.hpp"

#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>

namespace {

using colortrack::gimbal_sim::GimbalSim;
using colortrack::gimbal_sim::GimbalSimConfig;
using colortrack::gst_test_util::bgrBuffer;
using colortrack::gst_test_util::kFps;
using colortrack::gst_test_util::UdpReceiver;
using colortrack::gst_test_util::waitForCommandOf;
namespace mavlink = colortrack::mavlink;

constexpr int kCentreWithin = 60;      // frames
constexpr double kCentred = 1.0;       // degrees
constexpr guint kLostTimeoutMs = 500;  // robotctl's default

struct Rates {
  double pitch = 0, yaw = 0;  // rad/s
};

// The last GIMBAL_MANAGER_SET_PITCHYAW of the datagrams (heartbeats skipped); every frame must parse.
std::optional<Rates> lastRates(const std::vector<colortrack::node_mavlink::Datagram> &datagrams) {
  std::optional<Rates> rates;
  for (const auto &d : datagrams) {
    const std::optional<mavlink::Frame> frame = mavlink::parseFrame(d.bytes.data(), d.bytes.size());
    fail_unless(frame.has_value(), "a datagram that is no valid MAVLink frame");
    if (frame->messageId != mavlink::kGimbalManagerSetPitchyaw.id) continue;
    rates = Rates{mavlink::payloadFloat(frame->payload, 12), mavlink::payloadFloat(frame->payload, 16)};
  }
  return rates;
}

// A gimbal's gains: a turn of 1.0 is tan(hfov/2) rad/s (33 deg/s here); turn-gain 3 centres with a time
// constant of a third of a second. rate=200: every frame's decision is out before the next frame.
constexpr const char *kGimbalGains = "turn-gain=3 max-angular=1 max-angular-accel=20 turn-deadband=0.05";

// appsrc ! colortrack mode=threshold (init-box on the ball) ! robotctl mavlink-mode=gimbal, sending to a UDP
// socket on loopback, around a gimbal whose ball starts 15 degrees off the axis (12 right, 9 up).
struct GimbalLoop {
  UdpReceiver receiver;
  GimbalSimConfig config;
  GimbalSim gimbal;
  GstElement *pipeline = nullptr, *src = nullptr;
  GstBus *bus = nullptr;
  int frame = 0;
  Rates rates;

  static GimbalSimConfig fifteenDegreesOff() {
    GimbalSimConfig c;
    c.targetAzimuth = 12;
    c.targetElevation = 9;
    return c;
  }

  explicit GimbalLoop(const char *gains) : config(fifteenDegreesOff()), gimbal(config) {
    fail_unless(receiver.port() > 0);
    fail_unless(std::abs(gimbal.errorDegrees() - 15) < 0.1);
    const cv::Rect2d first = gimbal.targetBox();
    char launch[1024];
    std::snprintf(
        launch, sizeof launch,
        "appsrc name=src format=time caps=video/x-raw,format=BGR,width=%d,height=%d,framerate=%d/1 ! "
        "colortrack mode=threshold init-box=%d,%d,%d,%d draw=0 ! "
        "robotctl name=ctl location=%s sync=false post-messages=true rate=200 protocol=mavlink "
        "mavlink-mode=gimbal hfov=%g lost-timeout=%u %s",
        config.frameSize.width, config.frameSize.height, kFps, cvRound(first.x), cvRound(first.y),
        cvRound(first.width), cvRound(first.height), receiver.location().c_str(), config.horizontalFovDegrees,
        kLostTimeoutMs, gains);
    GError *error = nullptr;
    pipeline = gst_parse_launch(launch, &error);
    fail_unless(pipeline != nullptr, "%s", error ? error->message : "");
    src = gst_bin_get_by_name(GST_BIN(pipeline), "src");
    bus = gst_element_get_bus(pipeline);
    fail_unless(gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE);
  }
  ~GimbalLoop() {
    gst_element_set_state(pipeline, GST_STATE_NULL);
    gst_object_unref(bus);
    gst_object_unref(src);
    gst_object_unref(pipeline);
  }

  // One frame pushed, the command decided on it read back.
  Rates step() {
    fail_unless(gst_app_src_push_buffer(GST_APP_SRC(src), bgrBuffer(gimbal.render(), frame)) == GST_FLOW_OK);
    waitForCommandOf(bus, gst_util_uint64_scale_int(frame, GST_SECOND, kFps));
    const std::optional<Rates> received = lastRates(receiver.drain());
    fail_unless(received.has_value(), "frame %d: no GIMBAL_MANAGER_SET_PITCHYAW", frame);
    ++frame;
    return *received;
  }
};

struct Centring {
  int centredAt = -1;  // the frame from which the error stays under kCentred
  int overshoots = 0;  // times the yaw or the pitch error changed sign by more than kCentred / 2
  double finalError = 0;
};

// Frame by frame (each pushed, then the test waits for the command decided on it, so the loop does not depend
// on the machine's speed) for `frames` frames; a command reaches the motors `latency` frames after the frame
// it was decided on.
Centring centre(GimbalLoop &loop, int frames, int latency) {
  const double dt = 1.0 / kFps;
  std::vector<Rates> queue(latency);  // commands on their way, oldest first
  Centring c;
  int lastSign[2] = {0, 0};  // yaw, pitch
  for (int i = 0; i < frames; ++i) {
    queue.push_back(loop.step());
    loop.rates = queue.front();
    queue.erase(queue.begin());
    loop.gimbal.turn(loop.rates.pitch, loop.rates.yaw, dt);
    const double error = loop.gimbal.errorDegrees();
    // Yaw error's sign: the ball's azimuth left in camera terms (12 degrees right at the start).
    // Each axis's error: the ball is 12 degrees right and 9 up of the start.
    const double axisError[2] = {12 - loop.gimbal.yawDegrees(), 9 - loop.gimbal.pitchDegrees()};
    for (int a = 0; a < 2; ++a) {
      const int sign = axisError[a] > kCentred / 2 ? 1 : axisError[a] < -kCentred / 2 ? -1 : 0;
      if (sign != 0 && lastSign[a] != 0 && sign != lastSign[a]) ++c.overshoots;
      if (sign != 0) lastSign[a] = sign;
    }
    if (i % 10 == 0)
      std::printf("frame %2d: error %.2f deg (yaw %.2f, pitch %.2f), rates pitch %+.3f yaw %+.3f rad/s\n", i,
                  error, loop.gimbal.yawDegrees(), loop.gimbal.pitchDegrees(), loop.rates.pitch,
                  loop.rates.yaw);
    if (error < kCentred && c.centredAt < 0) c.centredAt = i;
    if (error >= kCentred) c.centredAt = -1;  // must stay centred
  }
  c.finalError = loop.gimbal.errorDegrees();
  return c;
}

// Centring: within 1 degree by frame 60 at 30 fps, and stays there. Vanishing: then in real time, the ball
// drifts right at 5 deg/s for a second (the gimbal follows it: rates not zero), disappears, and zero rates
// must arrive at once (within 150 ms: an unconfirmed target's turn is not held).
GST_START_TEST(test_gimbal_centres_the_target_and_stops_when_it_vanishes) {
  GimbalLoop loop(kGimbalGains);
  const Centring c = centre(loop, kCentreWithin + 30, 0);
  std::printf("centred (< %.0f degree) from frame %d on; final error %.2f degrees\n", kCentred, c.centredAt,
              c.finalError);
  fail_unless(c.centredAt >= 0 && c.centredAt <= kCentreWithin, "centred from frame %d", c.centredAt);

  // Following a drifting ball, then vanishing, in real time.
  const double dt = 1.0 / kFps;
  constexpr int kDriftFrames = kFps;
  loop.gimbal.setTargetAzimuthRate(5);
  const double start = UdpReceiver::now();
  double hiddenAt = 0, stoppedAfter = -1;
  Rates atLoss;
  for (int i = 0; i < kDriftFrames + 40 && stoppedAfter < 0; ++i, ++loop.frame) {
    if (i == kDriftFrames) {
      loop.gimbal.setTargetHidden(true);
      hiddenAt = UdpReceiver::now();
      atLoss = loop.rates;
    }
    fail_unless(gst_app_src_push_buffer(GST_APP_SRC(loop.src), bgrBuffer(loop.gimbal.render(), loop.frame)) ==
                GST_FLOW_OK);
    while (UdpReceiver::now() - start < (i + 1.0) * dt && stoppedAfter < 0) {
      for (const auto &d : loop.receiver.drain()) {
        const std::optional<Rates> r = lastRates({d});
        if (!r) continue;
        loop.rates = *r;
        if (i >= kDriftFrames && r->pitch == 0 && r->yaw == 0) {
          stoppedAfter = d.time - hiddenAt;
          break;
        }
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    loop.gimbal.turn(loop.rates.pitch, loop.rates.yaw, dt);
    loop.gimbal.moveTarget(dt);
  }
  std::printf(
      "following at 5 deg/s: yaw rate %.3f rad/s when the target vanished; zero rates %.0f ms later "
      "(lost-timeout %u ms)\n",
      atLoss.yaw, stoppedAfter * 1000, kLostTimeoutMs);
  fail_unless(atLoss.yaw > 0.03, "not following the drifting target: yaw rate %.3f rad/s", atLoss.yaw);
  // An unconfirmed target's turn is not held: zero rates on the first frame without the ball (33 ms), well
  // before lost-timeout (holding the turn, as before issue 25, stopped after about 470 ms).
  fail_unless(stoppedAfter >= 0 && stoppedAfter < 0.15, "stopped after %.3f s", stoppedAfter);
}
GST_END_TEST;

// Issue 25: with 100 ms between the frame and the motors (3 frames), the ball 15 degrees off is centred
// within 60 frames with at most one overshoot, with the gimbal's gains above and with robotctl's defaults
// (measured 2026-12-02: frame 21 and frame 48, no overshoot).
GST_START_TEST(test_gimbal_centres_under_latency) {
  for (const char *gains : {kGimbalGains, ""}) {
    GimbalLoop loop(gains);
    const Centring c = centre(loop, kCentreWithin + 30, 3);
    std::printf("100 ms latency, %s: centred from frame %d on, %d overshoot(s), final error %.2f degrees\n",
                *gains ? gains : "robotctl's defaults", c.centredAt, c.overshoots, c.finalError);
    fail_unless(c.centredAt >= 0 && c.centredAt <= kCentreWithin, "%s: centred from frame %d", gains,
                c.centredAt);
    fail_unless(c.overshoots <= 1, "%s: %d overshoots", gains, c.overshoots);
  }
}
GST_END_TEST;

Suite *gimbal_sim_suite(void) {
  Suite *s = suite_create("gimbal-sim");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_gimbal_centres_the_target_and_stops_when_it_vanishes);
  tcase_add_test(tc, test_gimbal_centres_under_latency);
  return s;
}

}  // namespace

GST_CHECK_MAIN(gimbal_sim);
