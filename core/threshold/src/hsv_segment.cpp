// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/hsv_segment.hpp"

#include "colortrack/settings.hpp"  // formatNumber

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <optional>
#include <vector>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

// HSV of a colour given as doubles in [0, 255] (LUT cell centres fall between 8-bit values). Not rgbToHsv():
// the hue is rounded differently ((60 * x) / d against 60 * (x / d)), and merging the two would move hues on
// integer range limits by one ulp and change which LUT cells a saved range selects.
Hsv hsvOf(double r, double g, double b) {
  const double mx = std::max({r, g, b}), mn = std::min({r, g, b}), delta = mx - mn;
  Hsv hsv;
  hsv.v = mx / 255.0;
  hsv.s = mx > 0 ? delta / mx : 0;
  if (delta > 0) {
    double h;
    if (mx == r)
      h = 60.0 * (g - b) / delta;
    else if (mx == g)
      h = 60.0 * (b - r) / delta + 120.0;
    else
      h = 60.0 * (r - g) / delta + 240.0;
    if (h < 0) h += 360.0;
    hsv.h = h >= 360.0 ? h - 360.0 : h;
  }
  return hsv;
}

}  // namespace

bool HsvRange::contains(const Hsv &hsv) const {
  if (hsv.s < lower.s || hsv.s > upper.s || hsv.v < lower.v || hsv.v > upper.v) return false;
  if (upper.h - lower.h >= 360.0) return true;
  if (lower.h <= upper.h) return hsv.h >= lower.h && hsv.h <= upper.h;
  return hsv.h >= lower.h || hsv.h <= upper.h;  // wraps through 0
}

Status validateRange(const HsvRange &range) {
  if (range.lower.s > range.upper.s)
    return Status::failure("lower saturation " + formatNumber(range.lower.s) + " exceeds upper saturation " +
                           formatNumber(range.upper.s));
  if (range.lower.v > range.upper.v)
    return Status::failure("lower value " + formatNumber(range.lower.v) + " exceeds upper value " +
                           formatNumber(range.upper.v));
  return {};
}

RangeLut::RangeLut(const HsvRange &range, PixelEncoding encoding, const YuvColorimetry &colorimetry)
    : range_(range), encoding_(encoding), colorimetry_(colorimetry), table_(std::size_t{1} << (3 * kBits)) {
  constexpr int cells = 1 << kBits;
  constexpr double width = 1 << kShift;
  const auto centre = [&](int cell) { return cell * width + (width - 1) / 2; };
  for (int a = 0; a < cells; ++a)
    for (int b = 0; b < cells; ++b)
      for (int c = 0; c < cells; ++c) {
        std::array<double, 3> rgb{centre(a), centre(b), centre(c)};
        if (encoding == PixelEncoding::Yuv) rgb = colorimetry.toRgb(rgb[0], rgb[1], rgb[2]);
        const bool inside = range.contains(hsvOf(rgb[0], rgb[1], rgb[2]));
        table_[(a << (2 * kBits)) | (b << kBits) | c] = inside ? 255 : 0;
      }
}

int autoDecimation(cv::Size frame) {
  return frame.area() <= 640 * 480 ? 1 : 2;
}

