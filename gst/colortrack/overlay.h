// SPDX-License-Identifier: LGPL-2.1-or-later
// Drawing the track on a mapped frame, in place, in every supported format.
#pragma once

#include <string>
#include <vector>

#include <gst/video/video.h>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"

namespace colortrack_gst {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

namespace colors {
constexpr Rgb kRed{255, 0, 0};        // colour-only match
constexpr Rgb kGreen{0, 255, 0};      // match confirmed by the edge check
constexpr Rgb kOrange{255, 160, 0};   // coasting on the prediction
constexpr Rgb kBlue{0, 96, 255};      // search window
constexpr Rgb kMagenta{255, 0, 255};  // threshold mask
constexpr Rgb kYellow{255, 230, 0};   // the trail (not red: a red line read as an unverified box)
}  // namespace colors

// A bright colour per track id, neighbouring ids far apart in hue (golden-angle steps).
Rgb idColour(int id);

// Draws on every plane of a frame with the colour translated to each plane's layout. Coordinates are luma
// (frame) pixels; subsampled planes get them divided by their subsampling.
class FrameCanvas {
 public:
  // `frame` must be mapped for writing and stay mapped while the canvas is used.
  explicit FrameCanvas(GstVideoFrame *frame);

  // Outline of `box` drawn inside it, `thickness` pixels wide. On chroma-subsampled formats the box is
  // first grown to even coordinates and a thick outline covers two whole chroma samples (4 px), so that
  // its colour is exact and stays so through chroma upsampling (videoconvert interpolates chroma).
  void boxOutline(const cv::Rect &box, const Rgb &colour, int thickness);
  void polyline(const std::vector<cv::Point> &points, const Rgb &colour, int thickness);
  // Light text with a dark outline, readable on any background. Luma only on YUV formats.
  void label(const std::string &text, cv::Point origin);
  // Blends `colour` half way into the pixels where `mask` (CV_8UC1 on a grid of every `step`-th frame pixel)
  // is set: shows what a colour threshold selects.
  void tintMask(const cv::Mat &mask, int step, const Rgb &colour);

 private:
  enum class PlaneKind { Packed, Luma, ChromaU, ChromaV, ChromaUV, Yuy2 };
  struct Plane {
    cv::Mat mat;
    PlaneKind kind;
    int xDiv, yDiv;  // frame coordinates / plane coordinates
  };
  cv::Scalar colourFor(const Plane &plane, const Rgb &colour) const;
  void fillRect(const cv::Rect &rect, const Rgb &colour);

  std::vector<Plane> planes_;
  cv::Mat textTarget_;  // packed plane, luma plane, or YUY2 viewed as (Y, chroma) pairs
  bool textOnYuv_ = false;
  int align_ = 1;  // coordinate alignment that keeps chroma samples whole
  cv::Size size_;
  int packedBytes_ = 0, red_ = 0, green_ = 0, blue_ = 0, filler_ = -1;
};

}  // namespace colortrack_gst
