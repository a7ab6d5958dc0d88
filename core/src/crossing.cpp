#include "colortrack/crossing.hpp"

#include <algorithm>
#include <cmath>

namespace colortrack {

namespace {

// The velocity is fitted to this many last places (a walker's steps and the peak's cell jitter).
constexpr std::size_t kFitFrames = 6;
// A second peak within this far (target sizes) from where the look-alike was expected is the same look-alike;
// further, it is another one and its motion starts again.
constexpr double kGate = 0.5;
// A look-alike that vanishes into the peak within this distance (target sizes) of the target merged with it
// (rather than left the window).
constexpr double kMerge = 1.0;
// Its motion must be known from this many frames to be extrapolated through a merge.
constexpr int kKnownFrames = 3;
// Two peaks are swapped only when swapping fits both motions better by this much in all (target sizes).
constexpr double kSwapMargin = 0.3;
// A merge not parted within this many frames is over (one of the two left, or they walk together).
constexpr int kMaxMergedFrames = 40;

}  // namespace

void Crossing::Motion::observe(cv::Point2d at, int after) {
  const double time = recent_.empty() ? 0 : recent_.back().first + after;
  recent_.emplace_back(time, at);
  if (recent_.size() > kFitFrames) recent_.pop_front();
  place = at;
  ++frames;
  // Least squares over the recent places (a peak moves by whole cells: one step is too noisy).
  double meanTime = 0;
  cv::Point2d meanPlace(0, 0);
  for (const auto &[t, p] : recent_) {
    meanTime += t;
    meanPlace += p;
  }
  meanTime /= recent_.size();
  meanPlace /= static_cast<double>(recent_.size());
  double spread = 0;
  cv::Point2d covariance(0, 0);
  for (const auto &[t, p] : recent_) {
    spread += (t - meanTime) * (t - meanTime);
    covariance += (t - meanTime) * (p - meanPlace);
  }
  velocity = spread > 0 ? covariance / spread : cv::Point2d(0, 0);
}

void Crossing::reset() {
  target_ = Motion();
  rival_ = Motion();
  merged_ = -1;
}

// Which of the two peaks continues the target's motion `ahead` frames after both motions were last seen:
// the second one, when swapping fits both motions better by the margin.
double Crossing::apart(cv::Point2d a, cv::Point2d b) const {
  return std::hypot((a.x - b.x) / size_.width, (a.y - b.y) / size_.height);
}

bool Crossing::swapped(cv::Point2d peak, cv::Point2d rival, int ahead) const {
  const cv::Point2d targetAt = target_.predicted(ahead), rivalAt = rival_.predicted(ahead);
  const double keep = apart(peak, targetAt) + apart(rival, rivalAt);
  const double swap = apart(rival, targetAt) + apart(peak, rivalAt);
  return swap < keep - kSwapMargin;
}

std::optional<cv::Point2d> Crossing::observe(cv::Point2d peak, std::optional<cv::Point2d> rival,
                                             cv::Size2d size) {
  size_ = cv::Size2d(std::max(size.width, 1.0), std::max(size.height, 1.0));
  const bool known = target_.frames >= kKnownFrames && rival_.frames >= kKnownFrames;
  if (merged_ > 0) {
    ++merged_;
    if (!rival) {
      if (merged_ > kMaxMergedFrames) reset();
      return std::nullopt;
    }
  }
  if (rival && known && swapped(peak, *rival, std::max(merged_, 1))) {
    // The peak went over to the look-alike: each motion takes its own place back.
    target_.observe(*rival, std::max(merged_, 1));
    rival_.observe(peak, std::max(merged_, 1));
    merged_ = -1;
    return *rival;
  }
  if (merged_ > 0 && rival) {
    target_.observe(peak, merged_);
    rival_.observe(*rival, merged_);
    merged_ = -1;
    return std::nullopt;
  }
  follow(peak, rival);
  return std::nullopt;
}

// Apart: both motions follow their peaks; a known look-alike that vanishes next to the target has merged.
void Crossing::follow(cv::Point2d peak, std::optional<cv::Point2d> rival) {
  if (!rival) {
    if (rival_.frames >= kKnownFrames && target_.frames >= kKnownFrames &&
        apart(rival_.predicted(1), target_.predicted(1)) < kMerge) {
      merged_ = 1;
      return;
    }
    rival_ = Motion();
    target_.observe(peak, 1);
    return;
  }
  if (rival_.frames > 0 && apart(*rival, rival_.predicted(1)) > kGate) rival_ = Motion();
  rival_.observe(*rival, 1);
  target_.observe(peak, 1);
}

}  // namespace colortrack
