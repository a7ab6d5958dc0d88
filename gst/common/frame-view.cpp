// SPDX-License-Identifier: LGPL-2.1-or-later
#include "frame-view.h"

#include <opencv2/imgproc.hpp>

#include "colortrack/scratch_image.hpp"
#include "colortrack/yuv_image.hpp"

namespace colortrack_gst {

bool isSupportedFormat(GstVideoFormat format) {
  switch (format) {
    case GST_VIDEO_FORMAT_BGR:
    case GST_VIDEO_FORMAT_RGB:
    case GST_VIDEO_FORMAT_BGRx:
    case GST_VIDEO_FORMAT_RGBx:
    case GST_VIDEO_FORMAT_xBGR:
    case GST_VIDEO_FORMAT_xRGB:
    case GST_VIDEO_FORMAT_BGRA:
    case GST_VIDEO_FORMAT_RGBA:
    case GST_VIDEO_FORMAT_ARGB:
    case GST_VIDEO_FORMAT_ABGR:
    case GST_VIDEO_FORMAT_I420:
    case GST_VIDEO_FORMAT_NV12:
    case GST_VIDEO_FORMAT_YUY2:
      return true;
    default:
      return false;
  }
}

PackedLayout packedLayout(const GstVideoFormatInfo *finfo) {
  PackedLayout layout;
  layout.pixelBytes = GST_VIDEO_FORMAT_INFO_PSTRIDE(finfo, 0);
  layout.red = GST_VIDEO_FORMAT_INFO_POFFSET(finfo, GST_VIDEO_COMP_R);
  layout.green = GST_VIDEO_FORMAT_INFO_POFFSET(finfo, GST_VIDEO_COMP_G);
  layout.blue = GST_VIDEO_FORMAT_INFO_POFFSET(finfo, GST_VIDEO_COMP_B);
  // Byte offsets of a 4-byte pixel sum to 0+1+2+3: the one left over is the alpha or padding byte.
  if (layout.pixelBytes == 4) layout.filler = 6 - layout.red - layout.green - layout.blue;
  return layout;
}

cv::Mat planeMat(const GstVideoFrame *frame, int plane, cv::Size size, int type) {
  return cv::Mat(size, type, GST_VIDEO_FRAME_PLANE_DATA(frame, plane),
                 static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(frame, plane)));
}

colortrack::YuvColorimetry yuvColorimetry(const GstVideoInfo *info) {
  colortrack::YuvColorimetry c;
  gdouble kr, kb;
  // An unknown or RGB matrix on YUV caps: BT.601, as videoconvert assumes.
  if (gst_video_color_matrix_get_Kr_Kb(info->colorimetry.matrix, &kr, &kb)) {
    c.kr = kr;
    c.kb = kb;
  }
  c.fullRange = info->colorimetry.range == GST_VIDEO_COLOR_RANGE_0_255;
  return c;
}

FrameView::FrameView(const GstVideoFrame *frame, colortrack::ScratchImage *cacheStorage)
    : frame_(frame),
      format_(GST_VIDEO_FRAME_FORMAT(frame)),
      size_(GST_VIDEO_FRAME_WIDTH(frame), GST_VIDEO_FRAME_HEIGHT(frame)),
      cacheStorage_(cacheStorage) {
  if (GST_VIDEO_FORMAT_INFO_IS_RGB(frame->info.finfo))
    packed_ = packedLayout(frame->info.finfo);
  else
    colorimetry_ = yuvColorimetry(&frame->info);
}

colortrack::SampledFrame FrameView::channels(cv::Mat & /*scratch*/) const {
  const GstVideoFrame *frame = frame_;
  const int w = size_.width, h = size_.height;
  const int cw = (w + 1) / 2, ch = (h + 1) / 2;
  const auto bytes = [frame](int plane, int rows, int rowBytes) {
    return cv::Mat(rows, rowBytes, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(frame, plane),
                   static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(frame, plane)));
  };
  colortrack::SampledFrame out;
  out.size = cv::Size(w, h);
  out.encoding = colortrack::PixelEncoding::Yuv;
  out.colorimetry = colorimetry_;
  switch (format_) {
    case GST_VIDEO_FORMAT_I420:
      out.channels = {colortrack::ChannelSampler{bytes(0, h, w), 0, 1, 1, 1},
                      colortrack::ChannelSampler{bytes(1, ch, cw), 0, 1, 2, 2},
                      colortrack::ChannelSampler{bytes(2, ch, cw), 0, 1, 2, 2}};
      break;
    case GST_VIDEO_FORMAT_NV12: {
      const cv::Mat uv = bytes(1, ch, 2 * cw);
      out.channels = {colortrack::ChannelSampler{bytes(0, h, w), 0, 1, 1, 1},
                      colortrack::ChannelSampler{uv, 0, 2, 2, 2}, colortrack::ChannelSampler{uv, 1, 2, 2, 2}};
      break;
    }
    case GST_VIDEO_FORMAT_YUY2: {
      const cv::Mat packed = bytes(0, h, 4 * cw);  // Y0 U Y1 V per two pixels
      out.channels = {colortrack::ChannelSampler{packed, 0, 2, 1, 1},
                      colortrack::ChannelSampler{packed, 1, 4, 2, 1},
                      colortrack::ChannelSampler{packed, 3, 4, 2, 1}};
      break;
    }
    default: {
      const PackedLayout &layout = packed_;
      const cv::Mat packed = bytes(0, h, w * layout.pixelBytes);
      out.encoding = colortrack::PixelEncoding::Rgb;
      out.channels = {colortrack::ChannelSampler{packed, layout.red, layout.pixelBytes, 1, 1},
                      colortrack::ChannelSampler{packed, layout.green, layout.pixelBytes, 1, 1},
                      colortrack::ChannelSampler{packed, layout.blue, layout.pixelBytes, 1, 1}};
      break;
    }
  }
  return out;
}

