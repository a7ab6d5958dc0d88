// SPDX-License-Identifier: LGPL-2.1-or-later
// The zone and proportional controllers and the failsafe, on exact figures (no I/O, given times).
#include <gtest/gtest.h>

#include <vector>

#include "colortrack/controller.hpp"

namespace colortrack {
namespace {

const cv::Size kFrame(320, 240);

// A box of the given height whose centre is at horizontal offset `offset` (fraction of half the width).
cv::Rect2d boxAt(double offset, double height) {
  const double cx = kFrame.width / 2.0 * (1 + offset);
  return cv::Rect2d(cx - height / 2, 100, height, height);
}

TEST(ControllerGeometry, OffsetAndDistanceCues) {
  EXPECT_DOUBLE_EQ(horizontalOffset(cv::Rect2d(240, 100, 40, 40), kFrame), 0.625);
  EXPECT_DOUBLE_EQ(horizontalOffset(cv::Rect2d(0, 0, 40, 40), kFrame), -0.875);
  EXPECT_DOUBLE_EQ(distanceCue(cv::Rect2d(0, 100, 48, 48), kFrame, DistanceCue::Size), 0.2);
  EXPECT_DOUBLE_EQ(distanceCue(cv::Rect2d(0, 100, 40, 40), kFrame, DistanceCue::Position), 140.0 / 240);
  // Too far (smaller than the set-point) is a positive, relative error.
  EXPECT_NEAR(distanceError(cv::Rect2d(0, 100, 48, 48), kFrame, DistanceCue::Size, 0.3), 1.0 / 3, 1e-12);
  EXPECT_NEAR(distanceError(cv::Rect2d(0, 100, 96, 96), kFrame, DistanceCue::Size, 0.3), -1.0 / 3, 1e-12);
}

TEST(ControllerGeometry, WheelsKeepTheTurnWhenSaturated) {
  double left = 0, right = 0;
  toWheels(0.5, 0.3, left, right);
  EXPECT_DOUBLE_EQ(left, 0.2);
  EXPECT_DOUBLE_EQ(right, 0.8);
  toWheels(1.0, 0.5, left, right);  // 0.5 and 1.5, scaled by 1/1.5
  EXPECT_DOUBLE_EQ(left, 0.5 / 1.5);
  EXPECT_DOUBLE_EQ(right, 1.0);
  EXPECT_EQ(classifyCommand(0, 0), DriveCommand::Stop);
  EXPECT_EQ(classifyCommand(0.2, 0.3), DriveCommand::Left);
  EXPECT_EQ(classifyCommand(0.2, -0.3), DriveCommand::Right);
  EXPECT_EQ(classifyCommand(-0.3, 0.2), DriveCommand::Backward);
}

TEST(ZoneController, DecisionsWithDeadbandAndHysteresis) {
  ControllerSettings s;  // deadbands 0.1, maxLinear 0.5, maxAngular 0.3
  s.hysteresis = 0.05;
  s.latency = 0;  // the paper's controller
  ZoneController zone(s);
  double t = 0;
  const auto update = [&](double offset, double distance) {
    return zone.update({offset, distance}, t += 0.1);
  };

  DriveOutput out = update(0.05, 0.0);
  EXPECT_EQ(out.command, DriveCommand::Stop);
  out = update(0.11, 0.0);
  EXPECT_EQ(out.command, DriveCommand::Right);
  EXPECT_DOUBLE_EQ(out.angular, -0.3);
  EXPECT_DOUBLE_EQ(out.left, 0.3);
  EXPECT_DOUBLE_EQ(out.right, -0.3);
  // Back inside the deadband but not by the hysteresis: still turning.
  EXPECT_EQ(update(0.08, 0.0).command, DriveCommand::Right);
  EXPECT_EQ(update(0.051, 0.0).command, DriveCommand::Right);
  EXPECT_EQ(update(0.049, 0.0).command, DriveCommand::Stop);
  // From the centre, 0.09 is not enough to start turning.
  EXPECT_EQ(update(0.09, 0.0).command, DriveCommand::Stop);
  EXPECT_EQ(update(-0.2, 0.0).command, DriveCommand::Left);
  // Straight across to the other side.
  EXPECT_EQ(update(0.2, 0.0).command, DriveCommand::Right);
  EXPECT_EQ(update(0.0, 0.0).command, DriveCommand::Stop);

  out = update(0.0, 0.15);
  EXPECT_EQ(out.command, DriveCommand::Forward);
  EXPECT_DOUBLE_EQ(out.left, 0.5);
  EXPECT_DOUBLE_EQ(out.right, 0.5);
  EXPECT_EQ(update(0.0, 0.07).command, DriveCommand::Forward);
  EXPECT_EQ(update(0.0, 0.04).command, DriveCommand::Stop);
  out = update(0.0, -0.2);
  EXPECT_EQ(out.command, DriveCommand::Backward);
  EXPECT_DOUBLE_EQ(out.linear, -0.5);
  // Turning comes before distance.
  EXPECT_EQ(update(0.2, 0.5).command, DriveCommand::Right);
  EXPECT_EQ(update(0.0, 0.5).command, DriveCommand::Forward);
}

TEST(ZoneController, NoChatterOnABorder) {
  ControllerSettings s;
  s.latency = 0;
  ZoneController zone(s);
  // A target jittering +-0.02 around the deadband border changes the command once, not on every frame.
  int changes = 0;
  DriveCommand previous = DriveCommand::Stop;
  for (int i = 0; i < 40; ++i) {
    const double offset = 0.1 + (i % 2 ? 0.02 : -0.02);
    const DriveCommand c = zone.update({offset, 0}, i * 0.1).command;
    changes += c != previous;
    previous = c;
  }
  EXPECT_EQ(changes, 1);
}

TEST(ZoneController, LatencyTurnsInSingleDecisionsNearTheCentre) {
  ControllerSettings s;  // latency 0.1 s
  ZoneController zone(s);
  // A target 0.15 off (beyond the deadband, within twice it) that does not move, decided at 30 fps: one
  // turn decision, then stops for the latency and a frame, then the next one.
  std::vector<int> turns;
  zone.update({0, 0}, -1 / 30.0);  // the frame period is known from the second decision on
  for (int i = 0; i < 30; ++i) {
    const DriveOutput out = zone.update({0.15, 0}, i / 30.0);
    EXPECT_TRUE(out.command == DriveCommand::Right || out.command == DriveCommand::Stop) << i;
    if (out.command == DriveCommand::Right) turns.push_back(i);
  }
  ASSERT_GE(turns.size(), 6u);
  EXPECT_EQ(turns.front(), 0);
  for (std::size_t k = 1; k < turns.size(); ++k) EXPECT_EQ(turns[k] - turns[k - 1], 4) << k;  // 3 stops
  // Centred again: no turn, and the hold does not delay driving.
  EXPECT_EQ(zone.update({0.0, 0.3}, 2.0).command, DriveCommand::Forward);
  // While a turn's effect is awaited the distance is corrected (the target is near the centre).
  ZoneController far(s);
  EXPECT_EQ(far.update({0.15, 0.3}, 0.0).command, DriveCommand::Right);  // turning first
  EXPECT_EQ(far.update({0.15, 0.3}, 1 / 30.0).command, DriveCommand::Forward);
}

TEST(ZoneController, LatencyEndsAFastTurnEarly) {
  ControllerSettings s;  // latency 0.1 s
  ZoneController zone(s);
  // Far off: full turn while the offset predicted a latency ahead is still out of the centre.
  EXPECT_EQ(zone.update({0.6, 0, 0, 0}, 0.0).command, DriveCommand::Right);
  EXPECT_EQ(zone.update({0.5, 0, -2.0, 0}, 0.033).command, DriveCommand::Right);  // predicted 0.3
  // Predicted 0.25 - 0.3 < 0: the robot will still turn past the centre, stop now and wait.
  EXPECT_EQ(zone.update({0.25, 0, -3.0, 0}, 0.067).command, DriveCommand::Stop);
  EXPECT_EQ(zone.update({0.22, 0, -3.0, 0}, 0.1).command, DriveCommand::Stop);  // waiting
  // The same decisions without the latency rule (the paper's): turn until inside.
  s.latency = 0;
  zone.setSettings(s);
  zone.reset();
  EXPECT_EQ(zone.update({0.25, 0, -3.0, 0}, 0.2).command, DriveCommand::Right);
}

TEST(ProportionalController, GainsDeadbandsAndLimits) {
  ControllerSettings s;  // deadbands 0.1, maxLinear 0.5, maxAngular 0.3
  s.kind = ControllerKind::Proportional;
  s.turnGain = s.driveGain = 1.5;
  s.turnIntegralGain = s.driveIntegralGain = 0;  // P alone here
  s.turnRateGain = s.driveRateGain = 0;
  s.maxLinearAccel = s.maxAngularAccel = 0;  // no slew limit here
  ProportionalController p(s);

  // The whole error counts (the set-point is reached, not the deadband's edge).
  DriveOutput out = p.update({0.1, 0.2}, 0.1);
  EXPECT_NEAR(out.angular, -0.15, 1e-12);  // -1.5 * 0.1
  EXPECT_NEAR(out.linear, 0.3, 1e-12);     // 1.5 * 0.2
  EXPECT_NEAR(out.left, 0.45, 1e-12);
  EXPECT_NEAR(out.right, 0.15, 1e-12);
  EXPECT_EQ(out.command, DriveCommand::Forward);

  out = p.update({-0.9, 1.0}, 0.1);
  EXPECT_DOUBLE_EQ(out.angular, 0.3);  // limited
  EXPECT_DOUBLE_EQ(out.linear, 0.5);

  out = p.update({0.04, -0.04}, 0.1);  // within half the deadbands, but not arrived: still correcting
  EXPECT_NEAR(out.angular, -0.06, 1e-12);
  EXPECT_NEAR(out.linear, -0.06, 1e-12);
  out = p.update({0.02, -0.02}, 0.1);  // within a quarter: arrived, stop (no creeping)
  EXPECT_EQ(out.command, DriveCommand::Stop);
  EXPECT_DOUBLE_EQ(out.left, 0.0);
  EXPECT_DOUBLE_EQ(out.right, 0.0);
  EXPECT_EQ(p.update({0.04, -0.04}, 0.1).command, DriveCommand::Stop);  // stays arrived within half
  out = p.update({0.0, -0.06}, 0.1);                                    // beyond half: again
  EXPECT_NEAR(out.linear, -0.09, 1e-12);

  out = p.update({0.0, -0.5}, 0.1);
  EXPECT_NEAR(out.linear, -0.5, 1e-12);  // 1.5 * -0.5 = -0.75, limited
  EXPECT_EQ(out.command, DriveCommand::Backward);
}

TEST(ProportionalController, SlewLimit) {
  ControllerSettings s;
  s.kind = ControllerKind::Proportional;
  s.turnGain = s.driveGain = 1.5;
  s.turnIntegralGain = s.driveIntegralGain = 0;
  s.maxLinearAccel = 2.0;  // per second
  s.maxAngularAccel = 1.0;
  ProportionalController p(s);
  EXPECT_DOUBLE_EQ(p.update({0, 1.0}, 0.0).linear, 0.0);  // no time has passed
  EXPECT_NEAR(p.update({0, 1.0}, 0.1).linear, 0.2, 1e-12);
  EXPECT_NEAR(p.update({0, 1.0}, 0.1).linear, 0.4, 1e-12);
  EXPECT_NEAR(p.update({0, 1.0}, 0.1).linear, 0.5, 1e-12);  // the limit
  EXPECT_NEAR(p.update({0, -1.0}, 0.05).linear, 0.4, 1e-12);
  DriveOutput out = p.update({1.0, 0.0}, 0.1);
  EXPECT_NEAR(out.angular, -0.1, 1e-12);
  EXPECT_NEAR(out.linear, 0.2, 1e-12);
  p.reset();
  EXPECT_NEAR(p.update({0, 1.0}, 0.1).linear, 0.2, 1e-12);
}

// Proportional, distance axis only in play: P gain 1, integral gain 2, no rate term, no slew limit.
ControllerSettings piOnDistance() {
  ControllerSettings s;
  s.kind = ControllerKind::Proportional;
  s.driveGain = 1.0;
  s.driveIntegralGain = 2.0;
  s.driveRateGain = 0;
  s.maxLinearAccel = 0;
  return s;
}

TEST(ProportionalController, IntegralRemovesTheSteadyError) {
  ProportionalController p(piOnDistance());
  // A steady error of 0.1 (a target receding as fast as the robot drives): the output grows past P's.
  double linear = 0;
  for (int i = 0; i < 10; ++i) linear = p.update({0, 0.1}, 0.1).linear;
  EXPECT_NEAR(p.driveAxis().integral(), 0.1, 1e-12);  // 0.1 for 1 s
  EXPECT_NEAR(linear, 0.1 + 2.0 * 0.1, 1e-12);
  // Arriving stops the drive (no push past the set-point) and keeps the integral while arrived.
  EXPECT_DOUBLE_EQ(p.update({0, 0.01}, 0.1).linear, 0.0);
  EXPECT_NEAR(p.driveAxis().integral(), 0.1, 1e-12);
  // The target moves off the same way (rate 0.2 a second: 0.11 half a second ahead): going again at once
  // with the speed it needed, 0.03 + 2 * (0.1 + 0.003).
  EXPECT_NEAR(p.update({0, 0.03, 0, 0.16}, 0.1).linear, 0.03 + 2.0 * 0.103, 1e-12);
  // Arrived again, then it moves off the other way: the integral, of the other direction, is cleared.
  p.update({0, 0.0}, 0.1);
  EXPECT_NEAR(p.update({0, -0.06}, 0.1).linear, -0.06 + 2.0 * -0.006, 1e-12);
  p.update({0, 0.2}, 0.1);
  p.reset();
  EXPECT_DOUBLE_EQ(p.driveAxis().integral(), 0.0);
}

TEST(ProportionalController, AntiWindupWhileSaturated) {
  ControllerSettings s = piOnDistance();
  ProportionalController p(s);
  // Far away (error 0.8 > the 0.5 limit on its own) for 3 s: the integrator must not grow.
  for (int i = 0; i < 30; ++i) EXPECT_DOUBLE_EQ(p.update({0, 0.8}, 0.1).linear, 0.5);
  EXPECT_DOUBLE_EQ(p.driveAxis().integral(), 0.0);
  // So once near, the output is P's alone (a wound-up integral would drive on at full speed).
  EXPECT_NEAR(p.update({0, 0.1}, 0.1).linear, 0.1 + 2.0 * 0.01, 1e-12);

  // The slew limit holding the output back counts as saturation too.
  s.maxLinearAccel = 0.5;  // 0.05 per 0.1 s
  p.setSettings(s);
  p.reset();
  for (int i = 0; i < 4; ++i) p.update({0, 0.3}, 0.1);  // wants 0.3, has reached 0.2
  EXPECT_DOUBLE_EQ(p.driveAxis().integral(), 0.0);
}

TEST(ProportionalController, RateTermFollowsTheTargetsMotion) {
  ControllerSettings s;
  s.kind = ControllerKind::Proportional;
  s.turnIntegralGain = s.driveIntegralGain = 0;
  s.maxLinearAccel = s.maxAngularAccel = 0;
  ProportionalController still(s), moving(s);
  const DriveOutput base = still.update({0.2, 0.1, 0, 0}, 0.1);
  // The target moving right and away: turn right harder and drive faster than for a still one.
  const DriveOutput out = moving.update({0.2, 0.1, 0.5, 0.2}, 0.1);
  EXPECT_NEAR(out.angular - base.angular, -s.turnRateGain * 0.5, 1e-12);
  EXPECT_NEAR(out.linear - base.linear, s.driveRateGain * 0.2, 1e-12);
  EXPECT_LT(out.angular, base.angular);
  EXPECT_GT(out.linear, base.linear);
}

Observation seen(double time, double offset, double height, TrackState state = TrackState::Tracking,
                 double score = 0.8) {
  Observation o;
  o.box = boxAt(offset, height);
  o.state = state;
  o.score = score;
  o.frameSize = kFrame;
  o.time = time;
  return o;
}

Observation unseen(double time) {
  Observation o;
  o.frameSize = kFrame;
  o.time = time;
  return o;
}

// The drive is held for the first half of lost-timeout, then stopped; the robot is lost at lost-timeout.
TEST(RobotController, HoldsTheDriveThroughDropoutsThenStops) {
  ControllerSettings c;
  FailsafeSettings f;  // 0.5 s
  f.searchTurn = true;
  RobotController robot(c, f);

  EXPECT_EQ(robot.update(unseen(0.0)).command, DriveCommand::Left);  // never seen: search
  DriveOutput out = robot.update(seen(1.0, 0.0, 30));                // centred and far
  EXPECT_EQ(out.command, DriveCommand::Forward);
  EXPECT_TRUE(out.targetVisible);
  out = robot.update(unseen(1.2));
  EXPECT_EQ(out.command, DriveCommand::Forward);  // held
  EXPECT_FALSE(out.targetVisible);
  EXPECT_EQ(robot.update(seen(1.249, 0.0, 30, TrackState::Coasting)).command, DriveCommand::Forward);
  out = robot.update(seen(1.25, 0.0, 30, TrackState::Coasting));  // half of lost-timeout: the drive stops
  EXPECT_EQ(out.command, DriveCommand::Stop);
  EXPECT_DOUBLE_EQ(out.left, 0.0);
  EXPECT_DOUBLE_EQ(out.right, 0.0);
  EXPECT_EQ(robot.update(unseen(1.499)).command, DriveCommand::Stop);  // not lost yet: no search turn
  out = robot.update(unseen(1.5));  // exactly lost-timeout after the last confirmed target
  EXPECT_EQ(out.command, DriveCommand::Left);
  EXPECT_DOUBLE_EQ(out.linear, 0.0);
  // Back again: the zone controller starts from the centre zone.
  EXPECT_EQ(robot.update(seen(5.1, 0.08, 72)).command, DriveCommand::Stop);
}

// Confirmed again before lost-timeout, after the drive hold ended: the zone law drives again at once.
TEST(RobotController, DrivesAgainWhenConfirmedAfterTheHold) {
  ControllerSettings c;
  RobotController robot(c, FailsafeSettings());
  EXPECT_EQ(robot.update(seen(1.0, 0.0, 30)).command, DriveCommand::Forward);
  EXPECT_EQ(robot.update(unseen(1.4)).command, DriveCommand::Stop);
  EXPECT_EQ(robot.update(seen(1.45, 0.0, 30)).command, DriveCommand::Forward);
}

// The proportional law after the hold: its drive ramps up from standstill (not back to the speed it had),
// never towards a target that came back nearer than wanted, and raising lost-timeout while the robot stands
// does not bring the held drive back.
TEST(RobotController, ProportionalDriveStartsFromStandstillAfterTheHold) {
  ControllerSettings c;
  c.kind = ControllerKind::Proportional;
  FailsafeSettings f;
  RobotController robot(c, f);
  DriveOutput out;
  for (double t = 0.0; t <= 0.5; t += 0.05) out = robot.update(seen(t, 0.0, 24));  // centred and far
  ASSERT_NEAR(out.linear, c.maxLinear, 1e-12);
  EXPECT_NEAR(robot.update(unseen(0.6)).linear, c.maxLinear, 1e-12);  // held
  EXPECT_DOUBLE_EQ(robot.update(unseen(0.8)).linear, 0.0);            // the hold is over
  f.lostTimeout = 2.0;
  robot.setSettings(c, f);
  EXPECT_DOUBLE_EQ(robot.update(unseen(0.85)).linear, 0.0);
  // Far again: from zero at max-linear-accel.
  out = robot.update(seen(0.9, 0.0, 24));
  EXPECT_NEAR(out.linear, c.maxLinearAccel * 0.05, 1e-9);
  // At full speed again, then a target back nearer than the set-point after another hold: never forward.
  for (double t = 0.95; t <= 1.5; t += 0.05) out = robot.update(seen(t, 0.0, 24));
  ASSERT_NEAR(out.linear, c.maxLinear, 1e-12);
  EXPECT_DOUBLE_EQ(robot.update(unseen(2.6)).linear, 0.0);
  out = robot.update(seen(2.65, 0.0, 110));
  EXPECT_LE(out.linear, 0.0);
}

// A turn is not held while the target is unconfirmed: the track coasts where the target was, and a turn
// held for lost-timeout would swing the camera off it (or onto a decoy crossing it). Both laws.
TEST(RobotController, StopsTurningWhileTheTargetIsUnconfirmed) {
  for (const ControllerKind kind : {ControllerKind::Zone, ControllerKind::Proportional}) {
    ControllerSettings c;
    c.kind = kind;
    RobotController robot(c, FailsafeSettings());
    DriveOutput out;
    for (double t = 1.0; t < 1.5; t += 0.05) out = robot.update(seen(t, 0.5, 30));  // right and far
    ASSERT_LT(out.angular, 0);                                                      // turning right
    out = robot.update(seen(1.5, 0.5, 30, TrackState::Coasting));
    EXPECT_DOUBLE_EQ(out.angular, 0.0);
    EXPECT_DOUBLE_EQ(out.left - out.right, 0.0);  // the wheels agree: no turn
    EXPECT_FALSE(out.targetVisible);
    // Confirmed again: it turns again.
    for (double t = 1.55; t < 2.0; t += 0.05) out = robot.update(seen(t, 0.5, 30));
    EXPECT_LT(out.angular, 0);
  }
}

TEST(RobotController, LowScoreAndCoastingAreNotConfirmed) {
  ControllerSettings c;
  FailsafeSettings f;
  f.minScore = 0.5;
  RobotController robot(c, f);
  EXPECT_FALSE(robot.confirmed(seen(0, 0.5, 30, TrackState::Tracking, 0.49)));
  EXPECT_TRUE(robot.confirmed(seen(0, 0.5, 30, TrackState::Tracking, 0.5)));
  EXPECT_FALSE(robot.confirmed(seen(0, 0.5, 30, TrackState::Coasting)));
  EXPECT_FALSE(robot.confirmed(seen(0, 0.5, 30, TrackState::Searching)));
  EXPECT_EQ(robot.update(seen(0, 0.5, 30, TrackState::Tracking, 0.3)).command, DriveCommand::Stop);
}

TEST(RobotController, SearchTurnTowardsTheLastSide) {
  ControllerSettings c;
  c.kind = ControllerKind::Proportional;
  FailsafeSettings f;
  f.searchTurn = true;
  f.searchSpeed = 0.15;
  RobotController robot(c, f);
  robot.update(seen(0.0, 0.625, 30));
  const DriveOutput out = robot.update(unseen(0.6));
  EXPECT_EQ(out.command, DriveCommand::Right);
  EXPECT_DOUBLE_EQ(out.angular, -0.15);
  EXPECT_DOUBLE_EQ(out.left, 0.15);
  EXPECT_DOUBLE_EQ(out.right, -0.15);
  EXPECT_FALSE(out.targetVisible);
}

TEST(RobotController, ProportionalRampsAndFollows) {
  ControllerSettings c;
  c.kind = ControllerKind::Proportional;
  FailsafeSettings f;
  RobotController robot(c, f);
  // Target centred and far (size 0.1 of 0.3: error 2/3): forward, ramping at 2/s from the first frame.
  EXPECT_DOUBLE_EQ(robot.update(seen(0.0, 0.0, 24)).linear, 0.0);
  EXPECT_NEAR(robot.update(seen(0.1, 0.0, 24)).linear, 0.2, 1e-12);
  const DriveOutput out = robot.update(seen(0.2, 0.0, 24));
  EXPECT_NEAR(out.linear, 0.4, 1e-12);
  EXPECT_EQ(out.command, DriveCommand::Forward);
  EXPECT_NEAR(out.left, 0.4, 1e-12);
}

TEST(RobotController, PanTiltTurnsAndTiltsAGimbalAndNeverDrives) {
  ControllerSettings c;  // kind auto: proportional for PanTilt
  c.axes = ControlAxes::PanTilt;
  c.maxAngularAccel = 0;
  c.turnIntegralGain = c.turnRateGain = 0;
  FailsafeSettings f;
  RobotController gimbal(c, f);
  Observation o = seen(0.0, 0.0, 24);
  o.box = cv::Rect2d(200, 150, 24, 24);  // right of centre (offset 0.325) and below (42 px: 0.2625)
  const DriveOutput out = gimbal.update(o);
  EXPECT_NEAR(out.angular, -c.turnGain * 0.325, 1e-12);  // pan right
  EXPECT_NEAR(out.tilt, -c.turnGain * 0.2625, 1e-12);    // tilt down, the vertical offset in half widths
  EXPECT_DOUBLE_EQ(out.linear, 0.0);                     // far, but a gimbal does not drive
  EXPECT_EQ(out.command, DriveCommand::Right);
  EXPECT_FALSE(isStill(out));
  // Straight below: the pan's command name says stop, but the tilt moves.
  o.time = 0.1;
  o.box = cv::Rect2d(148, 150, 24, 24);
  const DriveOutput below = gimbal.update(o);
  EXPECT_EQ(below.command, DriveCommand::Stop);
  EXPECT_LT(below.tilt, 0);
  EXPECT_FALSE(isStill(below));
  // Lost: stop, tilt included.
  EXPECT_TRUE(isStill(gimbal.update(unseen(1.0))));
  // A robot never tilts.
  c.axes = ControlAxes::TurnDrive;
  c.kind = ControllerKind::Proportional;
  RobotController robot(c, f);
  o.time = 0;
  EXPECT_DOUBLE_EQ(robot.update(o).tilt, 0.0);
}

TEST(ControllerKind, AutoIsZoneForABaseAndProportionalForAGimbal) {
  EXPECT_EQ(ControllerSettings{}.kind, ControllerKind::Auto);
  EXPECT_EQ(lawFor(ControllerKind::Auto, ControlAxes::TurnDrive), ControllerKind::Zone);
  EXPECT_EQ(lawFor(ControllerKind::Auto, ControlAxes::PanTilt), ControllerKind::Proportional);
  EXPECT_EQ(lawFor(ControllerKind::Proportional, ControlAxes::TurnDrive), ControllerKind::Proportional);
  EXPECT_EQ(lawFor(ControllerKind::Zone, ControlAxes::TurnDrive), ControllerKind::Zone);
  // The zone law cannot move a gimbal: it does not fit, and if asked anyway the proportional law runs.
  EXPECT_FALSE(lawFits(ControllerKind::Zone, ControlAxes::PanTilt));
  EXPECT_EQ(lawFor(ControllerKind::Zone, ControlAxes::PanTilt), ControllerKind::Proportional);
  for (ControllerKind kind : {ControllerKind::Auto, ControllerKind::Proportional})
    EXPECT_TRUE(lawFits(kind, ControlAxes::PanTilt));
  for (ControllerKind kind : {ControllerKind::Auto, ControllerKind::Zone, ControllerKind::Proportional})
    EXPECT_TRUE(lawFits(kind, ControlAxes::TurnDrive));
  // Auto on a base runs the zone law: full speed in a side zone.
  ControllerSettings c;
  RobotController robot(c, FailsafeSettings{});
  Observation o = seen(0.0, 0.0, 24);
  o.box = cv::Rect2d(280, 100, 24, 24);  // far right
  const DriveOutput out = robot.update(o);
  EXPECT_EQ(out.command, DriveCommand::Right);
  EXPECT_DOUBLE_EQ(out.angular, -c.maxAngular);
}

TEST(RobotController, RatesFromSuccessiveBoxesClearedWhenLost) {
  ControllerSettings c;
  c.kind = ControllerKind::Proportional;
  c.turnIntegralGain = c.driveIntegralGain = 0;
  c.maxLinearAccel = c.maxAngularAccel = 0;
  FailsafeSettings f;
  RobotController moving(c, f), still(c, f);
  // A target sliding right (offset 0.1 -> 0.2 in 0.1 s: 1/s, smoothed to half on the first step) turns
  // harder than one standing at 0.2.
  moving.update(seen(0.0, 0.1, 72));
  still.update(seen(0.0, 0.2, 72));
  const double slid = moving.update(seen(0.1, 0.2, 72)).angular;
  const double stood = still.update(seen(0.1, 0.2, 72)).angular;
  EXPECT_NEAR(slid - stood, -c.turnRateGain * 0.5, 1e-12);
  // Lost and found elsewhere: the jump is not a motion (no rate term on the first frame back, as for a
  // controller that never saw the target).
  moving.update(unseen(1.0));
  RobotController fresh(c, f);
  EXPECT_DOUBLE_EQ(moving.update(seen(1.1, -0.3, 72)).angular, fresh.update(seen(1.1, -0.3, 72)).angular);
}

TEST(RobotController, SetSettingsKeepsTheSlewStateAndTheHold) {
  ControllerSettings c;
  c.kind = ControllerKind::Proportional;
  FailsafeSettings f;
  RobotController robot(c, f);
  // Centred and far (error 2/3): the linear speed ramps at 2/s.
  EXPECT_DOUBLE_EQ(robot.update(seen(0.0, 0.0, 24)).linear, 0.0);
  EXPECT_NEAR(robot.update(seen(0.1, 0.0, 24)).linear, 0.2, 1e-12);

  // A gain change goes on from 0.2 (a rebuilt controller would restart from 0 with dt = 0).
  c.turnGain = 3.0;
  c.driveGain = 1.2;
  robot.setSettings(c, f);
  DriveOutput out = robot.update(seen(0.2, 0.0, 24));
  EXPECT_NEAR(out.linear, 0.4, 1e-12);
  // The new gain applies: an offset of 0.2 turns at -3 * 0.2 = -0.6, limited to -0.3, reached from 0 at 4/s.
  out = robot.update(seen(0.3, 0.2, 24));
  EXPECT_NEAR(out.angular, -0.3, 1e-12);
  EXPECT_NEAR(out.linear, 0.5, 1e-12);  // max-linear

  // A lower limit applies at once (the clamp), the ramp state is not reset: 0.5 -> 0.3 within 0.1 s at 2/s.
  c.maxLinear = 0.3;
  robot.setSettings(c, f);
  EXPECT_NEAR(robot.update(seen(0.4, 0.0, 24)).linear, 0.3, 1e-12);

  // The lost-target hold survives a settings change, and the new lost-timeout counts from the last
  // confirmed target (0.4 s): the drive is held for 0.15 s (0.25 s with the old one).
  f.lostTimeout = 0.3;
  robot.setSettings(c, f);
  out = robot.update(unseen(0.5));
  EXPECT_NEAR(out.linear, 0.3, 1e-12);  // held
  EXPECT_FALSE(out.targetVisible);
  EXPECT_EQ(robot.update(unseen(0.6)).command, DriveCommand::Stop);
}

TEST(RobotController, SetSettingsWithAnotherKindStartsFromStandstill) {
  ControllerSettings c;
  c.kind = ControllerKind::Proportional;
  FailsafeSettings f;
  RobotController robot(c, f);
  robot.update(seen(0.0, 0.0, 24));
  EXPECT_NEAR(robot.update(seen(0.1, 0.0, 24)).linear, 0.2, 1e-12);
  c.kind = ControllerKind::Zone;
  robot.setSettings(c, f);
  EXPECT_EQ(robot.update(seen(0.2, 0.0, 24)).command, DriveCommand::Forward);  // zone: max-linear at once
  c.kind = ControllerKind::Proportional;
  robot.setSettings(c, f);
  EXPECT_NEAR(robot.update(seen(0.3, 0.0, 24)).linear, 0.2, 1e-12);  // ramps again from 0
}

// set-point-at-start: the first confirmed box's distance cue is the set-point (a box of 30 px at 240 would
// be "far" against the default 0.3); a coasting box before it does not count. A box 20 % smaller is then too
// far and 20 % larger too near. Turning it off goes back to set-point; on again, or a reset, takes the next
// confirmed box.
TEST(RobotController, SetPointAtStartHoldsTheFirstConfirmedDistance) {
  ControllerSettings c;
  c.setPointAtStart = true;
  RobotController robot(c, FailsafeSettings());
  EXPECT_EQ(robot.update(seen(0.9, 0.0, 80, TrackState::Coasting)).command, DriveCommand::Stop);
  EXPECT_EQ(robot.update(seen(1.0, 0.0, 30)).command, DriveCommand::Stop);
  EXPECT_EQ(robot.update(seen(1.1, 0.0, 30)).command, DriveCommand::Stop);
  EXPECT_EQ(robot.update(seen(1.2, 0.0, 24)).command, DriveCommand::Forward);
  EXPECT_EQ(robot.update(seen(1.3, 0.0, 30)).command, DriveCommand::Stop);
  EXPECT_EQ(robot.update(seen(1.4, 0.0, 36)).command, DriveCommand::Backward);

  ControllerSettings fixed = c;
  fixed.setPointAtStart = false;
  robot.setSettings(fixed, FailsafeSettings());
  EXPECT_EQ(robot.update(seen(1.5, 0.0, 36)).command, DriveCommand::Forward);  // 36 / 240 is under 0.3
  robot.setSettings(c, FailsafeSettings());
  EXPECT_EQ(robot.update(seen(1.6, 0.0, 36)).command, DriveCommand::Stop);
  EXPECT_EQ(robot.update(seen(1.7, 0.0, 30)).command, DriveCommand::Forward);
  robot.reset();
  EXPECT_EQ(robot.update(seen(1.8, 0.0, 30)).command, DriveCommand::Stop);
}

}  // namespace
}  // namespace colortrack
