// SPDX-License-Identifier: LGPL-2.1-or-later
// The picture colortrack draws on a frame from its report, the same for both modes: the threshold mask, the
// search window, and per track its trail, box and label.
#pragma once

#include <cstddef>
#include <deque>
#include <map>
#include <vector>

#include <gst/video/video.h>

#include <opencv2/core.hpp>

#include "colortrack/frame_tracker.hpp"

namespace colortrack_gst {

// The recent centres of each reported track, oldest first, for drawing its path.
class Trails {
 public:
  // Forgets the tracks no longer reported, then adds each track's centre (keeping at most `length`).
  void update(const std::vector<colortrack::TrackReport> &tracks, std::size_t length);
  void clear() { byId_.clear(); }
  const std::deque<cv::Point2d> *of(int id) const;

 private:
  std::map<int, std::deque<cv::Point2d>> byId_;
};

// Which parts to draw (the element's `draw` flags).
struct OverlayParts {
  bool box = false, trail = false, searchWindow = false, label = false, mask = false;
  bool any() const { return box || trail || searchWindow || label || mask; }
};

// Draws `report` on `frame` (mapped for writing). A report that lists several tracks (threshold mode) colours
// each by its id and labels it with its area; a single track (template mode) is coloured by how sure it is
// (red: colour only, green: verified, orange: coasting) and labelled with its score.
void drawTracks(GstVideoFrame *frame, const colortrack::FrameReport &report, const Trails &trails,
                const OverlayParts &parts);

}  // namespace colortrack_gst
