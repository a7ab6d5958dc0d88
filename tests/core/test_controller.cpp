// The zone and proportional controllers and the failsafe, on exact figures (no I/O, given times).
#include <gtest/gtest.h>

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
  ControllerSettings s;  // deadbands 0.1, hysteresis 0.05, maxLinear 0.5, maxAngular 0.3
  ZoneController zone(s);

  DriveOutput out = zone.update(0.05, 0.0);
  EXPECT_EQ(out.command, DriveCommand::Stop);
  out = zone.update(0.11, 0.0);
  EXPECT_EQ(out.command, DriveCommand::Right);
  EXPECT_DOUBLE_EQ(out.angular, -0.3);
  EXPECT_DOUBLE_EQ(out.left, 0.3);
  EXPECT_DOUBLE_EQ(out.right, -0.3);
  // Back inside the deadband but not by the hysteresis: still turning.
  EXPECT_EQ(zone.update(0.08, 0.0).command, DriveCommand::Right);
  EXPECT_EQ(zone.update(0.051, 0.0).command, DriveCommand::Right);
  EXPECT_EQ(zone.update(0.049, 0.0).command, DriveCommand::Stop);
  // From the centre, 0.09 is not enough to start turning.
  EXPECT_EQ(zone.update(0.09, 0.0).command, DriveCommand::Stop);
  EXPECT_EQ(zone.update(-0.2, 0.0).command, DriveCommand::Left);
  // Straight across to the other side.
  EXPECT_EQ(zone.update(0.2, 0.0).command, DriveCommand::Right);
  EXPECT_EQ(zone.update(0.0, 0.0).command, DriveCommand::Stop);

  out = zone.update(0.0, 0.15);
  EXPECT_EQ(out.command, DriveCommand::Forward);
  EXPECT_DOUBLE_EQ(out.left, 0.5);
  EXPECT_DOUBLE_EQ(out.right, 0.5);
  EXPECT_EQ(zone.update(0.0, 0.07).command, DriveCommand::Forward);
  EXPECT_EQ(zone.update(0.0, 0.04).command, DriveCommand::Stop);
  out = zone.update(0.0, -0.2);
  EXPECT_EQ(out.command, DriveCommand::Backward);
  EXPECT_DOUBLE_EQ(out.linear, -0.5);
  // Turning comes before distance.
  EXPECT_EQ(zone.update(0.2, 0.5).command, DriveCommand::Right);
  EXPECT_EQ(zone.update(0.0, 0.5).command, DriveCommand::Forward);
}

TEST(ZoneController, NoChatterOnABorder) {
  ControllerSettings s;
  ZoneController zone(s);
  // A target jittering +-0.02 around the deadband border changes the command once, not on every frame.
  int changes = 0;
  DriveCommand previous = DriveCommand::Stop;
  for (int i = 0; i < 40; ++i) {
    const double offset = 0.1 + (i % 2 ? 0.02 : -0.02);
    const DriveCommand c = zone.update(offset, 0).command;
    changes += c != previous;
    previous = c;
  }
  EXPECT_EQ(changes, 1);
}

TEST(ProportionalController, GainsDeadbandsAndLimits) {
  ControllerSettings s;  // gains 1.5, deadbands 0.1, maxLinear 0.5, maxAngular 0.3
  s.kind = ControllerKind::Proportional;
  s.maxLinearAccel = s.maxAngularAccel = 0;  // no slew limit here
  ProportionalController p(s);

  DriveOutput out = p.update(0.2, 0.3, 0.1);
  EXPECT_NEAR(out.angular, -0.15, 1e-12);  // -1.5 * (0.2 - 0.1)
  EXPECT_NEAR(out.linear, 0.3, 1e-12);     // 1.5 * (0.3 - 0.1)
  EXPECT_NEAR(out.left, 0.45, 1e-12);
  EXPECT_NEAR(out.right, 0.15, 1e-12);
  EXPECT_EQ(out.command, DriveCommand::Forward);

  out = p.update(-0.9, 1.0, 0.1);
  EXPECT_DOUBLE_EQ(out.angular, 0.3);  // limited
  EXPECT_DOUBLE_EQ(out.linear, 0.5);

  out = p.update(0.05, -0.05, 0.1);  // inside both deadbands
  EXPECT_EQ(out.command, DriveCommand::Stop);
  EXPECT_DOUBLE_EQ(out.left, 0.0);
  EXPECT_DOUBLE_EQ(out.right, 0.0);

  out = p.update(0.0, -0.5, 0.1);
  EXPECT_NEAR(out.linear, -0.5, 1e-12);  // 1.5 * -0.4 = -0.6, limited
  EXPECT_EQ(out.command, DriveCommand::Backward);
}

