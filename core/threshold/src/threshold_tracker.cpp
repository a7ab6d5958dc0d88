// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/threshold_tracker.hpp"

#include <algorithm>

namespace colortrack {

namespace {

TrackReport reportOf(const TrackedObject &o) {
  TrackReport r;
  r.id = o.id;
  r.state = o.state;
  r.box = o.box;
  r.centre = o.centre;
  r.score = o.score;
  r.verified = true;  // blobs are found by colour alone: there is no edge check to fail
  r.scale = o.scale;
  r.vx = o.vx;
  r.vy = o.vy;
  r.area = o.area;
  return r;
}

}  // namespace

ThresholdTracker::ThresholdTracker(const BlobSettings &blobs, const MultiTrackerSettings &tracks)
    : detector_(blobs) {
  setTrackSettings(tracks);
}

void ThresholdTracker::setBlobSettings(const BlobSettings &settings) {
  detector_.setSettings(settings);
  setTrackSettings(tracks_.settings());
}

void ThresholdTracker::setTrackSettings(const MultiTrackerSettings &settings) {
  MultiTrackerSettings s = settings;
  s.minObjectArea = detector_.settings().minArea;  // one notion of the smallest object
  tracks_.setSettings(s);
}

std::vector<cv::Rect2d> movingObjects(const std::vector<Blob> &blobs) {
  constexpr int kMargin = 4;
  std::vector<cv::Rect2d> boxes;
  for (const Blob &b : blobs)
    boxes.emplace_back(b.box.x - kMargin, b.box.y - kMargin, b.box.width + 2 * kMargin,
                       b.box.height + 2 * kMargin);
  return boxes;
}

// The camera's motion since the last frame, measured on the background (the blobs left out, with a margin
// for their motion since then), moves every track before the blobs are assigned. Without it, a camera that
// jerks 10 px in a frame puts each prediction that far from its object, where the next object may be.
void ThresholdTracker::followCamera(const SampledFrame &frame, const std::vector<Blob> &blobs) {
  if (!tracks_.settings().followCamera) {
    camera_.reset();
    return;
  }
  const GlobalMotion::Shift moved = camera_.measure(frame, movingObjects(blobs));
  if (moved.valid) tracks_.followCamera(moved.offset);
}

FrameReport ThresholdTracker::track(const ImageSource &frame, double dt) {
  const SampledFrame bytes = frame.channels(converted_);
  const std::vector<Blob> blobs = detector_.detect(bytes);
  followCamera(bytes, blobs);
  const std::vector<TrackedObject> objects = tracks_.update(blobs, frame.size(), dt, detector_.labels());
  FrameReport report;
  report.listsTracks = true;
  // Reported as they lie in the frame: a box clipped to the frame, and only where at least min-area pixels
  // of it remain (a track running out of the frame is not reported as a sliver on the edge).
  const cv::Rect2d frameRect(cv::Point2d(), cv::Size2d(frame.size()));
  const double minArea = std::max(1, detector_.settings().minArea);
  std::vector<TrackedObject> shown;
  for (TrackedObject o : objects) {
    o.box &= frameRect;
    if (o.box.area() < minArea) continue;
    shown.push_back(o);
    report.tracks.push_back(reportOf(o));
  }
  const int primary = primaryIndex(shown);
  if (primary >= 0) report.primary = report.tracks[primary];
  report.mask = detector_.mask();
  report.maskStep = detector_.lastDecimation();
  return report;
}

}  // namespace colortrack
