#include "colortrack/controller.hpp"

#include <algorithm>
#include <cmath>

namespace colortrack {

namespace {

// The error beyond the deadband: zero inside it and continuous at its edge, so the output does not jump.
double beyondDeadband(double error, double deadband) {
  const double magnitude = std::max(0.0, std::abs(error) - deadband);
  return std::copysign(magnitude, error);
}

// Moves `current` towards `target` by at most rate * dt (rate 0 = no limit).
double slew(double current, double target, double rate, double dt) {
  if (rate <= 0) return target;
  const double step = rate * std::max(0.0, dt);
  return current + std::clamp(target - current, -step, step);
}

}  // namespace

const char *toString(DriveCommand command) {
  switch (command) {
    case DriveCommand::Forward:
      return "forward";
    case DriveCommand::Backward:
      return "backward";
    case DriveCommand::Left:
      return "left";
    case DriveCommand::Right:
      return "right";
    case DriveCommand::Stop:
      break;
  }
  return "stop";
}

const char *toString(ControllerKind kind) {
  return kind == ControllerKind::Zone ? "zone" : "proportional";
}

double horizontalOffset(const cv::Rect2d &box, cv::Size frame) {
  const double half = frame.width / 2.0;
  return (box.x + box.width / 2.0 - half) / half;
}

double distanceCue(const cv::Rect2d &box, cv::Size frame, DistanceCue cue) {
  const double extent = cue == DistanceCue::Size ? box.height : box.y + box.height;
  return extent / frame.height;
}

double distanceError(const cv::Rect2d &box, cv::Size frame, DistanceCue cue, double setPoint) {
  // Relative, so the same deadband and gain mean the same at any set-point; > 0 when the target looks
  // smaller (or higher) than wanted, i.e. too far.
  return (setPoint - distanceCue(box, frame, cue)) / setPoint;
}

void toWheels(double linear, double angular, double &left, double &right) {
  left = linear - angular;
  right = linear + angular;
  const double largest = std::max(std::abs(left), std::abs(right));
  if (largest > 1.0) {
    left /= largest;
    right /= largest;
  }
}

DriveCommand classifyCommand(double linear, double angular) {
  constexpr double kStill = 1e-9;
  if (std::abs(linear) < kStill && std::abs(angular) < kStill) return DriveCommand::Stop;
  if (std::abs(angular) > std::abs(linear)) return angular > 0 ? DriveCommand::Left : DriveCommand::Right;
  return linear > 0 ? DriveCommand::Forward : DriveCommand::Backward;
}

DriveOutput makeOutput(double linear, double angular, bool targetVisible) {
  DriveOutput out;
  out.command = classifyCommand(linear, angular);
  out.linear = linear;
  out.angular = angular;
  toWheels(linear, angular, out.left, out.right);
  out.targetVisible = targetVisible;
  return out;
}

// ---------------------------------------------------------------------------------------------------------

int ZoneController::nextZone(int zone, double error, double enter, double leave) {
  if (error > enter) return 1;
  if (error < -enter) return -1;
  // Inside the entry band: a side zone is kept until the error is well inside (the hysteresis).
  if (zone == 1 && error > leave) return 1;
  if (zone == -1 && error < -leave) return -1;
  return 0;
}

DriveOutput ZoneController::update(double offset, double distanceError) {
  const ControllerSettings &s = settings_;
  turnZone_ = nextZone(turnZone_, offset, s.turnDeadband, std::max(0.0, s.turnDeadband - s.hysteresis));
  distanceZone_ = nextZone(distanceZone_, distanceError, s.distanceDeadband,
                           std::max(0.0, s.distanceDeadband - s.hysteresis));

  DriveOutput out;
  // Turning first: driving towards an off-centre target would lose it from the side of the frame.
  if (turnZone_ != 0) {
    out = makeOutput(0, turnZone_ > 0 ? -s.maxAngular : s.maxAngular, true);
    out.command = turnZone_ > 0 ? DriveCommand::Right : DriveCommand::Left;
  } else if (distanceZone_ != 0) {
    out = makeOutput(distanceZone_ > 0 ? s.maxLinear : -s.maxLinear, 0, true);
    out.command = distanceZone_ > 0 ? DriveCommand::Forward : DriveCommand::Backward;
  } else {
    out = makeOutput(0, 0, true);
  }
  return out;
}

DriveOutput ProportionalController::update(double offset, double distanceError, double dt) {
  const ControllerSettings &s = settings_;
  const double angularTarget =
      std::clamp(-s.turnGain * beyondDeadband(offset, s.turnDeadband), -s.maxAngular, s.maxAngular);
  const double linearTarget =
      std::clamp(s.driveGain * beyondDeadband(distanceError, s.distanceDeadband), -s.maxLinear, s.maxLinear);
  linear_ = slew(linear_, linearTarget, s.maxLinearAccel, dt);
  angular_ = slew(angular_, angularTarget, s.maxAngularAccel, dt);
  return makeOutput(linear_, angular_, true);
}

// ---------------------------------------------------------------------------------------------------------

RobotController::RobotController(const ControllerSettings &controller, const FailsafeSettings &failsafe)
    : settings_(controller),
      failsafe_(failsafe),
      zone_(controller),
      proportional_(controller),
      watchdog_(failsafe.lostTimeout) {}

void RobotController::setSettings(const ControllerSettings &controller, const FailsafeSettings &failsafe) {
  if (controller.kind != settings_.kind) {
    zone_.reset();
    proportional_.reset();
  }
  settings_ = controller;
  failsafe_ = failsafe;
  zone_.setSettings(controller);
  proportional_.setSettings(controller);
  watchdog_.setTimeout(failsafe.lostTimeout);
}

bool RobotController::confirmed(const Observation &o) const {
  return o.box && o.box->width > 0 && o.box->height > 0 && !o.frameSize.empty() &&
         o.state == TrackState::Tracking && o.score >= failsafe_.minScore;
}

void RobotController::reset() {
  zone_.reset();
  proportional_.reset();
  watchdog_.clear();
  lastTime_.reset();
  last_ = DriveOutput();
  lastOffset_ = 0;
}

DriveOutput RobotController::failsafeOutput() const {
  if (!failsafe_.searchTurn) return DriveOutput();
  // Towards the side where the target was last seen (offset > 0: right, a negative angular).
  return makeOutput(0, lastOffset_ > 0 ? -failsafe_.searchSpeed : failsafe_.searchSpeed, false);
}

DriveOutput RobotController::update(const Observation &o) {
  const double dt = lastTime_ ? std::max(0.0, o.time - *lastTime_) : 0.0;
  lastTime_ = o.time;

  if (confirmed(o)) {
    watchdog_.feed(o.time);
    const double offset = horizontalOffset(*o.box, o.frameSize);
    const double error = distanceError(*o.box, o.frameSize, settings_.distanceCue, settings_.setPoint);
    last_ = settings_.kind == ControllerKind::Zone ? zone_.update(offset, error)
                                                   : proportional_.update(offset, error, dt);
    lastOffset_ = offset;
    return last_;
  }

  if (!watchdog_.expired(o.time)) {
    // A short dropout (a coasting track, one bad frame): keep going as decided.
    DriveOutput held = last_;
    held.targetVisible = false;
    return held;
  }

  // Lost: stop, and start from standstill (slew) and the centre zones (hysteresis) when it comes back.
  zone_.reset();
  proportional_.reset();
  last_ = failsafeOutput();
  return last_;
}

}  // namespace colortrack
