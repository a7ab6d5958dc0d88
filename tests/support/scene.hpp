// SPDX-License-Identifier: LGPL-2.1-or-later
// Synthetic scene with exact ground truth: a coloured, textured object on a textured background that
// moves, turns, grows and shrinks while the lighting changes. One generator serves the tests, the demo and
// the benchmarks, so every figure is produced on the same kind of input.
#pragma once

#include <cstdint>

#include <opencv2/core.hpp>

namespace colortrack::scene {

struct SceneConfig {
  cv::Size frameSize{640, 480};
  int frames = 240;                       // length of one pass of the motion script (it repeats after)
  std::uint32_t seed = 1;                 // background texture and object texture
  cv::Size objectSize{72, 72};            // at scale 1, unrotated
  double scaleMin = 1.0, scaleMax = 1.0;  // the object's scale oscillates between these
  double rotationDegrees = 0;             // the object turns from 0 to this angle and back over one pass
  double brightness = 0;                  // lighting varies by +- this fraction (0.4 = +-40%) over one pass
  double speed = 1.0;                     // multiplies the motion amplitude along the path
  bool decoy = false;  // an untextured disc of the object's mean colour, elsewhere in the frame
  // The object leaves the frame during [leaveFrom, leaveTo) and comes back at another place (-1: never).
  int leaveFrom = -1, leaveTo = -1;
  // > 0: the object goes round a circle about the path's centre at this many px/frame (speed 0 holds it
  // there) instead of the figure of eight.
  double circleSpeed = 0;
  // A panning camera: the background moves by this many whole px per frame in the image (over one pass;
  // it jumps back when the pass repeats).
  cv::Point backgroundVelocity{0, 0};
  // A flat board in the object's colours (wide bands, no texture) hides the object during
  // [occludeFrom, occludeTo), covering every place it passes in that time (-1: never).
  int occludeFrom = -1, occludeTo = -1;
};

struct SceneFrame {
  cv::Mat bgr;  // CV_8UC3
  bool objectVisible = true;
  cv::Rect2d box;            // ground truth: axis-aligned bounding box of the object (frame coords)
  double objectScale = 1.0;  // current scale relative to the template
  cv::Rect2d decoyBox;       // empty when there is no decoy
  cv::Rect boardBox;         // the occluding board while it is shown, else empty
};

class Scene {
 public:
  explicit Scene(const SceneConfig &config);
  const SceneConfig &config() const { return config_; }

  // Frame `index` (deterministic: the same index always gives the same pixels).
  SceneFrame render(int index) const;

  // The object at scale 1, unrotated, normal lighting, on its own: bgr + mask (CV_8UC1, 255 = object).
  void objectTemplate(cv::Mat &bgr, cv::Mat &mask) const;
  // Ground-truth box of frame 0's object, rounded to whole pixels (what a user would give as init-box).
  cv::Rect initBox() const;

 private:
  SceneConfig config_;
  cv::Mat background_;                  // texture: the frame, and what a pass of backgroundVelocity uncovers
  cv::Mat objectTexture_, objectMask_;  // objectSize
  cv::Mat decoyTexture_, decoyMask_;    // the object's colours in smooth rings
};

// Intersection over union of two boxes (0 when either is empty).
double iou(const cv::Rect2d &a, const cv::Rect2d &b);
// Distance between box centres.
double centreError(const cv::Rect2d &a, const cv::Rect2d &b);

}  // namespace colortrack::scene
