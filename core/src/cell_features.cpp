#include "colortrack/cell_features.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

constexpr float kClip = 0.2f;  // the usual HOG clipping of normalised values
constexpr float kEps = 1e-4f;
constexpr float kBinsPerDegree = kOrientations / 180.0f;
// The texture channels sum kOrientations clipped values; scaled by 1/sqrt(2 * kOrientations) (FHOG's choice)
// so they weigh about as much as one orientation channel.
const float kTextureScale = 1.0f / std::sqrt(2.0f * kOrientations);

// One pixel's gradient vote: contrast-insensitive orientation (a and a + 180 degrees share a bin), the
// magnitude shared linearly between the two nearest bins. `angle` in degrees, [0, 360). Each share is
// computed in float whatever the bins hold (float cells, or the double running sums of the integral images).
template <typename Bin>
inline void vote(float magnitude, float angle, Bin *bins) {
  if (magnitude <= 0) return;
  if (angle >= 180) angle -= 180;
  const float position = angle * kBinsPerDegree - 0.5f;
  const int lower = position < 0 ? -1 : static_cast<int>(position);
  const float upperShare = position - lower;
  bins[lower < 0 ? kOrientations - 1 : lower] += magnitude * (1 - upperShare);
  bins[lower + 1 >= kOrientations ? 0 : lower + 1] += magnitude * upperShare;
}

// [-1 0 1] gradients (the border repeated) as magnitude and angle in degrees, the whole patch at once:
// cartToPolar is vectorised (angle error ~0.3 degrees), where a per-pixel fastAtan2 call cost a fifth of the
// feature time.
void orientedGradients(const cv::Mat &gray, cv::Mat &magnitude, cv::Mat &angle) {
  thread_local cv::Mat dx, dy;
  cv::Sobel(gray, dx, CV_32F, 1, 0, 1, 1, 0, cv::BORDER_REPLICATE);
  cv::Sobel(gray, dy, CV_32F, 0, 1, 1, 1, 0, cv::BORDER_REPLICATE);
  cv::cartToPolar(dx, dy, magnitude, angle, true);
}

// From raw orientation histograms (one row of kOrientations per cell, cells in row order) and mean
// intensities (ch x cw) to the kCellChannels feature maps: each histogram normalised by the four 2x2 cell
// blocks around its cell (cells outside repeat the border) and clipped, as in Dalal-Triggs / Felzenszwalb.
void normaliseCells(const cv::Mat &hist, const cv::Mat &intensity, std::vector<cv::Mat> &channels) {
  const int ch = intensity.rows, cw = intensity.cols;
  thread_local cv::Mat energy, inverseBlockNorm;
  energy.create(ch, cw, CV_32F);
  for (int y = 0; y < ch; ++y) {
    float *e = energy.ptr<float>(y);
    for (int x = 0; x < cw; ++x) {
      const float *bins = hist.ptr<float>(y * cw + x);
      float sum = 0;
      for (int o = 0; o < kOrientations; ++o) sum += bins[o] * bins[o];
      e[x] = sum;
    }
  }
  // Block (by, bx) covers cells (by - 1 .. by, bx - 1 .. bx), clamped to the grid; each block's norm is
  // shared by its four cells.
  inverseBlockNorm.create(ch + 1, cw + 1, CV_32F);
  for (int by = 0; by <= ch; ++by) {
    const float *above = energy.ptr<float>(std::max(by - 1, 0)),
                *below = energy.ptr<float>(std::min(by, ch - 1));
    float *n = inverseBlockNorm.ptr<float>(by);
    for (int bx = 0; bx <= cw; ++bx) {
      const int left = std::max(bx - 1, 0), right = std::min(bx, cw - 1);
      n[bx] = 1.0f / std::sqrt(above[left] + above[right] + below[left] + below[right] + kEps);
    }
  }
  channels.resize(kCellChannels);
  for (auto &c : channels) c.create(ch, cw, CV_32F);
  float *out[kCellChannels];
  for (int y = 0; y < ch; ++y) {
    for (int c = 0; c < kCellChannels; ++c) out[c] = channels[c].ptr<float>(y);
    const float *normsAbove = inverseBlockNorm.ptr<float>(y),
                *normsBelow = inverseBlockNorm.ptr<float>(y + 1);
    const float *mean = intensity.ptr<float>(y);
    for (int x = 0; x < cw; ++x) {
      const float inverseNorm[4] = {normsAbove[x], normsAbove[x + 1], normsBelow[x], normsBelow[x + 1]};
      const float *bins = hist.ptr<float>(y * cw + x);
      float texture[4] = {0, 0, 0, 0};
      for (int o = 0; o < kOrientations; ++o) {
        float sum = 0;
        for (int n = 0; n < 4; ++n) {
          const float v = std::min(bins[o] * inverseNorm[n], kClip);
          sum += v;
          texture[n] += v;
        }
        out[o][x] = 0.5f * sum;
      }
      for (int n = 0; n < 4; ++n) out[kOrientations + n][x] = kTextureScale * texture[n];
      out[kOrientations + 4][x] = mean[x] - 0.5f;
    }
  }
}

}  // namespace

