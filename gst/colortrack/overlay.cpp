// SPDX-License-Identifier: LGPL-2.1-or-later
#include "overlay.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "frame-view.h"

namespace colortrack_gst {

Rgb idColour(int id) {
  const double hue = std::fmod(id * 137.508, 360.0) / 60.0;  // golden angle: successive ids spread out
  const double x = 1 - std::abs(std::fmod(hue, 2.0) - 1);
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(hue)) {
    case 0:
      r = 1;
      g = x;
      break;
    case 1:
      r = x;
      g = 1;
      break;
    case 2:
      g = 1;
      b = x;
      break;
    case 3:
      g = x;
      b = 1;
      break;
    case 4:
      r = x;
      b = 1;
      break;
    default:
      r = 1;
      b = x;
      break;
  }
  const auto byte = [](double c) { return static_cast<std::uint8_t>(std::lround(c * 255)); };
  return Rgb{byte(r), byte(g), byte(b)};
}

FrameCanvas::FrameCanvas(GstVideoFrame *frame)
    : size_(GST_VIDEO_FRAME_WIDTH(frame), GST_VIDEO_FRAME_HEIGHT(frame)) {
  const cv::Size half((size_.width + 1) / 2, (size_.height + 1) / 2);
  switch (GST_VIDEO_FRAME_FORMAT(frame)) {
    case GST_VIDEO_FORMAT_I420:
      planes_.push_back({planeMat(frame, 0, size_, CV_8UC1), PlaneKind::Luma, 1, 1});
      planes_.push_back({planeMat(frame, 1, half, CV_8UC1), PlaneKind::ChromaU, 2, 2});
      planes_.push_back({planeMat(frame, 2, half, CV_8UC1), PlaneKind::ChromaV, 2, 2});
      textTarget_ = planes_[0].mat;
      textOnYuv_ = true;
      align_ = 2;
      break;
    case GST_VIDEO_FORMAT_NV12:
      planes_.push_back({planeMat(frame, 0, size_, CV_8UC1), PlaneKind::Luma, 1, 1});
      planes_.push_back({planeMat(frame, 1, half, CV_8UC2), PlaneKind::ChromaUV, 2, 2});
      textTarget_ = planes_[0].mat;
      textOnYuv_ = true;
      align_ = 2;
      break;
    case GST_VIDEO_FORMAT_YUY2:
      // Macro-pixels (Y0 U Y1 V) of two frame pixels each: a plane half as wide, full height.
      planes_.push_back(
          {planeMat(frame, 0, cv::Size(half.width, size_.height), CV_8UC4), PlaneKind::Yuy2, 2, 1});
      // The same bytes as (Y, U) (Y, V) pairs: text at full resolution; its chroma byte is set neutral.
      textTarget_ = planeMat(frame, 0, cv::Size(2 * half.width, size_.height), CV_8UC2);
      textOnYuv_ = true;
      align_ = 2;
      break;
    default: {
      const PackedLayout layout = packedLayout(frame->info.finfo);
      packedBytes_ = layout.pixelBytes;
      red_ = layout.red;
      green_ = layout.green;
      blue_ = layout.blue;
      filler_ = layout.filler;
      planes_.push_back({planeMat(frame, 0, size_, CV_8UC(packedBytes_)), PlaneKind::Packed, 1, 1});
      textTarget_ = planes_[0].mat;
      break;
    }
  }
}

cv::Scalar FrameCanvas::colourFor(const Plane &plane, const Rgb &colour) const {
  const colortrack::Yuv yuv = colortrack::rgbToYuv601(colour.r, colour.g, colour.b);
  switch (plane.kind) {
    case PlaneKind::Packed: {
      cv::Scalar s;
      s[red_] = colour.r;
      s[green_] = colour.g;
      s[blue_] = colour.b;
      if (filler_ >= 0) s[filler_] = 255;  // opaque alpha (ignored by x formats)
      return s;
    }
    case PlaneKind::Luma:
      return cv::Scalar(yuv.y);
    case PlaneKind::ChromaU:
      return cv::Scalar(yuv.u);
    case PlaneKind::ChromaV:
      return cv::Scalar(yuv.v);
    case PlaneKind::ChromaUV:
      return cv::Scalar(yuv.u, yuv.v);
    case PlaneKind::Yuy2:
      return cv::Scalar(yuv.y, yuv.u, yuv.y, yuv.v);
  }
  return cv::Scalar();
}

