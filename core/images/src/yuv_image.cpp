// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/yuv_image.hpp"

#include <cstdint>
#include <vector>

#include <opencv2/core/hal/intrin.hpp>

namespace colortrack {

namespace {

// The colorimetry's matrix applied as GStreamer's 8-bit YUV-to-RGB paths apply it (videoconvert's fast path
// from I420, NV12 or YUY2 to any 8-bit RGB, GStreamer 1.22 to 1.26), so that a YUV frame read here is, byte
// for byte, the image `videoconvert ! video/x-raw,format=BGRx` gives the same frame: the weights rounded to
// 1/256, each sample centred on 128 as a signed byte and widened to 16 bits by repeating that byte, the high
// 16 bits of each product, the sum saturated. It has no luma offset: limited-range luma reads about 2 levels
// darker than the standard matrix says, as it does in what videoconvert delivers. Reading with OpenCV's
// rounding instead (14-bit weights, offsets kept) gave the same frames 1-2 levels apart in BGRx and I420,
// and the tracker's answer moved with them (docs/benchmarks-history.md, "Pixel formats").
struct VideoconvertMatrix {
  int luma, blueU, greenU, greenV, redV;  // weights, 256 = 1

  explicit VideoconvertMatrix(const YuvColorimetry &colorimetry) {
    const cv::Matx34f m = colorimetry.toBgrMatrix();
    const auto weight = [](float x) { return cvRound(double(x) * 256); };
    luma = weight(m(0, 0));
    blueU = weight(m(0, 1));
    greenU = weight(m(1, 1));
    greenV = weight(m(1, 2));
    redV = weight(m(2, 2));
  }
  // A sample centred on 128 as a signed byte, widened to 16 bits by repeating the byte (x * 257, and 256 more
  // when x is negative).
  static int widened(int sample) { return static_cast<std::int16_t>((sample ^ 0x80) * 257); }
  // The high 16 bits of the product (rounded down).
  static int product(int widenedSample, int weight) { return (widenedSample * weight) >> 16; }
  void pixel(int y, int u, int v, uchar *bgr) const {
    const int l = product(widened(y), luma) + 128, wu = widened(u), wv = widened(v);
    bgr[0] = cv::saturate_cast<uchar>(l + product(wu, blueU));
    bgr[1] = cv::saturate_cast<uchar>(l + product(wu, greenU) + product(wv, greenV));
    bgr[2] = cv::saturate_cast<uchar>(l + product(wv, redV));
  }
};

// n pixels from the Y, U and V samples under them to interleaved BGR: 16 at a time with OpenCV's universal
// intrinsics (the same integer maths as pixel(), so the result does not depend on the CPU), the rest one by
// one.
void convertRow(const VideoconvertMatrix &m, const uchar *y, const uchar *u, const uchar *v, int n,
                uchar *bgr) {
  int i = 0;
#if CV_SIMD128
  // Eight 16-bit lanes hold what videoconvert's 16-bit maths holds: zipping a vector of centred samples with
  // itself repeats each byte into a lane (widened()), v_mul_hi keeps a product's high 16 bits (product()),
  // and v_pack_u saturates to bytes.
  const cv::v_int16x8 luma = cv::v_setall_s16(static_cast<short>(m.luma)),
                      blueU = cv::v_setall_s16(static_cast<short>(m.blueU)),
                      greenU = cv::v_setall_s16(static_cast<short>(m.greenU)),
                      greenV = cv::v_setall_s16(static_cast<short>(m.greenV)),
                      redV = cv::v_setall_s16(static_cast<short>(m.redV)), centre = cv::v_setall_s16(128);
  const cv::v_uint8x16 signBit = cv::v_setall_u8(0x80);
  const auto widen = [&](const uchar *samples, cv::v_int16x8 out[2]) {
    const cv::v_uint8x16 centred = cv::v_load(samples) ^ signBit;
    cv::v_uint8x16 lo, hi;
    cv::v_zip(centred, centred, lo, hi);
    out[0] = cv::v_reinterpret_as_s16(lo);
    out[1] = cv::v_reinterpret_as_s16(hi);
  };
  const auto narrow = [](const cv::v_int16x8 q[2]) { return cv::v_pack_u(q[0], q[1]); };
  for (; i + 16 <= n; i += 16) {
    cv::v_int16x8 ys[2], us[2], vs[2], b[2], g[2], r[2];
    widen(y + i, ys);
    widen(u + i, us);
    widen(v + i, vs);
    for (int k = 0; k < 2; ++k) {
      const cv::v_int16x8 l = cv::v_mul_hi(ys[k], luma) + centre;
      b[k] = l + cv::v_mul_hi(us[k], blueU);
      g[k] = l + cv::v_mul_hi(us[k], greenU) + cv::v_mul_hi(vs[k], greenV);
      r[k] = l + cv::v_mul_hi(vs[k], redV);
    }
    cv::v_store_interleave(bgr + 3 * i, narrow(b), narrow(g), narrow(r));
  }
#endif
  for (; i < n; ++i) m.pixel(y[i], u[i], v[i], bgr + 3 * i);
}

// One channel's samples under the pixels of a frame row (subsampled by 1 or 2).
struct ChannelReader {
  const ChannelSampler &c;
  int xShift, yShift;
  explicit ChannelReader(const ChannelSampler &sampler)
      : c(sampler), xShift(sampler.xSub == 2 ? 1 : 0), yShift(sampler.ySub == 2 ? 1 : 0) {
    CV_Assert((c.xSub == 1 || c.xSub == 2) && (c.ySub == 1 || c.ySub == 2));
  }
  // Byte offset, from row(), of the sample covering frame column x.
  int offset(int x) const { return (x >> xShift) * c.sampleBytes; }
  // The samples under pixels x, x + step, ... (n of them) of frame row y: a pointer into the plane where
  // they lie side by side, else gathered into `gathered` through `offsets` (offset() of each pixel, every
  // `stride`-th int).
  const uchar *samples(int y, int x, int step, int n, const int *offsets, int stride, uchar *gathered) const {
    const uchar *row = c.plane.ptr(y >> yShift) + c.byteOffset;
    if (step == 1 && c.sampleBytes == 1 && xShift == 0) return row + x;
    int i = 0;
#if CV_SIMD128
    if (step == 1 && c.sampleBytes == 1) {  // 4:2:0 or 4:2:2 chroma: each sample twice
      if (x & 1) gathered[i++] = row[x >> 1];
      for (; i + 32 <= n; i += 32) {
        const cv::v_uint8x16 s = cv::v_load(row + ((x + i) >> 1));
        cv::v_uint8x16 lo, hi;
        cv::v_zip(s, s, lo, hi);
        cv::v_store(gathered + i, lo);
        cv::v_store(gathered + i + 16, hi);
      }
    }
#endif
    for (; i < n; ++i) gathered[i] = row[offsets[stride * i]];
    return gathered;
  }
};

}  // namespace

void yuvToBgr(const SampledFrame &frame, const cv::Rect &rect, int step, cv::Mat &out) {
  CV_Assert(frame.encoding == PixelEncoding::Yuv && step >= 1 &&
            (rect & cv::Rect(cv::Point(), frame.size)) == rect && !rect.empty());
  const VideoconvertMatrix matrix(frame.colorimetry);
  const ChannelReader luma(frame.channels[0]), blueDiff(frame.channels[1]), redDiff(frame.channels[2]);
  const cv::Size target = sampledSize(rect, step);
  out.create(target, CV_8UC3);
  // Each chroma sample covers its block of pixels, as videoconvert's fast paths to RGB and OpenCV read it
  // (interpolating would be closer to the picture and further from what a user's RGB caps deliver: up to 49
  // levels at sharp colour edges).
  thread_local std::vector<int> columns;  // per output column: byte offsets of Y, U, V
  columns.resize(3 * size_t(target.width));
  for (int i = 0; i < target.width; ++i) {
    const int x = rect.x + i * step;
    columns[3 * i] = luma.offset(x);
    columns[3 * i + 1] = blueDiff.offset(x);
    columns[3 * i + 2] = redDiff.offset(x);
  }
  // Each output row's samples are gathered first (planes differ in layout and subsampling), then converted.
  thread_local std::vector<uchar> samples;
  samples.resize(3 * size_t(target.width));
  uchar *gathered[3] = {samples.data(), samples.data() + target.width, samples.data() + 2 * target.width};
  const int *offsets = columns.data();  // not re-read through the thread-local vector in the loop
  for (int j = 0; j < target.height; ++j) {
    const int y = rect.y + j * step;
    const uchar *ys = luma.samples(y, rect.x, step, target.width, offsets, 3, gathered[0]);
    const uchar *us = blueDiff.samples(y, rect.x, step, target.width, offsets + 1, 3, gathered[1]);
    const uchar *vs = redDiff.samples(y, rect.x, step, target.width, offsets + 2, 3, gathered[2]);
    convertRow(matrix, ys, us, vs, target.width, out.ptr(j));
  }
}

SampledFrame sampledI420(const cv::Mat &i420, cv::Size size, const YuvColorimetry &colorimetry) {
  CV_Assert(i420.type() == CV_8UC1 && size.width % 2 == 0 && size.height % 2 == 0 &&
            i420.cols == size.width && i420.rows == size.height * 3 / 2 && i420.isContinuous());
  const cv::Size chroma(size.width / 2, size.height / 2);
  const cv::Mat u(chroma, CV_8UC1, const_cast<uchar *>(i420.ptr(size.height)));
  const cv::Mat v(chroma, CV_8UC1, const_cast<uchar *>(i420.ptr(size.height)) + chroma.area());
  SampledFrame frame;
  frame.encoding = PixelEncoding::Yuv;
  frame.colorimetry = colorimetry;
  frame.size = size;
  frame.channels = {ChannelSampler{i420.rowRange(0, size.height), 0, 1, 1, 1}, ChannelSampler{u, 0, 1, 2, 2},
                    ChannelSampler{v, 0, 1, 2, 2}};
  return frame;
}

}  // namespace colortrack
