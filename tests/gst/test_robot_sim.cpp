// Closed loop: a simulated robot's camera view goes through appsrc ! colortrack ! robotctl, the commands
// come back over a pseudo-terminal and move the robot. Each frame is pushed, then the test waits for the
// command decided on that frame (robotctl's message carries the frame's timestamp) and reads the bytes from
// the pty, so the loop advances frame by frame whatever the machine's speed.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "gst_test_util.hpp"
#include "robot_sim.hpp"

#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>
#include <gst/video/video.h>

namespace {

using colortrack::gst_test_util::bgrBuffer;
using colortrack::gst_test_util::kFps;
using colortrack::gst_test_util::waitForCommandOf;
using colortrack::robot_sim::CommandDecoder;
using colortrack::robot_sim::Pose;
using colortrack::robot_sim::RobotSim;
using colortrack::robot_sim::RobotSimConfig;
using colortrack::robot_sim::WheelCommand;

constexpr double kSetPoint = 0.3;
constexpr guint kLostTimeoutMs = 500;

struct Pty {
  int master = -1;
  std::string slave;
  Pty() {
    master = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
    fail_unless(master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0);
    slave = ptsname(master);
  }
  ~Pty() { close(master); }
  std::vector<std::uint8_t> drain() const {
    std::vector<std::uint8_t> bytes;
    std::uint8_t chunk[4096];
    ssize_t n;
    while ((n = read(master, chunk, sizeof chunk)) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
    return bytes;
  }
};

struct LoopResult {
  int centredAt = -1;      // first frame of kHold consecutive frames centred at the set-point
  double finalOffset = 0;  // |offset| / width at the end
  double finalSize = 0;    // ball height / frame height at the end
  int stopAfterHide = -1;  // frames from hiding the ball to the first stop received
  int commandsBeforeHide = 0, movingBeforeHide = 0;
  int rejected = 0;
};

// Runs the loop. `controller`: robotctl's controller; hideAt: frame at which the ball disappears (-1: never).
LoopResult runLoop(const char *controller, const char *protocol, CommandDecoder::Protocol decoding,
                   int maxFrames, int hideAt) {
  constexpr int kHold = 10;
  RobotSimConfig config;
  // The ball 3 m ahead, 12 degrees to the right: off-centre and far (its height 0.115 of the frame).
  const double bearing = -12 * CV_PI / 180;
  config.ball = cv::Point2d(3.0 * std::cos(bearing), 3.0 * std::sin(bearing));
  RobotSim robot(config, Pose{});
  // The firmware's zone speeds match robotctl's max-linear / max-angular.
  const double maxLinear = 0.5, maxAngular = 0.15;
  CommandDecoder decoder(decoding, maxLinear, maxAngular, 255);

  Pty pty;
  const cv::Rect2d first = robot.ballBox();
  char launch[1024];
  std::snprintf(
      launch, sizeof launch,
      "appsrc name=src format=time caps=video/x-raw,format=BGR,width=%d,height=%d,framerate=%d/1 ! "
      "colortrack init-box=%d,%d,%d,%d draw=0 ! "
      "robotctl name=ctl location=%s sync=false post-messages=true rate=200 controller=%s protocol=%s "
      "set-point=%g max-linear=%g max-angular=%g lost-timeout=%u",
      config.frameSize.width, config.frameSize.height, kFps, cvRound(first.x), cvRound(first.y),
      cvRound(first.width), cvRound(first.height), pty.slave.c_str(), controller, protocol, kSetPoint,
      maxLinear, maxAngular, kLostTimeoutMs);
  GError *error = nullptr;
  GstElement *pipeline = gst_parse_launch(launch, &error);
  fail_unless(pipeline != nullptr, "%s", error ? error->message : "");
  GstElement *src = gst_bin_get_by_name(GST_BIN(pipeline), "src");
  GstBus *bus = gst_element_get_bus(pipeline);
  fail_unless(gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE);

  LoopResult result;
  WheelCommand command;  // what the robot does: the last command it received
  int consecutive = 0;
  const double dt = 1.0 / kFps;
  const cv::Size frame = config.frameSize;
  for (int i = 0; i < maxFrames; ++i) {
    if (i == hideAt) robot.setBallHidden(true);
    fail_unless(gst_app_src_push_buffer(GST_APP_SRC(src), bgrBuffer(robot.render(), i)) == GST_FLOW_OK);
    waitForCommandOf(bus, gst_util_uint64_scale_int(i, GST_SECOND, kFps));
    const std::vector<std::uint8_t> bytes = pty.drain();
    const std::vector<WheelCommand> received = decoder.feed(bytes.data(), bytes.size());
    fail_if(received.empty(), "frame %d: nothing on the pty", i);
    command = received.back();
    robot.drive(command.left, command.right, dt);

    if (hideAt >= 0) {
      if (i < hideAt) {
        ++result.commandsBeforeHide;
        result.movingBeforeHide += !command.stop();
      } else if (result.stopAfterHide < 0 && command.stop()) {
        result.stopAfterHide = i - hideAt;
        break;
      }
      continue;
    }
    const cv::Rect2d box = robot.ballBox();
    fail_if(box.empty(), "frame %d: the ball left the view", i);
    result.finalOffset = std::abs(box.x + box.width / 2 - frame.width / 2.0) / frame.width;
    result.finalSize = box.height / frame.height;
    const bool centred = result.finalOffset <= 0.10 && std::abs(result.finalSize / kSetPoint - 1) <= 0.15;
    consecutive = centred ? consecutive + 1 : 0;
    if (consecutive == kHold) {
      result.centredAt = i - kHold + 1;
      break;
    }
  }
  result.rejected = decoder.rejected();
  gst_app_src_end_of_stream(GST_APP_SRC(src));
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(src);
  gst_object_unref(pipeline);
  return result;
}

GST_START_TEST(test_zone_controller_centres_the_ball) {
  const LoopResult r = runLoop("zone", "zone-char", CommandDecoder::Protocol::ZoneChar, 300, -1);
  std::printf("zone: centred from frame %d, offset %.3f of the width, size %.3f (set-point %.2f)\n",
              r.centredAt, r.finalOffset, r.finalSize, kSetPoint);
  fail_unless(r.centredAt >= 0, "not centred within 300 frames (offset %.3f, size %.3f)", r.finalOffset,
              r.finalSize);
  fail_unless_equals_int(r.rejected, 0);
}
GST_END_TEST;

GST_START_TEST(test_proportional_controller_centres_the_ball) {
  const LoopResult r = runLoop("proportional", "binary", CommandDecoder::Protocol::Binary, 300, -1);
  std::printf("proportional: centred from frame %d, offset %.3f of the width, size %.3f (set-point %.2f)\n",
              r.centredAt, r.finalOffset, r.finalSize, kSetPoint);
  fail_unless(r.centredAt >= 0, "not centred within 300 frames (offset %.3f, size %.3f)", r.finalOffset,
              r.finalSize);
  fail_unless_equals_int(r.rejected, 0);
}
GST_END_TEST;

GST_START_TEST(test_hidden_ball_stops_within_lost_timeout) {
  // Hidden while the robot is still on its way: it was moving, and must stop within lost-timeout.
  for (const char *controller : {"zone", "proportional"}) {
    const LoopResult r = runLoop(controller, "text", CommandDecoder::Protocol::Text, 120, 30);
    const int limit = static_cast<int>(std::ceil(kLostTimeoutMs / 1000.0 * kFps));
    std::printf("%s: moving in %d of %d frames before hiding; stop %d frames (%.0f ms) after hiding\n",
                controller, r.movingBeforeHide, r.commandsBeforeHide, r.stopAfterHide,
                r.stopAfterHide * 1000.0 / kFps);
    fail_unless(r.movingBeforeHide > 0);
    fail_unless(r.stopAfterHide >= 0, "%s: no stop after hiding the ball", controller);
    fail_unless(r.stopAfterHide <= limit, "%s: stop after %d frames, lost-timeout is %d frames", controller,
                r.stopAfterHide, limit);
    fail_unless_equals_int(r.rejected, 0);
  }
}
GST_END_TEST;

Suite *robot_sim_suite(void) {
  Suite *s = suite_create("robot_sim");
  TCase *tc = tcase_create("closed-loop");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_zone_controller_centres_the_ball);
  tcase_add_test(tc, test_proportional_controller_centres_the_ball);
  tcase_add_test(tc, test_hidden_ball_stops_within_lost_timeout);
  return s;
}

}  // namespace

GST_CHECK_MAIN(robot_sim);
