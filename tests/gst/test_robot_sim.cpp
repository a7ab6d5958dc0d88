// Closed loop: a simulated robot's camera view goes through appsrc ! colortrack ! robotctl, the commands
// come back over a pseudo-terminal and move the robot. Each frame is pushed, then the test waits for the
// command decided on that frame (robotctl's message carries the frame's timestamp) and reads the bytes from
// the pty, so the loop advances frame by frame whatever the machine's speed.
//
// The scenarios of issue 12, for both controllers, with robotctl's default controller properties (only the
// transport differs: rate=200 so that every frame's decision is sent before the next frame, which keeps
// the test fast and deterministic; the sim's latency stands for the real link's). The robot is
// RobotSimConfig's (1 m/s at full wheel speed, 0.4 m between the wheels, 320x240, 60 degree camera), and
// its firmware turns the zone characters into robotctl's default max-linear / max-angular.
//
// "Distance" is the metric distance on the floor from the camera to the ball; the set-point distance is
// the one at which the ball's box is set-point (0.3) of the frame height: 1.155 m (RobotSim::
// distanceForSizeCue). The distance error is |distance / set-point distance - 1|.
//
// Every scenario prints its figures with g_print (`meson test -C build gst-robot-sim -v`);
// docs/benchmarks.md ("Robot closed loop (issue 12)") has them for the old and the new controllers.
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

namespace {

using colortrack::gst_test_util::bgrBuffer;
using colortrack::gst_test_util::colortrackRois;
using colortrack::gst_test_util::kFps;
using colortrack::gst_test_util::waitForCommandOf;
using colortrack::robot_sim::CommandDecoder;
using colortrack::robot_sim::Pose;
using colortrack::robot_sim::RobotSim;
using colortrack::robot_sim::RobotSimConfig;
using colortrack::robot_sim::WheelCommand;

constexpr double kSetPoint = 0.3;      // robotctl's default
constexpr guint kLostTimeoutMs = 500;  // robotctl's default
constexpr double kMaxLinear = 0.5;     // robotctl's default max-linear: the firmware's F / B speed
constexpr double kMaxAngular = 0.3;    // robotctl's default max-angular: the firmware's L / R speed
constexpr int kLatencyFrames = 3;      // 100 ms at 30 fps
constexpr double kDeg = CV_PI / 180;

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
  // A second ball of the same colour (none while distractorRadius is 0), world frame.
  double distractorRadius = 0;
  cv::Point2d distractor{0, 0}, distractorVelocity{0, 0};
  const char *extra = "";  // more robotctl properties
};

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
  cv::Rect2d ballBox;             // ground truth, in the frame the decision was made on
  std::vector<Roi> rois;          // what robotctl was given on that frame
};

struct LoopResult {
  std::vector<Step> steps;
  int stopAfterHide = -1;  // frames from hiding the ball to the first stop received
  int commandsBeforeHide = 0, movingBeforeHide = 0;
  int rejected = 0;
};

// Records the colortrack ROIs of each buffer reaching robotctl.
struct RoiLog {
  std::mutex mutex;
  std::vector<std::vector<Roi>> frames;
};

