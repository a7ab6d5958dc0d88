// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/cell_features.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/core/hal/intrin.hpp>
#include <opencv2/core/utility.hpp>
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
// magnitude shared linearly between the two nearest bins. `angle` in degrees, [0, 360); bin o is
// bins[o * stride]. Each share is computed in float whatever the bins hold (float cells, or the double
// running sums of the integral images).
template <typename Bin>
inline void vote(float magnitude, float angle, Bin *bins, int stride = 1) {
  if (magnitude <= 0) return;
  if (angle >= 180) angle -= 180;
  const float position = angle * kBinsPerDegree - 0.5f;
  const int lower = position < 0 ? -1 : static_cast<int>(position);
  const float upperShare = position - lower;
  bins[(lower < 0 ? kOrientations - 1 : lower) * stride] += magnitude * (1 - upperShare);
  bins[(lower + 1 >= kOrientations ? 0 : lower + 1) * stride] += magnitude * upperShare;
}

// [-1 0 1] gradients (the border repeated) as magnitude and angle in degrees, the whole patch at once:
// cartToPolar is vectorised (angle error ~0.3 degrees), where a per-pixel fastAtan2 call cost a fifth of the
// feature time.
// Each caller keeps its own buffers (one set per call site and thread): shared, they would be resized between
// the window's size and the scale region's every frame.
struct Gradients {
  cv::Mat dx, dy, magnitude, angle;
};

void orientedGradients(const cv::Mat &gray, Gradients &g) {
  cv::Sobel(gray, g.dx, CV_32F, 1, 0, 1, 1, 0, cv::BORDER_REPLICATE);
  cv::Sobel(gray, g.dy, CV_32F, 0, 1, 1, 1, 0, cv::BORDER_REPLICATE);
  cv::cartToPolar(g.dx, g.dy, g.magnitude, g.angle, true);
}

// From raw orientation histograms (planar: row o holds orientation o of every cell, cells in row order) and
// mean intensities (ch x cw) to the kCellChannels feature maps: each histogram normalised by the four 2x2
// cell blocks around its cell (cells outside repeat the border) and clipped, as in Dalal-Triggs /
// Felzenszwalb. Every loop runs along a row of cells, so it vectorises; each value is summed in the same
// order as one cell at a time would (orientations in turn, the four blocks in turn), so the features are the
// same to the bit.
// The four inverse block norms of each cell of a ch x cw grid, as rows 0-3 in cell order, so that the loops
// of normaliseCells run over all cells at once. Block (by, bx) covers cells (by - 1 .. by, bx - 1 .. bx),
// clamped to the grid; each block's norm is shared by its four cells.
const cv::Mat &cellBlockNorms(const cv::Mat &hist, int ch, int cw) {
  thread_local cv::Mat energy, inverseBlockNorm;
  energy.create(ch, cw, CV_32F);
  float *__restrict e = energy.ptr<float>();
  std::fill(e, e + ch * cw, 0.0f);
  for (int o = 0; o < kOrientations; ++o) {
    const float *__restrict bins = hist.ptr<float>(o);
    for (int i = 0; i < ch * cw; ++i) e[i] += bins[i] * bins[i];
  }
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
  const int cells = ch * cw;
  thread_local cv::Mat cellNorms;
  cellNorms.create(4, cells, CV_32F);
  for (int y = 0; y < ch; ++y) {
    const float *above = inverseBlockNorm.ptr<float>(y), *below = inverseBlockNorm.ptr<float>(y + 1);
    for (int x = 0; x < cw; ++x) {
      const int i = y * cw + x;
      cellNorms.at<float>(0, i) = above[x];
      cellNorms.at<float>(1, i) = above[x + 1];
      cellNorms.at<float>(2, i) = below[x];
      cellNorms.at<float>(3, i) = below[x + 1];
    }
  }
  return cellNorms;
}

void normaliseCells(const cv::Mat &hist, const cv::Mat &intensity, std::vector<cv::Mat> &channels) {
  const int ch = intensity.rows, cw = intensity.cols, cells = ch * cw;
  CV_Assert(hist.rows == kOrientations && hist.cols == cells && hist.isContinuous() &&
            intensity.isContinuous());
  const cv::Mat &cellNorms = cellBlockNorms(hist, ch, cw);
  const float *__restrict n0 = cellNorms.ptr<float>(0), *__restrict n1 = cellNorms.ptr<float>(1);
  const float *__restrict n2 = cellNorms.ptr<float>(2), *__restrict n3 = cellNorms.ptr<float>(3);
  channels.resize(kCellChannels);
  for (auto &c : channels) c.create(ch, cw, CV_32F);
  // The texture channels gather their sums in place, then are scaled.
  float *__restrict t0 = channels[kOrientations].ptr<float>();
  float *__restrict t1 = channels[kOrientations + 1].ptr<float>();
  float *__restrict t2 = channels[kOrientations + 2].ptr<float>();
  float *__restrict t3 = channels[kOrientations + 3].ptr<float>();
  std::fill(t0, t0 + cells, 0.0f);
  std::fill(t1, t1 + cells, 0.0f);
  std::fill(t2, t2 + cells, 0.0f);
  std::fill(t3, t3 + cells, 0.0f);
  for (int o = 0; o < kOrientations; ++o) {
    const float *__restrict bins = hist.ptr<float>(o);
    float *__restrict out = channels[o].ptr<float>();
    int i = 0;
#if CV_SIMD128
    // v_min(v, clip) is std::min(v, clip) for every value that is not NaN (these are products of finite
    // values): the same features.
    using namespace cv;
    const v_float32x4 clip = v_setall_f32(kClip), half = v_setall_f32(0.5f);
    for (; i + 4 <= cells; i += 4) {
      const v_float32x4 b = v_load(bins + i);
      const v_float32x4 v0 = v_min(b * v_load(n0 + i), clip), v1 = v_min(b * v_load(n1 + i), clip);
      const v_float32x4 v2 = v_min(b * v_load(n2 + i), clip), v3 = v_min(b * v_load(n3 + i), clip);
      v_store(t0 + i, v_load(t0 + i) + v0);
      v_store(t1 + i, v_load(t1 + i) + v1);
      v_store(t2 + i, v_load(t2 + i) + v2);
      v_store(t3 + i, v_load(t3 + i) + v3);
      v_store(out + i, half * (((v_setzero_f32() + v0) + v1) + v2 + v3));
    }
#endif
    for (; i < cells; ++i) {
      const float b = bins[i];
      const float v0 = std::min(b * n0[i], kClip), v1 = std::min(b * n1[i], kClip);
      const float v2 = std::min(b * n2[i], kClip), v3 = std::min(b * n3[i], kClip);
      float sum = 0;
      sum += v0;
      sum += v1;
      sum += v2;
      sum += v3;
      t0[i] += v0;
      t1[i] += v1;
      t2[i] += v2;
      t3[i] += v3;
      out[i] = 0.5f * sum;
    }
  }
  for (float *t : {t0, t1, t2, t3})
    for (int i = 0; i < cells; ++i) t[i] = kTextureScale * t[i];
  const float *__restrict mean = intensity.ptr<float>();
  float *__restrict m = channels[kOrientations + 4].ptr<float>();
  for (int i = 0; i < cells; ++i) m[i] = mean[i] - 0.5f;
}

}  // namespace

