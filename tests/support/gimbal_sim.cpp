// SPDX-License-Identifier: LGPL-2.1-or-later
#include "gimbal_sim.hpp"

#include <algorithm>
#include <cmath>

#include "robot_sim.hpp"

namespace colortrack::gimbal_sim {

namespace {

constexpr double kRad = CV_PI / 180;

// A unit vector (x forward, y right, z up) at `azimuth` to the right and `elevation` up (rad).
cv::Point3d direction(double azimuth, double elevation) {
  return {std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
          std::sin(elevation)};
}

}  // namespace

GimbalSim::GimbalSim(const GimbalSimConfig &config)
    : config_(config),
      focal_(config.frameSize.width / 2.0 / std::tan(config.horizontalFovDegrees * kRad / 2)) {}

cv::Point3d GimbalSim::targetInCamera() const {
  const cv::Point3d target = direction(config_.targetAzimuth * kRad, config_.targetElevation * kRad);
  const cv::Point3d forward = direction(yaw_, pitch_);
  const cv::Point3d right(-std::sin(yaw_), std::cos(yaw_), 0);
  const cv::Point3d up(-std::sin(pitch_) * std::cos(yaw_), -std::sin(pitch_) * std::sin(yaw_),
                       std::cos(pitch_));
  return {target.dot(right), target.dot(up), target.dot(forward)};
}

cv::Rect2d GimbalSim::targetBox() const {
  const cv::Point3d p = targetInCamera();
  if (hidden_ || p.z <= 0.1) return {};
  const double u = config_.frameSize.width / 2.0 + focal_ * p.x / p.z;
  const double v = config_.frameSize.height / 2.0 - focal_ * p.y / p.z;
  const double radius = focal_ * std::tan(config_.targetRadiusDegrees * kRad) / p.z;
  return {u - radius, v - radius, 2 * radius, 2 * radius};
}

cv::Mat GimbalSim::render() const {
  cv::Mat image(config_.frameSize, CV_8UC3, cv::Scalar(200, 190, 170));
  robot_sim::drawBall(image, targetBox());
  return image;
}

void GimbalSim::turn(double pitchRate, double yawRate, double dt) {
  const double limit = config_.maxRateDegrees * kRad;
  yaw_ += std::clamp(yawRate, -limit, limit) * dt;
  pitch_ += std::clamp(pitchRate, -limit, limit) * dt;
}

double GimbalSim::errorDegrees() const {
  const cv::Point3d p = targetInCamera();
  return std::acos(std::clamp(p.z, -1.0, 1.0)) / kRad;
}

}  // namespace colortrack::gimbal_sim
