// SPDX-License-Identifier: LGPL-2.1-or-later
// GStreamer's analytics meta (GstAnalyticsRelationMeta, gstreamer-analytics-1.0, GStreamer 1.24 and newer):
// per reported track an object-detection mtd (type "colortrack", the ROI meta's box, the score clamped to
// 0..1) and a tracking mtd (track id, first and last seen, lost) related to it, so that analytics elements
// (objectdetectionoverlay, ...) read colortrack's tracks. Added next to the ROI metas, which stay.
//
// Built only when meson finds gstreamer-analytics-1.0 >= 1.24 (it defines COLORTRACK_HAVE_ANALYTICS);
// otherwise (GStreamer 1.22) AnalyticsTracks does nothing.
#pragma once

#include <gst/gst.h>

#include <opencv2/core.hpp>

#include "colortrack/frame_tracker.hpp"

#ifdef COLORTRACK_HAVE_ANALYTICS
#include <cstddef>
#include <map>
#include <utility>
#include <vector>
#endif

namespace colortrack_gst {

#ifdef COLORTRACK_HAVE_ANALYTICS

// The tracks one element has reported, for their first-seen times and to tell when one is gone.
class AnalyticsTracks {
 public:
  // Adds the analytics relation meta of `report` to `buffer` (or to the one already there): for each track
  // whose box lies in the `frame`-sized frame (the tracks that get a ROI meta), an od mtd with a tracking mtd
  // related to it (RELATE_TO, od -> tracking), last seen now; lost when the track's state is lost. A track
  // reported on the previous frame and missing now gets a tracking mtd alone, lost, with its last-seen time;
  // if it comes back under the same id, its first-seen time is the one from before.
  void attach(GstBuffer *buffer, const colortrack::FrameReport &report, cv::Size frame);

 private:
  // When track `id` was first reported: earlier, or (a new track) `now`.
  GstClockTime firstSeen(int id, GstClockTime now);

  struct Seen {
    GstClockTime first = GST_CLOCK_TIME_NONE;
    GstClockTime last = GST_CLOCK_TIME_NONE;
  };
  std::map<int, Seen> live_;  // by track id: the tracks reported on the previous frame
  // The first-seen times of the latest tracks gone (a tracker may give an object that comes back its old id:
  // threshold mode does, within max-coast-frames of leaving), oldest first; kept to kRememberedGone.
  std::vector<std::pair<int, GstClockTime>> gone_;
  static constexpr std::size_t kRememberedGone = 64;
};

#else

class AnalyticsTracks {
 public:
  void attach(GstBuffer *, const colortrack::FrameReport &, cv::Size) {}
};

#endif

}  // namespace colortrack_gst
