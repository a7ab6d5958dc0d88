// SPDX-License-Identifier: LGPL-2.1-or-later
// What the template tracker is told: the method that searches a frame and the settings the methods share.
#pragma once

#include "colortrack/color.hpp"
#include "colortrack/edges.hpp"
#include "colortrack/histogram.hpp"
#include "colortrack/kalman.hpp"
#include "colortrack/scale.hpp"

namespace colortrack {

// How a frame is searched for the target.
enum class Method {
  // The paper's modified colour indexing: the template's per-channel histograms against every window by
  // weighted histogram intersection, scale by window-versus-ring match.
  Indexing,
  // Object-versus-surroundings colour likelihood P(object | colour), learnt from the target box and the
  // ring around it and adapted slowly; windows scored by their mean likelihood with a motion prior, box size
  // and aspect by the likelihood mass they enclose. Falls back to Indexing until it has been learnt (a
  // template file has no surroundings: the first detection teaches it).
  Discriminative,
  // Two learners fused (as in Staple): a discriminative correlation filter over gradient-orientation cells
  // and intensity (shape, learnt online in the Fourier domain) and the colour likelihood above, their
  // response maps summed; a 1-D scale filter; the fused response's peak-to-sidelobe confidence decides
  // tracking / coasting / lost and gates learning; a lost target is re-detected over the whole frame.
  Fused,
};

struct TrackerSettings {
  Method method = Method::Fused;
  ColorSpace colorSpace = ColorSpace::Hsv;
  BinLayout bins;
  ChannelWeights weights;
  double matchThreshold = 0.25;  // minimum match value of a detection (a product of three intersections)
  ScaleParams scale;
  double searchMargin = 2.0;  // search region = box grown by margin * size + 3 sigma of the prediction
  KalmanParams kalman;
  int maxCoastFrames = 10;  // frames without detection before the track is lost
  // The camera's own motion (GlobalMotion) taken out of the predictions: a panning or turning camera moves
  // every track with the picture. Threshold mode.
  bool followCamera = true;
  VerifyMode verify = VerifyMode::Both;
  double verifyTolerance = 0.5;

  // Discriminative method only.
  double likelihoodThreshold = 0.3;  // minimum mean P(object | colour) in the box for a detection
  double modelUpdateRate = 0.05;     // how fast the likelihood follows appearance changes (0 = never)
  bool adaptAspect = true;           // let the box's width and height change independently
};

}  // namespace colortrack
