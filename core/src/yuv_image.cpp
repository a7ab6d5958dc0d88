#include "colortrack/yuv_image.hpp"

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

// One channel's samples inside `rect` (sample coordinates, inside the plane) as a CV_8UC1 image: a view of
// the plane when its samples lie side by side, else copied into `storage` (which only ever holds its own
// memory: extracting into a view would write into the frame).
cv::Mat channelRegion(const ChannelSampler &c, const cv::Rect &rect, cv::Mat &storage) {
  const cv::Mat samples(c.plane.rows, c.plane.cols / c.sampleBytes, CV_8UC(c.sampleBytes), c.plane.data,
                        c.plane.step);
  if (c.sampleBytes == 1) return samples(rect);
  cv::extractChannel(samples(rect), storage, c.byteOffset);
  return storage;
}

// Chroma channel `c` at every `step`-th luma pixel of `rect`: the sample covering each pixel, as
// videoconvert's fast paths from YUV to RGB and OpenCV's conversions read it (interpolating would be closer
// to the picture and further from what a user's RGB caps deliver: up to 50 levels at sharp colour edges).
void chromaAt(const ChannelSampler &c, const cv::Rect &rect, int step, cv::Size target, cv::Mat &out) {
  const cv::Size samples(c.plane.cols / c.sampleBytes, c.plane.rows);
  const cv::Point first(rect.x / c.xSub, rect.y / c.ySub);
  const cv::Point last((rect.x + step * (target.width - 1)) / c.xSub,
                       (rect.y + step * (target.height - 1)) / c.ySub);
  const cv::Rect covered = cv::Rect(first, last + cv::Point(1, 1)) & cv::Rect(cv::Point(), samples);
  thread_local cv::Mat storage;
  const cv::Mat region = channelRegion(c, covered, storage);
  // Output pixel (i, j) reads sample ((x + i * step) / xSub, (y + j * step) / ySub) rounded down: the map is
  // offset by half a luma pixel so that rounding to the nearest sample rounds down.
  const double sx = double(step) / c.xSub, sy = double(step) / c.ySub;
  const cv::Matx23d toSample(sx, 0, (rect.x + 0.5) / c.xSub - 0.5 - covered.x, 0, sy,
                             (rect.y + 0.5) / c.ySub - 0.5 - covered.y);
  cv::warpAffine(region, out, toSample, target, cv::INTER_NEAREST | cv::WARP_INVERSE_MAP,
                 cv::BORDER_REPLICATE);
}

}  // namespace

void yuvToBgr(const SampledFrame &frame, const cv::Rect &rect, int step, cv::Mat &out) {
  CV_Assert(frame.encoding == PixelEncoding::Yuv && step >= 1 &&
            (rect & cv::Rect(cv::Point(), frame.size)) == rect && !rect.empty());
  const cv::Size target = sampledSize(rect, step);
  // Scratch kept across calls; each holds only its own memory (never a view of a frame, which a later call
  // would otherwise write into).
  thread_local cv::Mat lumaStorage, sampledLuma, u, v, yuv;
  cv::Mat luma = channelRegion(frame.channels[0], sampledCover(rect, step), lumaStorage);
  if (step > 1) {
    cv::resize(luma, sampledLuma, target, 0, 0, cv::INTER_NEAREST);
    luma = sampledLuma;
  }
  chromaAt(frame.channels[1], rect, step, target, u);
  chromaAt(frame.channels[2], rect, step, target, v);
  const cv::Mat planes[3] = {luma, u, v};
  cv::merge(planes, 3, yuv);
  cv::transform(yuv, out, frame.colorimetry.toBgrMatrix());
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
