#include "colortrack/color.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

// Bin of a value in [0, 1] among n equal bins; 1.0 goes to the last bin.
int unitBin(double value, int n) { return std::clamp(static_cast<int>(std::floor(value * n)), 0, n - 1); }

// Bin of a hue in degrees [0, 360) among n equal bins.
int hueBin(double degrees, int n) { return unitBin(degrees / 360.0, n); }

void checkLayout(const BinLayout &layout) {
  for (int n : layout.bins)
    if (n < 1 || n > 256) throw std::invalid_argument("colortrack::BinMapper: bins per channel must be 1..256");
}

}  // namespace

Hsv rgbToHsv(std::uint8_t r, std::uint8_t g, std::uint8_t b) {
  const int maxc = std::max({r, g, b});
  const int minc = std::min({r, g, b});
  const double diff = maxc - minc;
  Hsv out;
  out.v = maxc / 255.0;
  out.s = maxc == 0 ? 0.0 : diff / maxc;
  if (diff == 0) return out;  // grey: hue undefined, conventionally 0
  double h;
  if (maxc == r)
    h = 60.0 * ((g - b) / diff);
  else if (maxc == g)
    h = 60.0 * ((b - r) / diff + 2.0);
  else
    h = 60.0 * ((r - g) / diff + 4.0);
  if (h < 0) h += 360.0;
  if (h >= 360.0) h -= 360.0;
  out.h = h;
  return out;
}

BinMapper::BinMapper(ColorSpace space, const BinLayout &layout) : space_(space), layout_(layout) {
  checkLayout(layout);
  for (int c = 0; c < 3; ++c) {
    const int n = layout.bins[c];
    for (int k = 0; k < 256; ++k) {
      int bin;
      if (space == ColorSpace::Hsv && c == 0)
        bin = hueBin(k * 360.0 / 256.0, n);  // HSV_FULL: 8-bit hue k stands for k * 360/256 degrees
      else
        bin = unitBin(k / 255.0, n);  // S, V (and R, G, B) are 0..255 for [0, 1]
      lut_[c][k] = static_cast<std::uint8_t>(bin);
    }
  }
}

void BinMapper::map(const cv::Mat &bgr, cv::Mat &out) const {
  CV_Assert(bgr.type() == CV_8UC3);
  cv::Mat converted;
  if (space_ == ColorSpace::Hsv)
    cv::cvtColor(bgr, converted, cv::COLOR_BGR2HSV_FULL);  // H spans 0..255 for the whole circle
  else
    cv::cvtColor(bgr, converted, cv::COLOR_BGR2RGB);
  // One 3-channel table: channel c of the table applies to channel c of the converted image.
  cv::Mat table(1, 256, CV_8UC3);
  auto *entry = table.ptr<cv::Vec3b>();
  for (int k = 0; k < 256; ++k) entry[k] = cv::Vec3b(lut_[0][k], lut_[1][k], lut_[2][k]);
  cv::LUT(converted, table, out);
}

std::array<int, 3> BinMapper::binOf(std::uint8_t r, std::uint8_t g, std::uint8_t b) const {
  if (space_ == ColorSpace::Hsv) {
    const Hsv hsv = rgbToHsv(r, g, b);
    return {hueBin(hsv.h, layout_.bins[0]), unitBin(hsv.s, layout_.bins[1]), unitBin(hsv.v, layout_.bins[2])};
  }
  return {unitBin(r / 255.0, layout_.bins[0]), unitBin(g / 255.0, layout_.bins[1]),
          unitBin(b / 255.0, layout_.bins[2])};
}

}  // namespace colortrack
