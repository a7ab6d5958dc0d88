// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode, tracking side: one Kalman track per object, blobs assigned to tracks frame to frame, stable
// ids through crossings and short disappearances.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/assignment.hpp"  // solveAssignment (blobs to tracks)
#include "colortrack/blobs.hpp"
#include "colortrack/kalman.hpp"
#include "colortrack/track.hpp"

namespace colortrack {

struct MultiTrackerSettings {
  KalmanParams kalman;
  int confirmFrames = 3;    // consecutive detections before a new track is reported (and gets its id)
  int maxCoastFrames = 10;  // frames without a detection before a reported track is dropped
  // Association gate: a blob may feed a track when its centroid lies within
  //   max(minGate, gateSize * half the predicted box diagonal) + 3 sigma of the prediction
  //   + coastGrowth * half diagonal per frame the track has coasted,
  // and its area is within maxAreaRatio of the track's.
  double minGate = 12.0;
  double gateSize = 1.0;
  double coastGrowth = 0.25;
  double maxAreaRatio = 8.0;
  // A blob this much larger than the track it is assigned to, that also lies in the gate of another
  // reported track, is taken as objects merged: none is corrected by its centroid, all coast on their
  // predictions without counting misses until they part.
  double mergeAreaRatio = 1.3;
  // The smallest object (frame pixels; ThresholdTracker sets the detector's minArea): a blob whose shape is
  // several round objects is split into them only where each is at least this large.
  int minObjectArea = 50;
  // ThresholdTracker measures the camera's motion between frames and moves the tracks with it
  // (followCamera()).
  bool followCamera = true;
};

// One track as reported.
struct TrackedObject {
  int id = 0;  // >= 1 once confirmed; 0 while tentative
  bool confirmed = false;
  TrackState state = TrackState::Tracking;  // tracking: measured this frame; coasting: on the prediction
  cv::Point2d centre;                       // filtered centroid
  cv::Rect2d box;                           // filtered box around it
  double area = 0;                          // pixel count of the last blob that fed the track
  double score = 0;       // this frame's blob fill ratio (area / box area); 0 when not measured
  double scale = 1.0;     // filtered size relative to the size at acquisition
  double vx = 0, vy = 0;  // filtered velocity, px/frame
  int hits = 0;           // frames measured since creation
  int misses = 0;         // consecutive frames without a measurement
};

class MultiTracker {
 public:
  MultiTracker();
  explicit MultiTracker(const MultiTrackerSettings &settings);
  ~MultiTracker();
  MultiTracker(const MultiTracker &);
  MultiTracker &operator=(const MultiTracker &);
  MultiTracker(MultiTracker &&) noexcept;
  MultiTracker &operator=(MultiTracker &&) noexcept;
  void setSettings(const MultiTrackerSettings &settings);
  const MultiTrackerSettings &settings() const { return settings_; }

  // Advances every track by dt frames, assigns the blobs (confirmed tracks first, then tentative ones, each
  // by minimum total cost), corrects, creates and drops tracks. Returns the confirmed tracks, by id. With the
  // blobs' `labels`, a blob that several tracks share (objects touching or passing over each other) is split
  // between them; without, those tracks ride on their predictions until the objects part. With them too, a
  // blob that is several round objects no reported track tells apart (they appeared touching) is split
  // into them.
  std::vector<TrackedObject> update(const std::vector<Blob> &blobs, cv::Size frame, double dt = 1.0,
                                    const BlobLabels &labels = BlobLabels());

  // The picture moved by `shift` px since the last frame (the camera turned or travelled; GlobalMotion
  // measures it): every track, what it saw and where tracks left the frame move with it, so the next
  // update() predicts each object's own motion from where the camera put it.
  void followCamera(cv::Point2d shift);

  // Every live track, tentative ones included (tests, debugging).
  std::vector<TrackedObject> allTracks() const;

  // Forgets every track; ids keep growing, so an id is never reused within one element's life.
  void reset();

 private:
  struct Track;
  void predict(Track &track, cv::Size frame, double dt) const;
  double gateRadius(const Track &track) const;
  double cost(const Track &track, const Blob &blob) const;
  bool touchesBorder(const Blob &blob) const;
  TrackedObject report(const Track &track) const;
  // The steps of update().
  std::vector<Blob> splitNewObjects(const std::vector<Blob> &blobs, const BlobLabels &labels) const;
  void associate(const std::vector<Blob> &blobs, bool confirmed, std::vector<int> &blobTrack) const;
  void findMerges(const std::vector<Blob> &blobs, const std::vector<int> &blobTrack,
                  std::vector<char> &merged, std::vector<int> &occludedIn) const;
  bool correctShared(int blob, const std::vector<Blob> &blobs, const BlobLabels &labels, int owner,
                     const std::vector<int> &occludedIn);
  // shared: the blob is the track's share of a split blob, which says where the object is but not how big.
  void correct(Track &track, const Blob &blob, bool shared = false);
  // The velocity a track that has just lost its object coasts with.
  void coastingVelocity(Track &track) const;
  void startTrack(const Blob &blob);
  void confirm(Track &track);
  std::optional<int> returningId(const Blob &blob);

  // A confirmed track that followed its object out of the frame.
  struct Exit {
    int id;
    cv::Point2d position;  // where its prediction left the frame
    double area, side;
    int age;  // frames since
  };

  MultiTrackerSettings settings_;
  std::vector<Track> tracks_;
  std::vector<Exit> exits_;
  cv::Size frame_;
  int nextId_ = 1;
};

// The report with the largest area (the primary target), or -1 when empty.
int primaryIndex(const std::vector<TrackedObject> &objects);

}  // namespace colortrack
