// SPDX-License-Identifier: LGPL-2.1-or-later
// Minimum-cost assignment: threshold mode's blobs to tracks, and the MOT evaluation's tracks to ground truth.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace colortrack {

// Minimum-cost assignment (Hungarian method with potentials, O(n^2 m)) for a rows x cols CV_64F cost matrix.
// Returns, per row, the column assigned to it, or -1 for the rows left over when rows > cols. Every cost
// must be finite; give forbidden pairs a large cost and discard them afterwards.
std::vector<int> solveAssignment(const cv::Mat &cost);

}  // namespace colortrack
