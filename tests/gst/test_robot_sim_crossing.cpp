// SPDX-License-Identifier: LGPL-2.1-or-later
// Closed loop (robot_loop_rig.hpp): a second ball of the same colour crosses while the robot follows the
// ball, in front of it and behind it, at several speeds, for both controllers.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <cmath>
#include <cstdlib>
#include <string>

#include "robot_loop_rig.hpp"

namespace {

using namespace colortrack::robot_loop;

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
// distractor): docs/benchmarks-history.md, "Robot closed loop".
// ROBOT_SIM_TRACE=1 prints every frame's ground truth and ROIs.
struct Crossing {
  double speed = 0.4;              // m/s, right to left
  cv::Point2d start{0.55, -0.85};  // m: between the robot and the ball, out of view on the right
  // 0: the crossing lasts until the distractor leaves the view (it passes in front). Otherwise it passes
  // behind the ball, and the crossing ends once it is this far (rad) left of the ball.
  double passedBy = 0;
};

constexpr int kMaxCoastFrames = 10;  // colortrack's default max-coast-frames

// Behind the ball (1.8 m from the robot, the ball 1.16 m), still visible beside it, at `speed`.
Crossing behind(double speed) {
  return Crossing{speed, cv::Point2d(1.8, -1.25), 12 * kDeg};
}

// `mode`: colortrack's mode. In template mode a track lost and taken back has a new id: there the ball's ROI
// after the crossing must be the one tracker's box on the ball, whatever its id.
void checkCrossing(const char *controller, const char *extra = "", const Crossing &c = Crossing(),
                   const char *mode = "threshold") {
  constexpr int kSettleAfter = 45, kAfter = 60;
  const bool templateMode = std::string(mode) == "template";
  Scenario sc = forController(controller);
  sc.extra = extra;
  sc.mode = mode;
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
      "crossing %s%s%s%s at %.2f m/s: distractor in view frames %d-%d (the ball's track not measured on %d); "
      "ball track id %d before, %d after; max |bearing| %.1f deg, distance %.3f-%.3f m (set-point %.3f m), "
      "longest turn away from the ball %d frames; centred from frame %d (%d after it left)\n",
      controller, templateMode ? " template mode" : "", *extra ? " " : "", extra, c.speed, enters, leaves - 1,
      unmeasured, idBefore, idAfter, maxBearing / kDeg, minDistance, maxDistance, setPointDistance(),
      longestAway, centredFrom, left ? centredFrom - leaves : -1);
  fail_unless(left, "%s: the distractor never left the view", controller);
  // A ball hidden for longer than a track coasts (max-coast-frames, 10) comes back under a new id.
  const bool hiddenLong = unmeasured > kMaxCoastFrames;
  fail_unless(idBefore > 0 && (idAfter == idBefore || ((templateMode || hiddenLong) && idAfter > 0)),
              "%s: the ball's track was %d before the crossing, %d after", controller, idBefore, idAfter);
  fail_unless(maxBearing < 10 * kDeg, "%s: turned %.1f deg off the ball", controller, maxBearing / kDeg);
  // In front, 3 frames at max-angular are 8.6 degrees. Behind, the distractor stays beside the ball for up to
  // 6 s and the split of their shared blob pulls the ball's centroid a little: the proportional law's small
  // corrections ran away from the ball for 3-4 frames (at most 3.8 degrees off); the bearing bound above is
  // what keeps it on the ball there.
  const int awayLimit = c.passedBy > 0 ? 6 : 3;
  fail_unless(longestAway <= awayLimit, "%s: turned away from the ball for %d frames", controller,
              longestAway);
  // While the ball is hidden for long the robot waits (it sees no ball of its own) and the ball rolls on
  // away from it; one that follows the decoy backs away far more (see above).
  const double distanceBound = hiddenLong ? 0.2 : 0.15;
  fail_unless(std::abs(minDistance / setPointDistance() - 1) <= distanceBound &&
                  std::abs(maxDistance / setPointDistance() - 1) <= distanceBound,
              "%s: distance %.3f-%.3f m during the crossing", controller, minDistance, maxDistance);
  fail_unless(centredFrom - leaves <= kSettleAfter,
              "%s: not centred on the ball %d frames after the crossing", controller, kSettleAfter);
  fail_unless_equals_int(r.rejected, 0);
}