void FrameView::bgr(const cv::Rect &rect, cv::Mat &out) const {
  CV_Assert((rect & cv::Rect(cv::Point(), size_)) == rect && !rect.empty());
  // The tracker reads several regions of one frame, most of them inside the first (the search window): those
  // are cut from its conversion. Each pixel converts on its own (from the chroma sample covering it), so a
  // cut is exactly what converting it would give.
  {
    const std::lock_guard<std::mutex> lock(cacheMutex_);
    if ((rect & cachedRect_) == rect) {
      cached_(rect - cachedRect_.tl()).copyTo(out);
      return;
    }
  }
  convert(rect, out);
  const std::lock_guard<std::mutex> lock(cacheMutex_);
  if (rect.area() > cachedRect_.area()) {
    if (cacheStorage_) cached_ = cacheStorage_->view(out.size(), out.type());
    out.copyTo(cached_);
    cachedRect_ = rect;
  }
}

void FrameView::convert(const cv::Rect &rect, cv::Mat &out) const {
  if (GST_VIDEO_FORMAT_INFO_IS_RGB(frame_->info.finfo))
    packedToBgr(rect, out);
  else
    yuvToBgr(rect, 1, out);
}

void FrameView::yuvToBgr(const cv::Rect &rect, int step, cv::Mat &out) const {
  cv::Mat unused;  // channels() reads YUV frames in place
  colortrack::yuvToBgr(channels(unused), rect, step, out);
}

void FrameView::packedToBgr(const cv::Rect &rect, cv::Mat &out) const {
  packedToBgr(planeMat(frame_, 0, size_, CV_8UC(packed_.pixelBytes))(rect), out);
}

void FrameView::packedToBgr(const cv::Mat &roi, cv::Mat &out) const {
  const PackedLayout &p = packed_;
  const bool bgrOrder = p.blue == 0 && p.green == 1 && p.red == 2;
  const bool rgbOrder = p.red == 0 && p.green == 1 && p.blue == 2;
  if (p.pixelBytes == 3 && bgrOrder) {
    roi.copyTo(out);
  } else if (p.pixelBytes == 3 && rgbOrder) {
    cv::cvtColor(roi, out, cv::COLOR_RGB2BGR);
  } else if (bgrOrder) {
    cv::cvtColor(roi, out, cv::COLOR_BGRA2BGR);
  } else if (rgbOrder) {
    cv::cvtColor(roi, out, cv::COLOR_RGBA2BGR);
  } else {
    // xRGB, ARGB, xBGR, ABGR: the padding byte comes first, which cvtColor has no code for.
    out.create(roi.size(), CV_8UC3);
    const int fromTo[] = {p.blue, 0, p.green, 1, p.red, 2};
    cv::mixChannels(&roi, 1, &out, 1, fromTo, 3);
  }
}

void FrameView::sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const {
  CV_Assert((rect & cv::Rect(cv::Point(), size_)) == rect && !rect.empty());
  if (step <= 1) return bgr(rect, out);
  const cv::Size target = colortrack::sampledSize(rect, step);
  if (GST_VIDEO_FORMAT_INFO_IS_RGB(frame_->info.finfo)) {
    cv::Mat sample;
    cv::resize(planeMat(frame_, 0, size_, CV_8UC(packed_.pixelBytes))(colortrack::sampledCover(rect, step)),
               sample, target, 0, 0, cv::INTER_NEAREST);
    packedToBgr(sample, out);
    return;
  }
  yuvToBgr(rect, step, out);
}

}  // namespace colortrack_gst
