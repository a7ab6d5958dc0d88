// Robot following: from where the target is in the frame to drive commands for a differential-drive base.
// Pure logic (no I/O, no clock): every input, including the time, is given by the caller, so the
// behaviour is exactly reproducible in tests.
//
// Conventions: the horizontal offset is (target centre - frame centre) / (frame width / 2), in [-1, 1],
// positive when the target is right of centre. Outputs are fractions of full scale in [-1, 1]: linear > 0
// drives forward, angular > 0 turns left (counter-clockwise seen from above), and the wheel speeds are
// left = linear - angular, right = linear + angular (scaled down together if either exceeds 1).
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/track.hpp"

namespace colortrack {

// The five commands of the zone controller; the proportional controller's output is named by the one it
// is closest to (see classifyCommand).
enum class DriveCommand { Stop, Forward, Backward, Left, Right };
const char *toString(DriveCommand command);

enum class ControllerKind { Zone, Proportional };
const char *toString(ControllerKind kind);

// What says how far away the target is.
enum class DistanceCue {
  Size,      // box height / frame height: a closer target looks bigger
  Position,  // box bottom / frame height: on a flat floor a closer target sits lower in the image
};

// One frame's view of the target.
struct Observation {
  std::optional<cv::Rect2d> box;  // pixels; none when nothing is tracked
  TrackState state = TrackState::Tracking;
  double score = 1.0;
  cv::Size frameSize;
  double time = 0;  // seconds, monotonic
};

struct ControllerSettings {
  ControllerKind kind = ControllerKind::Zone;
  DistanceCue distanceCue = DistanceCue::Size;
  double setPoint = 0.3;          // wanted distance cue (fraction of the frame height)
  double turnDeadband = 0.1;      // |offset| below which the target counts as centred
  double distanceDeadband = 0.1;  // |relative distance error| below which the distance counts as right
  double hysteresis = 0.05;       // zone: a border zone is left only once this far inside the deadband
  double turnGain = 1.5;          // proportional: angular per unit offset
  double driveGain = 1.5;         // proportional: linear per unit relative distance error
  double maxLinear = 0.5;         // output limits, also the zone controller's speeds
  double maxAngular = 0.3;
  double maxLinearAccel = 2.0;  // slew limits per second (proportional; 0 = unlimited)
  double maxAngularAccel = 4.0;
};

struct FailsafeSettings {
  double lostTimeout = 0.5;   // seconds without a confirmed target before stopping
  double minScore = 0.0;      // a lower score counts as no target
  bool searchTurn = false;    // after the timeout turn slowly towards where the target was last seen
  double searchSpeed = 0.15;  // angular of the search turn
};

struct DriveOutput {
  DriveCommand command = DriveCommand::Stop;
  double linear = 0, angular = 0;
  double left = 0, right = 0;
  bool targetVisible = false;  // a confirmed target drove this decision
};

// Horizontal offset and relative distance error of a box (see the conventions above); error > 0 = too far.
double horizontalOffset(const cv::Rect2d &box, cv::Size frame);
double distanceCue(const cv::Rect2d &box, cv::Size frame, DistanceCue cue);
double distanceError(const cv::Rect2d &box, cv::Size frame, DistanceCue cue, double setPoint);

// Wheel speeds from linear/angular, scaled down together so neither exceeds 1 (the turn is kept).
void toWheels(double linear, double angular, double &left, double &right);
// A complete output for linear/angular, its command named by the larger of the two motions.
DriveOutput makeOutput(double linear, double angular, bool targetVisible);
DriveCommand classifyCommand(double linear, double angular);

// The paper's controller: the frame is split into left/centre/right by the offset and into
// too-far/right/too-close by the distance cue; turning comes before distance so the target stays in view.
// Each axis is a Schmitt trigger: a side zone is entered beyond the deadband and left only once the error
// is `hysteresis` inside it, so a target on a border does not make the command chatter.
class ZoneController {
 public:
  explicit ZoneController(const ControllerSettings &settings) : settings_(settings) {}
  DriveOutput update(double offset, double distanceError);
  void reset() { turnZone_ = 0, distanceZone_ = 0; }
  // New limits from the next update; the zones (the hysteresis state) are kept.
  void setSettings(const ControllerSettings &settings) { settings_ = settings; }

 private:
  static int nextZone(int zone, double error, double enter, double leave);
  ControllerSettings settings_;
  int turnZone_ = 0;      // -1 target left, 0 centred, +1 target right
  int distanceZone_ = 0;  // -1 too close, 0 right, +1 too far
};

// The control law: angular = -turnGain * offset, linear = driveGain * distance error, each with its
// deadband taken off (continuous at the deadband's edge), clamped to the limits and slew-limited.
class ProportionalController {
 public:
  explicit ProportionalController(const ControllerSettings &settings) : settings_(settings) {}
  // dt: seconds since the previous update (the slew limit allows accel * dt of change).
  DriveOutput update(double offset, double distanceError, double dt);
  // Starts again from standstill (after a stop, the slew limit ramps up from zero).
  void reset() { linear_ = 0, angular_ = 0; }
  // New gains and limits from the next update; the current speeds (the slew state) are kept.
  void setSettings(const ControllerSettings &settings) { settings_ = settings; }

 private:
  ControllerSettings settings_;
  double linear_ = 0, angular_ = 0;
};

// No-target timing, from given times: has there been a confirmed target within the timeout?
class Watchdog {
 public:
  explicit Watchdog(double timeout) : timeout_(timeout) {}
  void feed(double now) { last_ = now; }
  void clear() { last_.reset(); }
  // True when never fed or the last feed is `timeout` or more ago.
  bool expired(double now) const { return !last_ || now - *last_ >= timeout_; }
  // Applies to the time since the last feed, which is kept.
  void setTimeout(double timeout) { timeout_ = timeout; }

 private:
  double timeout_;
  std::optional<double> last_;
};

// The controller and the failsafe together: one decision per frame.
//  - a confirmed target (a box, state tracking, score >= minScore) drives the controller;
//  - without one, the last decision is held until lostTimeout after the last confirmed target, then the
//    robot stops (or turns slowly towards where the target was last seen, with searchTurn).
class RobotController {
 public:
  RobotController(const ControllerSettings &controller, const FailsafeSettings &failsafe);
  // New settings from the next update, keeping the dynamic state: the slew-limited speeds, the zones, the
  // last decision and when the target was last confirmed (a held command stays held). A change of
  // `controller.kind` starts both controllers from standstill (the idle one's state is stale).
  void setSettings(const ControllerSettings &controller, const FailsafeSettings &failsafe);
  DriveOutput update(const Observation &observation);
  bool confirmed(const Observation &observation) const;
  void reset();

 private:
  DriveOutput failsafeOutput() const;
  ControllerSettings settings_;
  FailsafeSettings failsafe_;
  ZoneController zone_;
  ProportionalController proportional_;
  Watchdog watchdog_;
  std::optional<double> lastTime_;
  DriveOutput last_;
  double lastOffset_ = 0;
};

}  // namespace colortrack
