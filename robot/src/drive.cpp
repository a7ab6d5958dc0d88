// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/drive.hpp"

#include <algorithm>
#include <cmath>

namespace colortrack {

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
  return nickOf(kControllerKinds, kind);
}

bool lawFits(ControllerKind kind, ControlAxes axes) {
  return !(kind == ControllerKind::Zone && axes == ControlAxes::PanTilt);
}

ControllerKind lawFor(ControllerKind kind, ControlAxes axes) {
  if (axes == ControlAxes::PanTilt) return ControllerKind::Proportional;
  return kind == ControllerKind::Auto ? ControllerKind::Zone : kind;
}

double horizontalOffset(const cv::Rect2d &box, cv::Size frame) {
  const double half = frame.width / 2.0;
  return (box.x + box.width / 2.0 - half) / half;
}

double verticalOffset(const cv::Rect2d &box, cv::Size frame) {
  return (box.y + box.height / 2.0 - frame.height / 2.0) / (frame.width / 2.0);
}

bool isStill(const DriveOutput &output) {
  return output.command == DriveCommand::Stop && output.tilt == 0;
}

DriveOutput withoutTurn(const DriveOutput &output) {
  return makeOutput(output.linear, 0, output.targetVisible);
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

}  // namespace colortrack
