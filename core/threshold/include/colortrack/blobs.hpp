// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode, pixel side: connected components ("blobs") of the segmented mask (hsv_segment.hpp: the HSV
// range, its lookup table and the clean-up), plus learning a range from the pixels of a box.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/hsv_segment.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/settings.hpp"  // parseHsv, formatHsv

namespace colortrack {

struct BlobSettings {
  HsvRange range;
  int morphSize = 5;   // kernel side in frame pixels for the opening then closing; 0 disables
  int minArea = 50;    // in frame pixels
  int maxObjects = 8;  // the largest blobs kept
  int decimation = 0;  // segment every n-th pixel in x and y; 0 = automatic (1 up to 640x480, else 2)
};

// A connected component, in frame coordinates (measured on the decimated grid and scaled back).
struct Blob {
  double area = 0;       // pixel count, frame pixels
  cv::Point2d centroid;  // centre of mass
  cv::Rect box;          // bounding box: x1 = box.x, x2 = box.x + box.width - 1 (and y alike)
  double fill = 0;       // area / box area
  int label = 0;         // its component in BlobDetector::labels() (0: not from a detector)
};

// The samples of one blob (or part of one) on a segmentation grid, gathered one by one.
struct GridMoments {
  long long count = 0, sumX = 0, sumY = 0;
  int minX = std::numeric_limits<int>::max(), maxX = -1, minY = std::numeric_limits<int>::max(), maxY = -1;
  void add(int x, int y) {
    ++count;
    sumX += x;
    sumY += y;
    minX = std::min(minX, x);
    maxX = std::max(maxX, x);
    minY = std::min(minY, y);
    maxY = std::max(maxY, y);
  }
  // The blob they make in frame coordinates, grid sample (x, y) being frame pixel (x step, y step), its box
  // clipped to `bounds`. Needs count > 0.
  Blob toBlob(int step, const cv::Rect &bounds) const;
};

// Where each blob's pixels are: the detector's component labels on its (decimated) grid, grid sample (x, y)
// being frame pixel (x step, y step). Empty when unknown.
struct BlobLabels {
  cv::Mat labels;  // CV_32S
  int step = 1;
  bool empty() const { return labels.empty(); }
};

class BlobDetector {
 public:
  explicit BlobDetector(const BlobSettings &settings = BlobSettings());
  void setSettings(const BlobSettings &settings);
  const BlobSettings &settings() const { return settings_; }

  // Segments, cleans and labels a frame; blobs sorted by decreasing area, at most maxObjects of them.
  std::vector<Blob> detect(const SampledFrame &frame);
  std::vector<Blob> detect(const ImageSource &frame);  // converts the whole frame to BGR first (tests)

  // The cleaned mask of the last frame (255 = inside) on the decimated grid, and that grid's step.
  const cv::Mat &mask() const { return mask_; }
  int lastDecimation() const { return lastDecimation_; }
  // The last frame's component labels, which Blob::label refers to.
  BlobLabels labels() const { return BlobLabels{labels_, lastDecimation_}; }

 private:
  const RangeLut &lutFor(const SampledFrame &frame);
  BlobSettings settings_;
  std::optional<RangeLut> rgbLut_, yuvLut_;
  cv::Mat mask_, labels_;
  cv::Rect labelledBox_;  // where labels_ may be non-zero
  std::vector<GridMoments> moments_;
  int lastDecimation_ = 1;
  cv::Mat bgr_;
};

// Learns a range from the pixels of `box` (frame coordinates, inside the frame). The object is taken to be
// the ellipse inscribed in the box (the rest is likely background); hue is averaged as an angle and its
// spread measured as signed angular distances from that mean, so red objects straddling 0 deg work. The
// 5th..95th percentiles of each channel, widened by margins that let the object get ~35% darker or
// brighter, make the range. Grey objects (low saturation) get every hue.
HsvRange learnRange(const ImageSource &frame, const cv::Rect &box);

}  // namespace colortrack
