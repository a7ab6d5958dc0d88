// SPDX-License-Identifier: LGPL-2.1-or-later
// Colour spaces and per-pixel bin indices: the first step of colour indexing.
#pragma once

#include <array>
#include <cstdint>

#include <opencv2/core.hpp>

#include "colortrack/choice.hpp"

namespace colortrack {

// rgb: the original colour indexing (Swain & Ballard); hsv: the modified method (default), where the
// V channel can be weighted down for robustness to lighting.
enum class ColorSpace { Rgb, Hsv };
inline constexpr Choice<ColorSpace> kColorSpaces[] = {
    {ColorSpace::Rgb, "rgb", "RGB histograms (original colour indexing)"},
    {ColorSpace::Hsv, "hsv", "HSV histograms (modified colour indexing, lighting-robust)"},
};

// Standard RGB -> HSV. h in degrees [0, 360), s and v in [0, 1]; h = 0 when max == min, s = 0 when max == 0.
struct Hsv {
  double h = 0, s = 0, v = 0;
};
Hsv rgbToHsv(std::uint8_t r, std::uint8_t g, std::uint8_t b);

// BT.601 limited range ("studio swing"), the matrix of SD video and of OpenCV's YUV <-> BGR conversions: both
// directions here, so that everything drawn or segmented on YUV frames uses the same one.
struct Yuv {
  std::uint8_t y = 16, u = 128, v = 128;
};
Yuv rgbToYuv601(std::uint8_t r, std::uint8_t g, std::uint8_t b);

// How the bytes of a YUV frame stand for RGB: the matrix (by its Kr and Kb) and the range. GStreamer's caps
// say it (colorimetry): a JPEG decoder's output is full range, most video limited range. Reading a frame by
// the wrong one changes its contrast and saturation by 14-16 %.
struct YuvColorimetry {
  double kr = 0.299, kb = 0.114;  // BT.601
  bool fullRange = false;

  // r, g, b in [0, 255] (clamped), for y, u, v anywhere in [0, 255].
  std::array<double, 3> toRgb(double y, double u, double v) const;
  // The same as an affine map of (Y, U, V) to (B, G, R), for cv::transform.
  cv::Matx34f toBgrMatrix() const;
  bool operator==(const YuvColorimetry &o) const {
    return kr == o.kr && kb == o.kb && fullRange == o.fullRange;
  }
  bool operator!=(const YuvColorimetry &o) const { return !(*this == o); }
};

// Number of bins of each of the three channels, in channel order (H,S,V) or (R,G,B). 1..256 each.
struct BinLayout {
  std::array<int, 3> bins{16, 16, 8};
  int total() const { return bins[0] + bins[1] + bins[2]; }
  int offset(int channel) const { return channel == 0 ? 0 : channel == 1 ? bins[0] : bins[0] + bins[1]; }
  bool operator==(const BinLayout &o) const { return bins == o.bins; }
};

// Maps 8-bit BGR pixels to bin indices. Holds the lookup tables, so build one per (space, layout) and reuse.
class BinMapper {
 public:
  BinMapper(ColorSpace space, const BinLayout &layout);

  ColorSpace space() const { return space_; }
  const BinLayout &layout() const { return layout_; }

  // bgr: CV_8UC3 (any step). out: CV_8UC3 of the same size; out channel c holds the bin of colour
  // channel c (H,S,V or R,G,B). Exact: equals binOf() for every colour. Not OpenCV's 8-bit HSV conversion,
  // whose quantised hue and saturation put ~4% of pixels in a neighbouring bin (and which, followed by a
  // lookup table, is slower); the bins are computed straight from RGB with OpenCV's SIMD intrinsics.
  void map(const cv::Mat &bgr, cv::Mat &out) const;

  // The bin of one pixel through the exact rgbToHsv() (or raw RGB) path. Reference for the tests.
  std::array<int, 3> binOf(std::uint8_t r, std::uint8_t g, std::uint8_t b) const;

 private:
  ColorSpace space_;
  BinLayout layout_;
  std::array<std::array<std::uint8_t, 256>, 3> lut_{};  // 8-bit channel value -> bin
};

// A bin image and where its top-left pixel lies in frame coordinates, so that core functions can work on
// a search region without copying the frame. All rectangles given to core functions are in frame
// coordinates.
struct BinImage {
  cv::Mat bins;        // CV_8UC3
  cv::Point origin{};  // frame coordinates of bins(0,0)
  cv::Rect frameRect() const { return cv::Rect(origin, bins.size()); }
};

}  // namespace colortrack