GST_START_TEST(test_zone_keeps_the_ball_when_another_crosses) {
  checkCrossing("zone");
}
GST_END_TEST;

GST_START_TEST(test_proportional_keeps_the_ball_when_another_crosses) {
  checkCrossing("proportional");
}
GST_END_TEST;

// With lock-on=largest the distractor, larger in the image, would be the choice on every frame it is in view:
// only the lock keeps the robot on the ball.
GST_START_TEST(test_largest_lock_keeps_the_ball_when_a_larger_one_crosses) {
  checkCrossing("zone", "lock-on=largest");
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
// 0.1, 0.2, 0.3 and 0.5 m/s. Issue 47: in front at 0.1 m/s the decoy hides the ball for about 3 s, and the
// ball's track is lost; robotctl's lock does not move on to the decoy (a track seen beside the target), the
// robot waits, and it takes the ball's new track when the ball is back (before, it followed the decoy).
GST_START_TEST(test_keeps_the_ball_at_every_crossing_speed) {
  for (const char *controller : {"zone", "proportional"}) {
    for (const double speed : {0.1, 0.2, 0.5}) checkCrossing(controller, "", Crossing{speed});
    for (const double speed : {0.1, 0.2, 0.3, 0.5}) checkCrossing(controller, "", behind(speed));
  }
}
GST_END_TEST;

// Issue 25, "both modes": driven by mode=template (init-box on the ball), both laws keep the ball when the
// distractor passes in front at 0.2, 0.3, 0.4 and 0.5 m/s and behind it at 0.1, 0.2, 0.3 and 0.5 m/s. Before
// the fused method refused a detection far from the last confirmed size after coasting, the zone robot at
// 0.4 m/s turned 87 degrees after the distractor: the scale filter jumped 35 % onto it as it covered the
// ball. Before robotctl held an unconfirmed target's drive for half of lost-timeout only (it held it for all
// of it), the zone robot at 0.5 m/s closed to 0.94 m (-19 %): the ball's box, partly covered, shrank the
// frame before the track coasted, and the zone law's last command was forward.
GST_START_TEST(test_template_mode_keeps_the_ball_when_another_crosses) {
  for (const char *controller : {"zone", "proportional"}) {
    for (const double speed : {0.1, 0.2, 0.3, 0.4, 0.5})
      checkCrossing(controller, "", Crossing{speed}, "template");
    for (const double speed : {0.1, 0.2, 0.3, 0.5}) checkCrossing(controller, "", behind(speed), "template");
  }
}
GST_END_TEST;

Suite *robot_sim_crossing_suite(void) {
  Suite *s = suite_create("robot_sim_crossing");
  TCase *tc = tcase_create("closed-loop");
  tcase_set_timeout(tc, 180);
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_zone_keeps_the_ball_when_another_crosses);
  tcase_add_test(tc, test_proportional_keeps_the_ball_when_another_crosses);
  tcase_add_test(tc, test_largest_lock_keeps_the_ball_when_a_larger_one_crosses);
  tcase_add_test(tc, test_zone_keeps_the_ball_when_another_crosses_slowly);
  tcase_add_test(tc, test_proportional_keeps_the_ball_when_another_crosses_slowly);
  tcase_add_test(tc, test_keeps_the_ball_at_every_crossing_speed);
  tcase_add_test(tc, test_template_mode_keeps_the_ball_when_another_crosses);
  return s;
}

}  // namespace

GST_CHECK_MAIN(robot_sim_crossing);