void FrameCanvas::fillRect(const cv::Rect &rect, const Rgb &colour) {
  for (const Plane &plane : planes_) {
    const cv::Rect scaled(rect.x / plane.xDiv, rect.y / plane.yDiv, rect.width / plane.xDiv,
                          rect.height / plane.yDiv);
    const cv::Rect clipped = scaled & cv::Rect(cv::Point(), plane.mat.size());
    if (!clipped.empty()) plane.mat(clipped).setTo(colourFor(plane, colour));
  }
}

void FrameCanvas::boxOutline(const cv::Rect &box, const Rgb &colour, int thickness) {
  // Grow to multiples of the chroma subsampling (the plane's size is ceil(size / 2), so a box grown
  // past an odd frame edge still maps inside every plane; fillRect clips what falls outside).
  const int a = align_;
  const int x0 = box.x / a * a, y0 = box.y / a * a;
  const int x1 = (box.x + box.width + a - 1) / a * a, y1 = (box.y + box.height + a - 1) / a * a;
  // A line of one chroma sample gets blended with its neighbours by any chroma upsampling downstream; two
  // samples keep the middle pixels exactly the colour asked for. Hairlines (thickness 1) stay one sample.
  int t = std::max(1, thickness);
  if (a > 1) t = thickness <= 1 ? a : std::max(2 * a, (thickness + a - 1) / a * a);
  if (x1 - x0 <= 0 || y1 - y0 <= 0) return;
  fillRect(cv::Rect(x0, y0, x1 - x0, std::min(t, y1 - y0)), colour);                    // top
  fillRect(cv::Rect(x0, std::max(y0, y1 - t), x1 - x0, std::min(t, y1 - y0)), colour);  // bottom
  fillRect(cv::Rect(x0, y0, std::min(t, x1 - x0), y1 - y0), colour);                    // left
  fillRect(cv::Rect(std::max(x0, x1 - t), y0, std::min(t, x1 - x0), y1 - y0), colour);  // right
}

void FrameCanvas::polyline(const std::vector<cv::Point> &points, const Rgb &colour, int thickness) {
  if (points.size() < 2) return;
  std::vector<cv::Point> scaled(points.size());
  for (const Plane &plane : planes_) {
    for (size_t i = 0; i < points.size(); ++i)
      scaled[i] = cv::Point(points[i].x / plane.xDiv, points[i].y / plane.yDiv);
    const int planeThickness = std::max(1, thickness / std::max(plane.xDiv, plane.yDiv));
    cv::polylines(plane.mat, scaled, false, colourFor(plane, colour), planeThickness, cv::LINE_8);
  }
}

void FrameCanvas::label(const std::string &text, cv::Point origin) {
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  const double scale = 0.4;
  int baseline = 0;
  const cv::Size extent = cv::getTextSize(text, font, scale, 1, &baseline);
  // Keep the text inside the frame: above the given point, or below the top edge when there is no room.
  origin.x = std::clamp(origin.x, 0, std::max(0, size_.width - extent.width));
  origin.y = std::clamp(origin.y, extent.height + 1, std::max(extent.height + 1, size_.height - baseline));

  cv::Scalar dark, light;
  if (textOnYuv_) {
    // Luma of black and white; on YUY2's (Y, chroma) pairs the chroma byte becomes neutral grey.
    dark = cv::Scalar(16, 128);
    light = cv::Scalar(235, 128);
  } else {
    dark = colourFor(planes_[0], Rgb{0, 0, 0});
    light = colourFor(planes_[0], Rgb{255, 255, 255});
  }
  cv::putText(textTarget_, text, origin, font, scale, dark, 3, cv::LINE_8);
  cv::putText(textTarget_, text, origin, font, scale, light, 1, cv::LINE_8);
}

void FrameCanvas::tintMask(const cv::Mat &mask, int step, const Rgb &colour) {
  if (mask.empty()) return;
  cv::Mat planeMask, tinted;
  for (const Plane &plane : planes_) {
    // The mask's grid onto this plane's samples (nearest neighbour keeps it binary).
    const double fx = static_cast<double>(step) / plane.xDiv, fy = static_cast<double>(step) / plane.yDiv;
    const cv::Size target(std::min(plane.mat.cols, cvRound(mask.cols * fx)),
                          std::min(plane.mat.rows, cvRound(mask.rows * fy)));
    if (target.empty()) continue;
    cv::resize(mask, planeMask, target, 0, 0, cv::INTER_NEAREST);
    cv::Mat region = plane.mat(cv::Rect(cv::Point(), target));
    const cv::Mat solid(target, region.type(), colourFor(plane, colour));
    cv::addWeighted(region, 0.5, solid, 0.5, 0.0, tinted);
    tinted.copyTo(region, planeMask);
  }
}

}  // namespace colortrack_gst
