// SPDX-License-Identifier: LGPL-2.1-or-later
// The colour methods' frame loop (indexing, discriminative, and fused until its filters start): search
// around the Kalman prediction while tracking, over the whole frame while searching, and now and then over
// the whole frame for a verified target while the track is colour-only. What scores the windows is a
// ColorCue, the part that differs between the colour methods.
#pragma once

#include <iterator>
#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/detection_method.hpp"
#include "colortrack/image_source.hpp"

namespace colortrack {

// The object may have changed size while it was away: each search of the whole frame tries the next scale of
// this list (the last size first), which keeps the cost of a frame to one search.
inline constexpr double kSearchScales[] = {1.0, 1.0 / 1.4, 1.4, 0.5, 2.0};
inline constexpr int kSearchScaleCount = static_cast<int>(std::size(kSearchScales));

class ColorCue {
 public:
  virtual ~ColorCue() = default;
  // The best detection in `region` (frame coordinates) for a box of `scale`, near `prior` when given (a
  // cue may ignore it); none when nothing passes the cue's threshold.
  virtual std::optional<Detection> detectIn(const ImageSource &frame, const cv::Rect &region, double scale,
                                            const cv::Point2d *prior) = 0;
  // The top-left corner of the best `window` in `coarse` (a whole frame at reduced resolution); none if
  // nothing fits.
  virtual std::optional<cv::Point> bestCoarseWindow(const BinImage &coarse, cv::Size window) = 0;
  // Learns from the target found at `box` (after the track has been started or updated there).
  virtual void learn(const ImageSource &frame, const cv::Rect2d &box) = 0;
};

class ColorSearch {
 public:
  // `cue` must outlive the search.
  ColorSearch(const MethodContext &context, ColorCue &cue) : context_(context), cue_(cue) {}

  // One frame, as DetectionMethod::process.
  void process(const ImageSource &frame, double dt, TrackOutput &out);

 private:
  void follow(const ImageSource &frame, double dt, TrackOutput &out);
  void acquire(const ImageSource &frame, TrackOutput &out);
  bool switchToVerifiedTarget(const ImageSource &frame, double scale, TrackOutput &out);
  std::optional<Detection> detectEverywhere(const ImageSource &frame, double scale);

  MethodContext context_;
  ColorCue &cue_;
  cv::Mat small_;  // scratch reused across frames
  BinImage coarseBins_;
};

// A method that is the colour search over one cue (the indexing and discriminative methods): the cue learns
// from the box a track starts at, and what it learns belongs to the template model, which forgets it itself.
template <class Cue>
class ColorSearchMethod final : public DetectionMethod {
 public:
  explicit ColorSearchMethod(const MethodContext &context) : cue_(context), search_(context, cue_) {}

  void start(const ImageSource &frame, const cv::Rect2d &box) override { cue_.learn(frame, box); }
  void process(const ImageSource &frame, double dt, TrackOutput &out) override {
    search_.process(frame, dt, out);
  }
  void forget() override {}

 private:
  Cue cue_;
  ColorSearch search_;
};

}  // namespace colortrack
