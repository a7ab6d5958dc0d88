#include "colortrack/yuv_image.hpp"

#include <vector>

#include <opencv2/core/hal/intrin.hpp>

namespace colortrack {

namespace {

// The colorimetry's matrix in fixed point (14 fractional bits, as OpenCV's own YUV conversions). Every
// Y'CbCr matrix gives B from Y and U, R from Y and V, G from all three, with one luma weight.
struct FixedPointMatrix {
  static constexpr int kShift = 14;
  int luma, blueU, greenU, greenV, redV;  // weights
  int blue0, green0, red0;                // offsets, with the rounding of the shift

  explicit FixedPointMatrix(const YuvColorimetry &colorimetry) {
    const cv::Matx34f m = colorimetry.toBgrMatrix();
    const auto fixed = [](double x) { return cvRound(x * (1 << kShift)); };
    luma = fixed(m(0, 0));
    blueU = fixed(m(0, 1));
    greenU = fixed(m(1, 1));
    greenV = fixed(m(1, 2));
    redV = fixed(m(2, 2));
    blue0 = fixed(m(0, 3)) + (1 << (kShift - 1));
    green0 = fixed(m(1, 3)) + (1 << (kShift - 1));
    red0 = fixed(m(2, 3)) + (1 << (kShift - 1));
  }
  void pixel(int y, int u, int v, uchar *bgr) const {
    const int l = luma * y;
    bgr[0] = cv::saturate_cast<uchar>((l + blueU * u + blue0) >> kShift);
    bgr[1] = cv::saturate_cast<uchar>((l + greenU * u + greenV * v + green0) >> kShift);
    bgr[2] = cv::saturate_cast<uchar>((l + redV * v + red0) >> kShift);
  }
};

// n pixels from the Y, U and V samples under them to interleaved BGR: 16 at a time with OpenCV's universal
// intrinsics (the same integer maths as pixel(), so the result does not depend on the CPU), the rest one by
// one.
void convertRow(const FixedPointMatrix &m, const uchar *y, const uchar *u, const uchar *v, int n,
                uchar *bgr) {
  int i = 0;
#if CV_SIMD128
  const cv::v_int32x4 luma = cv::v_setall_s32(m.luma), blueU = cv::v_setall_s32(m.blueU),
                      greenU = cv::v_setall_s32(m.greenU), greenV = cv::v_setall_s32(m.greenV),
                      redV = cv::v_setall_s32(m.redV), blue0 = cv::v_setall_s32(m.blue0),
                      green0 = cv::v_setall_s32(m.green0), red0 = cv::v_setall_s32(m.red0);
  // The 16 bytes of a vector as four vectors of four int32.
  const auto widen = [](const cv::v_uint8x16 &bytes, cv::v_int32x4 out[4]) {
    cv::v_uint16x8 lo, hi;
    cv::v_expand(bytes, lo, hi);
    cv::v_uint32x4 q[4];
    cv::v_expand(lo, q[0], q[1]);
    cv::v_expand(hi, q[2], q[3]);
    for (int k = 0; k < 4; ++k) out[k] = cv::v_reinterpret_as_s32(q[k]);
  };
  const auto narrow = [](const cv::v_int32x4 q[4]) {
    return cv::v_pack_u(cv::v_pack(q[0], q[1]), cv::v_pack(q[2], q[3]));
  };
  for (; i + 16 <= n; i += 16) {
    cv::v_int32x4 ys[4], us[4], vs[4], b[4], g[4], r[4];
    widen(cv::v_load(y + i), ys);
    widen(cv::v_load(u + i), us);
    widen(cv::v_load(v + i), vs);
    for (int k = 0; k < 4; ++k) {
      const cv::v_int32x4 l = luma * ys[k];
      b[k] = cv::v_shr<FixedPointMatrix::kShift>(l + blueU * us[k] + blue0);
      g[k] = cv::v_shr<FixedPointMatrix::kShift>(l + greenU * us[k] + greenV * vs[k] + green0);
      r[k] = cv::v_shr<FixedPointMatrix::kShift>(l + redV * vs[k] + red0);
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
  const FixedPointMatrix matrix(frame.colorimetry);
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
