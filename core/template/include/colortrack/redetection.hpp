// SPDX-License-Identifier: LGPL-2.1-or-later
// The fused method's re-detection over the whole frame: the colour likelihood proposes places at a few sizes,
// the correlation filter and its scale filter judge them, and only a confident one restarts the track.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/fused_detector.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/likelihood.hpp"

namespace colortrack {

// What a detection of this track usually looks like (running means over learnt frames); `known` is false
// until there are enough of them, and the bars are then absolute.
struct UsualDetection {
  bool known = false;
  double confidence = 0;  // peak-to-sidelobe ratio of the fused response
  double colour = 0;      // colour cue at the peak
};

class Redetector {
 public:
  // The best place over the whole frame for a target last seen at `last` with `size` (sizes are kept within
  // [minSize, frame]), if it passes the proposal bars against `usual`. A place under the confirmation bar
  // (confirmed()) is a guess to follow, not yet the target. A `lost` track's search also takes candidates
  // from the colours the whole frame rarely shows (FusedDetector::colourCandidates).
  std::optional<FusedDetector::Estimate> search(const ImageSource &frame, FusedDetector &detector,
                                                const BinMapper &colors, const ColorLikelihood &likelihood,
                                                cv::Point2d last, cv::Size2d size, cv::Size2d minSize,
                                                const UsualDetection &usual, bool lost);
  // Whether `e` is sure enough to be the target again: a re-detection, or a frame of a track begun from one.
  static bool confirmed(const FusedDetector::Estimate &e, const UsualDetection &usual);

 private:
  static bool colourLike(const FusedDetector::Estimate &e, const UsualDetection &usual);
  static bool proposed(const FusedDetector::Estimate &e, const UsualDetection &usual);
  static bool passes(const FusedDetector::Estimate &e, const UsualDetection &usual, double share);

  int nextSize_ = 0;  // which of the relative sizes the next search tries
};

}  // namespace colortrack
