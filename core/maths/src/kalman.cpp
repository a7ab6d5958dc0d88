// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/kalman.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Cholesky>

namespace colortrack {

namespace {

using Mat3 = Eigen::Matrix3d;
using Meas = Eigen::Vector3d;
using MeasCov = Eigen::Matrix3d;
using MeasMatrix = Eigen::Matrix<double, 3, 9>;

// Each tracked quantity (x, y, scale) owns one 3x3 block [value, rate, acceleration] of the state.
constexpr int kBlock[3] = {0, 3, 6};

Mat3 axisTransition(double dt) {
  Mat3 f;
  f << 1, dt, 0.5 * dt * dt,  //
      0, 1, dt,               //
      0, 0, 1;
  return f;
}

// Discrete white-noise-jerk process noise for one axis (jerk spectral density q integrated over dt).
Mat3 axisProcessNoise(double q, double dt) {
  const double dt2 = dt * dt, dt3 = dt2 * dt, dt4 = dt3 * dt, dt5 = dt4 * dt;
  Mat3 qm;
  qm << dt5 / 20, dt4 / 8, dt3 / 6,  //
      dt4 / 8, dt3 / 3, dt2 / 2,     //
      dt3 / 6, dt2 / 2, dt;
  return q * qm;
}

MeasMatrix measurementMatrix() {
  MeasMatrix h = MeasMatrix::Zero();
  for (int axis = 0; axis < 3; ++axis) h(axis, kBlock[axis]) = 1.0;
  return h;
}

MeasCov measurementNoise(const KalmanParams &p) {
  return Meas(p.measurementNoise, p.measurementNoise, p.measurementNoise * p.scaleNoiseRatio).asDiagonal();
}

}  // namespace

KalmanFilter9::KalmanFilter9(const KalmanParams &params) : params_(params) {}

void KalmanFilter9::init(double x, double y, double scale) {
  state_.setZero();
  state_(kBlock[0]) = x;
  state_(kBlock[1]) = y;
  state_(kBlock[2]) = scale;

  // Position is known to measurement accuracy; rates and accelerations are unknown, so their variances are
  // wide enough (10 px/frame, ~3 px/frame^2) for the first few corrections to settle them.
  const double kVelocityVar = 100.0, kAccelerationVar = 10.0;
  cov_.setZero();
  for (int axis = 0; axis < 3; ++axis) {
    const double unit = axis == 2 ? params_.scaleNoiseRatio : 1.0;
    const int b = kBlock[axis];
    cov_(b, b) = params_.measurementNoise * unit;
    cov_(b + 1, b + 1) = kVelocityVar * unit;
    cov_(b + 2, b + 2) = kAccelerationVar * unit;
  }
  initialised_ = true;
}

void KalmanFilter9::predict(double dt) {
  if (!initialised_ || dt <= 0) return;
  const Mat3 f = axisTransition(dt);
  Cov fm = Cov::Zero(), qm = Cov::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    const double q = axis == 2 ? params_.processNoise * params_.scaleNoiseRatio : params_.processNoise;
    fm.block<3, 3>(kBlock[axis], kBlock[axis]) = f;
    qm.block<3, 3>(kBlock[axis], kBlock[axis]) = axisProcessNoise(q, dt);
  }
  state_ = fm * state_;
  cov_ = fm * cov_ * fm.transpose() + qm;
  cov_ = 0.5 * (cov_ + cov_.transpose());  // keep it exactly symmetric against rounding drift
}

void KalmanFilter9::holdForCoasting() {
  for (int index : {2, 5, 7, 8}) state_(index) = 0;  // ax, ay, vs, as
}

void KalmanFilter9::dropAcceleration() {
  for (int index : {2, 5}) state_(index) = 0;  // ax, ay
}

void KalmanFilter9::setVelocity(double vx, double vy) {
  state_(1) = vx;
  state_(4) = vy;
}

void KalmanFilter9::translate(double dx, double dy) {
  state_(0) += dx;
  state_(3) += dy;
}

void KalmanFilter9::correct(double x, double y, double scale) {
  if (!initialised_) {
    init(x, y, scale);
    return;
  }
  const MeasMatrix h = measurementMatrix();
  const MeasCov r = measurementNoise(params_);
  const Meas innovation = Meas(x, y, scale) - h * state_;
  const MeasCov s = h * cov_ * h.transpose() + r;
  // K = P H^T S^-1, solved through a Cholesky factorisation rather than an explicit inverse.
  const Eigen::Matrix<double, 9, 3> gain = s.ldlt().solve(h * cov_).transpose();
  state_ += gain * innovation;
  // Joseph form: stays symmetric positive semi-definite even with a slightly suboptimal gain.
  const Cov ikh = Cov::Identity() - gain * h;
  cov_ = ikh * cov_ * ikh.transpose() + gain * r * gain.transpose();
  cov_ = 0.5 * (cov_ + cov_.transpose());
}

void KalmanFilter9::correctPosition(double x, double y, double scale) {
  const double vx = this->vx(), vy = this->vy();
  correct(x, y, scale);
  setVelocity(vx, vy);
  dropAcceleration();
}

double KalmanFilter9::stdX() const {
  return std::sqrt(std::max(0.0, cov_(0, 0)));
}
double KalmanFilter9::stdY() const {
  return std::sqrt(std::max(0.0, cov_(3, 3)));
}

}  // namespace colortrack
