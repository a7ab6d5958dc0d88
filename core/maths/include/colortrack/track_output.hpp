// SPDX-License-Identifier: LGPL-2.1-or-later
// What the template tracker reports for a frame.
#pragma once

#include <opencv2/core.hpp>

#include "colortrack/track.hpp"

namespace colortrack {

struct TrackOutput {
  TrackState state = TrackState::Searching;
  bool hasBox = false;  // a track exists (tracking or coasting)
  int id = 0;           // track id, >= 1 once a track has existed; grows at every new acquisition
  cv::Rect2d box;       // filtered box, frame coordinates
  // Indexing and discriminative: match value of this frame's detection against the template (0 when
  // coasting). Fused: the frame's confidence relative to the track's usual one, capped at 1 and at
  // 1 - rival / 2 when a look-alike answers in the window (under 0.5: not a detection, a guess or doubted).
  double score = 0;
  bool verified = false;  // edge check passed (always true when verify = None)
  double scale = 1.0;     // box size relative to the template
  double vx = 0, vy = 0;  // filtered velocity, px/frame
  cv::Rect searchRegion;  // where this frame was searched (empty if nothing was searched)
};

}  // namespace colortrack