namespace {

// Table indices of one grid row when channel c's sample of grid column x is p_c[x * S_c]: with the strides
// known at compile time the compiler vectorises the index arithmetic (the table loads that follow cannot be).
template <int S0, int S1, int S2>
void stridedIndices(const std::uint8_t *p0, const std::uint8_t *p1, const std::uint8_t *p2, int n, int *idx) {
  for (int x = 0; x < n; ++x) idx[x] = RangeLut::index(p0[x * S0], p1[x * S1], p2[x * S2]);
}

#if CV_SIMD128
// The table indices of 16 samples, each channel given as two vectors of 16-bit lanes holding the sample's top
// six bits in place (sample & 0xFC): ((c0 >> 2) << 12) | ((c1 >> 2) << 6) | (c2 >> 2), as RangeLut::index;
// the first two parts fit 16 bits.
void storeIndices(const cv::v_uint16x8 (&lo)[3], const cv::v_uint16x8 (&hi)[3], int *idx) {
  const cv::v_uint16x8 high[2]{cv::v_shl<4>(lo[0]) | cv::v_shr<2>(lo[1]),
                               cv::v_shl<4>(hi[0]) | cv::v_shr<2>(hi[1])};
  const cv::v_uint16x8 low[2]{cv::v_shr<2>(lo[2]), cv::v_shr<2>(hi[2])};
  for (int h = 0; h < 2; ++h) {
    cv::v_uint32x4 high0, high1, low0, low1;
    cv::v_expand(high[h], high0, high1);
    cv::v_expand(low[h], low0, low1);
    cv::v_store(idx + 8 * h, cv::v_reinterpret_as_s32(cv::v_shl<6>(high0) | low0));
    cv::v_store(idx + 8 * h + 4, cv::v_reinterpret_as_s32(cv::v_shl<6>(high1) | low1));
  }
}
#endif

// Packed 3-byte pixels, every Step-th of them (1 or 2), channel c in byte c (RGB) or, Reversed, in byte 2 - c
// (BGR): a stride of 3 or 6 bytes defeats the auto-vectoriser, so the bytes are split with OpenCV's universal
// intrinsics. `rowBytes` bounds the reads. Writes whole blocks of 16 indices and returns how many it wrote.
template <int Step, bool Reversed>
int packed3Indices(const std::uint8_t *row, int rowBytes, int n, int *idx) {
  int x = 0;
#if CV_SIMD128
  constexpr int block = 16, bytesPerBlock = block * Step * 3;
  const cv::v_uint16x8 top6 = cv::v_setall_u16(0xFC);  // the bits the table uses, of the low byte
  for (; x + block <= n && (x + block) * Step * 3 <= rowBytes; x += block) {
    cv::v_uint8x16 bytes[2][3];
    for (int part = 0; part < Step; ++part)
      cv::v_load_deinterleave(row + x * Step * 3 + part * (bytesPerBlock / Step), bytes[part][0],
                              bytes[part][1], bytes[part][2]);
    // Each channel's 16 samples as two vectors of 16-bit lanes (sample in the low byte).
    cv::v_uint16x8 lo[3], hi[3];
    for (int c = 0; c < 3; ++c) {
      const int b = Reversed ? 2 - c : c;
      if constexpr (Step == 2) {  // the even pixels are the low bytes of the 16-bit lanes
        lo[c] = cv::v_reinterpret_as_u16(bytes[0][b]) & top6;
        hi[c] = cv::v_reinterpret_as_u16(bytes[1][b]) & top6;
      } else {
        cv::v_expand(bytes[0][b], lo[c], hi[c]);
        lo[c] = lo[c] & top6;
        hi[c] = hi[c] & top6;
      }
    }
    storeIndices(lo, hi, idx + x);
  }
#else
  (void)row, (void)rowBytes, (void)n, (void)idx;
#endif
  return x;
}

// Planar 4:2:0 (I420, YV12) at decimation 2, byte strides 2, 1, 1: GCC vectorised stridedIndices<2, 1, 1>
// with scalar luma loads (8 instructions a sample in callgrind), hence this (about 2).
// yBytes, uBytes, vBytes bound the reads. Writes whole blocks of 16 indices and returns how many it wrote.
int planar420Indices(const std::uint8_t *y, const std::uint8_t *u, const std::uint8_t *v, int yBytes,
                     int uBytes, int vBytes, int n, int *idx) {
  int x = 0;
#if CV_SIMD128
  constexpr int block = 16;
  const cv::v_uint16x8 top6 = cv::v_setall_u16(0xFC);
  for (; x + block <= n && 2 * (x + block) <= yBytes && x + block <= std::min(uBytes, vBytes); x += block) {
    cv::v_uint16x8 lo[3], hi[3];
    // The luma samples are the low bytes of 16-bit lanes.
    lo[0] = cv::v_reinterpret_as_u16(cv::v_load(y + 2 * x)) & top6;
    hi[0] = cv::v_reinterpret_as_u16(cv::v_load(y + 2 * x + block)) & top6;
    cv::v_expand(cv::v_load(u + x), lo[1], hi[1]);
    cv::v_expand(cv::v_load(v + x), lo[2], hi[2]);
    for (int c = 1; c < 3; ++c) {
      lo[c] = lo[c] & top6;
      hi[c] = hi[c] & top6;
    }
    storeIndices(lo, hi, idx + x);
  }
#else
  (void)y, (void)u, (void)v, (void)yBytes, (void)uBytes, (void)vBytes, (void)n, (void)idx;
#endif
  return x;
}

using PackedIndices = int (*)(const std::uint8_t *, int, int, int *);

// The vectorised indices for one packed 3-byte plane read at every pixel or every other one (channels in
// bytes 0, 1, 2 or 2, 1, 0), else null.
PackedIndices packed3IndicesFor(const SampledFrame &frame, int d) {
  bool inOrder = d <= 2, reversed = d <= 2;
  for (int c = 0; c < 3; ++c) {
    const ChannelSampler &ch = frame.channels[c];
    if (ch.plane.data != frame.channels[0].plane.data || ch.plane.step != frame.channels[0].plane.step ||
        ch.sampleBytes != 3 || ch.xSub != 1 || ch.ySub != 1)
      return nullptr;
    inOrder = inOrder && ch.byteOffset == c;
    reversed = reversed && ch.byteOffset == 2 - c;
  }
  if (inOrder) return d == 1 ? packed3Indices<1, false> : packed3Indices<2, false>;
  if (reversed) return d == 1 ? packed3Indices<1, true> : packed3Indices<2, true>;
  return nullptr;
}

using RowIndices = void (*)(const std::uint8_t *, const std::uint8_t *, const std::uint8_t *, int, int *);

// The common layouts at decimation 2, by the byte stride of each channel from one grid column to the next.
RowIndices stridedIndicesFor(const std::array<int, 3> &stride) {
  if (stride == std::array<int, 3>{2, 2, 2}) return stridedIndices<2, 2, 2>;  // NV12, NV21
  if (stride == std::array<int, 3>{8, 8, 8}) return stridedIndices<8, 8, 8>;  // BGRx, RGBx, xRGB...
  return nullptr;
}

// Reading every d-th row defeats the hardware prefetcher (it streams the rows read into the rows skipped and
// then waits at each new row), so segment() asks for the next grid row while it reads the current one, a
// chunk of kChunk columns at a time: 10-35 % off the stage for 1080p BGR on frames not in cache (measured
// 2026-11-30 on a loaded machine). GCC and Clang only; elsewhere none.
constexpr int kChunk = 64;  // grid columns; a multiple of packed3Indices' block
void prefetch(const std::uint8_t *begin, int bytes) {
#if defined(__GNUC__)
  for (int b = 0; b < bytes; b += 64) __builtin_prefetch(begin + b);
#else
  (void)begin, (void)bytes;
#endif
}

// Linear layouts (every channel subsampled by a divisor of d, which covers every format at decimation 2):
// channel c's sample of grid column x is at byteOffset + x * stride[c], and a row is done in two passes,
// table indices (vectorised for the common layouts) then table loads.
void segmentLinear(const SampledFrame &frame, const RangeLut &lut, int d, const std::array<int, 3> &stride,
                   cv::Mat &mask) {
  const cv::Size grid = mask.size();
  const std::uint8_t *table = lut.table();
  const PackedIndices packed3 = packed3IndicesFor(frame, d);
  const RowIndices strided = stridedIndicesFor(stride);
  const bool planar420 = stride == std::array<int, 3>{2, 1, 1};
  std::array<int, 3> rowBytes;  // readable from a channel's first sample in a row
  for (int c = 0; c < 3; ++c) rowBytes[c] = frame.channels[c].plane.cols - frame.channels[c].byteOffset;
  // Channels sharing a plane with an earlier one (packed pixels, NV12's UV) share its prefetches.
  std::array<bool, 3> ownPlane;
  for (int c = 0; c < 3; ++c)
    ownPlane[c] = c == 0 || (frame.channels[c].plane.data != frame.channels[0].plane.data &&
                             (c == 1 || frame.channels[c].plane.data != frame.channels[1].plane.data));
  const auto rowOf = [&](int c, int y) {
    const ChannelSampler &ch = frame.channels[c];
    return ch.plane.ptr(y * d / ch.ySub) + ch.byteOffset;
  };
  std::vector<int> idx(grid.width);
  for (int y = 0; y < grid.height; ++y) {
    std::array<const std::uint8_t *, 3> p, next;
    for (int c = 0; c < 3; ++c) {
      p[c] = rowOf(c, y);
      next[c] = rowOf(c, std::min(y + 1, grid.height - 1));
    }
    for (int x0 = 0; x0 < grid.width; x0 += kChunk) {
      const int x1 = std::min(x0 + kChunk, grid.width);
      for (int c = 0; c < 3; ++c)
        if (ownPlane[c]) prefetch(next[c] + x0 * stride[c], (x1 - x0) * stride[c]);
      int x = x0;
      if (packed3) {
        const ChannelSampler &ch = frame.channels[0];
        const int begin = x0 * d * 3;
        const std::uint8_t *row = ch.plane.ptr(y * d) + begin;
        x += packed3(row, ch.plane.cols - begin, x1 - x0, &idx[x0]);
      } else if (planar420) {
        const std::array<int, 3> offset{x0 * 2, x0, x0};
        x += planar420Indices(p[0] + offset[0], p[1] + offset[1], p[2] + offset[2], rowBytes[0] - offset[0],
                              rowBytes[1] - offset[1], rowBytes[2] - offset[2], x1 - x0, &idx[x0]);
      } else if (strided) {
        strided(p[0] + x0 * stride[0], p[1] + x0 * stride[1], p[2] + x0 * stride[2], x1 - x0, &idx[x0]);
        x = x1;
      }
      for (; x < x1; ++x)  // the rest, or every column of the layouts not special-cased
        idx[x] = RangeLut::index(p[0][x * stride[0]], p[1][x * stride[1]], p[2][x * stride[2]]);
    }
    std::uint8_t *out = mask.ptr(y);
    for (int x = 0; x < grid.width; ++x) out[x] = table[idx[x]];
  }
}

// Any other layout: the byte offset of every grid column in each channel's row from tables.
void segmentByColumnTables(const SampledFrame &frame, const RangeLut &lut, int d, cv::Mat &mask) {
  const cv::Size grid = mask.size();
  const std::uint8_t *table = lut.table();
  constexpr int shift = RangeLut::kShift, bits = RangeLut::kBits;
  std::array<std::vector<int>, 3> columns;
  for (int c = 0; c < 3; ++c) {
    const ChannelSampler &ch = frame.channels[c];
    columns[c].resize(grid.width);
    for (int x = 0; x < grid.width; ++x) columns[c][x] = (x * d / ch.xSub) * ch.sampleBytes + ch.byteOffset;
  }
  const int *col0 = columns[0].data(), *col1 = columns[1].data(), *col2 = columns[2].data();
  for (int y = 0; y < grid.height; ++y) {
    const int fy = y * d;
    const std::uint8_t *p0 = frame.channels[0].plane.ptr(fy / frame.channels[0].ySub);
    const std::uint8_t *p1 = frame.channels[1].plane.ptr(fy / frame.channels[1].ySub);
    const std::uint8_t *p2 = frame.channels[2].plane.ptr(fy / frame.channels[2].ySub);
    std::uint8_t *out = mask.ptr(y);
    for (int x = 0; x < grid.width; ++x) {
      const int index =
          ((p0[col0[x]] >> shift) << (2 * bits)) | ((p1[col1[x]] >> shift) << bits) | (p2[col2[x]] >> shift);
      out[x] = table[index];
    }
  }
}

}  // namespace

void segment(const SampledFrame &frame, const RangeLut &lut, int decimation, cv::Mat &mask) {
  const int d = std::max(1, decimation);
  mask.create(cv::Size((frame.size.width + d - 1) / d, (frame.size.height + d - 1) / d), CV_8UC1);
  bool linear = true;
  std::array<int, 3> stride;
  for (int c = 0; c < 3; ++c) {
    const ChannelSampler &ch = frame.channels[c];
    linear = linear && d % ch.xSub == 0;
    stride[c] = d / ch.xSub * ch.sampleBytes;
  }
  if (linear)
    segmentLinear(frame, lut, d, stride, mask);
  else
    segmentByColumnTables(frame, lut, d, mask);
}

void cleanMask(cv::Mat &mask, int size) {
  if (size < 2) return;
  // Square kernels: separable, so OpenCV runs them as two cheap 1-D passes.
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(size, size));
  cv::morphologyEx(mask, mask, cv::MORPH_OPEN, kernel);
  cv::morphologyEx(mask, mask, cv::MORPH_CLOSE, kernel);
}

}  // namespace colortrack
