// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/color.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <opencv2/core.hpp>
#include <opencv2/core/hal/intrin.hpp>

namespace colortrack {

namespace {

// Bin of a value in [0, 1] among n equal bins; 1.0 goes to the last bin. The tiny bias absorbs the
// rounding of value * n when it is mathematically a whole number (value = k/n exactly): a non-whole
// value * n from 8-bit inputs lies at least 1/1530 below the next whole number, so the bias never
// moves a value that is not on a border.
int unitBin(double value, int n) {
  return std::clamp(static_cast<int>(std::floor(value * n + 1e-9)), 0, n - 1);
}

// Bin of a hue in degrees [0, 360) among n equal bins.
int hueBin(double degrees, int n) {
  return unitBin(degrees / 360.0, n);
}

void checkLayout(const BinLayout &layout) {
  for (int n : layout.bins)
    if (n < 1 || n > 256)
      throw std::invalid_argument("colortrack::BinMapper: bins per channel must be 1..256");
}

// HSV bins straight from 8-bit RGB, exactly floor(h/360*n), floor(s*n), floor(v*n) (clamped) without
// going through OpenCV's 8-bit HSV, whose quantised hue and saturation put ~4% of pixels in a neighbouring
// bin. With diff = max - min, h/60 = sector + num/diff, so h/360*n = hueNumerator*n / (6*diff) where
// hueNumerator = sector*diff + num is a whole number in [0, 6*diff).
struct HsvBinner {
  int hueBins, satBins, valBins;

  static int hueNumerator(int r, int g, int b, int maxc, int diff) {
    if (maxc == r) return g >= b ? g - b : g - b + 6 * diff;
    if (maxc == g) return b - r + 2 * diff;
    return r - g + 4 * diff;
  }

  cv::Vec3b operator()(int r, int g, int b) const {
    const int maxc = std::max({r, g, b});
    const int diff = maxc - std::min({r, g, b});
    const int h = diff == 0 ? 0 : hueNumerator(r, g, b, maxc, diff) * hueBins / (6 * diff);
    const int s = maxc == 0 ? 0 : diff * satBins / maxc;
    const int v = maxc * valBins / 255;
    return cv::Vec3b(static_cast<std::uint8_t>(std::min(h, hueBins - 1)),
                     static_cast<std::uint8_t>(std::min(s, satBins - 1)),
                     static_cast<std::uint8_t>(std::min(v, valBins - 1)));
  }

#if CV_SIMD128
  // 16 pixels at a time. Hue and saturation quotients are computed in float: numerators and denominators
  // are whole numbers below 2^24 (exact in float), and a correctly rounded division of them cannot cross a
  // whole number, since a non-whole quotient of these sizes stays further from one than float precision.
  // V = floor(max*n / 255) uses the 16-bit identity floor(x/255) = (x * 0x8081) >> 23, exact for x < 2^16.
  // Returns how many leading pixels of the row it did (a multiple of 16).
  int rowSimd(const std::uint8_t *bgr, std::uint8_t *out, int width) const {
    using namespace cv;
    const v_float32x4 hueScale = v_setall_f32(float(hueBins)), satScale = v_setall_f32(float(satBins));
    const v_uint16x8 valScale = v_setall_u16(std::uint16_t(valBins)), div255 = v_setall_u16(0x8081);
    const v_int16x8 oneS16 = v_setall_s16(1);
    const v_uint8x16 hueLast = v_setall_u8(std::uint8_t(hueBins - 1));
    const v_uint8x16 satLast = v_setall_u8(std::uint8_t(satBins - 1));
    const v_uint8x16 valLast = v_setall_u8(std::uint8_t(valBins - 1));
    int x = 0;
    for (; x + 16 <= width; x += 16, bgr += 48, out += 48) {
      v_uint8x16 b8, g8, r8;
      v_load_deinterleave(bgr, b8, g8, r8);
      const v_uint8x16 max8 = v_max(r8, v_max(g8, b8));
      const v_uint8x16 diff8 = max8 - v_min(r8, v_min(g8, b8));

      v_uint16x8 r16[2], g16[2], b16[2], max16[2], diff16[2];
      v_expand(r8, r16[0], r16[1]);
      v_expand(g8, g16[0], g16[1]);
      v_expand(b8, b16[0], b16[1]);
      v_expand(max8, max16[0], max16[1]);
      v_expand(diff8, diff16[0], diff16[1]);

      v_int16x8 hue16[2], sat16[2];
      v_uint16x8 val16[2];
      for (int part = 0; part < 2; ++part) {
        const v_int16x8 r = v_reinterpret_as_s16(r16[part]), g = v_reinterpret_as_s16(g16[part]);
        const v_int16x8 b = v_reinterpret_as_s16(b16[part]), maxc = v_reinterpret_as_s16(max16[part]);
        const v_int16x8 diff = v_reinterpret_as_s16(diff16[part]);
        const v_int16x8 diff2 = diff + diff, diff4 = diff2 + diff2, diff6 = diff4 + diff2;
        v_int16x8 numR = g - b;
        numR = v_select(numR < v_setzero_s16(), numR + diff6, numR);
        const v_int16x8 numerator =
            v_select(maxc == r, numR, v_select(maxc == g, b - r + diff2, r - g + diff4));

        val16[part] = v_mul_hi(v_mul_wrap(max16[part], valScale), div255) >> 7;

        // All four are non-negative, so they widen as unsigned. Grey (diff 0) and black (max 0) have zero
        // numerators; a denominator of at least 1 then gives bin 0 without dividing by zero.
        v_uint32x4 num32[2], diff32[2], hueDen32[2], satDen32[2];
        v_expand(v_reinterpret_as_u16(numerator), num32[0], num32[1]);
        v_expand(diff16[part], diff32[0], diff32[1]);
        v_expand(v_reinterpret_as_u16(v_max(diff6, oneS16)), hueDen32[0], hueDen32[1]);
        v_expand(v_reinterpret_as_u16(v_max(maxc, oneS16)), satDen32[0], satDen32[1]);
        v_int32x4 hue32[2], sat32[2];
        for (int q = 0; q < 2; ++q) {
          hue32[q] = v_trunc(v_cvt_f32(v_reinterpret_as_s32(num32[q])) * hueScale /
                             v_cvt_f32(v_reinterpret_as_s32(hueDen32[q])));
          sat32[q] = v_trunc(v_cvt_f32(v_reinterpret_as_s32(diff32[q])) * satScale /
                             v_cvt_f32(v_reinterpret_as_s32(satDen32[q])));
        }
        hue16[part] = v_pack(hue32[0], hue32[1]);
        sat16[part] = v_pack(sat32[0], sat32[1]);
      }
      // Bins reach n only at h/s/v = 1 exactly; pack to bytes (256 saturates to 255) and clamp to n - 1.
      const v_uint8x16 hue = v_min(v_pack_u(hue16[0], hue16[1]), hueLast);
      const v_uint8x16 sat = v_min(v_pack_u(sat16[0], sat16[1]), satLast);
      const v_uint8x16 val = v_min(v_pack(val16[0], val16[1]), valLast);
      v_store_interleave(out, hue, sat, val);
    }
    return x;
  }
#endif

