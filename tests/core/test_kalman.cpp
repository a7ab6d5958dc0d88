// SPDX-License-Identifier: LGPL-2.1-or-later
// KalmanFilter9: convergence on a constant-acceleration track, lead of the prediction over the last
// measurement, noise reduction, fractional and non-unit time steps, covariance health.
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include "colortrack/kalman.hpp"

namespace colortrack {
namespace {

// A point moving with constant acceleration in x, y and scale; time in frames.
struct Trajectory {
  double x0 = 100, vx = 2.0, ax = 0.05;
  double y0 = 80, vy = -1.5, ay = 0.02;
  double s0 = 1.0, vs = 0.002, as = 0.0;
  double x(double t) const { return x0 + vx * t + 0.5 * ax * t * t; }
  double y(double t) const { return y0 + vy * t + 0.5 * ay * t * t; }
  double s(double t) const { return s0 + vs * t + 0.5 * as * t * t; }
  double velX(double t) const { return vx + ax * t; }
};

double rms(const std::vector<double> &errors) {
  double sum = 0;
  for (double e : errors) sum += e * e;
  return errors.empty() ? 0 : std::sqrt(sum / errors.size());
}

TEST(Kalman, ConvergesOnConstantAccelerationTrack) {
  const Trajectory truth;
  KalmanFilter9 kf;  // default parameters, exact measurements
  kf.init(truth.x(0), truth.y(0), truth.s(0));
  for (int t = 1; t <= 60; ++t) {
    kf.predict(1.0);
    kf.correct(truth.x(t), truth.y(t), truth.s(t));
  }
  const double t = 60;
  EXPECT_NEAR(kf.x(), truth.x(t), 0.05);
  EXPECT_NEAR(kf.y(), truth.y(t), 0.05);
  EXPECT_NEAR(kf.scale(), truth.s(t), 1e-3);
  EXPECT_NEAR(kf.vx(), truth.velX(t), 0.02);
  EXPECT_NEAR(kf.state()(2), truth.ax, 5e-3);  // estimated acceleration
  EXPECT_NEAR(kf.state()(5), truth.ay, 5e-3);
  EXPECT_NEAR(kf.vscale(), truth.vs, 2e-4);
}

TEST(Kalman, EstimatesAccelerationFromNoisyMeasurements) {
  const Trajectory truth;
  KalmanParams params;
  // A smooth target: the jerk density must be small for the acceleration to be averaged over many frames
  // (the filter's own acceleration sigma is ~0.03 at 1e-4 and ~0.004 at 1e-6).
  params.processNoise = 1e-6;
  params.measurementNoise = 1.0;
  KalmanFilter9 kf(params);
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  kf.init(truth.x(0) + noise(rng), truth.y(0) + noise(rng), truth.s(0));
  for (int t = 1; t <= 150; ++t) {
    kf.predict(1.0);
    kf.correct(truth.x(t) + noise(rng), truth.y(t) + noise(rng), truth.s(t));
  }
  const double accelerationSigma = std::sqrt(kf.covariance()(2, 2));
  EXPECT_LT(accelerationSigma, 0.01);
  // Within 3 sigma of the filter's own uncertainty, i.e. its covariance is honest.
  EXPECT_NEAR(kf.state()(2), truth.ax, 3 * accelerationSigma);
  EXPECT_NEAR(kf.state()(5), truth.ay, 3 * accelerationSigma);
  EXPECT_NEAR(kf.x(), truth.x(150), 3 * kf.stdX());
}

TEST(Kalman, PredictionLeadsTheLastMeasurement) {
  // A fast target (3 px/frame): the prediction made before correct() must sit nearer the truth than the
  // previous measurement does, which is where a filter-less tracker would search.
  Trajectory truth;
  truth.vx = 3.0;
  truth.vy = 2.0;
  KalmanFilter9 kf;
  std::mt19937 rng(11);
  std::normal_distribution<double> noise(0.0, 1.0);
  double prevX = truth.x(0) + noise(rng), prevY = truth.y(0) + noise(rng);
  kf.init(prevX, prevY, 1.0);
  std::vector<double> predictionErrors, lastMeasurementErrors;
  for (int t = 1; t <= 200; ++t) {
    kf.predict(1.0);
    if (t > 20) {  // after the filter has settled
      predictionErrors.push_back(std::hypot(kf.x() - truth.x(t), kf.y() - truth.y(t)));
      lastMeasurementErrors.push_back(std::hypot(prevX - truth.x(t), prevY - truth.y(t)));
    }
    prevX = truth.x(t) + noise(rng);
    prevY = truth.y(t) + noise(rng);
    kf.correct(prevX, prevY, 1.0);
  }
  const double predictionRms = rms(predictionErrors), lastMeasurementRms = rms(lastMeasurementErrors);
  RecordProperty("prediction_rms", std::to_string(predictionRms));
  RecordProperty("last_measurement_rms", std::to_string(lastMeasurementRms));
  EXPECT_LT(predictionRms, 0.5 * lastMeasurementRms);
}

TEST(Kalman, ReducesMeasurementNoise) {
  Trajectory truth;
  truth.ax = truth.ay = 0;  // constant velocity
  KalmanParams params;
  params.processNoise = 1e-4;
  params.measurementNoise = 4.0;  // sigma 2 px, matches the simulated noise
  KalmanFilter9 kf(params);
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 2.0);
  kf.init(truth.x(0) + noise(rng), truth.y(0) + noise(rng), 1.0);
  std::vector<double> measurementErrors, filteredErrors;
  for (int t = 1; t <= 300; ++t) {
    kf.predict(1.0);
    const double mx = truth.x(t) + noise(rng), my = truth.y(t) + noise(rng);
    kf.correct(mx, my, 1.0);
    if (t > 30) {
      measurementErrors.push_back(std::hypot(mx - truth.x(t), my - truth.y(t)));
      filteredErrors.push_back(std::hypot(kf.x() - truth.x(t), kf.y() - truth.y(t)));
    }
  }
  const double measured = rms(measurementErrors), filtered = rms(filteredErrors);
  RecordProperty("measurement_rms", std::to_string(measured));
  RecordProperty("filtered_rms", std::to_string(filtered));
  EXPECT_LT(filtered, 0.75 * measured);
  // The reported per-axis sigma matches the actual per-axis error to within 30%.
  const double perAxisError = filtered / std::sqrt(2.0);
  EXPECT_NEAR(kf.stdX() / perAxisError, 1.0, 0.3);
}

TEST(Kalman, FractionalAndLongTimeSteps) {
  // Irregular sampling (as with buffer timestamps): the filter must still track in per-frame units.
  const Trajectory truth;
  KalmanFilter9 kf;
  kf.init(truth.x(0), truth.y(0), truth.s(0));
  const std::vector<double> steps = {0.5, 1.5, 2.5, 0.25, 1.0};
  double t = 0;
  for (int i = 0; i < 80; ++i) {
    const double dt = steps[i % steps.size()];
    t += dt;
    kf.predict(dt);
    kf.correct(truth.x(t), truth.y(t), truth.s(t));
  }
  EXPECT_NEAR(kf.x(), truth.x(t), 0.05);
  EXPECT_NEAR(kf.vx(), truth.velX(t), 0.02);
  EXPECT_NEAR(kf.state()(2), truth.ax, 5e-3);

  // One long step: the prediction extrapolates with the estimated velocity and acceleration.
  const double gap = 3.0;
  kf.predict(gap);
  EXPECT_NEAR(kf.x(), truth.x(t + gap), 0.1);
  EXPECT_NEAR(kf.y(), truth.y(t + gap), 0.1);
}

TEST(Kalman, UncertaintyShrinksWithMeasurementsAndGrowsWhenCoasting) {
  KalmanParams params;
  KalmanFilter9 kf(params);
  kf.init(50, 50, 1.0);
  const double initialStd = kf.stdX();
  EXPECT_NEAR(initialStd, std::sqrt(params.measurementNoise), 1e-9);
  for (int t = 1; t <= 30; ++t) {
    kf.predict();
    kf.correct(50 + t, 50, 1.0);
  }
  const double settledStd = kf.stdX();
  EXPECT_LT(settledStd, initialStd);
  EXPECT_NEAR(kf.stdY(), settledStd, 1e-9);  // x and y see the same noise

  double previous = settledStd;
  for (int t = 0; t < 10; ++t) {  // coasting: predictions only
    kf.predict();
    EXPECT_GT(kf.stdX(), previous);
    previous = kf.stdX();
  }

  // The covariance stays symmetric and positive definite.
  const KalmanFilter9::Cov &p = kf.covariance();
  EXPECT_LT((p - p.transpose()).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(p.llt().info(), Eigen::Success);  // Cholesky exists only for positive definite matrices
}

TEST(Kalman, CorrectBeforeInitInitialises) {
  KalmanFilter9 kf;
  EXPECT_FALSE(kf.initialised());
  kf.correct(12, 34, 1.2);
  ASSERT_TRUE(kf.initialised());
  EXPECT_DOUBLE_EQ(kf.x(), 12);
  EXPECT_DOUBLE_EQ(kf.y(), 34);
  EXPECT_DOUBLE_EQ(kf.scale(), 1.2);
  EXPECT_DOUBLE_EQ(kf.vx(), 0);
}

}  // namespace
}  // namespace colortrack

