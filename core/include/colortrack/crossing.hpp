// Identities through a crossing (issue 46): a look-alike that meets the target in the search window answers
// the filters as well as the target, and when the two part again the window's peak may be on either. Each
// keeps its own motion while they cross, so the one whose place continues the target's motion from before
// the meeting is the target. The window's second peak (FusedDetector::Estimate::rival) is followed as the
// look-alike; while the two are merged into one peak both are extrapolated at their velocities from before.
#pragma once

#include <deque>
#include <optional>
#include <utility>

#include <opencv2/core.hpp>

namespace colortrack {

class Crossing {
 public:
  void reset();
  // A frame the track follows: the window's peak `peak`, its second peak `rival` if it answers nearly as
  // well, and the target's size, frame px. Returns the second peak when it, not the peak, continues the
  // target's motion (and the peak the look-alike's).
  std::optional<cv::Point2d> observe(cv::Point2d peak, std::optional<cv::Point2d> rival, cv::Size2d size);

 private:
  // A place and its velocity (px per frame): a straight line fitted to the last few places.
  struct Motion {
    cv::Point2d place;
    cv::Point2d velocity{0, 0};
    int frames = 0;  // observations; 0: none
    cv::Point2d predicted(int ahead) const { return place + velocity * ahead; }
    // Seen at `at`, `after` frames after the last place.
    void observe(cv::Point2d at, int after);

   private:
    std::deque<std::pair<double, cv::Point2d>> recent_;  // (time in frames, place)
  };
  void follow(cv::Point2d peak, std::optional<cv::Point2d> rival);
  bool swapped(cv::Point2d peak, cv::Point2d rival, int ahead) const;
  // How far apart two places are, in target widths and heights.
  double apart(cv::Point2d a, cv::Point2d b) const;

  cv::Size2d size_{1, 1};  // the target's size this frame
  Motion target_;
  Motion rival_;
  int merged_ = -1;  // frames since both were last seen apart, while merged; negative: apart
};

}  // namespace colortrack
