// SPDX-License-Identifier: LGPL-2.1-or-later
// Where the tracker reads pixels from: lets the GStreamer layer convert only the regions the tracker
// asks for (a search window while tracking) instead of whole frames.
#pragma once

#include <array>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/scratch_image.hpp"

namespace colortrack {

// Size of a sample of `rect` taking every `step`-th pixel, and the part of `rect` it covers exactly (so that
// a nearest-neighbour resize of that part to the sample size reads pixel i * step, as the tracker assumes).
cv::Size sampledSize(const cv::Rect &rect, int step);
cv::Rect sampledCover(const cv::Rect &rect, int step);

// What the three bytes sampled from a frame mean.
enum class PixelEncoding {
  Rgb,  // channels R, G, B
  Yuv,  // channels Y, U, V as the frame's YuvColorimetry says
};

// One colour channel of a frame as bytes in memory: the sample of frame pixel (x, y) is
// plane.ptr(y / ySub)[(x / xSub) * sampleBytes + byteOffset]. Describes packed RGB (any byte order),
// planar and semi-planar 4:2:0 and packed 4:2:2 alike, so a frame is segmented without converting it.
struct ChannelSampler {
  cv::Mat plane;  // CV_8UC1 view of the plane's bytes (width = bytes per row in use)
  int byteOffset = 0;
  int sampleBytes = 1;
  int xSub = 1, ySub = 1;
};

// A frame's bytes as three channels in the order the encoding names them (threshold mode segments them
// where they lie).
struct SampledFrame {
  std::array<ChannelSampler, 3> channels;
  PixelEncoding encoding = PixelEncoding::Rgb;
  YuvColorimetry colorimetry;  // with PixelEncoding::Yuv
  cv::Size size;               // frame size in pixels
};

// A BGR image (CV_8UC3) as a SampledFrame (a view: `bgr` must outlive it).
SampledFrame sampledBgr(const cv::Mat &bgr);

class ImageSource {
 public:
  virtual ~ImageSource() = default;
  virtual cv::Size size() const = 0;
  // Writes the pixels of `rect` (inside the frame) as CV_8UC3 BGR into `out` (reallocated if needed).
  virtual void bgr(const cv::Rect &rect, cv::Mat &out) const = 0;
  // Every `step`-th pixel of `rect` in both directions (nearest neighbour), as BGR: size rect / step. Sources
  // that can read a sample without converting the whole rectangle override this.
  virtual void sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const;
  // The whole frame channel by channel. Sources that can describe their bytes in place override this; the
  // default converts the frame to BGR into `scratch` (which the result then views).
  virtual SampledFrame channels(cv::Mat &scratch) const;
};

// An ImageSource over a BGR cv::Mat (tests, benchmarks, template files).
class MatImageSource : public ImageSource {
 public:
  explicit MatImageSource(const cv::Mat &bgr) : bgr_(bgr) {}
  cv::Size size() const override { return bgr_.size(); }
  void bgr(const cv::Rect &rect, cv::Mat &out) const override { bgr_(rect).copyTo(out); }
  void sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const override;
  SampledFrame channels(cv::Mat &scratch) const override;

 private:
  cv::Mat bgr_;
};

// Reads a region of a frame once, as a sample, and cuts patches out of it resampled to a fixed size; where a
// patch reaches outside the frame the frame's border is repeated. Lets a tracker take several patches (a
// search window, a range of scales) for the price of one read.
class PatchSampler {
 public:
  // Reads `region` (frame coordinates; may reach outside the frame) taking every `step`-th pixel.
  void load(const ImageSource &frame, const cv::Rect2d &region, int step);
  // Turns what was read into grey levels (CV_32FC1 in [0,1]), for pixels().
  void toGray();
  // `rect` moved and sized to whole read pixels, resampled to `size` (area-averaging when shrinking,
  // bilinear otherwise), CV_8UC3 BGR. Snapping the position to the read grid makes this several times
  // cheaper than a sub-pixel warp; callers measure positions against the returned frame rectangle, which the
  // patch actually covers, so no precision is lost.
  cv::Rect2d extract(const cv::Rect2d &rect, cv::Size size, cv::Mat &out) const;

  // What was read (BGR, or grey after toGray()), and a frame rectangle in its pixel coordinates.
  const cv::Mat &pixels() const { return pixels_; }
  cv::Rect2d toSampled(const cv::Rect2d &rect) const;

  // The sampling step that keeps at least one read pixel per output pixel for a patch of `rect` at `size`.
  static int stepFor(const cv::Size2d &rect, cv::Size size);

 private:
  cv::Mat pixels_;  // a view of one of the buffers below
  ScratchImage read_, padded_, grayBytes_, gray_;
  cv::Point origin_;  // frame coordinates of pixels_(0, 0)
  int step_ = 1;
};

}  // namespace colortrack
