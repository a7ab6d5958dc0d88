// SPDX-License-Identifier: LGPL-2.1-or-later
// Shrinking an 8-bit image by area averaging, as cv::resize's INTER_AREA does, for the search window the
// fused method cuts every frame.
#pragma once

#include <opencv2/core.hpp>

namespace colortrack {

// `source` (CV_8UC1 .. CV_8UC4) shrunk to `size` (no larger than the source in either direction): each output
// pixel is the mean of the source area it covers, pixels cut by its edges weighted by the part inside. The
// same result as cv::resize(..., INTER_AREA) to within one grey level.
void shrinkByArea(const cv::Mat &source, cv::Size size, cv::Mat &out);

}  // namespace colortrack