void cellFeatures(const cv::Mat &gray, int cell, std::vector<cv::Mat> &channels) {
  CV_Assert(gray.type() == CV_32FC1 && cell >= 1);
  const int cw = gray.cols / cell, ch = gray.rows / cell;
  thread_local cv::Mat hist, intensity, magnitude, angle;
  orientedGradients(gray, magnitude, angle);
  hist.create(ch * cw, kOrientations, CV_32F);
  hist.setTo(0);
  for (int y = 0; y < ch * cell; ++y) {
    float *cellRow = hist.ptr<float>((y / cell) * cw);
    const float *m = magnitude.ptr<float>(y), *a = angle.ptr<float>(y);
    for (int x = 0; x < cw * cell; ++x) vote(m[x], a[x], cellRow + (x / cell) * kOrientations);
  }
  cv::resize(gray(cv::Rect(0, 0, cw * cell, ch * cell)), intensity, cv::Size(cw, ch), 0, 0, cv::INTER_AREA);
  normaliseCells(hist, intensity, channels);
}

void CellFeatureIntegral::build(const cv::Mat &gray) {
  CV_Assert(gray.type() == CV_32FC1 && !gray.empty());
  const int stride = kPlanes;
  sums_.assign(static_cast<size_t>(gray.rows + 1) * (gray.cols + 1) * stride, 0.0);
  size_ = gray.size();
  thread_local cv::Mat magnitude, angle;
  orientedGradients(gray, magnitude, angle);
  for (int y = 0; y < gray.rows; ++y) {
    const double *above = &sums_[static_cast<size_t>(y) * (gray.cols + 1) * stride];
    double *here = &sums_[static_cast<size_t>(y + 1) * (gray.cols + 1) * stride];
    const float *m = magnitude.ptr<float>(y), *a = angle.ptr<float>(y), *g = gray.ptr<float>(y);
    double rowSum[kPlanes] = {};
    for (int x = 0; x < gray.cols; ++x) {
      // The pixel's two orientation votes go straight into the row's running sums (a vote of zero would not
      // change them), then each plane's integral is the row above plus the running sum.
      vote(m[x], a[x], rowSum);
      rowSum[kOrientations] += g[x];
      const double *up = above + (x + 1) * stride;
      double *out = here + (x + 1) * stride;
      for (int c = 0; c < kPlanes; ++c) out[c] = up[c] + rowSum[c];
    }
  }
}

void CellFeatureIntegral::features(const cv::Rect2d &rect, cv::Size cells,
                                   std::vector<cv::Mat> &channels) const {
  CV_Assert(!sums_.empty() && cells.width >= 1 && cells.height >= 1);
  thread_local cv::Mat hist, intensity;
  hist.create(cells.area(), kOrientations, CV_32F);
  intensity.create(cells, CV_32F);
  const int stride = kPlanes, rowStride = (size_.width + 1) * stride;
  // Cell edges, rounded to whole pixels and kept inside the image with at least one pixel per cell.
  auto edges = [](double start, double length, int count, int limit) {
    std::vector<int> e(count + 1);
    for (int i = 0; i <= count; ++i)
      e[i] = std::clamp(static_cast<int>(std::lround(start + length * i / count)), 0, limit);
    for (int i = 1; i <= count; ++i)
      if (e[i] <= e[i - 1]) e[i] = std::min(limit, e[i - 1] + 1);
    for (int i = count - 1; i >= 0; --i)
      if (e[i] >= e[i + 1]) e[i] = std::max(0, e[i + 1] - 1);
    return e;
  };
  const std::vector<int> xs = edges(rect.x, rect.width, cells.width, size_.width);
  const std::vector<int> ys = edges(rect.y, rect.height, cells.height, size_.height);
  for (int j = 0; j < cells.height; ++j)
    for (int i = 0; i < cells.width; ++i) {
      const double *a = &sums_[ys[j] * rowStride + xs[i] * stride];
      const double *b = &sums_[ys[j] * rowStride + xs[i + 1] * stride];
      const double *c = &sums_[ys[j + 1] * rowStride + xs[i] * stride];
      const double *d = &sums_[ys[j + 1] * rowStride + xs[i + 1] * stride];
      float *bins = hist.ptr<float>(j * cells.width + i);
      for (int o = 0; o < kOrientations; ++o) bins[o] = static_cast<float>(d[o] - b[o] - c[o] + a[o]);
      const double area = std::max(1, (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]));
      const int k = kOrientations;
      intensity.at<float>(j, i) = static_cast<float>((d[k] - b[k] - c[k] + a[k]) / area);
    }
  normaliseCells(hist, intensity, channels);
}

}  // namespace colortrack
