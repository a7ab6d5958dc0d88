// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/likelihood.hpp"

#include <algorithm>

namespace colortrack {

namespace {

std::array<int, 3> coarsened(const BinLayout &layout) {
  std::array<int, 3> bins = layout.bins;
  auto product = [&] { return static_cast<size_t>(bins[0]) * bins[1] * bins[2]; };
  while (product() > ColorLikelihood::kMaxJointBins) {
    int &largest = *std::max_element(bins.begin(), bins.end());
    largest = (largest + 1) / 2;
  }
  return bins;
}

}  // namespace

ColorLikelihood::ColorLikelihood(const BinLayout &layout)
    : layout_(layout),
      jointBins_(coarsened(layout)),
      objectShare_(static_cast<size_t>(jointBins_[0]) * jointBins_[1] * jointBins_[2], 0.f),
      table_(objectShare_.size(), 0.5f),
      strict_(table_.size(), 0.f) {
  for (int c = 0; c < 3; ++c)
    for (int b = 0; b < 256; ++b)
      reduce_[c][b] =
          static_cast<std::uint8_t>(std::min(b, layout.bins[c] - 1) * jointBins_[c] / layout.bins[c]);
}

void ColorLikelihood::learn(const BinImage &bins, const cv::Rect &object, const cv::Rect &surroundings,
                            double rate) {
  const cv::Rect limits = bins.frameRect();
  const cv::Rect inner = object & limits, outer = (surroundings | object) & limits;
  if (inner.empty()) return;
  objectCounts_.assign(table_.size(), 0.f);
  ringCounts_.assign(table_.size(), 0.f);
  std::vector<float> &objectCounts = objectCounts_, &ringCounts = ringCounts_;
  // Each row in runs: ring, then object, then ring (rows outside the object are all ring).
  const auto count = [this](const cv::Vec3b *row, int from, int to, float *counts) {
    for (int x = from; x < to; ++x) counts[jointBin(row[x])] += 1.f;
  };
  for (int y = outer.y; y < outer.br().y; ++y) {
    const cv::Vec3b *row = bins.bins.ptr<cv::Vec3b>(y - bins.origin.y) - bins.origin.x;
    if (y >= inner.y && y < inner.br().y) {
      count(row, outer.x, inner.x, ringCounts.data());
      count(row, inner.x, inner.br().x, objectCounts.data());
      count(row, inner.br().x, outer.br().x, ringCounts.data());
    } else {
      count(row, outer.x, outer.br().x, ringCounts.data());
    }
  }
  // P(O|c) = H_O(c) / (H_O(c) + H_S(c)) on raw counts: the ring's larger area is the prior that a colour
  // seen in both belongs to the background more often than not.
  const float keep = static_cast<float>(learned_ ? 1.0 - rate : 0.0), add = 1.f - keep;
  const float objectArea = static_cast<float>(inner.area());
  for (size_t j = 0; j < table_.size(); ++j) {
    objectShare_[j] = keep * objectShare_[j] + add * objectCounts[j] / objectArea;
    const float total = objectCounts[j] + ringCounts[j];
    const float p = total > 0 ? objectCounts[j] / total : 0.5f;
    table_[j] = keep * table_[j] + add * p;
    strict_[j] = keep * strict_[j] + add * (total > 0 ? p : 0.f);
  }
  learned_ = true;
}

void ColorLikelihood::map(const BinImage &bins, cv::Mat &probability) const {
  mapWith(table_, bins, probability);
}

void ColorLikelihood::mapWith(const std::vector<float> &table, const BinImage &bins,
                              cv::Mat &probability) const {
  probability.create(bins.bins.size(), CV_32FC1);
  for (int y = 0; y < bins.bins.rows; ++y) {
    const cv::Vec3b *in = bins.bins.ptr<cv::Vec3b>(y);
    float *out = probability.ptr<float>(y);
    for (int x = 0; x < bins.bins.cols; ++x) out[x] = table[jointBin(in[x])];
  }
}

void ColorLikelihood::countImageColours(const BinImage &bins, ImageColours &image) const {
  image.counts.assign(table_.size(), 0.f);
  for (int y = 0; y < bins.bins.rows; ++y) {
    const cv::Vec3b *in = bins.bins.ptr<cv::Vec3b>(y);
    for (int x = 0; x < bins.bins.cols; ++x) image.counts[jointBin(in[x])] += 1.f;
  }
}

void ColorLikelihood::mapAgainstImage(const BinImage &bins, double objectArea, ImageColours &image,
                                      cv::Mat &probability) const {
  CV_Assert(image.counts.size() == table_.size());
  // The same ratio as learn()'s, with the image for the ring: the image's larger area is again the prior.
  image.table.resize(table_.size());
  for (size_t j = 0; j < image.table.size(); ++j) {
    const float object = static_cast<float>(objectArea) * objectShare_[j];
    image.table[j] = object > 0 ? object / (object + image.counts[j]) : 0.f;
  }
  mapWith(image.table, bins, probability);
}

double ColorLikelihood::confidence(const BinImage &bins, const cv::Rect &rect) const {
  const cv::Rect r = rect & bins.frameRect();
  if (r.empty()) return 0;
  double sum = 0;
  for (int y = r.y; y < r.br().y; ++y) {
    const cv::Vec3b *row = bins.bins.ptr<cv::Vec3b>(y - bins.origin.y) - bins.origin.x;
    for (int x = r.x; x < r.br().x; ++x) sum += strict_[jointBin(row[x])];
  }
  return sum / r.area();
}

double boxSum(const cv::Mat &integral, const cv::Rect &r) {
  return integral.at<double>(r.y, r.x) + integral.at<double>(r.br().y, r.br().x) -
         integral.at<double>(r.y, r.br().x) - integral.at<double>(r.br().y, r.x);
}

}  // namespace colortrack
