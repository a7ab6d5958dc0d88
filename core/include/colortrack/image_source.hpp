// Where the tracker reads pixels from: lets the GStreamer layer convert only the regions the tracker
// asks for (a search window while tracking) instead of whole frames.
#pragma once

#include <opencv2/core.hpp>

namespace colortrack {

// Size of a sample of `rect` taking every `step`-th pixel, and the part of `rect` it covers exactly (so that
// a nearest-neighbour resize of that part to the sample size reads pixel i * step, as the tracker assumes).
cv::Size sampledSize(const cv::Rect &rect, int step);
cv::Rect sampledCover(const cv::Rect &rect, int step);

class ImageSource {
 public:
  virtual ~ImageSource() = default;
  virtual cv::Size size() const = 0;
  // Writes the pixels of `rect` (inside the frame) as CV_8UC3 BGR into `out` (reallocated if needed).
  virtual void bgr(const cv::Rect &rect, cv::Mat &out) const = 0;
  // Every `step`-th pixel of `rect` in both directions (nearest neighbour), as BGR: size rect / step. Sources
  // that can read a sample without converting the whole rectangle override this.
  virtual void sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const;
};

// An ImageSource over a BGR cv::Mat (tests, benchmarks, template files).
class MatImageSource : public ImageSource {
 public:
  explicit MatImageSource(const cv::Mat &bgr) : bgr_(bgr) {}
  cv::Size size() const override { return bgr_.size(); }
  void bgr(const cv::Rect &rect, cv::Mat &out) const override { bgr_(rect).copyTo(out); }
  void sampledBgr(const cv::Rect &rect, int step, cv::Mat &out) const override;

 private:
  cv::Mat bgr_;
};

}  // namespace colortrack