TEST(Kalman, CoastingHoldsVelocityAndSize) {
  colortrack::KalmanFilter9 kf;
  kf.init(100, 100, 1.0);
  // A target accelerating and growing: the filter learns acceleration and scale velocity.
  for (int t = 1; t <= 30; ++t) {
    kf.predict(1);
    kf.correct(100 + 2 * t + 0.1 * t * t, 100, 1.0 + 0.01 * t);
  }
  const double vx = kf.vx(), scale = kf.scale();
  ASSERT_GT(std::abs(kf.state()(2)), 0.05);  // it did learn an acceleration
  kf.holdForCoasting();
  const double x0 = kf.x();
  for (int t = 0; t < 10; ++t) kf.predict(1);
  EXPECT_NEAR(kf.x(), x0 + 10 * vx, 1e-6);  // constant velocity, no acceleration
  EXPECT_NEAR(kf.scale(), scale, 1e-9);     // constant size
}

TEST(Kalman, CorrectingThePositionOnlyKeepsTheVelocity) {
  // A target moving at 3 px/frame in x and 1 in y, then measured 6 px and 4 px off its path (part of it
  // covered): correctPosition moves the estimate towards the measurement and keeps the predicted velocity;
  // correct, given the same measurement, takes the jump for motion.
  colortrack::KalmanFilter9 tracked;
  tracked.init(100, 100, 1.0);
  for (int t = 1; t <= 30; ++t) {
    tracked.predict(1);
    tracked.correct(100 + 3 * t, 100 + t, 1.0);
  }
  tracked.predict(1);
  const double predictedX = tracked.x(), vx = tracked.vx(), vy = tracked.vy();
  colortrack::KalmanFilter9 full = tracked;
  tracked.correctPosition(predictedX + 6, tracked.y() - 4, 1.0);
  full.correct(predictedX + 6, full.y() - 4, 1.0);
  EXPECT_GT(tracked.x(), predictedX + 1);
  EXPECT_DOUBLE_EQ(tracked.vx(), vx);
  EXPECT_DOUBLE_EQ(tracked.vy(), vy);
  EXPECT_EQ(tracked.state()(2), 0.0);  // ax
  EXPECT_EQ(tracked.state()(5), 0.0);  // ay
  EXPECT_GT(full.vx(), vx + 0.5);
  EXPECT_LT(full.vy(), vy - 0.3);
}
