#include "colortrack/threshold_tracker.hpp"

#include <algorithm>

#include "colortrack/round_split.hpp"

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
    : detector_(blobs), tracks_(tracks) {}

FrameReport ThresholdTracker::track(const ImageSource &frame, double dt) {
  // Objects touching make one blob; those whose shape shows they are several round objects are split here,
  // so that each gets its track from the start.
  const BlobSettings &settings = detector_.settings();
  const std::vector<Blob> detected = detector_.detect(frame.channels(converted_));
  const std::vector<Blob> blobs =
      splitRoundBlobs(detected, detector_.labels(), settings.minArea, settings.maxObjects);
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
