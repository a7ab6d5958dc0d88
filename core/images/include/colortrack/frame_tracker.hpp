// SPDX-License-Identifier: LGPL-2.1-or-later
// The one interface the element drives, whatever the mode: a frame in, the tracks it reports out. The
// template tracker (tracker.hpp) and the threshold tracker (threshold_tracker.hpp) implement it, so the
// element writes its metadata, messages, overlay and trails once for both.
#pragma once

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/choice.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/track.hpp"

namespace colortrack {

// Which FrameTracker follows the stream: how the object to track is defined.
enum class TrackingMode { Template, Threshold };
inline constexpr Choice<TrackingMode> kTrackingModes[] = {
    {TrackingMode::Template, "template", "Track the object of a template (template-location or init-box)"},
    {TrackingMode::Threshold, "threshold",
     "Track every blob inside an HSV range (hsv-lower/hsv-upper, or learnt from init-box), each with an id"},
};

// One tracked object as reported.
struct TrackReport {
  int id = 0;  // >= 1 once a track has existed
  TrackState state = TrackState::Searching;
  cv::Rect2d box;      // filtered box, frame coordinates; empty without a track
  cv::Point2d centre;  // the point a trail follows: the box centre, or (threshold) the blob's centroid
  double score = 0;
  bool verified = false;       // the edge check accepted the match (threshold mode: always, no such check)
  double scale = 1.0;          // size relative to the template or to the size at acquisition
  double vx = 0, vy = 0;       // filtered velocity, px/frame
  std::optional<double> area;  // threshold mode: pixels of the blob that fed the track
};

struct FrameReport {
  // The primary target (what a robot follows). Without one, its state says why (searching, lost) and its
  // box is empty.
  TrackReport primary;
  // Every reported track (template mode: the primary when it has a box).
  std::vector<TrackReport> tracks;
  // Several objects are followed (threshold mode): reports list every track, not just the primary.
  bool listsTracks = false;
  cv::Rect searchRegion;  // where this frame was searched (template mode; empty when nothing was)
  cv::Mat mask;           // threshold mode: the cleaned mask, one value per maskStep x maskStep pixels
  int maskStep = 1;
};

class FrameTracker {
 public:
  virtual ~FrameTracker() = default;
  // One frame; dt is the time since the previous one in frames.
  virtual FrameReport track(const ImageSource &frame, double dt) = 0;
  // Forgets every track and keeps what defines the target (template, colour range).
  virtual void reset() = 0;
};

}  // namespace colortrack
