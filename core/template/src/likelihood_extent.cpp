// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/likelihood_extent.hpp"

#include <algorithm>

#include "colortrack/likelihood.hpp"

namespace colortrack {

namespace {

// Mean likelihood inside the box of `size` at `centre` minus the mean in the ring around it; far below any
// contrast when the box leaves the map.
double contrastOf(const cv::Mat &integral, cv::Point2d centre, cv::Size2d size, double ringWidth) {
  const cv::Rect limits(0, 0, integral.cols - 1, integral.rows - 1);
  const cv::Rect inner(cvRound(centre.x - size.width / 2), cvRound(centre.y - size.height / 2),
                       std::max(1, cvRound(size.width)), std::max(1, cvRound(size.height)));
  if ((inner & limits) != inner) return -1e9;
  const int ring = std::max(1, cvRound(ringWidth * std::min(size.width, size.height)));
  const cv::Rect outer =
      cv::Rect(inner.x - ring, inner.y - ring, inner.width + 2 * ring, inner.height + 2 * ring) & limits;
  const double innerSum = boxSum(integral, inner), ringArea = double(outer.area()) - inner.area();
  const double inside = innerSum / inner.area();
  const double around = ringArea > 0 ? (boxSum(integral, outer) - innerSum) / ringArea : 0;
  return inside - around;
}

}  // namespace

ExtentVote likelihoodExtent(const cv::Mat &integral, cv::Point2d centre, cv::Size2d size,
                            const std::vector<double> &factors, const std::vector<double> &shifts,
                            double ringWidth) {
  std::vector<double> sides{1}, offsets{0};
  sides.insert(sides.end(), factors.begin(), factors.end());
  offsets.insert(offsets.end(), shifts.begin(), shifts.end());
  ExtentVote best;
  best.contrast = contrastOf(integral, centre, size, ringWidth);
  for (double sy : offsets)
    for (double sx : offsets) {
      const cv::Point2d at(centre.x + sx * size.width, centre.y + sy * size.height);
      for (double fw : sides)
        for (double fh : sides) {
          const double contrast =
              contrastOf(integral, at, cv::Size2d(size.width * fw, size.height * fh), ringWidth);
          // Strictly better only, so that ties keep the box tried.
          if (contrast > best.contrast + 1e-9) {
            best.contrast = contrast;
            best.factor = cv::Size2d(fw, fh);
            best.shift = cv::Point2d(sx, sy);
          }
        }
    }
  return best;
}

}  // namespace colortrack
