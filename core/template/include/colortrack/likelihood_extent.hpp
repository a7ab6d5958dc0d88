// SPDX-License-Identifier: LGPL-2.1-or-later
// The target's extent read off a colour likelihood map: the box whose inside is most object-like and whose
// surroundings are least (DAT, Possegger et al. 2015, sizes its box from the same map). The fused method's
// scale filter compares gradient patterns at a few sizes and lags a target that shrinks or changes shape;
// the colour map shows where the object's colours end.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace colortrack {

struct ExtentVote {
  cv::Size2d factor{1, 1};  // the chosen width and height relative to the size tried
  cv::Point2d shift{0, 0};  // the chosen centre's offset from the one tried, as a share of the size tried
  double contrast = 0;      // mean likelihood inside minus in the ring around it, at the chosen box
};

// Tries every box of width size * fw and height size * fh (fw, fh each 1 or from `factors`) centred at
// `centre` + (sx * width, sy * height) (sx, sy each 0 or from `shifts`) on `integral`, the CV_64F integral
// image of a likelihood map in the same coordinates, and keeps the one with the largest contrast. The ring
// around a box is `ringWidth` times its smaller side wide, clipped to the map; a box that leaves the map is
// not tried.
ExtentVote likelihoodExtent(const cv::Mat &integral, cv::Point2d centre, cv::Size2d size,
                            const std::vector<double> &factors, const std::vector<double> &shifts,
                            double ringWidth);

}  // namespace colortrack
