// SPDX-License-Identifier: LGPL-2.1-or-later
// A search region read at reduced resolution as colour bins: `f` full-resolution pixels make one local pixel
// (nearest neighbour: a sample of the pixels is enough for histograms and likelihoods), local coordinates
// start at the padded region's corner. Boxes are reduced to a smaller side of about kReducedWindowSide
// pixels, so the cost per frame stays about the same whatever the object's size.
#pragma once

#include <optional>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/image_source.hpp"

namespace colortrack {

constexpr double kReducedWindowSide = 40;

struct ReducedRegion {
  cv::Rect padded;  // frame coordinates
  int f = 1;
  cv::Rect searchL;  // where windows may lie, local coordinates
  cv::Size2d sizeL;  // the window size, local
  cv::Rect2d toFull(const cv::Rect2d &b) const {
    return cv::Rect2d(padded.x + b.x * f, padded.y + b.y * f, b.width * f, b.height * f);
  }
  cv::Point2d toLocal(double x, double y) const {
    return cv::Point2d((x - padded.x) / f, (y - padded.y) / f);
  }
};

class RegionReader {
 public:
  // Reads `region` (clipped to the frame) grown by `pad` on each side, for windows of `size` (frame px), into
  // bins(). None when no window fits.
  std::optional<ReducedRegion> read(const ImageSource &frame, const cv::Rect &region, cv::Size2d size,
                                    int pad, const BinMapper &mapper);
  // The bins of the last region read.
  const BinImage &bins() const { return bins_; }

 private:
  cv::Mat small_;
  BinImage bins_;
};

}  // namespace colortrack
