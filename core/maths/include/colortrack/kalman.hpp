// SPDX-License-Identifier: LGPL-2.1-or-later
// 9-state constant-acceleration Kalman filter over (x, y, scale).
#pragma once

#include <Eigen/Core>

namespace colortrack {

struct KalmanParams {
  // Spectral density of the jerk (white-noise jerk model) for x and y, in px^2 per frame^5 units. Scale
  // uses processNoise * scaleNoiseRatio, since scale is ~1 while positions are in pixels.
  double processNoise = 10.0;
  double measurementNoise = 4.0;  // variance of measured x and y, px^2; scale: * scaleNoiseRatio
  double scaleNoiseRatio = 1e-4;
};

class KalmanFilter9 {
 public:
  // State order: x, vx, ax, y, vy, ay, s, vs, as.
  using State = Eigen::Matrix<double, 9, 1>;
  using Cov = Eigen::Matrix<double, 9, 9>;

  explicit KalmanFilter9(const KalmanParams &params = KalmanParams());

  void setParams(const KalmanParams &params) { params_ = params; }
  void init(double x, double y, double scale);
  bool initialised() const { return initialised_; }

  // Advance by dt frames (1 = one frame; fractional values when buffer timestamps are used).
  void predict(double dt = 1.0);
  // Measurement update with a detection.
  void correct(double x, double y, double scale);
  // Measurement update with a detection that says where the object is but not how it moves (its centroid
  // jumps as something else covers more or less of it): the predicted velocity is kept and the acceleration
  // dropped.
  void correctPosition(double x, double y, double scale);
  // Without measurements, extrapolating accelerations (and a changing size) runs away within a few frames:
  // while coasting, keep moving at constant velocity and constant size.
  void holdForCoasting();
  // Only the position's acceleration (ax, ay) set to zero: a prediction at constant velocity, size as before.
  void dropAcceleration();
  // Sets the position's velocity (vx, vy), e.g. to a slower estimate before coasting.
  void setVelocity(double vx, double vy);
  // Moves the position by (dx, dy) and leaves the rest: the picture moved under the object (the camera
  // turned), which says nothing about how the object itself moves.
  void translate(double dx, double dy);

  double x() const { return state_(0); }
  double y() const { return state_(3); }
  double scale() const { return state_(6); }
  double vx() const { return state_(1); }
  double vy() const { return state_(4); }
  double vscale() const { return state_(7); }
  double stdX() const;  // sqrt of the x variance
  double stdY() const;
  const State &state() const { return state_; }
  const Cov &covariance() const { return cov_; }

 private:
  KalmanParams params_;
  State state_ = State::Zero();
  Cov cov_ = Cov::Identity();
  bool initialised_ = false;
};

}  // namespace colortrack