TEST(ProportionalController, SlewLimit) {
  ControllerSettings s;
  s.kind = ControllerKind::Proportional;
  s.maxLinearAccel = 2.0;  // per second
  s.maxAngularAccel = 1.0;
  ProportionalController p(s);
  EXPECT_DOUBLE_EQ(p.update(0, 1.0, 0.0).linear, 0.0);  // no time has passed
  EXPECT_NEAR(p.update(0, 1.0, 0.1).linear, 0.2, 1e-12);
  EXPECT_NEAR(p.update(0, 1.0, 0.1).linear, 0.4, 1e-12);
  EXPECT_NEAR(p.update(0, 1.0, 0.1).linear, 0.5, 1e-12);  // the limit
  EXPECT_NEAR(p.update(0, -1.0, 0.05).linear, 0.4, 1e-12);
  DriveOutput out = p.update(1.0, 0.0, 0.1);
  EXPECT_NEAR(out.angular, -0.1, 1e-12);
  EXPECT_NEAR(out.linear, 0.2, 1e-12);
  p.reset();
  EXPECT_NEAR(p.update(0, 1.0, 0.1).linear, 0.2, 1e-12);
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

TEST(RobotController, HoldsThroughDropoutsThenStops) {
  ControllerSettings c;
  FailsafeSettings f;  // 0.5 s
  RobotController robot(c, f);

  EXPECT_EQ(robot.update(unseen(0.0)).command, DriveCommand::Stop);  // never seen: stop
  DriveOutput out = robot.update(seen(1.0, 0.5, 30));
  EXPECT_EQ(out.command, DriveCommand::Right);
  EXPECT_TRUE(out.targetVisible);
  out = robot.update(unseen(1.2));
  EXPECT_EQ(out.command, DriveCommand::Right);  // held
  EXPECT_FALSE(out.targetVisible);
  EXPECT_EQ(robot.update(seen(1.3, 0.5, 30, TrackState::Coasting)).command, DriveCommand::Right);
  EXPECT_EQ(robot.update(unseen(1.499)).command, DriveCommand::Right);
  out = robot.update(unseen(1.5));  // exactly lost-timeout after the last confirmed target
  EXPECT_EQ(out.command, DriveCommand::Stop);
  EXPECT_DOUBLE_EQ(out.left, 0.0);
  EXPECT_EQ(robot.update(unseen(5.0)).command, DriveCommand::Stop);
  // Back again: the zone controller starts from the centre zone.
  EXPECT_EQ(robot.update(seen(5.1, 0.08, 72)).command, DriveCommand::Stop);
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
  // The new gain applies: an offset of 0.2 turns at -3 * (0.2 - 0.1) = -0.3, from 0 at 4/s: -0.3 in 0.1 s.
  out = robot.update(seen(0.3, 0.2, 24));
  EXPECT_NEAR(out.angular, -0.3, 1e-12);
  EXPECT_NEAR(out.linear, 0.5, 1e-12);  // max-linear

  // A lower limit applies at once (the clamp), the ramp state is not reset: 0.5 -> 0.3 within 0.1 s at 2/s.
  c.maxLinear = 0.3;
  robot.setSettings(c, f);
  EXPECT_NEAR(robot.update(seen(0.4, 0.0, 24)).linear, 0.3, 1e-12);

  // The lost-target hold survives a settings change, and the new lost-timeout counts from the last
  // confirmed target (0.4 s).
  f.lostTimeout = 0.3;
  robot.setSettings(c, f);
  out = robot.update(unseen(0.6));
  EXPECT_NEAR(out.linear, 0.3, 1e-12);  // held
  EXPECT_FALSE(out.targetVisible);
  EXPECT_EQ(robot.update(unseen(0.75)).command, DriveCommand::Stop);
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

}  // namespace
}  // namespace colortrack
