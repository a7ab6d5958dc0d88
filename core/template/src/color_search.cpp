// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/color_search.hpp"

#include <algorithm>

namespace colortrack {

namespace {

// Full-frame searches run on a frame reduced so that the window's smaller side is about this many pixels:
// histograms need only a sample of the pixels, and this keeps a 1080p search within a few milliseconds.
constexpr int kCoarseWindowSide = 16;
// While the track is colour-only (unverified), look over the whole frame this often for a verified target.
constexpr int kUnverifiedGlobalSearchPeriod = 5;

}  // namespace

void ColorSearch::process(const ImageSource &frame, double dt, TrackOutput &out) {
  if (context_.track.active())
    follow(frame, dt, out);
  else
    acquire(frame, out);
}

// Tracking or coasting: the region around the prediction.
void ColorSearch::follow(const ImageSource &frame, double dt, TrackOutput &out) {
  const TrackerSettings &s = context_.settings;
  KalmanTrack &track = context_.track;
  const cv::Size frameSize = frame.size();
  const cv::Size templateSize = context_.model.templateSize();
  track.kalman.predict(dt);
  // Keep the predicted scale sane: the window must fit in the frame.
  const double maxScale = std::min(static_cast<double>(frameSize.width) / templateSize.width,
                                   static_cast<double>(frameSize.height) / templateSize.height);
  // Search around the last measured size, not the predicted one: a scale velocity learnt from noisy sizes
  // would otherwise run ahead of the +-6% the refinement can pull back each frame, and collapse the box.
  const double scale = std::clamp(track.lastScale, 0.1, maxScale);
  out.searchRegion = track.predictionRegion(s.searchMargin) & cv::Rect(cv::Point(), frameSize);
  const cv::Point2d predicted(track.kalman.x(), track.kalman.y());
  const std::optional<Detection> detection = cue_.detectIn(frame, out.searchRegion, scale, &predicted);
  if (detection && !detection->verified && s.verify != VerifyMode::None &&
      ++track.unverifiedFrames % kUnverifiedGlobalSearchPeriod == 0 &&
      switchToVerifiedTarget(frame, scale, out))
    return;
  if (!detection) {
    track.coast(s.maxCoastFrames);
    return;
  }
  if (detection->verified) track.unverifiedFrames = 0;
  track.update(detection->box);
  cue_.learn(frame, detection->box);
  out.score = detection->score;
  track.lastVerified = detection->verified;
}

// A colour-only track may be a same-colour decoy: look over the whole frame for a verified target and move to
// it (a new track, since it is another object). True when it moved.
bool ColorSearch::switchToVerifiedTarget(const ImageSource &frame, double scale, TrackOutput &out) {
  const std::optional<Detection> global = detectEverywhere(frame, scale);
  if (!global || !global->verified) return false;
  context_.track.start(global->box, context_.settings.kalman);
  cue_.learn(frame, global->box);
  out.searchRegion = cv::Rect(cv::Point(), frame.size());
  out.score = global->score;
  context_.track.lastVerified = true;
  return true;
}

// Searching: the whole frame, at the next size of the list.
void ColorSearch::acquire(const ImageSource &frame, TrackOutput &out) {
  KalmanTrack &track = context_.track;
  out.searchRegion = cv::Rect(cv::Point(), frame.size());
  const double factor = kSearchScales[track.searchFrames++ % kSearchScaleCount];
  const std::optional<Detection> detection =
      detectEverywhere(frame, std::clamp(track.lastScale * factor, 0.1, 10.0));
  if (!detection) return;
  track.start(detection->box, context_.settings.kalman);
  cue_.learn(frame, detection->box);
  out.score = detection->score;
  track.lastVerified = detection->verified;
}

// Full-frame search: a coarse pass on a reduced frame, then a full-resolution search around its best.
std::optional<Detection> ColorSearch::detectEverywhere(const ImageSource &frame, double scale) {
  const cv::Size frameSize = frame.size();
  const cv::Size2d size = context_.track.windowSize(scale);
  if (size.width > frameSize.width || size.height > frameSize.height) return std::nullopt;
  const int factor = std::max(1, static_cast<int>(std::min(size.width, size.height) / kCoarseWindowSide));
  if (factor == 1) return cue_.detectIn(frame, cv::Rect(cv::Point(), frameSize), scale, nullptr);

  // A sample of the pixels is enough for histograms; no need for a filtered image.
  frame.sampledBgr(cv::Rect(cv::Point(), frameSize), factor, small_);
  context_.model.mapper().map(small_, coarseBins_.bins);
  coarseBins_.origin = cv::Point();
  const cv::Size coarseWindow(std::max(1, cvRound(size.width / factor)),
                              std::max(1, cvRound(size.height / factor)));
  const std::optional<cv::Point> coarseBest = cue_.bestCoarseWindow(coarseBins_, coarseWindow);
  if (!coarseBest) return std::nullopt;
  const cv::Rect around(coarseBest->x * factor - 2 * factor, coarseBest->y * factor - 2 * factor,
                        cvRound(size.width) + 4 * factor, cvRound(size.height) + 4 * factor);
  return cue_.detectIn(frame, around, scale, nullptr);
}

}  // namespace colortrack
