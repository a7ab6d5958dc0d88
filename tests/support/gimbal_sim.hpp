// SPDX-License-Identifier: LGPL-2.1-or-later
// A simulated camera on a two-axis gimbal (yaw and pitch, each rate-limited) looking at a red ball far away
// in a given direction. It renders what the camera sees (pinhole model) and turns at the rates a
// GIMBAL_MANAGER_SET_PITCHYAW asks for, so robotctl's MAVLink gimbal mode can be tested in a closed loop.
#pragma once

#include <opencv2/core.hpp>

namespace colortrack::gimbal_sim {

struct GimbalSimConfig {
  cv::Size frameSize{320, 240};
  double horizontalFovDegrees = 60;  // the vertical one follows from the aspect ratio (square pixels)
  double maxRateDegrees = 60;        // per axis, deg/s: the gimbal's motors
  // The ball's direction (deg): azimuth > 0 to the right, elevation > 0 up; and its angular radius.
  double targetAzimuth = 0, targetElevation = 0;
  double targetRadiusDegrees = 3;
  double targetAzimuthRate = 0;  // deg/s, applied by moveTarget
};

class GimbalSim {
 public:
  explicit GimbalSim(const GimbalSimConfig &config);

  // The view: a plain pale background and the ball (BGR, CV_8UC3).
  cv::Mat render() const;
  void setTargetHidden(bool hidden) { hidden_ = hidden; }
  void setTargetAzimuthRate(double degreesPerSecond) { config_.targetAzimuthRate = degreesPerSecond; }
  // Moves the ball for dt seconds at its azimuth rate.
  void moveTarget(double dt) { config_.targetAzimuth += config_.targetAzimuthRate * dt; }
  // Where the ball appears; empty when hidden or behind the camera.
  cv::Rect2d targetBox() const;
  // Turns for dt seconds at the asked rates (rad/s, MAVLink's signs: yaw > 0 to the right, pitch > 0 up),
  // each clamped to the gimbal's limit.
  void turn(double pitchRate, double yawRate, double dt);
  // Angle between the camera's axis and the ball's direction (deg): the pointing error.
  double errorDegrees() const;
  double yawDegrees() const { return yaw_ * 180 / CV_PI; }
  double pitchDegrees() const { return pitch_ * 180 / CV_PI; }

 private:
  // The ball's direction in camera coordinates: right, up, forward.
  cv::Point3d targetInCamera() const;

  GimbalSimConfig config_;
  double focal_;
  double yaw_ = 0, pitch_ = 0;  // rad
  bool hidden_ = false;
};

}  // namespace colortrack::gimbal_sim
