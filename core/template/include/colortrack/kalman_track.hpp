// SPDX-License-Identifier: LGPL-2.1-or-later
// The template tracker's one track: a Kalman filter on centre and scale, the box's aspect, the state and the
// counters every detection method moves. Plain data with the steps all methods share.
#pragma once

#include <opencv2/core.hpp>

#include "colortrack/kalman.hpp"
#include "colortrack/track.hpp"
#include "colortrack/track_output.hpp"

namespace colortrack {

struct KalmanTrack {
  KalmanFilter9 kalman;
  TrackState state = TrackState::Searching;
  int id = 0;
  int coastFrames = 0;
  int unverifiedFrames = 0;  // colour-only detections since the last verified one
  int searchFrames = 0;      // frames searched since the track was lost (picks the scale to try)
  double lastScale = 1.0;    // last measured scale
  bool lastVerified = false;
  // Measured and followed, but not vouched for: reported coasting (and unverified) until the method clears
  // it. The fused method sets it when a look-alike answers beside the target (FusedMethod::follow).
  bool doubted = false;
  // The method's score fell suddenly (ScoreFall): also reported coasting; set by the method every frame.
  bool scoreFell = false;
  // The method holds a detection back for other reasons (a look-alike was in view lately, the track came back
  // far from where it was last reported tracking): also reported coasting; set every frame.
  bool heldBack = false;
  double aspect = 1.0;    // (box width / height) / (template width / height)
  cv::Size templateSize;  // boxes are measured relative to it

  bool active() const { return state == TrackState::Tracking || state == TrackState::Coasting; }
  // A box of `scale` at the current aspect.
  cv::Size2d windowSize(double scale) const;
  // The filtered box.
  cv::Rect2d box() const;
  // The search region around the prediction: the window grown by `margin` box sizes and by three standard
  // deviations of the predicted position.
  cv::Rect predictionRegion(double margin) const;

  // A new template: shape and scale start from it.
  void newTemplate(cv::Size size);
  // Forgets the track (keeps the id count and the shape).
  void reset(const KalmanParams &params);
  // A new track at `box` (a new id).
  void start(const cv::Rect2d &box, const KalmanParams &params);
  // A new track at a guess `box` (a new id), reported coasting until a detection confirms it with update();
  // lost as coast() says if none does.
  void startUnconfirmed(const cv::Rect2d &box, const KalmanParams &params);
  // The track measured at `box`.
  void update(const cv::Rect2d &box);
  // A frame without detection: coasting, lost after `maxCoastFrames`.
  void coast(int maxCoastFrames);
  // A frame whose detection was not confident enough: coasting as coast() does, but the track waits at the
  // detector's best guess `centre`, standing still, instead of running on at its last velocity.
  void coastAt(cv::Point2d centre, int maxCoastFrames);
  // The output's track fields: state, id, and box, scale and motion when there is a track.
  void report(TrackOutput &out) const;

 private:
  void measureShape(const cv::Rect2d &box, double aspectRate);
};

}  // namespace colortrack