void cellFeatures(const cv::Mat &gray, int cell, std::vector<cv::Mat> &channels) {
  CV_Assert(gray.type() == CV_32FC1 && cell >= 1);
  const int cw = gray.cols / cell, ch = gray.rows / cell;
  thread_local cv::Mat hist, intensity;
  thread_local Gradients gradients;
  orientedGradients(gray, gradients);
  const cv::Mat &magnitude = gradients.magnitude, &angle = gradients.angle;
  hist.create(kOrientations, ch * cw, CV_32F);
  hist.setTo(0);
  const int plane = ch * cw;
  for (int y = 0; y < ch * cell; ++y) {
    float *cellRow = hist.ptr<float>() + (y / cell) * cw;
    const float *m = magnitude.ptr<float>(y), *a = angle.ptr<float>(y);
    for (int x = 0; x < cw * cell; ++x) vote(m[x], a[x], cellRow + x / cell, plane);
  }
  cv::resize(gray(cv::Rect(0, 0, cw * cell, ch * cell)), intensity, cv::Size(cw, ch), 0, 0, cv::INTER_AREA);
  normaliseCells(hist, intensity, channels);
}

void CellFeatureIntegral::build(const cv::Mat &gray) {
  CV_Assert(gray.type() == CV_32FC1 && !gray.empty());
  const int stride = kPlanes;
  const size_t rowLength = static_cast<size_t>(gray.cols + 1) * stride;
  sums_.resize((gray.rows + 1) * rowLength);
  std::fill(sums_.begin(), sums_.begin() + rowLength, 0.0);
  size_ = gray.size();
  // Each row's running sums first, two halves of the rows on OpenCV's thread pool (the gradients of a half
  // read the neighbouring rows of the whole image, as one pass would): the pixel's two orientation votes go
  // straight into the row's running sums (a vote of zero would not change them).
  cv::parallel_for_(
      cv::Range(0, gray.rows),
      [&](const cv::Range &rows) {
        thread_local Gradients gradients;
        orientedGradients(gray.rowRange(rows.start, rows.end), gradients);
        const cv::Mat &magnitude = gradients.magnitude, &angle = gradients.angle;
        for (int y = rows.start; y < rows.end; ++y) {
          double *here = &sums_[(y + 1) * rowLength];
          std::fill(here, here + stride, 0.0);
          const float *m = magnitude.ptr<float>(y - rows.start), *a = angle.ptr<float>(y - rows.start),
                      *g = gray.ptr<float>(y);
          double rowSum[kPlanes] = {};
          for (int x = 0; x < gray.cols; ++x) {
            vote(m[x], a[x], rowSum);
            rowSum[kOrientations] += g[x];
            std::copy(rowSum, rowSum + kPlanes, here + (x + 1) * stride);
          }
        }
      },
      2);
  // Then each plane's integral is the row above plus the running sum.
  for (int y = 1; y < gray.rows; ++y) {
    const double *__restrict above = &sums_[y * rowLength];
    double *__restrict here = &sums_[(y + 1) * rowLength];
    for (size_t i = stride; i < rowLength; ++i) here[i] += above[i];
  }
}

void CellFeatureIntegral::features(const cv::Rect2d &rect, cv::Size cells,
                                   std::vector<cv::Mat> &channels) const {
  CV_Assert(!sums_.empty() && cells.width >= 1 && cells.height >= 1);
  thread_local cv::Mat hist, intensity;
  hist.create(kOrientations, cells.area(), CV_32F);
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
      float *bins = hist.ptr<float>() + j * cells.width + i;
      for (int o = 0; o < kOrientations; ++o)
        bins[o * cells.area()] = static_cast<float>(d[o] - b[o] - c[o] + a[o]);
      const double area = std::max(1, (xs[i + 1] - xs[i]) * (ys[j + 1] - ys[j]));
      const int k = kOrientations;
      intensity.at<float>(j, i) = static_cast<float>((d[k] - b[k] - c[k] + a[k]) / area);
    }
  normaliseCells(hist, intensity, channels);
}

}  // namespace colortrack
