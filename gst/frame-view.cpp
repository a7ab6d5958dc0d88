#include "frame-view.h"

#include <opencv2/imgproc.hpp>

#include "colortrack/scratch_image.hpp"

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

FrameView::FrameView(const GstVideoFrame *frame, colortrack::ScratchImage *cacheStorage)
    : frame_(frame),
      format_(GST_VIDEO_FRAME_FORMAT(frame)),
      size_(GST_VIDEO_FRAME_WIDTH(frame), GST_VIDEO_FRAME_HEIGHT(frame)),
      cacheStorage_(cacheStorage) {
  if (GST_VIDEO_FORMAT_INFO_IS_RGB(frame->info.finfo)) packed_ = packedLayout(frame->info.finfo);
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
  out.encoding = colortrack::PixelEncoding::Yuv601;
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
  // are cut from its conversion. Each pixel converts on its own (chroma is shared by whole 2x2 or 2x1
  // blocks, and the conversions keep block alignment), so a cut is exactly what converting it would give.
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
  switch (format_) {
    case GST_VIDEO_FORMAT_I420:
    case GST_VIDEO_FORMAT_NV12:
      planarToBgr(rect, out);
      break;
    case GST_VIDEO_FORMAT_YUY2:
      yuy2ToBgr(rect, out);
      break;
    default:
      packedToBgr(rect, out);
      break;
  }
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
  // YUV: gather every step-th luma pixel and the chroma sample under it into a small I420 image, then let
  // OpenCV convert that, so the sample goes through the very matrix bgr() uses (cvtColor's BT.601 I420).
  const cv::Size even(target.width + (target.width & 1), target.height + (target.height & 1));
  thread_local colortrack::ScratchImage yuvScratch,
      convertedScratch;  // kept across frames, see scratch_image.hpp
  cv::Mat yuv = yuvScratch.view(cv::Size(even.width, even.height * 3 / 2), CV_8UC1);
  uchar *uOut = yuv.ptr(even.height), *vOut = uOut + even.area() / 4;
  const int maxX = size_.width - 1, maxY = size_.height - 1;
  auto lumaX = [&](int i) { return std::min(rect.x + i * step, maxX); };
  auto lumaY = [&](int j) { return std::min(rect.y + j * step, maxY); };
  const guint8 *base0 = static_cast<const guint8 *>(GST_VIDEO_FRAME_PLANE_DATA(frame_, 0));
  const int stride0 = GST_VIDEO_FRAME_PLANE_STRIDE(frame_, 0);
  if (format_ == GST_VIDEO_FORMAT_YUY2) {
    for (int j = 0; j < even.height; ++j) {
      const guint8 *row = base0 + static_cast<size_t>(lumaY(j)) * stride0;
      uchar *yRow = yuv.ptr(j);
      for (int i = 0; i < even.width; ++i) yRow[i] = row[2 * lumaX(i)];
      if (j & 1) continue;
      uchar *uRow = uOut + (j / 2) * (even.width / 2), *vRow = vOut + (j / 2) * (even.width / 2);
      for (int i = 0; i < even.width / 2; ++i) {
        const guint8 *macro = row + 4 * (lumaX(2 * i) / 2);
        uRow[i] = macro[1];
        vRow[i] = macro[3];
      }
    }
  } else {
    const guint8 *base1 = static_cast<const guint8 *>(GST_VIDEO_FRAME_PLANE_DATA(frame_, 1));
    const int stride1 = GST_VIDEO_FRAME_PLANE_STRIDE(frame_, 1);
    const bool nv12 = format_ == GST_VIDEO_FORMAT_NV12;
    const guint8 *base2 = nv12 ? nullptr : static_cast<const guint8 *>(GST_VIDEO_FRAME_PLANE_DATA(frame_, 2));
    const int stride2 = nv12 ? 0 : GST_VIDEO_FRAME_PLANE_STRIDE(frame_, 2);
    for (int j = 0; j < even.height; ++j) {
      const guint8 *row = base0 + static_cast<size_t>(lumaY(j)) * stride0;
      uchar *yRow = yuv.ptr(j);
      for (int i = 0; i < even.width; ++i) yRow[i] = row[lumaX(i)];
    }
    for (int j = 0; j < even.height / 2; ++j) {
      const int chromaRow = lumaY(2 * j) / 2;
      const guint8 *row1 = base1 + static_cast<size_t>(chromaRow) * stride1;
      const guint8 *row2 = nv12 ? nullptr : base2 + static_cast<size_t>(chromaRow) * stride2;
      uchar *uRow = uOut + j * (even.width / 2), *vRow = vOut + j * (even.width / 2);
      for (int i = 0; i < even.width / 2; ++i) {
        const int c = lumaX(2 * i) / 2;
        uRow[i] = nv12 ? row1[2 * c] : row1[c];
        vRow[i] = nv12 ? row1[2 * c + 1] : row2[c];
      }
    }
  }
  cv::Mat converted = convertedScratch.view(even, CV_8UC3);
  cv::cvtColor(yuv, converted, cv::COLOR_YUV2BGR_I420);
  converted(cv::Rect(cv::Point(), target)).copyTo(out);
}

