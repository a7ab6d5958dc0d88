// SPDX-License-Identifier: LGPL-2.1-or-later
// Robot following: the control laws (zone, proportional) and the controller that runs one with its failsafe.
// Pure logic (no I/O, no clock): every input, including the time, is given by the caller, so the
// behaviour is exactly reproducible in tests. The conventions, settings and outputs they share: drive.hpp.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/choice.hpp"
#include "colortrack/drive.hpp"
#include "colortrack/track.hpp"

namespace colortrack {

// The paper's controller: the frame is split into left/centre/right by the offset and into
// too-far/right/too-close by the distance cue; turning comes before distance so the target stays in view.
// Each axis is a Schmitt trigger: a side zone is entered beyond the deadband and left only once the error
// is `hysteresis` inside it, so a target on a border does not make the command chatter. The distance zone
// is also entered once the error half a second ahead (at its rate) is beyond the deadband on the side the
// error already lies: a target moving away is met, not trailed at the deadband's edge.
// With a latency (settings.latency > 0) a turn at full speed would overshoot the centre by the distance
// turned during the latency, and the next turn overshoot back: so a turn ends once the offset predicted a
// latency ahead is inside, and within twice the deadband of the centre the robot turns one decision at a
// time, each followed by no turn for the latency and a frame (the turn's average speed falls near the
// centre); meanwhile the distance zone drives.
class ZoneController {
 public:
  explicit ZoneController(const ControllerSettings &settings) : settings_(settings) {}
  // now: seconds, monotonic (the pulses' timing).
  DriveOutput update(const Errors &errors, double now);
  void reset() { turnZone_ = 0, distanceZone_ = 0, holdUntil_ = -1e300, lastNow_.reset(); }
  // New limits from the next update; the zones (the hysteresis state) are kept.
  void setSettings(const ControllerSettings &settings) { settings_ = settings; }

 private:
  static int nextZone(int zone, double error, double enter, double leave);
  DriveOutput turn(int zone) const;
  ControllerSettings settings_;
  int turnZone_ = 0;           // -1 target left, 0 centred, +1 target right
  int distanceZone_ = 0;       // -1 too close, 0 right, +1 too far
  double holdUntil_ = -1e300;  // no turn before this time: the last turn's effect is not seen yet
  std::optional<double> lastNow_;
};

// One axis of the proportional controller: P + I + rate terms, the integrator frozen while the output is
// limited (by the clamp or the slew limit) in the error's direction.
// An axis arrives (output 0, no creeping) when its error is within a quarter of the deadband and starts
// again once the error leaves half of it, or leaves a quarter while the error half a second ahead (at its
// rate) is beyond half: the target moves off. The integral is kept while arrived and cleared on starting
// again only if it pushes the other way, so a target being followed is met at the speed it needed.
class PiAxis {
 public:
  struct Gains {
    double p = 0, i = 0, rate = 0;
    double deadband = 0, limit = 0, accel = 0;  // accel 0: no slew limit
  };
  double update(const Gains &gains, double error, double rate, double dt);
  void reset() { output_ = 0, integral_ = 0, arrived_ = false; }
  double integral() const { return integral_; }

 private:
  double output_ = 0, integral_ = 0;
  bool arrived_ = false;
};

// The control law: angular = -(turn terms on the offset), linear = drive terms on the distance error,
// clamped to the limits and slew-limited (see PiAxis). PanTilt: tilt = -(turn terms on the vertical
// offset) instead of the drive.
class ProportionalController {
 public:
  explicit ProportionalController(const ControllerSettings &settings) : settings_(settings) {}
  // dt: seconds since the previous update (the slew limit allows accel * dt of change).
  DriveOutput update(const Errors &errors, double dt);
  // Starts again from standstill (after a stop, the slew limit ramps up from zero, integrators empty).
  void reset() { turn_.reset(), drive_.reset(), tilt_.reset(); }
  // The turn (and the tilt) were stopped while the drive goes on: those axes start from standstill.
  void stopTurning() { turn_.reset(), tilt_.reset(); }
  // New gains and limits from the next update; the current speeds and integrators are kept.
  void setSettings(const ControllerSettings &settings) { settings_ = settings; }
  const PiAxis &turnAxis() const { return turn_; }
  const PiAxis &driveAxis() const { return drive_; }

 private:
  ControllerSettings settings_;
  PiAxis turn_, drive_, tilt_;
};

// No-target timing, from given times: has there been a confirmed target within the timeout?
class Watchdog {
 public:
  explicit Watchdog(double timeout) : timeout_(timeout) {}
  void feed(double now) { last_ = now; }
  void clear() { last_.reset(); }
  // True when never fed or the last feed is `timeout` or more ago.
  bool expired(double now) const { return !last_ || now - *last_ >= timeout_; }
  // True when fed within `share` of the timeout (share in [0, 1]).
  bool within(double now, double share) const { return last_ && now - *last_ < share * timeout_; }
  // Applies to the time since the last feed, which is kept.
  void setTimeout(double timeout) { timeout_ = timeout; }

 private:
  double timeout_;
  std::optional<double> last_;
};

// The controller and the failsafe together: one decision per frame.
//  - a confirmed target (a box, state tracking, score >= minScore) drives the controller;
//  - without one, the last decision's drive (linear speed) is held, without its turn or tilt, for half of
//    lostTimeout after the last confirmed target; the robot then stands still, and at lostTimeout it is
//    lost: it stays stopped (or turns slowly towards where the target was last seen, with searchTurn). A
//    target confirmed again after the hold is driven from standstill.
class RobotController {
 public:
  RobotController(const ControllerSettings &controller, const FailsafeSettings &failsafe);
  // New settings from the next update, keeping the dynamic state: the slew-limited speeds, the zones, the
  // last decision and when the target was last confirmed (a held command stays held). A change of
  // `controller.kind` or `axes` starts both controllers from standstill (the idle one's state is stale).
  void setSettings(const ControllerSettings &controller, const FailsafeSettings &failsafe);
  DriveOutput update(const Observation &observation);
  bool confirmed(const Observation &observation) const;
  void reset();

 private:
  DriveOutput failsafeOutput() const;
  double setPointFor(const Observation &confirmed);
  ControllerSettings settings_;
  FailsafeSettings failsafe_;
  ZoneController zone_;
  ProportionalController proportional_;
  Watchdog watchdog_;
  std::optional<double> lastTime_;
  DriveOutput last_;
  double lastOffset_ = 0;
  // The errors of the previous confirmed frame and their smoothed rates (cleared when the target is lost).
  std::optional<Errors> lastErrors_;
  std::optional<double> startCue_;  // setPointAtStart: the first confirmed target's distance cue
};

}  // namespace colortrack
