// SPDX-License-Identifier: LGPL-2.1-or-later
// Robot following: from where the target is in the frame to drive commands for a differential-drive base.
// Pure logic (no I/O, no clock): every input, including the time, is given by the caller, so the
// behaviour is exactly reproducible in tests.
//
// Conventions: the horizontal offset is (target centre - frame centre) / (frame width / 2), in [-1, 1],
// positive when the target is right of centre; the vertical offset is measured in the same unit (half the
// frame width, so both are the same angle per unit with square pixels), positive when the target is below.
// Outputs are fractions of full scale in [-1, 1]: linear > 0 drives forward, angular > 0 turns left
// (counter-clockwise seen from above), and the wheel speeds are left = linear - angular, right = linear +
// angular (scaled down together if either exceeds 1).
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/choice.hpp"
#include "colortrack/track.hpp"

namespace colortrack {

// The five commands of the zone controller; the proportional controller's output is named by the one it
// is closest to (see classifyCommand).
enum class DriveCommand { Stop, Forward, Backward, Left, Right };
const char *toString(DriveCommand command);

// Auto: the law that suits the axes (lawFor).
enum class ControllerKind { Zone, Proportional, Auto };
inline constexpr Choice<ControllerKind> kControllerKinds[] = {
    {ControllerKind::Zone, "zone", "Forward/backward/left/right/stop by frame zone"},
    {ControllerKind::Proportional, "proportional", "Wheel speeds proportional to the errors"},
    {ControllerKind::Auto, "auto", "Zone for a robot or a drone, proportional for a gimbal"},
};
const char *toString(ControllerKind kind);

// What the proportional controller moves: a base that turns and drives (a robot, a drone), or a camera that
// pans and tilts (a gimbal: the turn's gains also tilt, nothing drives).
enum class ControlAxes { TurnDrive, PanTilt };

// Whether a law can move these axes: the zone law cannot move a gimbal (its commands are one motion at a
// time at a fixed speed: a gimbal must pan and tilt together, at a rate that falls as it centres).
bool lawFits(ControllerKind kind, ControlAxes axes);
// The law that runs: Auto is the zone law for a base (the paper's) and the proportional one for a gimbal;
// a law that does not fit (see lawFits) falls back to the proportional one.
ControllerKind lawFor(ControllerKind kind, ControlAxes axes);

// What says how far away the target is.
enum class DistanceCue {
  Size,      // box height / frame height: a closer target looks bigger
  Position,  // box bottom / frame height: on a flat floor a closer target sits lower in the image
};
inline constexpr Choice<DistanceCue> kDistanceCues[] = {
    {DistanceCue::Size, "size", "Box height / frame height"},
    {DistanceCue::Position, "position", "Box bottom / frame height"},
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
  ControllerKind kind = ControllerKind::Auto;
  ControlAxes axes = ControlAxes::TurnDrive;  // PanTilt: always proportional (lawFor)
  DistanceCue distanceCue = DistanceCue::Size;
  double setPoint = 0.3;  // wanted distance cue (fraction of the frame height)
  // Instead of setPoint, the distance cue of the first confirmed target (after start, a reset, or this
  // turning on): the distance the robot was at when tracking began is kept, whatever share of the object
  // the box covers (a box drawn inside it, a click's square), as follow-me drones do.
  bool setPointAtStart = false;
  double turnDeadband = 0.1;      // |offset| below which the target counts as centred
  double distanceDeadband = 0.1;  // |relative distance error| below which the distance counts as right
  double hysteresis = 0.07;       // zone: a border zone is left only once this far inside the deadband
  // Proportional: angular per unit offset, linear per unit relative distance error (the P terms).
  double turnGain = 0.6;
  double driveGain = 2.0;
  // Proportional: the I terms, per second of error (they remove what the P terms leave: the lag behind a
  // moving target, a robot that turns or drives slower than commanded).
  double turnIntegralGain = 0.6;
  double driveIntegralGain = 1.0;
  // Proportional: the terms on how fast each error changes (per second), i.e. on the target's motion
  // relative to the robot: they start following as soon as the target moves and damp the approach.
  double turnRateGain = 0.05;
  double driveRateGain = 0.3;
  double maxLinear = 0.5;  // output limits, also the zone controller's speeds
  double maxAngular = 0.3;
  double maxLinearAccel = 2.0;  // slew limits per second (proportional; 0 = unlimited)
  double maxAngularAccel = 4.0;
  // Zone: seconds from a decision to the wheels (serial link, command period, firmware, motors). A turn
  // ends this much early (the offset's rate tells how far the robot still turns) and, near the centre,
  // turns are single decisions each followed by this long without a turn to see where they led. 0: the
  // paper's controller exactly.
  double latency = 0.1;
};

struct FailsafeSettings {
  double lostTimeout = 0.5;   // seconds without a confirmed target before the target is lost
  double minScore = 0.0;      // a lower score counts as no target
  bool searchTurn = false;    // after the timeout turn slowly towards where the target was last seen
  double searchSpeed = 0.15;  // angular of the search turn
};

struct DriveOutput {
  DriveCommand command = DriveCommand::Stop;
  double linear = 0, angular = 0;
  double tilt = 0;  // PanTilt: > 0 tilts up (the command names the pan alone)
  double left = 0, right = 0;
  bool targetVisible = false;  // a confirmed target drove this decision
};

// Nothing moves: stop, and no tilt either.
bool isStill(const DriveOutput &output);
// The same drive (forward or backward speed) with no turn and no tilt: what is held while the decision's
// ground is gone (a coasting target, a stalled stream), since a held turn swings the camera off the target.
DriveOutput withoutTurn(const DriveOutput &output);

// The share of lost-timeout for which a drive is held without a fresh decision: no confirmed target
// (RobotController), or no buffer at all (robotctl's writer). Then the robot stands still.
constexpr double kDriveHoldShare = 0.5;

// Horizontal offset and relative distance error of a box (see the conventions above); error > 0 = too far.
double horizontalOffset(const cv::Rect2d &box, cv::Size frame);
double verticalOffset(const cv::Rect2d &box, cv::Size frame);
double distanceCue(const cv::Rect2d &box, cv::Size frame, DistanceCue cue);
double distanceError(const cv::Rect2d &box, cv::Size frame, DistanceCue cue, double setPoint);

// One frame's errors (see above) and how fast they change, per second (0 when not known yet).
struct Errors {
  double offset = 0, distance = 0;
  double offsetRate = 0, distanceRate = 0;
  double vertical = 0, verticalRate = 0;  // the vertical offset (PanTilt)
};

// Wheel speeds from linear/angular, scaled down together so neither exceeds 1 (the turn is kept).
void toWheels(double linear, double angular, double &left, double &right);
// A complete output for linear/angular, its command named by the larger of the two motions.
DriveOutput makeOutput(double linear, double angular, bool targetVisible);
DriveCommand classifyCommand(double linear, double angular);

}  // namespace colortrack