  void row(const std::uint8_t *bgr, std::uint8_t *out, int width) const {
    int x = 0;
#if CV_SIMD128
    x = rowSimd(bgr, out, width);
#endif
    for (; x < width; ++x) {
      const std::uint8_t *p = bgr + 3 * x;
      const cv::Vec3b bins = (*this)(p[2], p[1], p[0]);
      out[3 * x] = bins[0];
      out[3 * x + 1] = bins[1];
      out[3 * x + 2] = bins[2];
    }
  }
};

// RGB bins: floor(c * n / 255) per channel (clamped), which is what the lookup tables hold; the SIMD path
// computes it with the same 16-bit identity as V above, the tail uses the tables.
struct RgbBinner {
  const std::array<std::array<std::uint8_t, 256>, 3> &lut;
  std::array<int, 3> bins;

  void row(const std::uint8_t *bgr, std::uint8_t *out, int width) const {
    int x = 0;
#if CV_SIMD128
    using namespace cv;
    const v_uint16x8 div255 = v_setall_u16(0x8081);
    const auto binsOf = [&](const v_uint8x16 &channel, int n) {
      v_uint16x8 lo, hi;
      v_expand(channel, lo, hi);
      const v_uint16x8 scale = v_setall_u16(std::uint16_t(n));
      lo = v_mul_hi(v_mul_wrap(lo, scale), div255) >> 7;
      hi = v_mul_hi(v_mul_wrap(hi, scale), div255) >> 7;
      return v_min(v_pack(lo, hi), v_setall_u8(std::uint8_t(n - 1)));
    };
    for (; x + 16 <= width; x += 16) {
      v_uint8x16 b, g, r;
      v_load_deinterleave(bgr + 3 * x, b, g, r);
      v_store_interleave(out + 3 * x, binsOf(r, bins[0]), binsOf(g, bins[1]), binsOf(b, bins[2]));
    }
#endif
    for (; x < width; ++x) {  // input B,G,R; output R,G,B bins
      const std::uint8_t *p = bgr + 3 * x;
      out[3 * x] = lut[0][p[2]];
      out[3 * x + 1] = lut[1][p[1]];
      out[3 * x + 2] = lut[2][p[0]];
    }
  }
};

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

Yuv rgbToYuv601(std::uint8_t r8, std::uint8_t g8, std::uint8_t b8) {
  const double r = r8 / 255.0, g = g8 / 255.0, b = b8 / 255.0;
  Yuv yuv;
  yuv.y = cv::saturate_cast<std::uint8_t>(16.0 + 65.481 * r + 128.553 * g + 24.966 * b);
  yuv.u = cv::saturate_cast<std::uint8_t>(128.0 - 37.797 * r - 74.203 * g + 112.0 * b);
  yuv.v = cv::saturate_cast<std::uint8_t>(128.0 + 112.0 * r - 93.786 * g - 18.214 * b);
  return yuv;
}

cv::Matx34f YuvColorimetry::toBgrMatrix() const {
  // Y' = Kr R + (1 - Kr - Kb) G + Kb B, and U, V the scaled B - Y' and R - Y' (ITU-R BT.601/709/2020 alike).
  const double kg = 1 - kr - kb;
  const double yScale = fullRange ? 1.0 : 255.0 / 219.0, cScale = fullRange ? 1.0 : 255.0 / 224.0;
  const double yOffset = fullRange ? 0.0 : -16.0 * yScale;
  const double vToR = 2 * (1 - kr) * cScale, uToB = 2 * (1 - kb) * cScale;
  const double uToG = -uToB * kb / kg, vToG = -vToR * kr / kg;
  const auto row = [&](double u, double v) {
    return std::array<double, 4>{yScale, u, v, yOffset - 128.0 * (u + v)};
  };
  const std::array<double, 4> b = row(uToB, 0), g = row(uToG, vToG), r = row(0, vToR);
  return cv::Matx34f(float(b[0]), float(b[1]), float(b[2]), float(b[3]),  //
                     float(g[0]), float(g[1]), float(g[2]), float(g[3]),  //
                     float(r[0]), float(r[1]), float(r[2]), float(r[3]));
}

std::array<double, 3> YuvColorimetry::toRgb(double y, double u, double v) const {
  const cv::Matx34f m = toBgrMatrix();
  const auto channel = [&](int row) {
    return std::clamp(m(row, 0) * y + m(row, 1) * u + m(row, 2) * v + m(row, 3), 0.0, 255.0);
  };
  return {channel(2), channel(1), channel(0)};
}

BinMapper::BinMapper(ColorSpace space, const BinLayout &layout) : space_(space), layout_(layout) {
  checkLayout(layout);
  // The tables serve the RGB path (channel value k stands for k/255). HSV bins are computed per pixel.
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 256; ++k) lut_[c][k] = static_cast<std::uint8_t>(unitBin(k / 255.0, layout.bins[c]));
}

void BinMapper::map(const cv::Mat &bgr, cv::Mat &out) const {
  CV_Assert(bgr.type() == CV_8UC3);
  const cv::Mat input = bgr;                  // keeps the pixels alive if `out` is the same object as `bgr`
  if (out.data == input.data) out.release();  // in-place call: write to fresh memory
  out.create(input.size(), CV_8UC3);
  const HsvBinner hsv{layout_.bins[0], layout_.bins[1], layout_.bins[2]};
  const RgbBinner rgb{lut_, layout_.bins};
  const bool isHsv = space_ == ColorSpace::Hsv;
  // Rows are independent: split them over OpenCV's thread pool (a no-op with one thread), one stripe per
  // 64 K pixels. A search window of ~100 x 100 px stays on the calling thread: waking the pool would cost
  // more than mapping it.
  const double stripes = std::max(1.0, static_cast<double>(input.total()) / (1 << 16));
  cv::parallel_for_(
      cv::Range(0, input.rows),
      [&](const cv::Range &rows) {
        for (int y = rows.start; y < rows.end; ++y) {
          const std::uint8_t *in = input.ptr<std::uint8_t>(y);
          std::uint8_t *binsRow = out.ptr<std::uint8_t>(y);
          if (isHsv)
            hsv.row(in, binsRow, input.cols);
          else
            rgb.row(in, binsRow, input.cols);
        }
      },
      stripes);
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
