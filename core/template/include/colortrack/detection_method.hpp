// SPDX-License-Identifier: LGPL-2.1-or-later
// How the template tracker finds its target in a frame: one DetectionMethod per `Method`, each in its own
// file (core/template/src/method_<name>.cpp), created through the registry (method_registry.cpp). The
// Tracker owns what the methods share (the template model and the track) and hands it to the method it
// creates; the method moves the track, frame by frame.
#pragma once

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/image_source.hpp"
#include "colortrack/kalman_track.hpp"
#include "colortrack/template_model.hpp"
#include "colortrack/track_output.hpp"
#include "colortrack/tracker_settings.hpp"

namespace colortrack {

// What a method works on, owned by the Tracker and outliving the method.
struct MethodContext {
  const TrackerSettings &settings;  // the Tracker's current settings (they may change between frames)
  TemplateModel &model;
  KalmanTrack &track;
};

// One frame's find: a box in frame coordinates, its score and the edge check.
struct Detection {
  cv::Rect2d box;
  double score = 0;
  bool verified = false;
};

class DetectionMethod {
 public:
  virtual ~DetectionMethod() = default;

  // The target is at `box` of `frame` and the track has just been started there: learn from it.
  virtual void start(const ImageSource &frame, const cv::Rect2d &box) = 0;
  // One frame (the template fits in it; a lost track has become searching): move the track (update, coast,
  // start, lose it) and set the output's score and search region. The Tracker reports the track afterwards.
  virtual void process(const ImageSource &frame, double dt, TrackOutput &out) = 0;
  // The template or the colour model changed: drop whatever was learnt from the old one. (Tracker::reset()
  // leaves the method alone: it forgets the track, not the target; the fused method's re-detection after a
  // reset still uses its filters.)
  virtual void forget() = 0;
  // The picture cut to another scene (SceneCut): the Tracker has lost the track, if there was one, and does
  // not search this frame. What is found next may be anything.
  virtual void sceneCut() {}
};

// The method registered for `method`; throws std::logic_error for a value without a registration.
std::unique_ptr<DetectionMethod> createDetectionMethod(Method method, const MethodContext &context);

// One tracking method: its value, the name a user types, what it does, and its factory. The registry's table
// (method_registry.cpp) is the one list of the methods; the element's enum type is made from it.
struct MethodDescriptor {
  Method value;
  const char *nick;
  const char *description;
  std::unique_ptr<DetectionMethod> (*make)(const MethodContext &context);
};
// In Method's order (each row's value is its position).
const std::vector<MethodDescriptor> &methodDescriptors();

}  // namespace colortrack
