// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode's HSV range segmentation: the range, its lookup table and the mask of a frame (vectorised
// for the common layouts), with its morphological clean-up. blobs.hpp labels the mask into blobs.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/image_source.hpp"
#include "colortrack/status.hpp"

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

// Both ends together: s and v of `lower` must not exceed those of `upper` (hue may wrap).
Status validateRange(const HsvRange &range);

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

// The decimation of BlobSettings::decimation 0 (automatic) for a frame of this size.
int autoDecimation(cv::Size frame);

// Writes 255 where the sampled colour is inside the LUT's range on the grid of every `decimation`-th frame
// pixel: mask size = ceil(frame size / decimation).
void segment(const SampledFrame &frame, const RangeLut &lut, int decimation, cv::Mat &mask);

// Opening (removes specks) then closing (fills small holes) with a size x size square; 0 or 1 does nothing.
void cleanMask(cv::Mat &mask, int size);

}  // namespace colortrack
