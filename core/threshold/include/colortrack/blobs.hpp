// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode, pixel side: HSV range segmentation through a lookup table, morphological clean-up and
// connected components ("blobs"), plus learning a range from the pixels of a box.
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
#include "colortrack/image_source.hpp"
#include "colortrack/settings.hpp"  // parseHsv, formatHsv

namespace colortrack {

// An HSV box: h in degrees [0, 360], s and v in [0, 1]. A pixel is inside when all three channels are.
// Hue is an angle: lower.h > upper.h means the range wraps through 0 (340..20 is red); upper.h - lower.h
// >= 360 (e.g. 0..360) accepts every hue.
struct HsvRange {
  Hsv lower{340, 0.5, 0.25};
  Hsv upper{20, 1.0, 1.0};
  bool contains(const Hsv &hsv) const;
  bool wrapsHue() const { return lower.h > upper.h; }
};

// Both ends together: s and v of `lower` must not exceed those of `upper` (hue may wrap). Empty when valid.
std::string validateRange(const HsvRange &range);

// Inside/outside for every colour, in a table indexed by the top 6 bits of each channel (256 KiB). A cell
// is decided by its centre colour, so a range edge is resolved to +-2 of 255 per channel: the price of one
// table load per pixel instead of a per-pixel HSV conversion.
class RangeLut {
 public:
  static constexpr int kBits = 6;
  static constexpr int kShift = 8 - kBits;

  // `colorimetry` says what YUV bytes stand for (with PixelEncoding::Yuv).
  RangeLut(const HsvRange &range, PixelEncoding encoding, const YuvColorimetry &colorimetry = {});
  const HsvRange &range() const { return range_; }
  PixelEncoding encoding() const { return encoding_; }
  const YuvColorimetry &colorimetry() const { return colorimetry_; }
  static int index(std::uint8_t c0, std::uint8_t c1, std::uint8_t c2) {
    return ((c0 >> kShift) << (2 * kBits)) | ((c1 >> kShift) << kBits) | (c2 >> kShift);
  }
  std::uint8_t at(std::uint8_t c0, std::uint8_t c1, std::uint8_t c2) const {
    return table_[index(c0, c1, c2)];
  }
  const std::uint8_t *table() const { return table_.data(); }

 private:
  HsvRange range_;
  PixelEncoding encoding_;
  YuvColorimetry colorimetry_;
  std::vector<std::uint8_t> table_;  // 255 inside, 0 outside
};

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

int autoDecimation(cv::Size frame);

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

// Writes 255 where the sampled colour is inside the LUT's range on the grid of every `decimation`-th frame
// pixel: mask size = ceil(frame size / decimation).
void segment(const SampledFrame &frame, const RangeLut &lut, int decimation, cv::Mat &mask);

// Opening (removes specks) then closing (fills small holes) with a size x size square; 0 or 1 does nothing.
void cleanMask(cv::Mat &mask, int size);

// Learns a range from the pixels of `box` (frame coordinates, inside the frame). The object is taken to be
// the ellipse inscribed in the box (the rest is likely background); hue is averaged as an angle and its
// spread measured as signed angular distances from that mean, so red objects straddling 0 deg work. The
// 5th..95th percentiles of each channel, widened by margins that let the object get ~35% darker or
// brighter, make the range. Grey objects (low saturation) get every hue.
HsvRange learnRange(const ImageSource &frame, const cv::Rect &box);

}  // namespace colortrack
