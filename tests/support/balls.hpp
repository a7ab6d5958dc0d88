// SPDX-License-Identifier: LGPL-2.1-or-later
// Synthetic scenes for threshold mode: shaded balls of given colours moving along piecewise-linear paths over
// a cluttered background, with optional salt-and-pepper noise, a specular highlight (a hole in the colour
// blob) and a global brightness change. Exact ground truth per ball and frame.
#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace colortrack::balls {

struct Waypoint {
  int frame;
  cv::Point2d centre;
};

struct Ball {
  double hue = 0, saturation = 0.85, value = 0.85;  // h in degrees, at the ball's centre
  double radius = 20;
  // Linear between waypoints, held before the first and after the last. May leave the frame.
  std::vector<Waypoint> path;
  double highlight = 0;  // radius of a white specular spot, off-centre (0 = none)
};

struct BallSceneConfig {
  cv::Size frameSize{640, 480};
  std::uint32_t seed = 1;
  // Background: grey texture plus `clutterPatches` coloured rectangles whose hue keeps at least
  // `clutterHueClearance` degrees from every ball's hue (saturation up to clutterSaturation).
  int clutterPatches = 40;
  double clutterHueClearance = 60;
  double clutterSaturation = 0.9;
  double saltPepper = 0;      // fraction of pixels replaced, per frame, by ball 0's colour, white or black
  double brightness = 0;      // the whole frame's brightness varies by +- this fraction
  int brightnessPeriod = 60;  // frames per brightness cycle
  // A camera that looks at part of a larger scene: the background and the balls' paths are in the
  // coordinates of a scene of `sceneSize` (empty: the frame's size), and frame `index` shows the part whose
  // top-left corner is cameraPath[index] (the last one after the end; empty: the origin).
  cv::Size sceneSize;
  std::vector<cv::Point> cameraPath;
  // The camera also turns and zooms about the frame's centre: frame `index` shows the scene turned by
  // cameraTurn[index] degrees (counter-clockwise) and magnified cameraZoom[index] times (each the last one
  // after the end; empty: 0 and 1). Balls stay discs, their radius magnified too.
  std::vector<double> cameraTurn, cameraZoom;
};

struct BallTruth {
  cv::Point2d centre;
  double radius = 0;
  bool fullyVisible = false;  // the whole disc lies inside the frame
  bool visible = false;       // some of it does
};

class BallScene {
 public:
  BallScene(const BallSceneConfig &config, std::vector<Ball> balls);
  const BallSceneConfig &config() const { return config_; }
  const std::vector<Ball> &balls() const { return balls_; }

  // Frame `index` (deterministic) and, optionally, every ball's ground truth in that frame.
  cv::Mat render(int index, std::vector<BallTruth> *truth = nullptr) const;
  // In frame coordinates.
  BallTruth truthOf(int ball, int index) const;
  // The top-left corner of frame `index` in the scene (before the turn and the zoom).
  cv::Point cameraAt(int index) const;
  // Scene coordinates to frame `index`'s, a similarity (2x3).
  cv::Matx23d sceneToFrame(int index) const;
  // The ball's bounding box in frame `index`, rounded to whole pixels (an init-box a user would draw).
  cv::Rect boxOf(int ball, int index) const;

 private:
  BallSceneConfig config_;
  std::vector<Ball> balls_;
  cv::Mat background_;
};

cv::Vec3b bgrOfHsv(double hue, double saturation, double value);

// Three saturated balls (hue 0, 120, 240) on 640x480 whose straight paths cross within 90 frames (two of
// them overlap for several frames), over clutter too pale for a saturated range: the crossing scene of the
// multi-tracker's tests, in the core and in the element.
BallScene threeCrossingBalls();

}  // namespace colortrack::balls
