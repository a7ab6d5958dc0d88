// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/controller.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colortrack {

namespace {

// The error half a second ahead at its current rate: tells a target that moves off (away from the
// set-point) from one that stands, before the error itself does.
double errorAhead(double error, double rate) {
  constexpr double kHorizon = 0.5;  // s
  return error + rate * kHorizon;
}

// Moves `current` towards `target` by at most rate * dt (rate 0 = no limit).
double slew(double current, double target, double rate, double dt) {
  if (rate <= 0) return target;
  const double step = rate * std::max(0.0, dt);
  return current + std::clamp(target - current, -step, step);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------

int ZoneController::nextZone(int zone, double error, double enter, double leave) {
  if (error > enter) return 1;
  if (error < -enter) return -1;
  // Inside the entry band: a side zone is kept until the error is well inside (the hysteresis).
  if (zone == 1 && error > leave) return 1;
  if (zone == -1 && error < -leave) return -1;
  return 0;
}

DriveOutput ZoneController::turn(int zone) const {
  DriveOutput out = makeOutput(0, zone > 0 ? -settings_.maxAngular : settings_.maxAngular, true);
  out.command = zone > 0 ? DriveCommand::Right : DriveCommand::Left;
  return out;
}

DriveOutput ZoneController::update(const Errors &e, double now) {
  const ControllerSettings &s = settings_;
  const double frame = lastNow_ ? std::max(0.0, now - *lastNow_) : 0.0;
  lastNow_ = now;
  const double turnLeave = std::max(0.0, s.turnDeadband - s.hysteresis);
  turnZone_ = nextZone(turnZone_, e.offset, s.turnDeadband, turnLeave);
  // The distance zone is entered on the error a moment ahead: a target moving away (or closer) is met
  // before it leaves the deadband, not trailed at its edge.
  const double distanceLeave = std::max(0.0, s.distanceDeadband - s.hysteresis);
  const double distanceAhead = errorAhead(e.distance, e.distanceRate);
  distanceZone_ = nextZone(distanceZone_, e.distance, s.distanceDeadband, distanceLeave);
  if (distanceZone_ == 0 && std::abs(e.distance) > distanceLeave) {
    const int ahead = nextZone(0, distanceAhead, s.distanceDeadband, distanceLeave);
    if (ahead * e.distance > 0) distanceZone_ = ahead;  // never away from where the target is now
  }

  // Turning first: driving towards an off-centre target would lose it from the side of the frame.
  bool turning = turnZone_ != 0;
  if (turning && s.latency > 0) {
    if (now < holdUntil_) {
      // The last turn's effect is not seen yet: no turn (it would overshoot), but the target is near the
      // centre, so the distance may be corrected meanwhile.
      turning = false;
    } else {
      // The offset where the robot will have stopped if it stops now: still turning for the latency.
      const double predicted = e.offset + e.offsetRate * s.latency;
      const bool near = std::abs(e.offset) < 2 * s.turnDeadband;
      if (near || turnZone_ * predicted < turnLeave) {
        // One decision's turn near the centre (no turn where the prediction says it would overshoot),
        // then no turn for the latency and the next frame (the first to show where it led; half a frame
        // here, so that times rounded to the frame period do not add or drop one).
        holdUntil_ = now + s.latency + frame / 2;
        turning = near;
      }
    }
  }
  if (turning) return turn(turnZone_);
  if (distanceZone_ != 0) {
    DriveOutput out = makeOutput(distanceZone_ > 0 ? s.maxLinear : -s.maxLinear, 0, true);
    out.command = distanceZone_ > 0 ? DriveCommand::Forward : DriveCommand::Backward;
    return out;
  }
  return makeOutput(0, 0, true);
}

double PiAxis::update(const Gains &g, double error, double rate, double dt) {
  dt = std::max(0.0, dt);
  // Arrived: stop rather than creep at a speed the motors cannot hold; go again once the error grows, or
  // once the error a moment ahead does (a target moving off while the robot stands). The integral is kept
  // while arrived: a target that moves on the same way again (one being followed) is met at the speed it
  // needed, not trailed by half the deadband while the integral builds up anew; one that moves the other
  // way clears it.
  const double ahead = errorAhead(error, rate);
  const bool movingOff = error * ahead > 0 && std::abs(ahead) > g.deadband / 2;
  if (arrived_ && (std::abs(error) > g.deadband / 2 || (movingOff && std::abs(error) > g.deadband / 4))) {
    arrived_ = false;
    if (integral_ * error < 0) integral_ = 0;
  }
  if (!arrived_ && std::abs(error) < g.deadband / 4) arrived_ = true;
  double target = 0;
  if (!arrived_) {
    const double integral = integral_ + error * dt;
    const double wanted = g.p * error + g.i * integral + g.rate * rate;
    target = std::clamp(wanted, -g.limit, g.limit);
    const double step = g.accel > 0 ? g.accel * dt : std::numeric_limits<double>::infinity();
    // Anti-windup: no integration while the output is held back (clamp or slew limit) in the direction
    // the error pushes, or the integral would grow during the saturation and overshoot afterwards.
    const bool clamped = wanted != target && (wanted > 0) == (error > 0);
    const bool slewing = std::abs(target - output_) > step && (target > output_) == (error > 0);
    if (!clamped && !slewing) integral_ = integral;
    // The I term alone never asks for more than the limit.
    if (g.i > 0) integral_ = std::clamp(integral_, -g.limit / g.i, g.limit / g.i);
    target = std::clamp(g.p * error + g.i * integral_ + g.rate * rate, -g.limit, g.limit);
  }
  output_ = slew(output_, target, g.accel, dt);
  return output_;
}

DriveOutput ProportionalController::update(const Errors &e, double dt) {
  const ControllerSettings &s = settings_;
  const PiAxis::Gains turn{s.turnGain,     s.turnIntegralGain, s.turnRateGain,
                           s.turnDeadband, s.maxAngular,       s.maxAngularAccel};
  const PiAxis::Gains drive{s.driveGain,        s.driveIntegralGain, s.driveRateGain,
                            s.distanceDeadband, s.maxLinear,         s.maxLinearAccel};
  // Offset > 0 (target right) turns right: a negative angular.
  const double angular = -turn_.update(turn, e.offset, e.offsetRate, dt);
  if (s.axes == ControlAxes::PanTilt) {
    // Vertical > 0 (target below) tilts down; the same gains and limits as the pan.
    DriveOutput out = makeOutput(0, angular, true);
    out.tilt = -tilt_.update(turn, e.vertical, e.verticalRate, dt);
    return out;
  }
  const double linear = drive_.update(drive, e.distance, e.distanceRate, dt);
  return makeOutput(linear, angular, true);
}

// ---------------------------------------------------------------------------------------------------------

RobotController::RobotController(const ControllerSettings &controller, const FailsafeSettings &failsafe)
    : settings_(controller),
      failsafe_(failsafe),
      zone_(controller),
      proportional_(controller),
      watchdog_(failsafe.lostTimeout) {}

void RobotController::setSettings(const ControllerSettings &controller, const FailsafeSettings &failsafe) {
  if (lawFor(controller.kind, controller.axes) != lawFor(settings_.kind, settings_.axes) ||
      controller.axes != settings_.axes) {
    zone_.reset();
    proportional_.reset();
  }
  if (controller.setPointAtStart != settings_.setPointAtStart) startCue_.reset();
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
  lastErrors_.reset();
  startCue_.reset();
}

double RobotController::setPointFor(const Observation &confirmed) {
  if (!settings_.setPointAtStart) return settings_.setPoint;
  // Within set-point's own range: a box filling the frame (or a sliver) at the start must not stand for an
  // impossible distance.
  if (!startCue_)
    startCue_ =
        std::clamp(distanceCue(*confirmed.box, confirmed.frameSize, settings_.distanceCue), 0.01, 1.0);
  return *startCue_;
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
    Errors e;
    e.offset = horizontalOffset(*o.box, o.frameSize);
    e.distance = distanceError(*o.box, o.frameSize, settings_.distanceCue, setPointFor(o));
    e.vertical = verticalOffset(*o.box, o.frameSize);
    if (lastErrors_ && dt > 0) {
      // Rates by differences, smoothed over ~0.1 s: the boxes come rounded to whole pixels.
      constexpr double kSmoothing = 0.1;  // s
      const double a = dt / (dt + kSmoothing);
      e.offsetRate =
          lastErrors_->offsetRate + a * ((e.offset - lastErrors_->offset) / dt - lastErrors_->offsetRate);
      e.distanceRate = lastErrors_->distanceRate +
                       a * ((e.distance - lastErrors_->distance) / dt - lastErrors_->distanceRate);
      e.verticalRate = lastErrors_->verticalRate +
                       a * ((e.vertical - lastErrors_->vertical) / dt - lastErrors_->verticalRate);
    } else if (lastErrors_) {
      e.offsetRate = lastErrors_->offsetRate, e.distanceRate = lastErrors_->distanceRate;
      e.verticalRate = lastErrors_->verticalRate;
    }
    lastErrors_ = e;
    const bool zone = lawFor(settings_.kind, settings_.axes) == ControllerKind::Zone;
    last_ = zone ? zone_.update(e, o.time) : proportional_.update(e, dt);
    lastOffset_ = e.offset;
    return last_;
  }
  // The rates are of a continuous view of the target.
  lastErrors_.reset();

  if (!watchdog_.expired(o.time)) {
    // A short dropout (a coasting track, one bad frame): keep driving as decided, but do not turn. The track
    // coasts where the target was last seen, and a turn held for lost-timeout swings the camera off a
    // target that did not move, or onto a same-coloured object crossing it; the next confirmed frame turns
    // again if it must. (The turn axis starts from standstill then, as the robot does.) The drive is held for
    // half of lost-timeout only: a box that shrank as something covered the target asked for "forward" on
    // its last confirmed frame, and driving blind for all of it closed 20 % of the distance (issue 25).
    proportional_.stopTurning();
    if (!watchdog_.within(o.time, kDriveHoldShare)) {
      // The hold is over: stand still until confirmed again, then start from standstill (the slew limit
      // ramps the drive up from zero; a target back nearer than wanted is not driven at), and keep still
      // if lost-timeout is raised meanwhile.
      last_ = DriveOutput();
      proportional_.reset();
    }
    DriveOutput held = withoutTurn(last_);
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
