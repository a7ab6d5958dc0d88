#include "colortrack/yuv_image.hpp"

#include <array>
#include <vector>

namespace colortrack {

namespace {

// The colorimetry's matrix as integer tables, 10 fractional bits. Every Y'CbCr matrix gives B from Y and U,
// R from Y and V, G from all three, with the same luma weight: B = luma[Y] + blue[U], G = luma[Y] + green[U]
// + greenV[V], R = luma[Y] + red[V], each >> 10. One pass with table loads, chroma terms shared by the pixels
// a sample covers, is about as fast as cv::cvtColor's fixed BT.601 I420 conversion (which takes no other
// matrix or range) and several times faster than gathering the planes for cv::transform's float matrix.
struct MatrixTables {
  std::array<int, 256> luma, blue, green, greenV, red;

  explicit MatrixTables(const YuvColorimetry &colorimetry) {
    const cv::Matx34f m = colorimetry.toBgrMatrix();
    for (int k = 0; k < 256; ++k) {
      luma[k] = cvRound(m(0, 0) * k * 1024) + 512;  // + 512: rounds the sums
      blue[k] = cvRound((m(0, 1) * k + m(0, 3)) * 1024);
      green[k] = cvRound((m(1, 1) * k + m(1, 3)) * 1024);
      greenV[k] = cvRound(m(1, 2) * k * 1024);
      red[k] = cvRound((m(2, 2) * k + m(2, 3)) * 1024);
    }
  }
};

// Byte offset of the sample covering frame column x, and the row pointer of frame row y, of one channel
// (subsampled by 1 or 2).
struct ChannelReader {
  const ChannelSampler &c;
  int xShift, yShift;
  explicit ChannelReader(const ChannelSampler &sampler)
      : c(sampler), xShift(sampler.xSub == 2 ? 1 : 0), yShift(sampler.ySub == 2 ? 1 : 0) {
    CV_Assert((c.xSub == 1 || c.xSub == 2) && (c.ySub == 1 || c.ySub == 2));
  }
  const uchar *row(int y) const { return c.plane.ptr(y >> yShift) + c.byteOffset; }
  int offset(int x) const { return (x >> xShift) * c.sampleBytes; }
};

}  // namespace

void yuvToBgr(const SampledFrame &frame, const cv::Rect &rect, int step, cv::Mat &out) {
  CV_Assert(frame.encoding == PixelEncoding::Yuv && step >= 1 &&
            (rect & cv::Rect(cv::Point(), frame.size)) == rect && !rect.empty());
  const MatrixTables t(frame.colorimetry);
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
  const int *offsets = columns.data();  // not re-read through the thread-local vector in the loop
  for (int j = 0; j < target.height; ++j) {
    const int y = rect.y + j * step;
    const uchar *yRow = luma.row(y), *uRow = blueDiff.row(y), *vRow = redDiff.row(y);
    uchar *o = out.ptr(j);
    int lastU = -1, lastV = -1, b = 0, g = 0, r = 0;
    for (int i = 0; i < target.width; ++i, o += 3) {
      const int *column = offsets + 3 * i;
      if (column[1] != lastU || column[2] != lastV) {
        lastU = column[1];
        lastV = column[2];
        const int U = uRow[lastU], V = vRow[lastV];
        b = t.blue[U];
        g = t.green[U] + t.greenV[V];
        r = t.red[V];
      }
      const int Y = t.luma[yRow[column[0]]];
      o[0] = cv::saturate_cast<uchar>((Y + b) >> 10);
      o[1] = cv::saturate_cast<uchar>((Y + g) >> 10);
      o[2] = cv::saturate_cast<uchar>((Y + r) >> 10);
    }
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
