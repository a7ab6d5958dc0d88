// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl protocol=mavlink over UDP on loopback, in a running pipeline (appsrc ! colortrack ! robotctl):
// the stream captured and decoded field by field by node-mavlink (tests/support/node_mavlink.hpp), an
// implementation independent of ours: every CRC valid, sequence numbers consecutive, our ids, heartbeats at
// 1 Hz +- 10 %, rates and velocities with the right signs while the target is off centre, and the stop form
// once it is lost and at the end. Skipped (77) without node-mavlink.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "gimbal_sim.hpp"
#include "gst_test_util.hpp"
#include "node_mavlink.hpp"
#include "udp_receiver.hpp"

#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>

namespace {

using colortrack::gimbal_sim::GimbalSim;
using colortrack::gimbal_sim::GimbalSimConfig;
using colortrack::gst_test_util::bgrBuffer;
using colortrack::gst_test_util::kFps;
using colortrack::gst_test_util::UdpReceiver;
using colortrack::node_mavlink::Datagram;
using nlohmann::json;

constexpr double kLostTimeout = 0.5;  // robotctl's default, s

// One decoded frame, with when it arrived relative to the first frame pushed.
struct Frame {
  double time = 0;
  json message;
};

// What a "robotctl" bus message said was sent: pitch-rate (gimbal) or vx (follow), and yaw-rate.
struct Posted {
  double first = 0, yawRate = 0;
};

// A "robotctl" bus message read as Posted; it may not carry wheel speeds (MAVLink sends none).
void readPosted(GstMessage *m, const char *firstField, std::vector<Posted> &posted) {
  const GstStructure *s = gst_message_get_structure(m);
  if (!gst_structure_has_name(s, "robotctl")) return;
  fail_if(gst_structure_has_field(s, "left") || gst_structure_has_field(s, "right"),
          "wheel speeds in a MAVLink message: %" GST_PTR_FORMAT, s);
  Posted p;
  fail_unless(gst_structure_get_double(s, firstField, &p.first) &&
                  gst_structure_get_double(s, "yaw-rate", &p.yawRate),
              "%" GST_PTR_FORMAT, s);
  posted.push_back(p);
}

// Runs the pipeline in real time: `visibleFrames` frames with the ball off centre (right of and above the
// centre: 10 degrees right, 6 up), then `hiddenFrames` without it, then EOS; returns what node-mavlink read
// from the datagrams, and the time the ball vanished (s after the first frame). With `posted`, also what the
// bus messages said was sent (post-messages=true; `firstField` pitch-rate or vx).
std::vector<Frame> capture(const std::string &properties, int visibleFrames, int hiddenFrames,
                           double &hiddenAt, std::vector<Posted> *posted = nullptr,
                           const char *firstField = nullptr) {
  UdpReceiver receiver;
  fail_unless(receiver.port() > 0);
  GimbalSimConfig config;
  config.targetAzimuth = 10;
  config.targetElevation = 6;
  GimbalSim sim(config);
  const cv::Rect2d first = sim.targetBox();
  char launch[1024];
  std::snprintf(launch, sizeof launch,
                "appsrc name=src format=time caps=video/x-raw,format=BGR,width=320,height=240,framerate=%d/1 "
                "! colortrack mode=threshold init-box=%d,%d,%d,%d draw=0 ! robotctl location=%s sync=false "
                "protocol=mavlink %s",
                kFps, cvRound(first.x), cvRound(first.y), cvRound(first.width), cvRound(first.height),
                receiver.location().c_str(), properties.c_str());
  GError *error = nullptr;
  GstElement *pipeline = gst_parse_launch(launch, &error);
  fail_unless(pipeline != nullptr, "%s", error ? error->message : "");
  GstElement *src = gst_bin_get_by_name(GST_BIN(pipeline), "src");
  fail_unless(gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE);

  std::vector<Datagram> datagrams;
  const auto take = [&] {
    for (Datagram &d : receiver.drain()) datagrams.push_back(std::move(d));
  };
  const double start = UdpReceiver::now();
  for (int i = 0; i < visibleFrames + hiddenFrames; ++i) {
    if (i == visibleFrames) {
      sim.setTargetHidden(true);
      hiddenAt = UdpReceiver::now() - start;
    }
    fail_unless(gst_app_src_push_buffer(GST_APP_SRC(src), bgrBuffer(sim.render(), i)) == GST_FLOW_OK);
    // Real time, taking the datagrams as they come (their times are the heartbeats' periods).
    while (UdpReceiver::now() - start < (i + 1.0) / kFps) {
      take();
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  gst_app_src_end_of_stream(GST_APP_SRC(src));
  GstBus *bus = gst_element_get_bus(pipeline);
  GstMessage *eos = nullptr;
  while (GstMessage *m = gst_bus_timed_pop_filtered(
             bus, 10 * GST_SECOND,
             static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR | GST_MESSAGE_ELEMENT))) {
    if (GST_MESSAGE_TYPE(m) != GST_MESSAGE_ELEMENT) {
      eos = m;
      break;
    }
    if (posted) readPosted(m, firstField, *posted);
    gst_message_unref(m);
  }
  fail_unless(eos != nullptr && GST_MESSAGE_TYPE(eos) == GST_MESSAGE_EOS, "no EOS");
  gst_message_unref(eos);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  take();
  gst_element_set_state(pipeline, GST_STATE_NULL);  // a last stop as the port closes
  take();
  gst_object_unref(bus);
  gst_object_unref(src);
  gst_object_unref(pipeline);

  std::vector<Frame> frames;
  for (const std::string &line : colortrack::node_mavlink::decode(datagrams)) {
    const json message = json::parse(line);
    fail_if(message.contains("garbage"), "bytes that are no MAVLink frame: %s", line.c_str());
    frames.push_back({message["time"].get<double>() - start, message});
  }
  fail_unless(frames.size() >= datagrams.size(), "node-mavlink read %zu frames from %zu datagrams",
              frames.size(), datagrams.size());
  return frames;
}

// What every frame of a stream must be: a valid CRC, our ids, the next sequence number.
void checkFraming(const std::vector<Frame> &frames) {
  fail_unless(frames.size() > 10, "only %zu frames", frames.size());
  int previous = -1;
  for (const Frame &f : frames) {
    const json &m = f.message;
    fail_unless(m["crcValid"].get<bool>(), "bad CRC: %s", m.dump().c_str());
    fail_unless_equals_int(m["sysid"].get<int>(), 1);
    fail_unless_equals_int(m["compid"].get<int>(), 191);
    const int seq = m["seq"].get<int>();
    if (previous >= 0) fail_unless_equals_int(seq, (previous + 1) % 256);
    previous = seq;
  }
}

// The heartbeats: HEARTBEAT of an onboard controller, once a second (+- 10 %).
void checkHeartbeats(const std::vector<Frame> &frames, int atLeast) {
  std::vector<double> times;
  for (const Frame &f : frames) {
    if (f.message["msgid"] != 0) continue;
    fail_unless_equals_int(f.message["fields"]["type"].get<int>(), 18);      // MAV_TYPE_ONBOARD_CONTROLLER
    fail_unless_equals_int(f.message["fields"]["autopilot"].get<int>(), 8);  // MAV_AUTOPILOT_INVALID
    fail_unless_equals_int(f.message["fields"]["mavlinkVersion"].get<int>(), 3);
    times.push_back(f.time);
  }
  fail_unless(static_cast<int>(times.size()) >= atLeast, "%zu heartbeats", times.size());
  for (std::size_t i = 1; i < times.size(); ++i) {
    const double period = times[i] - times[i - 1];
    std::printf("heartbeat period %.3f s\n", period);
    fail_unless(period > 0.9 && period < 1.1, "heartbeat period %.3f s", period);
  }
}

double number(const json &fields, const char *name) {
  const json &v = fields[name];
  return v.is_string() ? std::nan("") : v.get<double>();
}

// Each bus message says what went out: its pair of values is that of a frame of message `msgid` (as floats,
// exactly), with MAVLink's signs (the ball right of centre: yaw rate > 0 in both).
void checkPosted(const std::vector<Frame> &frames, const std::vector<Posted> &posted, int msgid,
                 const char *firstField) {
  int turningRight = 0;
  for (const Posted &p : posted) {
    const bool sent = std::any_of(frames.begin(), frames.end(), [&](const Frame &f) {
      return f.message["msgid"] == msgid &&
             static_cast<float>(number(f.message["fields"], firstField)) == static_cast<float>(p.first) &&
             static_cast<float>(number(f.message["fields"], "yawRate")) == static_cast<float>(p.yawRate);
    });
    fail_unless(sent, "posted %s %g, yaw-rate %g: no such frame was sent", firstField, p.first, p.yawRate);
    turningRight += p.yawRate > 0;
  }
  std::printf("%zu commands posted, %d turning right\n", posted.size(), turningRight);
  fail_unless(turningRight > 10);
}

GST_START_TEST(test_gimbal_stream_over_udp) {
  double hiddenAt = 0;
  // 2.4 s with the ball, 1.2 s without: three heartbeats at least, and the lost-target stop.
  std::vector<Posted> posted;
  const std::vector<Frame> frames =
      capture("mavlink-mode=gimbal rate=20 post-messages=true", 72, 36, hiddenAt, &posted, "pitch-rate");
  checkFraming(frames);
  checkHeartbeats(frames, 3);
  checkPosted(frames, posted, 287, "pitchRate");
  int turning = 0, stopsAfterLoss = 0;
  double firstStop = -1;
  for (const Frame &f : frames) {
    if (f.message["msgid"] != 287) continue;
    const json &fields = f.message["fields"];
    fail_unless_equals_int(fields["targetSystem"].get<int>(), 1);
    fail_unless_equals_int(fields["targetComponent"].get<int>(), 1);
    fail_unless(fields["pitch"] == "NaN" && fields["yaw"] == "NaN", "%s", fields.dump().c_str());
    const double pitchRate = number(fields, "pitchRate"), yawRate = number(fields, "yawRate");
    if (f.time > 0.5 && f.time < hiddenAt) {
      // The ball right of and above the centre: turn right (yaw rate > 0) and up (pitch rate > 0).
      fail_unless(yawRate > 0 && pitchRate > 0, "at %.3f s: pitch rate %g, yaw rate %g", f.time, pitchRate,
                  yawRate);
      ++turning;
    }
    if (f.time > hiddenAt && pitchRate == 0 && yawRate == 0) {
      if (firstStop < 0) firstStop = f.time;
      ++stopsAfterLoss;
    } else if (firstStop >= 0) {
      fail("a moving command after the stop at %.3f s: %s", f.time, fields.dump().c_str());
    }
  }
  std::printf("gimbal: %zu frames, %d turning, stop %.0f ms after the ball vanished\n", frames.size(),
              turning, (firstStop - hiddenAt) * 1000);
  fail_unless(turning > 20);
  fail_unless(firstStop > 0 && firstStop - hiddenAt < kLostTimeout + 0.1, "stop %.3f s after the loss",
              firstStop - hiddenAt);
  fail_unless(stopsAfterLoss > 3);
  const json &last = frames.back().message;
  fail_unless(last["msgid"] == 287 && number(last["fields"], "yawRate") == 0, "last: %s",
              last.dump().c_str());
}
GST_END_TEST;

GST_START_TEST(test_follow_stream_over_udp) {
  double hiddenAt = 0;
  std::vector<Posted> posted;
  const std::vector<Frame> frames =
      capture("mavlink-mode=follow controller=proportional rate=20 post-messages=true", 45, 24, hiddenAt,
              &posted, "vx");
  checkFraming(frames);
  checkHeartbeats(frames, 2);
  checkPosted(frames, posted, 84, "vx");
  int moving = 0;
  double firstStop = -1;
  for (const Frame &f : frames) {
    if (f.message["msgid"] != 84) continue;
    const json &fields = f.message["fields"];
    fail_unless_equals_int(fields["typeMask"].get<int>(), 1479);      // velocity and yaw rate
    fail_unless_equals_int(fields["coordinateFrame"].get<int>(), 9);  // MAV_FRAME_BODY_OFFSET_NED
    // vy and vz are used, at zero: no sideways motion, altitude held.
    for (const char *unused : {"x", "y", "z", "vy", "vz", "afx", "afy", "afz", "yaw"})
      fail_unless(number(fields, unused) == 0, "%s: %s", unused, fields.dump().c_str());
    const double vx = number(fields, "vx"), yawRate = number(fields, "yawRate");
    if (f.time > 0.5 && f.time < hiddenAt) {
      // The ball right of centre and small (far): forward, turning right.
      fail_unless(vx > 0 && yawRate > 0, "at %.3f s: vx %g, yaw rate %g", f.time, vx, yawRate);
      ++moving;
    }
    if (f.time > hiddenAt && vx == 0 && yawRate == 0 && firstStop < 0) firstStop = f.time;
  }
  std::printf("follow: %zu frames, %d moving, stop %.0f ms after the ball vanished\n", frames.size(), moving,
              (firstStop - hiddenAt) * 1000);
  fail_unless(moving > 10);
  fail_unless(firstStop > 0 && firstStop - hiddenAt < kLostTimeout + 0.1);
}
GST_END_TEST;

Suite *robotctl_mavlink_suite(void) {
  Suite *s = suite_create("robotctl-mavlink");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_gimbal_stream_over_udp);
  tcase_add_test(tc, test_follow_stream_over_udp);
  return s;
}

}  // namespace

// GST_CHECK_MAIN, but "skipped" (77) without node-mavlink.
int main(int argc, char **argv) {
  gst_check_init(&argc, &argv);
  std::string why;
  if (!colortrack::node_mavlink::available(why)) {
    std::printf("skipped: %s\n", why.c_str());
    return colortrack::node_mavlink::kSkip;
  }
  return gst_check_run_suite(robotctl_mavlink_suite(), "robotctl_mavlink", __FILE__);
}
