// SPDX-License-Identifier: LGPL-2.1-or-later
// The closed loop of the robot simulations (test_robot_sim*.cpp): a simulated robot's camera view goes
// through appsrc ! colortrack ! robotctl, the commands come back over a pseudo-terminal and move the robot.
// Each frame is pushed, then the loop waits for the command decided on that frame (robotctl's message
// carries the frame's timestamp) and reads the bytes from the pty, so the loop advances frame by frame
// whatever the machine's speed.
#pragma once

// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <fcntl.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "gst_test_util.hpp"
#include "robot_sim.hpp"

#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>

#include "pty.hpp"
#include <gst/video/video.h>

namespace colortrack::robot_loop {

using colortrack::gst_test_util::bgrBuffer;
using colortrack::gst_test_util::colortrackRois;
using colortrack::gst_test_util::kFps;
using colortrack::gst_test_util::waitForCommandOf;
using colortrack::robot_sim::Backdrop;
using colortrack::robot_sim::CommandDecoder;
using colortrack::robot_sim::Pose;
using colortrack::robot_sim::RobotSim;
using colortrack::robot_sim::RobotSimConfig;
using colortrack::robot_sim::WheelCommand;

inline constexpr double kSetPoint = 0.3;      // robotctl's default
inline constexpr guint kLostTimeoutMs = 500;  // robotctl's default
inline constexpr double kMaxLinear = 0.5;     // robotctl's default max-linear: the firmware's F / B speed
inline constexpr double kMaxAngular = 0.3;    // robotctl's default max-angular: the firmware's L / R speed
inline constexpr int kLatencyFrames = 3;      // 100 ms at 30 fps
inline constexpr double kDeg = CV_PI / 180;

using colortrack::gst_test_util::Pty;

struct Scenario {
  const char *controller = "zone";
  const char *protocol = "zone-char";
  CommandDecoder::Protocol decoding = CommandDecoder::Protocol::ZoneChar;
  double distance = 2.0;           // m, ball from the robot at the start
  double bearing = 0;              // rad, > 0 left of the robot's heading
  cv::Point2d ballVelocity{0, 0};  // m/s, world frame (the robot starts facing +x)
  int latency = 0;                 // frames between a command's arrival and the wheels
  int frames = 210;
  int hideAt = -1;  // frame at which the ball disappears (-1: never)
  // Frame from which the camera shows another place (-1: never): the mottled backdrop, without the ball.
  int cutAt = -1;
  // A second ball of the same colour (none while distractorRadius is 0), world frame.
  double distractorRadius = 0;
  cv::Point2d distractor{0, 0}, distractorVelocity{0, 0};
  // Frame at which the distractor first shows (-1: from the start, at `distractor`): then it is put
  // distractorOffset (rad, > 0 to the left) from the ball's bearing, at the ball's distance.
  int distractorAt = -1;
  double distractorOffset = 0;
  // With hideAt or cutAt: run every frame and record its step (else the run ends at the first stop).
  bool runAfterStop = false;
  const char *extra = "";          // more robotctl properties
  const char *mode = "threshold";  // colortrack's mode (init-box on the ball either way)
  // The init-box: the ball's box scaled by initBoxShare about its centre (a box drawn inside the ball), or,
  // when initBoxSquare > 0, a square of that many px at the ball's centre (what a click gives).
  double initBoxShare = 1.0;
  int initBoxSquare = 0;
};

// The init-box `sc` asks for, on the ball's box `ball` at the start.
inline cv::Rect2d initBoxFor(const Scenario &sc, const cv::Rect2d &ball) {
  const cv::Point2d centre(ball.x + ball.width / 2, ball.y + ball.height / 2);
  const cv::Size2d size = sc.initBoxSquare > 0 ? cv::Size2d(sc.initBoxSquare, sc.initBoxSquare)
                                               : cv::Size2d(ball.width, ball.height) * sc.initBoxShare;
  return cv::Rect2d(centre.x - size.width / 2, centre.y - size.height / 2, size.width, size.height);
}

// One colortrack ROI as robotctl received it.
struct Roi {
  int id = 0;
  cv::Rect2d box;
  std::string state;
};

// What happened on each frame, after the robot moved.
struct Step {
  double bearing = 0;   // rad
  double distance = 0;  // m
  int turn = 0;         // direction of the command the wheels ran: +1 left, -1 right, 0 no turn
  bool inView = false;
  double distractorBearing = 0;   // rad
  bool distractorInView = false;  // some of the distractor's box lies in the frame
  double distractorDistance = 0;  // m
  cv::Rect2d ballBox;             // ground truth, in the frame the decision was made on
  cv::Rect2d distractorBox;       // the same
  std::vector<Roi> rois;          // what robotctl was given on that frame
  WheelCommand command;           // the one decided on that frame
  Pose pose;                      // the robot's
};

struct LoopResult {
  std::vector<Step> steps;
  int stopAfterHide = -1;  // frames from hiding the ball (or the cut) to the first stop received
  int commandsBeforeHide = 0, movingBeforeHide = 0;
  int rejected = 0;
};

// Records the colortrack ROIs of each buffer reaching robotctl.
struct RoiLog {
  std::mutex mutex;
  std::vector<std::vector<Roi>> frames;
};

inline GstPadProbeReturn recordRois(GstPad *, GstPadProbeInfo *info, gpointer data) {
  auto *log = static_cast<RoiLog *>(data);
  std::vector<Roi> rois;
  for (GstVideoRegionOfInterestMeta *meta : colortrackRois(GST_PAD_PROBE_INFO_BUFFER(info))) {
    Roi roi;
    roi.id = meta->id;
    roi.box = cv::Rect2d(meta->x, meta->y, meta->w, meta->h);
    if (const GstStructure *p = gst_video_region_of_interest_meta_get_param(meta, "colortrack"))
      if (const char *state = gst_structure_get_string(p, "state")) roi.state = state;
    rois.push_back(roi);
  }
  std::lock_guard<std::mutex> lock(log->mutex);
  log->frames.push_back(rois);
  return GST_PAD_PROBE_OK;
}

inline LoopResult runLoop(const Scenario &sc) {
  RobotSimConfig config;
  config.ball = cv::Point2d(sc.distance * std::cos(sc.bearing), sc.distance * std::sin(sc.bearing));
  config.ballVelocity = sc.ballVelocity;
  config.distractorRadius = sc.distractorRadius;
  config.distractor = sc.distractor;
  config.distractorVelocity = sc.distractorVelocity;
  RobotSim robot(config, Pose{});
  robot.setDistractorHidden(sc.distractorAt >= 0);
  CommandDecoder decoder(sc.decoding, kMaxLinear, kMaxAngular, 255);

  Pty pty;
  const cv::Rect2d first = initBoxFor(sc, robot.ballBox());
  char launch[1024];
  std::snprintf(launch, sizeof launch,
                "appsrc name=src format=time caps=video/x-raw,format=BGR,width=%d,height=%d,framerate=%d/1 ! "
                "colortrack mode=%s init-box=%d,%d,%d,%d draw=0 ! "
                "robotctl name=ctl location=%s sync=false post-messages=true rate=200 controller=%s "
                "protocol=%s %s",
                config.frameSize.width, config.frameSize.height, kFps, sc.mode, cvRound(first.x),
                cvRound(first.y), cvRound(first.width), cvRound(first.height), pty.slave.c_str(),
                sc.controller, sc.protocol, sc.extra);
  GError *error = nullptr;
  GstElement *pipeline = gst_parse_launch(launch, &error);
  fail_unless(pipeline != nullptr, "%s", error ? error->message : "");
  GstElement *src = gst_bin_get_by_name(GST_BIN(pipeline), "src");
  GstBus *bus = gst_element_get_bus(pipeline);
  RoiLog roiLog;
  GstElement *ctl = gst_bin_get_by_name(GST_BIN(pipeline), "ctl");
  GstPad *sinkPad = gst_element_get_static_pad(ctl, "sink");
  gst_pad_add_probe(sinkPad, GST_PAD_PROBE_TYPE_BUFFER, recordRois, &roiLog, nullptr);
  gst_object_unref(sinkPad);
  gst_object_unref(ctl);
  fail_unless(gst_element_set_state(pipeline, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE);

  LoopResult result;
  WheelCommand received;                                          // the last command that arrived
  std::deque<WheelCommand> inFlight(sc.latency, WheelCommand());  // arrived, not yet at the wheels
  const double dt = 1.0 / kFps;
  for (int i = 0; i < sc.frames; ++i) {
    if (i == sc.hideAt || i == sc.cutAt) robot.setBallHidden(true);
    if (i == sc.cutAt) robot.setBackdrop(Backdrop::Mottled);
    if (i == sc.distractorAt) {
      robot.placeDistractor(robot.ballBearing() + sc.distractorOffset, robot.ballDistance());
      robot.setDistractorHidden(false);
    }
    const cv::Rect2d ballBox = robot.ballBox(), distractorBox = robot.distractorBox();
    fail_unless(gst_app_src_push_buffer(GST_APP_SRC(src), bgrBuffer(robot.render(), i)) == GST_FLOW_OK);
    waitForCommandOf(bus, gst_util_uint64_scale_int(i, GST_SECOND, kFps));
    const std::vector<std::uint8_t> bytes = pty.drain();
    const std::vector<WheelCommand> commands = decoder.feed(bytes.data(), bytes.size());
    fail_if(commands.empty(), "frame %d: nothing on the pty", i);
    received = commands.back();
    inFlight.push_back(received);
    const WheelCommand wheels = inFlight.front();
    inFlight.pop_front();
    robot.drive(wheels.left, wheels.right, dt);
    robot.moveBall(dt);

    const int goneAt = sc.cutAt >= 0 ? sc.cutAt : sc.hideAt;
    if (goneAt >= 0) {
      if (i < goneAt) {
        ++result.commandsBeforeHide;
        result.movingBeforeHide += !received.stop();
      } else if (result.stopAfterHide < 0 && received.stop()) {
        result.stopAfterHide = i - goneAt;
        if (!sc.runAfterStop) break;
      }
      if (!sc.runAfterStop) continue;
    }
    Step step;
    step.bearing = robot.ballBearing();
    step.distance = robot.ballDistance();
    const double spin = wheels.right - wheels.left;
    step.turn = spin > 1e-9 ? 1 : spin < -1e-9 ? -1 : 0;
    step.inView = !robot.ballBox().empty();
    step.distractorBearing = robot.distractorBearing();
    const cv::Rect2d frameRect(cv::Point2d(), cv::Size2d(config.frameSize));
    step.distractorInView = (robot.distractorBox() & frameRect).area() > 0;
    step.distractorDistance = robot.distractorDistance();
    step.ballBox = ballBox;
    step.distractorBox = distractorBox;
    step.command = received;
    step.pose = robot.pose();
    {
      std::lock_guard<std::mutex> lock(roiLog.mutex);
      if (roiLog.frames.size() > static_cast<size_t>(i)) step.rois = roiLog.frames[i];
    }
    result.steps.push_back(step);
  }
  result.rejected = decoder.rejected();
  gst_app_src_end_of_stream(GST_APP_SRC(src));
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(src);
  gst_object_unref(pipeline);
  return result;
}

inline double setPointDistance() {
  RobotSimConfig config;
  return RobotSim(config, Pose{}).distanceForSizeCue(kSetPoint);
}

// Centred within 5 degrees and within 5 % of the set-point distance.
inline bool settled(const Step &s) {
  return std::abs(s.bearing) < 5 * kDeg && std::abs(s.distance / setPointDistance() - 1) <= 0.05;
}

// The first frame from which every later frame is settled (steps.size() when the last one is not).
inline int settledFrom(const std::vector<Step> &steps) {
  int from = static_cast<int>(steps.size());
  while (from > 0 && settled(steps[from - 1])) --from;
  return from;
}

// Changes of turn direction among the turning frames of [begin, end).
inline int turnReversals(const std::vector<Step> &steps, std::size_t begin, std::size_t end) {
  int reversals = 0, last = 0;
  for (std::size_t i = begin; i < end && i < steps.size(); ++i) {
    if (steps[i].turn == 0) continue;
    reversals += last != 0 && steps[i].turn != last;
    last = steps[i].turn;
  }
  return reversals;
}

struct Following {
  double meanBearingDeg = 0, meanDistanceError = 0;
  int reversals = 0;
  bool inView = true;
};

inline Following follow(const std::vector<Step> &steps, std::size_t begin) {
  Following f;
  int n = 0;
  for (std::size_t i = begin; i < steps.size(); ++i, ++n) {
    f.meanBearingDeg += std::abs(steps[i].bearing) / kDeg;
    f.meanDistanceError += std::abs(steps[i].distance / setPointDistance() - 1);
    f.inView = f.inView && steps[i].inView;
  }
  f.meanBearingDeg /= std::max(1, n);
  f.meanDistanceError /= std::max(1, n);
  f.reversals = turnReversals(steps, begin, steps.size());
  return f;
}

inline Scenario forController(const char *controller) {
  Scenario sc;
  sc.controller = controller;
  if (std::string(controller) == "proportional") {
    sc.protocol = "binary";
    sc.decoding = CommandDecoder::Protocol::Binary;
  }
  return sc;
}

// The ROI that is the ball on a step: the one overlapping the ball's true box most (nullptr when none does).
inline const Roi *ballRoi(const Step &step) {
  const Roi *best = nullptr;
  double bestOverlap = 0;
  for (const Roi &roi : step.rois) {
    const double overlap = (roi.box & step.ballBox).area();
    if (overlap > bestOverlap) {
      best = &roi;
      bestOverlap = overlap;
    }
  }
  return best;
}

}  // namespace colortrack::robot_loop
