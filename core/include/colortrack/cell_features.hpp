// Gradient-orientation cell features (HOG-like) and intensity: the shape cue of the correlation filter.
//
// Written here rather than taken from dlib's FHOG: dlib is a large header library whose fhog works on its own
// image types (a copy per call), and the filter needs only a few small patches per frame; this is ~100 lines
// and tested (tests/core/test_cell_features.cpp).
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

}  // namespace colortrack
