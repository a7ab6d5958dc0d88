// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/kalman_track.hpp"

#include <algorithm>
#include <cmath>

#include "colortrack/box.hpp"

namespace colortrack {

namespace {

constexpr double kAspectRate = 0.3;  // smoothing of the measured aspect ratio

}  // namespace

cv::Size2d KalmanTrack::windowSize(double scale) const {
  const double a = std::sqrt(aspect);
  return cv::Size2d(templateSize.width * scale * a, templateSize.height * scale / a);
}

cv::Rect2d KalmanTrack::box() const {
  return centredBox(kalman.x(), kalman.y(), windowSize(kalman.scale()));
}

cv::Rect KalmanTrack::predictionRegion(double margin) const {
  const cv::Size2d size = windowSize(kalman.scale());
  const double growX = margin * size.width / 2 + 3 * kalman.stdX();
  const double growY = margin * size.height / 2 + 3 * kalman.stdY();
  return roundRect(cv::Rect2d(kalman.x() - size.width / 2 - growX, kalman.y() - size.height / 2 - growY,
                              size.width + 2 * growX, size.height + 2 * growY));
}

void KalmanTrack::newTemplate(cv::Size size) {
  templateSize = size;
  aspect = 1.0;
  lastScale = 1.0;
}

void KalmanTrack::reset(const KalmanParams &params) {
  state = TrackState::Searching;
  doubted = false;
  scoreFell = false;
  heldBack = false;
  coastFrames = 0;
  unverifiedFrames = 0;
  searchFrames = 0;
  kalman = KalmanFilter9(params);
}

void KalmanTrack::start(const cv::Rect2d &box, const KalmanParams &params) {
  searchFrames = 0;
  kalman.setParams(params);
  measureShape(box, 1.0);
  const cv::Point2d centre = boxCentre(box);
  kalman.init(centre.x, centre.y, lastScale);
  ++id;
  state = TrackState::Tracking;
  doubted = false;
  coastFrames = 0;
  unverifiedFrames = 0;
}

void KalmanTrack::startUnconfirmed(const cv::Rect2d &box, const KalmanParams &params) {
  start(box, params);
  state = TrackState::Coasting;
}

void KalmanTrack::update(const cv::Rect2d &box) {
  measureShape(box, kAspectRate);
  const cv::Point2d centre = boxCentre(box);
  kalman.correct(centre.x, centre.y, lastScale);
  state = TrackState::Tracking;
  coastFrames = 0;
}

void KalmanTrack::coast(int maxCoastFrames) {
  kalman.holdForCoasting();
  ++coastFrames;
  state = coastFrames > maxCoastFrames ? TrackState::Lost : TrackState::Coasting;
}

void KalmanTrack::coastAt(cv::Point2d centre, int maxCoastFrames) {
  coast(maxCoastFrames);
  if (!active()) return;
  kalman.translate(centre.x - kalman.x(), centre.y - kalman.y());
  kalman.setVelocity(0, 0);
}

void KalmanTrack::report(TrackOutput &out) const {
  out.state =
      state == TrackState::Tracking && (doubted || scoreFell || heldBack) ? TrackState::Coasting : state;
  out.id = id;
  if (!active()) return;
  out.hasBox = true;
  out.box = box();
  out.scale = kalman.scale();
  out.vx = kalman.vx();
  out.vy = kalman.vy();
  out.verified = out.state == TrackState::Tracking && lastVerified;
}

// Scale (for the Kalman filter: the square root of the box's area relative to the template's, so aspect
// changes leave it alone) and aspect (smoothed here: it changes slowly and the filter has no state for it).
void KalmanTrack::measureShape(const cv::Rect2d &box, double aspectRate) {
  const double boxAspect =
      (box.width / box.height) / (static_cast<double>(templateSize.width) / templateSize.height);
  aspect = std::clamp((1 - aspectRate) * aspect + aspectRate * boxAspect, 0.25, 4.0);
  lastScale = std::sqrt(box.area() / (static_cast<double>(templateSize.width) * templateSize.height));
}

}  // namespace colortrack
