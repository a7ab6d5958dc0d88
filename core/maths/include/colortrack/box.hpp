// SPDX-License-Identifier: LGPL-2.1-or-later
// Box arithmetic shared by the template tracker's parts.
#pragma once

#include <algorithm>

#include <opencv2/core.hpp>

namespace colortrack {

// The whole-pixel rectangle nearest to `r`, at least one pixel on each side.
inline cv::Rect roundRect(const cv::Rect2d &r) {
  return cv::Rect(cvRound(r.x), cvRound(r.y), std::max(1, cvRound(r.width)), std::max(1, cvRound(r.height)));
}

inline cv::Rect2d centredBox(double cx, double cy, cv::Size2d size) {
  return cv::Rect2d(cx - size.width / 2, cy - size.height / 2, size.width, size.height);
}

inline cv::Point2d boxCentre(const cv::Rect2d &box) {
  return cv::Point2d(box.x + box.width / 2, box.y + box.height / 2);
}

}  // namespace colortrack
