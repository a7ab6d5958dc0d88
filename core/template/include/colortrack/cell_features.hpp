// SPDX-License-Identifier: LGPL-2.1-or-later
// Gradient-orientation cell features (HOG-like) and intensity: the shape cue of the correlation filter.
//
// Written here rather than taken from dlib's FHOG: dlib is a large header library whose fhog works on its own
// image types (a copy per call), and the filter needs only a few small patches per frame; this is ~100 lines
// and tested (tests/core/test_correlation_filter.cpp).
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace colortrack {

// Channels per cell: kOrientations contrast-insensitive orientation bins, each normalised by the four 2x2
// cell blocks around the cell (clipped, as in Dalal-Triggs / Felzenszwalb), four texture-energy channels (the
// gradient energy under each of the four normalisations) and the cell's mean intensity.
constexpr int kOrientations = 9;
constexpr int kCellChannels = kOrientations + 4 + 1;

// gray: CV_32FC1 in [0,1]; its width and height are multiples of `cell`. Writes kCellChannels maps of
// (width / cell) x (height / cell), CV_32FC1, reusing the matrices in `channels`.
void cellFeatures(const cv::Mat &gray, int cell, std::vector<cv::Mat> &channels);

// The same features for many rectangles of one image (a scale filter's samples): every pixel's orientation
// votes and intensity are summed once into integral images, after which each cell costs a few lookups
// instead of resampling and re-differentiating every sample. Gradients are taken at the image's resolution,
// so a cell of a large rectangle sums more pixels than one of a small rectangle; the block normalisation
// makes the features comparable.
class CellFeatureIntegral {
 public:
  // gray: CV_32FC1 in [0,1].
  void build(const cv::Mat &gray);
  // Features of `rect` (image coordinates, may be fractional; cells are rounded to whole pixels and kept
  // inside the image) divided into `cells` cells.
  void features(const cv::Rect2d &rect, cv::Size cells, std::vector<cv::Mat> &channels) const;

 private:
  static constexpr int kPlanes = kOrientations + 1;  // orientation votes and intensity
  std::vector<double> sums_;                         // (rows + 1) x (cols + 1) x kPlanes
  cv::Size size_;
};

}  // namespace colortrack
