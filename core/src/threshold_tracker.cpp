#include "colortrack/threshold_tracker.hpp"

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
  const std::vector<Blob> blobs = detector_.detect(frame.channels(converted_));
  const std::vector<TrackedObject> objects = tracks_.update(blobs, frame.size(), dt);
  FrameReport report;
  report.listsTracks = true;
  for (const TrackedObject &o : objects) report.tracks.push_back(reportOf(o));
  const int primary = primaryIndex(objects);
  if (primary >= 0) report.primary = report.tracks[primary];
  report.mask = detector_.mask();
  report.maskStep = detector_.lastDecimation();
  return report;
}

}  // namespace colortrack