void FrameView::planarToBgr(const cv::Rect &rect, cv::Mat &out) const {
  // One chroma sample covers 2x2 luma pixels: convert the rect grown to even coordinates, then crop.
  const int x0 = rect.x & ~1, y0 = rect.y & ~1;
  const int x1 = (rect.x + rect.width + 1) & ~1, y1 = (rect.y + rect.height + 1) & ~1;
  const int w = x1 - x0, h = y1 - y0;
  const cv::Size chromaSize((size_.width + 1) / 2, (size_.height + 1) / 2);

  // cvtColor wants the planes back to back: h luma rows, then the chroma (U then V, or interleaved UV).
  thread_local colortrack::ScratchImage yuvScratch, fullScratch;  // kept across frames, see scratch_image.hpp
  cv::Mat yuv = yuvScratch.view(cv::Size(w, h + h / 2), CV_8UC1);
  cv::Mat lumaOut = yuv.rowRange(0, h);
  // With an odd frame width or height the grown rect can run one pixel past the luma plane (never past
  // the chroma plane, which is ceil(size / 2)): replicate the last row/column into it.
  const cv::Rect lumaInside = cv::Rect(x0, y0, w, h) & cv::Rect(cv::Point(), size_);
  const cv::Mat luma = planeMat(frame_, 0, size_, CV_8UC1);
  cv::copyMakeBorder(luma(lumaInside), lumaOut, 0, h - lumaInside.height, 0, w - lumaInside.width,
                     cv::BORDER_REPLICATE);

  const cv::Rect chromaRect(x0 / 2, y0 / 2, w / 2, h / 2);
  uchar *chromaOut = yuv.ptr(h);
  int code;
  if (format_ == GST_VIDEO_FORMAT_I420) {
    const size_t planeBytes = chromaRect.area();
    cv::Mat uOut(chromaRect.size(), CV_8UC1, chromaOut);
    cv::Mat vOut(chromaRect.size(), CV_8UC1, chromaOut + planeBytes);
    planeMat(frame_, 1, chromaSize, CV_8UC1)(chromaRect).copyTo(uOut);
    planeMat(frame_, 2, chromaSize, CV_8UC1)(chromaRect).copyTo(vOut);
    code = cv::COLOR_YUV2BGR_I420;
  } else {
    cv::Mat uvOut(chromaRect.size(), CV_8UC2, chromaOut);
    planeMat(frame_, 1, chromaSize, CV_8UC2)(chromaRect).copyTo(uvOut);
    code = cv::COLOR_YUV2BGR_NV12;
  }

  if (w == rect.width && h == rect.height) {
    cv::cvtColor(yuv, out, code);
  } else {
    cv::Mat full = fullScratch.view(cv::Size(w, h), CV_8UC3);
    cv::cvtColor(yuv, full, code);
    full(cv::Rect(rect.x - x0, rect.y - y0, rect.width, rect.height)).copyTo(out);
  }
}

void FrameView::yuy2ToBgr(const cv::Rect &rect, cv::Mat &out) const {
  // Y0 U Y1 V macro-pixels: only x needs aligning. The plane always holds ceil(width / 2) macro-pixels,
  // so the grown rect stays inside the mapped memory even for an odd width.
  const int x0 = rect.x & ~1, x1 = (rect.x + rect.width + 1) & ~1;
  const cv::Size planeSize(2 * ((size_.width + 1) / 2), size_.height);
  const cv::Mat roi = planeMat(frame_, 0, planeSize, CV_8UC2)(cv::Rect(x0, rect.y, x1 - x0, rect.height));
  if (x0 == rect.x && x1 - x0 == rect.width) {
    cv::cvtColor(roi, out, cv::COLOR_YUV2BGR_YUY2);
  } else {
    cv::Mat full;
    cv::cvtColor(roi, full, cv::COLOR_YUV2BGR_YUY2);
    full(cv::Rect(rect.x - x0, 0, rect.width, rect.height)).copyTo(out);
  }
}

}  // namespace colortrack_gst
