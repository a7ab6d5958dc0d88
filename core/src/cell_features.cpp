#include "colortrack/cell_features.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {
constexpr float kClip = 0.2f;  // the usual HOG clipping of normalised values
constexpr float kEps = 1e-4f;
}  // namespace

void cellFeatures(const cv::Mat &gray, int cell, std::vector<cv::Mat> &channels) {
  CV_Assert(gray.type() == CV_32FC1 && cell >= 1);
  const int cw = gray.cols / cell, ch = gray.rows / cell;
  // Scratch kept per thread: the scale filter calls this for a few dozen small patches per frame, where
  // allocating these each time cost more than the arithmetic.
  thread_local cv::Mat hist, energy, intensity;
  // Raw orientation histograms, one row of kOrientations per cell. Gradients by [-1 0 1] differences (the
  // border repeated), contrast-insensitive orientation (a and a + 180 degrees share a bin), each pixel's
  // magnitude shared linearly between the two nearest bins.
  hist.create(ch * cw, kOrientations, CV_32F);
  hist.setTo(0);
  const float binsPerDegree = kOrientations / 180.0f;
  for (int y = 0; y < ch * cell; ++y) {
    const float *row = gray.ptr<float>(y);
    const float *up = gray.ptr<float>(std::max(0, y - 1));
    const float *down = gray.ptr<float>(std::min(gray.rows - 1, y + 1));
    float *cellRow = hist.ptr<float>((y / cell) * cw);
    const int last = gray.cols - 1;
    for (int x = 0; x < cw * cell; ++x) {
      const float dx = row[std::min(last, x + 1)] - row[std::max(0, x - 1)];
      const float dy = down[x] - up[x];
      const float magnitude = std::sqrt(dx * dx + dy * dy);
      if (magnitude <= 0) continue;
      float angle = cv::fastAtan2(dy, dx);  // degrees in [0, 360), error ~0.3 degrees
      if (angle >= 180) angle -= 180;
      const float position = angle * binsPerDegree - 0.5f;
      const int lower = position < 0 ? -1 : static_cast<int>(position);
      const float upperShare = position - lower;
      float *bins = cellRow + (x / cell) * kOrientations;
      bins[lower < 0 ? kOrientations - 1 : lower] += magnitude * (1 - upperShare);
      bins[lower + 1 >= kOrientations ? 0 : lower + 1] += magnitude * upperShare;
    }
  }
  // Energy per cell, then the inverse norm of each 2x2 block (cells outside repeat the border).
  energy.create(ch, cw, CV_32F);
  for (int i = 0; i < ch * cw; ++i) {
    const float *bins = hist.ptr<float>(i);
    float e = 0;
    for (int o = 0; o < kOrientations; ++o) e += bins[o] * bins[o];
    energy.at<float>(i / cw, i % cw) = e;
  }
  auto energyAt = [&](int y, int x) {
    return energy.at<float>(std::clamp(y, 0, ch - 1), std::clamp(x, 0, cw - 1));
  };
  channels.resize(kCellChannels);
  for (auto &c : channels) c.create(ch, cw, CV_32F);
  cv::resize(gray(cv::Rect(0, 0, cw * cell, ch * cell)), intensity, cv::Size(cw, ch), 0, 0, cv::INTER_AREA);
  for (int y = 0; y < ch; ++y)
    for (int x = 0; x < cw; ++x) {
      float inverseNorm[4];
      int k = 0;
      for (int by = -1; by <= 0; ++by)
        for (int bx = -1; bx <= 0; ++bx)
          inverseNorm[k++] =
              1.0f / std::sqrt(energyAt(y + by, x + bx) + energyAt(y + by, x + bx + 1) +
                               energyAt(y + by + 1, x + bx) + energyAt(y + by + 1, x + bx + 1) + kEps);
      const float *bins = hist.ptr<float>(y * cw + x);
      float texture[4] = {0, 0, 0, 0};
      for (int o = 0; o < kOrientations; ++o) {
        float sum = 0;
        for (int n = 0; n < 4; ++n) {
          const float v = std::min(bins[o] * inverseNorm[n], kClip);
          sum += v;
          texture[n] += v;
        }
        channels[o].at<float>(y, x) = 0.5f * sum;
      }
      for (int n = 0; n < 4; ++n) channels[kOrientations + n].at<float>(y, x) = 0.2357f * texture[n];
      channels[kOrientations + 4].at<float>(y, x) = intensity.at<float>(y, x) - 0.5f;
    }
}

}  // namespace colortrack
