// SPDX-License-Identifier: LGPL-2.1-or-later
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
// docs/benchmarks-history.md ("Robot closed loop (issue 12)") has them for the old and the new controllers.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <cmath>
#include <cstdlib>
#include <utility>

#include "robot_loop_rig.hpp"

namespace {

using namespace colortrack::robot_loop;

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

// Issue 25, item 3: driven by mode=template (init-box on the ball), from 2 m to the set-point (1.155 m), both
// laws: the reported box's height (the distance cue) within 5 % of the ball's on every frame, and the
// distance within 5 % of the set-point on each of the last 150 frames of 300; then a ball rolling away and
// across at 0.2 m/s (as checkFollows), whose mean |distance error| over the last 150 frames must be within
// 5 % (the zone law drives in pulses, so single frames reach 6-7 %).
GST_START_TEST(test_template_mode_holds_the_distance) {
  for (const char *controller : {"zone", "proportional"}) {
    for (const double speed : {0.0, 0.2}) {
      Scenario sc = forController(controller);
      sc.mode = "template";
      sc.ballVelocity = cv::Point2d(speed * std::cos(60 * kDeg), speed * std::sin(60 * kDeg));
      sc.frames = 300;
      const LoopResult r = runLoop(sc);
      double worstDistance = 0, meanDistance = 0, meanAbsDistance = 0, worstHeight = 0;
      for (int i = 0; i < static_cast<int>(r.steps.size()); ++i) {
        const Step &st = r.steps[i];
        const Roi *roi = ballRoi(st);
        fail_unless(roi != nullptr, "%s: frame %d has no box on the ball", controller, i);
        worstHeight = std::max(worstHeight, std::abs(roi->box.height / st.ballBox.height - 1));
        if (i < 150) continue;
        const double e = st.distance / setPointDistance() - 1;
        worstDistance = std::max(worstDistance, std::abs(e));
        meanDistance += e / (r.steps.size() - 150);
        meanAbsDistance += std::abs(e) / (r.steps.size() - 150);
      }
      g_print(
          "template mode, %s, ball at %.1f m/s: box height within %.1f %% of the ball's; distance error over "
          "the last 150 frames mean %+.1f %%, mean |error| %.1f %%, worst %.1f %%\n",
          controller, speed, 100 * worstHeight, 100 * meanDistance, 100 * meanAbsDistance,
          100 * worstDistance);
      fail_unless(worstHeight <= 0.05, "%s: box height %.1f %% off", controller, 100 * worstHeight);
      // Still: every frame within 5 %; rolling: on average (the zone law works in pulses).
      const double error = speed == 0 ? worstDistance : meanAbsDistance;
      fail_unless(error <= 0.05, "%s: distance %.1f %% off", controller, 100 * error);
      fail_unless_equals_int(r.rejected, 0);
    }
  }
}
GST_END_TEST;

// Issue 47, item 2: with set-point-at-start, template mode holds the distance the robot started at, whatever
// share of the ball the init-box covers (60, 75 and 100 % of it, or a click's 64 px square, larger than the
// ball here), both laws: with the ball still (and 15 degrees off the heading, so the robot turns), every one
// of the last 150 frames of 240 within 5 % of the start distance; rolling away and across at 0.2 m/s (as
// checkFollows), the mean |error| over them within 5 %.
GST_START_TEST(test_template_mode_holds_the_start_distance_whatever_the_box) {
  const std::pair<double, int> boxes[] = {{0.6, 0}, {0.75, 0}, {1.0, 0}, {1.0, 64}};
  int failures = 0;
  for (const char *controller : {"zone", "proportional"}) {
    for (const auto &[share, square] : boxes) {
      for (const double speed : {0.0, 0.2}) {
        Scenario sc = forController(controller);
        sc.mode = "template";
        sc.extra = "set-point-at-start=true";
        sc.distance = 1.2;
        sc.bearing = speed == 0 ? 15 * kDeg : 0;
        sc.initBoxShare = share;
        sc.initBoxSquare = square;
        sc.ballVelocity = cv::Point2d(speed * std::cos(60 * kDeg), speed * std::sin(60 * kDeg));
        sc.frames = 240;
        const LoopResult r = runLoop(sc);
        double worst = 0, mean = 0, meanAbs = 0, boxDrift = 0;
        const Roi *firstRoi = ballRoi(r.steps[0]);
        const double startRatio = firstRoi ? firstRoi->box.height / r.steps[0].ballBox.height : 1;
        const int from = static_cast<int>(r.steps.size()) - 150;
        for (int i = from; i < static_cast<int>(r.steps.size()); ++i) {
          const double e = r.steps[i].distance / sc.distance - 1;
          worst = std::max(worst, std::abs(e));
          mean += e / 150;
          meanAbs += std::abs(e) / 150;
          if (const Roi *roi = ballRoi(r.steps[i]))
            boxDrift += (roi->box.height / r.steps[i].ballBox.height / startRatio - 1) / 150;
        }
        g_print(
            "start distance, %s, box %s %.0f %%, ball at %.1f m/s: distance error over the last 150 frames "
            "mean %+.1f %%, mean |error| %.1f %%, worst %.1f %%; box / ball against the start %+.1f %%\n",
            controller, square > 0 ? "click square" : "share",
            square > 0 ? 100.0 * square / r.steps[0].ballBox.height : 100 * share, speed, 100 * mean,
            100 * meanAbs, 100 * worst, 100 * boxDrift);
        fail_unless(r.steps.size() == static_cast<std::size_t>(sc.frames), "%s: the run ended early",
                    controller);
        const double error = speed == 0 ? worst : meanAbs;
        if (error > 0.05) ++failures;  // every run prints its figures first
        fail_unless_equals_int(r.rejected, 0);
      }
    }
  }
  fail_unless_equals_int(failures, 0);
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
  tcase_add_test(tc, test_template_mode_holds_the_distance);
  tcase_add_test(tc, test_template_mode_holds_the_start_distance_whatever_the_box);
  return s;
}

}  // namespace

GST_CHECK_MAIN(robot_sim);