GstPadProbeReturn recordRois(GstPad *, GstPadProbeInfo *info, gpointer data) {
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

LoopResult runLoop(const Scenario &sc) {
  RobotSimConfig config;
  config.ball = cv::Point2d(sc.distance * std::cos(sc.bearing), sc.distance * std::sin(sc.bearing));
  config.ballVelocity = sc.ballVelocity;
  config.distractorRadius = sc.distractorRadius;
  config.distractor = sc.distractor;
  config.distractorVelocity = sc.distractorVelocity;
  RobotSim robot(config, Pose{});
  CommandDecoder decoder(sc.decoding, kMaxLinear, kMaxAngular, 255);

  Pty pty;
  const cv::Rect2d first = robot.ballBox();
  char launch[1024];
  std::snprintf(launch, sizeof launch,
                "appsrc name=src format=time caps=video/x-raw,format=BGR,width=%d,height=%d,framerate=%d/1 ! "
                "colortrack mode=threshold init-box=%d,%d,%d,%d draw=0 ! "
                "robotctl name=ctl location=%s sync=false post-messages=true rate=200 controller=%s "
                "protocol=%s %s",
                config.frameSize.width, config.frameSize.height, kFps, cvRound(first.x), cvRound(first.y),
                cvRound(first.width), cvRound(first.height), pty.slave.c_str(), sc.controller, sc.protocol,
                sc.extra);
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
    if (i == sc.hideAt) robot.setBallHidden(true);
    const cv::Rect2d ballBox = robot.ballBox();
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

    if (sc.hideAt >= 0) {
      if (i < sc.hideAt) {
        ++result.commandsBeforeHide;
        result.movingBeforeHide += !received.stop();
      } else if (result.stopAfterHide < 0 && received.stop()) {
        result.stopAfterHide = i - sc.hideAt;
        break;
      }
      continue;
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
    step.ballBox = ballBox;
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

double setPointDistance() {
  RobotSimConfig config;
  return RobotSim(config, Pose{}).distanceForSizeCue(kSetPoint);
}

// Centred within 5 degrees and within 5 % of the set-point distance.
bool settled(const Step &s) {
  return std::abs(s.bearing) < 5 * kDeg && std::abs(s.distance / setPointDistance() - 1) <= 0.05;
}

// The first frame from which every later frame is settled (steps.size() when the last one is not).
int settledFrom(const std::vector<Step> &steps) {
  int from = static_cast<int>(steps.size());
  while (from > 0 && settled(steps[from - 1])) --from;
  return from;
}

// Changes of turn direction among the turning frames of [begin, end).
int turnReversals(const std::vector<Step> &steps, std::size_t begin, std::size_t end) {
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

Following follow(const std::vector<Step> &steps, std::size_t begin) {
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

Scenario forController(const char *controller) {
  Scenario sc;
  sc.controller = controller;
  if (std::string(controller) == "proportional") {
    sc.protocol = "binary";
    sc.decoding = CommandDecoder::Protocol::Binary;
  }
  return sc;
}

// From 2 m and 25 degrees to the right: settled within 150 frames (5 s), and still settled 60 frames
// later (the run is 210 frames and must end settled from frame <= 150 on).
void checkSettles(const char *controller, int latency) {
  Scenario sc = forController(controller);
  sc.bearing = -25 * kDeg;
  sc.latency = latency;
  sc.frames = 210;
  const LoopResult r = runLoop(sc);
  const int from = settledFrom(r.steps);
  const Step &last = r.steps.back();
  const int reversals = turnReversals(r.steps, 0, r.steps.size());
  g_print(
      "settle %s, latency %d ms: settled from frame %d; at the end bearing %.1f deg, distance %.3f m "
      "(set-point %.3f m); %d turn reversals\n",
      controller, latency * 1000 / kFps, from, last.bearing / kDeg, last.distance, setPointDistance(),
      reversals);
  fail_unless(from <= 150, "%s: not settled from frame 150 on (from %d; bearing %.1f deg, distance %.3f m)",
              controller, from, last.bearing / kDeg, last.distance);
  fail_unless(reversals <= 4, "%s: %d turn reversals while settling", controller, reversals);
  fail_unless_equals_int(r.rejected, 0);
}

// A ball rolling at 0.2 m/s, 60 degrees left of the robot's first heading (0.1 m/s away, 0.17 m/s across),
// from 1.2 m ahead. The first 60 frames (2 s) are the acquisition; the next 180 (6 s) are scored.
void checkFollows(const char *controller, int latency) {
  constexpr int kAcquisition = 60;
  Scenario sc = forController(controller);
  sc.distance = 1.2;
  sc.ballVelocity = cv::Point2d(0.2 * std::cos(60 * kDeg), 0.2 * std::sin(60 * kDeg));
  sc.latency = latency;
  sc.frames = kAcquisition + 180;
  const LoopResult r = runLoop(sc);
  const Following f = follow(r.steps, kAcquisition);
  // Sustained oscillation shows as turn reversals late in the run, when following is steady.
  const int lateReversals = turnReversals(r.steps, r.steps.size() - 90, r.steps.size());
  g_print(
      "follow %s, latency %d ms: mean |bearing| %.2f deg, mean distance error %.1f %%, %d turn reversals "
      "(%d in the last 90 frames)\n",
      controller, latency * 1000 / kFps, f.meanBearingDeg, f.meanDistanceError * 100, f.reversals,
      lateReversals);
  fail_unless(f.inView, "%s: lost the ball from view", controller);
  fail_unless(f.meanBearingDeg < 5, "%s: mean |bearing| %.2f deg", controller, f.meanBearingDeg);
  fail_unless(f.meanDistanceError < 0.15, "%s: mean distance error %.3f", controller, f.meanDistanceError);
  fail_unless(lateReversals <= 6, "%s: %d turn reversals in the last 3 s: oscillating", controller,
              lateReversals);
  fail_unless_equals_int(r.rejected, 0);
}

// The ROI that is the ball on a step: the one overlapping the ball's true box most (nullptr when none does).
const Roi *ballRoi(const Step &step) {
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

// Issue 12's crossing: "a same-coloured object crossing in front does not steal the robot". The robot starts
// at the set-point distance, facing the ball, which rolls slowly to the right (0.1 m/s across), so the robot
// is following when a second ball of the same colour, smaller (0.12 m) but nearer (0.55 m ahead: 121 px
// wide in the image against the ball's 72), rolls from the right to the left at 0.4 m/s between the robot
// and the ball. In the image it passes over the lower three quarters of the ball: the blobs touch (and are
// split between the tracks by their pixels), then merge (the ball's track coasts inside the merged blob for
// about 20 frames, longer than lost-timeout), then part. It appears after the ball, so its track has the
// higher id; the ball's track must live through the merge, and robotctl must keep following it
// (lock-on=first-confirmed, the default; with it, the lock and "the lowest id" agree as long as the tracker
// keeps the ball's id, so a third run with lock-on=largest, for which the distractor is the choice on every
// frame it is in view, shows the lock itself).
//
// Required, while the distractor is in view: the robot never turns more than 10 degrees off the ball (the
// ball drifts about 5 degrees while robotctl holds, then stops, during the merge; a robot that follows the
// distractor instead turns 85-90 degrees off), never turns away from the ball for more than 3 frames in a
// row (8.6 degrees at max-angular 0.3), and its distance to the ball stays within 15 % of the set-point
// distance (one that follows the distractor backs away from it: +38 % to +48 %). Within 45 frames (1.5 s)
// of the distractor leaving the view it is centred on the ball (|bearing| < 5 degrees, distance within
// 15 %) to the end of the run, and the ball's ROI has the same id after the crossing as before.
// The distractor rolls at 0.4 m/s, and at 0.3 m/s: then the zone robot makes a single turn while the
// distractor touches the ball, the ball jumps 13 px in the image and its track, merged a moment later, must
// not coast on that jump out of the merged blob (and out of the frame, leaving robotctl only the
// distractor): docs/benchmarks.md, "Robot closed loop".
// ROBOT_SIM_TRACE=1 prints every frame's ground truth and ROIs.
struct Crossing {
  double speed = 0.4;              // m/s, right to left
  cv::Point2d start{0.55, -0.85};  // m: between the robot and the ball, out of view on the right
  // 0: the crossing lasts until the distractor leaves the view (it passes in front). Otherwise it passes
  // behind the ball, and the crossing ends once it is this far (rad) left of the ball.
  double passedBy = 0;
};

// Behind the ball (1.8 m from the robot, the ball 1.16 m), still visible beside it, at `speed`.
Crossing behind(double speed) {
  return Crossing{speed, cv::Point2d(1.8, -1.25), 12 * kDeg};
}

void checkCrossing(const char *controller, const char *extra = "", const Crossing &c = Crossing()) {
  constexpr int kSettleAfter = 45, kAfter = 60;
  Scenario sc = forController(controller);
  sc.extra = extra;
  sc.distance = setPointDistance();
  sc.distractorRadius = 0.12;
  sc.ballVelocity = cv::Point2d(0, -0.1);
  sc.distractor = c.start;
  sc.distractorVelocity = cv::Point2d(0, c.speed);
  // In front it leaves the view at frame 85 at 0.4 m/s. Behind, its bearing gains on the ball's by
  // speed / 1.8 + 0.1 / 1.16 rad/s from 0.69 + 0.16 rad behind (the right edge of the view, the ball's
  // drift).
  const double behindSeconds = (0.69 + 0.16 + c.passedBy) / (c.speed / c.start.x + 0.1 / sc.distance);
  sc.frames = (c.passedBy > 0 ? static_cast<int>(behindSeconds * kFps) + 20
                              : static_cast<int>(std::lround(85 * 0.4 / c.speed))) +
              kAfter;
  const LoopResult r = runLoop(sc);
  const bool trace = std::getenv("ROBOT_SIM_TRACE") != nullptr;

  int enters = -1, leaves = -1;
  for (int i = 0; i < static_cast<int>(r.steps.size()); ++i) {
    const Step &s = r.steps[i];
    const bool passed = c.passedBy > 0 ? s.distractorBearing - s.bearing > c.passedBy : !s.distractorInView;
    if (enters < 0 && s.distractorInView) enters = i;
    if (enters >= 0 && leaves < 0 && passed) leaves = i;
  }
  fail_unless(enters > 0, "the distractor never came into view");
  const bool left = leaves > 0;  // it stays in view when the robot follows it
  if (!left) leaves = static_cast<int>(r.steps.size());

  const Roi *before = ballRoi(r.steps[enters - 1]);
  const Roi *after = ballRoi(r.steps.back());
  const int idBefore = before ? before->id : -1, idAfter = after ? after->id : -1;
  // While the distractor is in view: how far the robot turned from the ball and how its distance changed,
  // the longest run of frames turning away from the ball (more than 1 degree off, and the turn takes it
  // further), and the frames on which the ball's track was not measured (coasting inside the merged blob).
  double maxBearing = 0, minDistance = 1e9, maxDistance = 0;
  int awayRun = 0, longestAway = 0, unmeasured = 0;
  for (int i = enters; i < leaves; ++i) {
    const Step &s = r.steps[i];
    maxBearing = std::max(maxBearing, std::abs(s.bearing));
    minDistance = std::min(minDistance, s.distance);
    maxDistance = std::max(maxDistance, s.distance);
    const int away = s.bearing > kDeg ? -1 : s.bearing < -kDeg ? 1 : 0;
    awayRun = away != 0 && s.turn == away ? awayRun + 1 : 0;
    longestAway = std::max(longestAway, awayRun);
    bool tracking = false;
    for (const Roi &roi : s.rois) tracking = tracking || (roi.id == idBefore && roi.state == "tracking");
    unmeasured += !tracking;
  }
  int centredFrom = static_cast<int>(r.steps.size());
  while (centredFrom > leaves && std::abs(r.steps[centredFrom - 1].bearing) < 5 * kDeg &&
         std::abs(r.steps[centredFrom - 1].distance / setPointDistance() - 1) <= 0.15)
    --centredFrom;
  if (trace) {
    for (int i = 0; i < static_cast<int>(r.steps.size()); ++i) {
      const Step &s = r.steps[i];
      g_print("  %3d: ball %5.1f deg %.3f m (box %.0f,%.0f %.0fx%.0f) distractor %6.1f deg%s turn %+d:", i,
              s.bearing / kDeg, s.distance, s.ballBox.x, s.ballBox.y, s.ballBox.width, s.ballBox.height,
              s.distractorBearing / kDeg, s.distractorInView ? " (in view)" : "", s.turn);
      for (const Roi &roi : s.rois)
        g_print(" [%d %s %.0f,%.0f %.0fx%.0f]", roi.id, roi.state.c_str(), roi.box.x, roi.box.y,
                roi.box.width, roi.box.height);
      g_print("\n");
    }
  }
  g_print(
      "crossing %s%s%s at %.2f m/s: distractor in view frames %d-%d (the ball's track not measured on %d); "
      "ball track id %d before, %d after; max |bearing| %.1f deg, distance %.3f-%.3f m (set-point %.3f m), "
      "longest turn away from the ball %d frames; centred from frame %d (%d after it left)\n",
      controller, *extra ? " " : "", extra, c.speed, enters, leaves - 1, unmeasured, idBefore, idAfter,
      maxBearing / kDeg, minDistance, maxDistance, setPointDistance(), longestAway, centredFrom,
      left ? centredFrom - leaves : -1);
  fail_unless(left, "%s: the distractor never left the view", controller);
  fail_unless(idBefore > 0 && idAfter == idBefore,
              "%s: the ball's track was %d before the crossing, %d after", controller, idBefore, idAfter);
  fail_unless(maxBearing < 10 * kDeg, "%s: turned %.1f deg off the ball", controller, maxBearing / kDeg);
  fail_unless(longestAway <= 3, "%s: turned away from the ball for %d frames", controller, longestAway);
  fail_unless(std::abs(minDistance / setPointDistance() - 1) <= 0.15 &&
                  std::abs(maxDistance / setPointDistance() - 1) <= 0.15,
              "%s: distance %.3f-%.3f m during the crossing", controller, minDistance, maxDistance);
  fail_unless(centredFrom - leaves <= kSettleAfter,
              "%s: not centred on the ball %d frames after the crossing", controller, kSettleAfter);
  fail_unless_equals_int(r.rejected, 0);
}

GST_START_TEST(test_zone_settles) {
  checkSettles("zone", 0);
}
GST_END_TEST;

GST_START_TEST(test_proportional_settles) {
  checkSettles("proportional", 0);
}
GST_END_TEST;

GST_START_TEST(test_zone_settles_with_latency) {
  checkSettles("zone", kLatencyFrames);
}
GST_END_TEST;

GST_START_TEST(test_proportional_settles_with_latency) {
  checkSettles("proportional", kLatencyFrames);
}
GST_END_TEST;

GST_START_TEST(test_zone_follows_a_rolling_ball) {
  checkFollows("zone", 0);
}
GST_END_TEST;

GST_START_TEST(test_proportional_follows_a_rolling_ball) {
  checkFollows("proportional", 0);
}
GST_END_TEST;

GST_START_TEST(test_zone_follows_with_latency) {
  checkFollows("zone", kLatencyFrames);
}
GST_END_TEST;

GST_START_TEST(test_proportional_follows_with_latency) {
  checkFollows("proportional", kLatencyFrames);
}
GST_END_TEST;

GST_START_TEST(test_hidden_ball_stops_within_lost_timeout) {
  // Hidden while the robot is still on its way: it was moving, and must stop within lost-timeout + 100 ms
  // (the decision is made on the frame after the timeout; the stop is then on its way).
  for (const char *controller : {"zone", "proportional"}) {
    Scenario sc = forController(controller);
    sc.protocol = "text";
    sc.decoding = CommandDecoder::Protocol::Text;
    sc.bearing = -12 * kDeg;
    sc.distance = 3.0;
    sc.frames = 120;
    sc.hideAt = 30;
    const LoopResult r = runLoop(sc);
    const int limit = static_cast<int>(std::ceil((kLostTimeoutMs + 100) / 1000.0 * kFps));
    g_print("hide %s: moving in %d of %d frames before hiding; stop %d frames (%.0f ms) after hiding\n",
            controller, r.movingBeforeHide, r.commandsBeforeHide, r.stopAfterHide,
            r.stopAfterHide * 1000.0 / kFps);
    fail_unless(r.movingBeforeHide > 0);
    fail_unless(r.stopAfterHide >= 0, "%s: no stop after hiding the ball", controller);
    fail_unless(r.stopAfterHide <= limit, "%s: stop after %d frames, the limit is %d frames", controller,
                r.stopAfterHide, limit);
    fail_unless_equals_int(r.rejected, 0);
  }
}
GST_END_TEST;

GST_START_TEST(test_zone_keeps_the_ball_when_another_crosses) {
  checkCrossing("zone");
}
GST_END_TEST;

GST_START_TEST(test_proportional_keeps_the_ball_when_another_crosses) {
  checkCrossing("proportional");
}
GST_END_TEST;

// Slower, the distractor touches the ball while the zone robot turns: the ball's track must not coast on the
// jump that turn makes in the image (see checkCrossing).
GST_START_TEST(test_zone_keeps_the_ball_when_another_crosses_slowly) {
  checkCrossing("zone", "", Crossing{0.3});
}
GST_END_TEST;

GST_START_TEST(test_proportional_keeps_the_ball_when_another_crosses_slowly) {
  checkCrossing("proportional", "", Crossing{0.3});
}
GST_END_TEST;

// Issue 25: while the robot turns to follow the ball's drift, both laws keep the ball when the distractor
// passes in front at 0.2 and 0.5 m/s (0.3 and 0.4 above; before follow-camera and the hold without a turn,
// the zone robot at 0.2 m/s turned 37 degrees off and lost the ball), and when it passes behind the ball at
// 0.1, 0.2, 0.3 and 0.5 m/s. (In front at 0.1 m/s it hides the ball for 8 s: the track is lost, and the lock
// moves on to the only ball in view, as lock-on says.)
GST_START_TEST(test_keeps_the_ball_at_every_crossing_speed) {
  for (const char *controller : {"zone", "proportional"}) {
    for (const double speed : {0.2, 0.5}) checkCrossing(controller, "", Crossing{speed});
    for (const double speed : {0.1, 0.2, 0.3, 0.5}) checkCrossing(controller, "", behind(speed));
  }
}
GST_END_TEST;

// With lock-on=largest the distractor, larger in the image, would be the choice on every frame it is in view:
// only the lock keeps the robot on the ball.
GST_START_TEST(test_largest_lock_keeps_the_ball_when_a_larger_one_crosses) {
  checkCrossing("zone", "lock-on=largest");
}
GST_END_TEST;

Suite *robot_sim_suite(void) {
  Suite *s = suite_create("robot_sim");
  TCase *tc = tcase_create("closed-loop");
  tcase_set_timeout(tc, 180);
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_zone_settles);
  tcase_add_test(tc, test_proportional_settles);
  tcase_add_test(tc, test_zone_settles_with_latency);
  tcase_add_test(tc, test_proportional_settles_with_latency);
  tcase_add_test(tc, test_zone_follows_a_rolling_ball);
  tcase_add_test(tc, test_proportional_follows_a_rolling_ball);
  tcase_add_test(tc, test_zone_follows_with_latency);
  tcase_add_test(tc, test_proportional_follows_with_latency);
  tcase_add_test(tc, test_hidden_ball_stops_within_lost_timeout);
  tcase_add_test(tc, test_zone_keeps_the_ball_when_another_crosses);
  tcase_add_test(tc, test_proportional_keeps_the_ball_when_another_crosses);
  tcase_add_test(tc, test_largest_lock_keeps_the_ball_when_a_larger_one_crosses);
  tcase_add_test(tc, test_zone_keeps_the_ball_when_another_crosses_slowly);
  tcase_add_test(tc, test_proportional_keeps_the_ball_when_another_crosses_slowly);
  tcase_add_test(tc, test_keeps_the_ball_at_every_crossing_speed);
  return s;
}

}  // namespace

GST_CHECK_MAIN(robot_sim);
