// SPDX-License-Identifier: LGPL-2.1-or-later
// Read access to a mapped GstVideoFrame for the tracker: converts only the rectangles the tracker asks for.
#pragma once

#include <mutex>

#include <gst/video/video.h>

#include <opencv2/core.hpp>

#include "colortrack/image_source.hpp"
#include "colortrack/scratch_image.hpp"

namespace colortrack_gst {

// The caps formats the element accepts, as a caps-string list.
#define COLORTRACK_VIDEO_FORMATS \
  "{ BGR, RGB, BGRx, RGBx, xBGR, xRGB, BGRA, RGBA, ARGB, ABGR, I420, NV12, YUY2 }"

// True for the formats FrameView and the overlay understand.
bool isSupportedFormat(GstVideoFormat format);

// Byte offsets of B, G, R (and the fourth, alpha/padding byte, or -1) inside one pixel of a packed RGB
// format, and the pixel size. Taken from GstVideoFormatInfo, so one code path covers the whole family.
struct PackedLayout {
  int pixelBytes = 0;
  int blue = 0, green = 0, red = 0;
  int filler = -1;
};
PackedLayout packedLayout(const GstVideoFormatInfo *finfo);

// A plane of the frame as a cv::Mat header over the mapped memory, with the plane's real stride.
// `type` gives the element type (CV_8UC1, CV_8UC2 for NV12's UV, CV_8UC4 for YUY2 macro-pixels ...).
cv::Mat planeMat(const GstVideoFrame *frame, int plane, cv::Size size, int type);

// The colorimetry of a YUV frame (matrix, range), as its caps say.
colortrack::YuvColorimetry yuvColorimetry(const GstVideoInfo *info);

// colortrack::ImageSource over a mapped frame. YUV formats are converted by the caps' colorimetry, as
// videoconvert would convert them (colortrack::yuvToBgr), so that a source delivering YUV and one delivering
// the same frames as RGB give the tracker the same image.
class FrameView : public colortrack::ImageSource {
 public:
  // `frame` must stay mapped for the lifetime of the view. `cacheStorage`, if given, holds the cache of
  // converted pixels (below) and keeps its memory for the next frame's view; it belongs to one element, which
  // makes one view at a time.
  explicit FrameView(const GstVideoFrame *frame, colortrack::ScratchImage *cacheStorage = nullptr);

  cv::Size size() const override { return size_; }
  void bgr(const cv::Rect &rect, cv::Mat &out) const override;
  // Samples first and converts only the sample: a 1080p frame reduced 4x costs 1/16 of its conversion.
  void sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const override;
  // The frame's bytes described channel by channel, read in place in every format (YUV ones through a YUV
  // lookup table): threshold mode segments the frame without converting it. `scratch` is not needed.
  colortrack::SampledFrame channels(cv::Mat &scratch) const override;

 private:
  void convert(const cv::Rect &rect, cv::Mat &out) const;
  void packedToBgr(const cv::Rect &rect, cv::Mat &out) const;
  void packedToBgr(const cv::Mat &pixels, cv::Mat &out) const;
  void yuvToBgr(const cv::Rect &rect, int step, cv::Mat &out) const;

  const GstVideoFrame *frame_;
  GstVideoFormat format_;
  cv::Size size_;
  PackedLayout packed_;                     // RGB formats
  colortrack::YuvColorimetry colorimetry_;  // YUV formats
  // The largest region converted so far, for the regions inside it (the tracker may read from two threads).
  mutable std::mutex cacheMutex_;
  mutable cv::Rect cachedRect_;
  mutable cv::Mat cached_;  // in *cacheStorage_ when there is one
  colortrack::ScratchImage *cacheStorage_;
};

}  // namespace colortrack_gst
