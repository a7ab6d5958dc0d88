// SPDX-License-Identifier: LGPL-2.1-or-later
// Object-versus-surroundings colour likelihood: P(object | colour) from joint colour histograms of the
// target box and of the ring around it (the idea behind DAT, Possegger et al. 2015). Colours the
// surroundings share count less, which is what a plain template histogram cannot express.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"

namespace colortrack {

// A whole frame's colours against the object's (ColorLikelihood::mapAgainstImage), kept by the caller
// between frames so that the lost frames that use them allocate nothing.
struct ImageColours {
  std::vector<float> counts;  // joint bin -> pixels of that colour in the image
  std::vector<float> table;   // joint bin -> P(object | colour) against them
};

class ColorLikelihood {
 public:
  explicit ColorLikelihood(const BinLayout &layout = BinLayout());

  const BinLayout &layout() const { return layout_; }
  bool empty() const { return !learned_; }

  // Learns from a bin image covering `object` (frame coordinates) and its surroundings: the ring between
  // `object` and `surroundings` (clipped to the bin image). rate in (0,1]: 1 replaces the model, smaller
  // values blend the new estimate into the old one (slow adaptation to appearance change).
  void learn(const BinImage &bins, const cv::Rect &object, const cv::Rect &surroundings, double rate);

  // Per-pixel P(object | colour) of a bin image, CV_32FC1 in [0,1]. Colours never seen count 0.5.
  void map(const BinImage &bins, cv::Mat &probability) const;

  // The colour counts of a whole bin image (`image.counts`), for mapAgainstImage().
  void countImageColours(const BinImage &bins, ImageColours &image) const;
  // Per-pixel P(object | colour) of a bin image taken as the whole background: the object's learnt colour
  // distribution, counted as `objectArea` pixels, against the colour counts of `bins` themselves, counted
  // before by countImageColours(). For a search over a whole frame after a loss, where the colours that tell
  // the target apart are the ones the frame rarely shows, not the ones its last surroundings lacked.
  // CV_32FC1 in [0,1]; `image.table` holds the table used.
  void mapAgainstImage(const BinImage &bins, double objectArea, ImageColours &image,
                       cv::Mat &probability) const;

  // Mean P(object | colour) over `rect` with colours never seen counted as background (0): the confidence
  // that the box holds the object, which unseen colours (0.5 for the search) must not raise.
  double confidence(const BinImage &bins, const cv::Rect &rect) const;

  // P(object | colour) of one joint bin.
  float probability(int jointBin) const { return table_[jointBin]; }
  int jointBin(const cv::Vec3b &bins) const {
    return (reduce_[0][bins[0]] * jointBins_[1] + reduce_[1][bins[1]]) * jointBins_[2] + reduce_[2][bins[2]];
  }
  // Size of the joint table: the product of the bins, coarsened (largest channel halved first) to at most
  // kMaxJointBins, so that bins=256,256,256 stays a 64 K table instead of a 16 M one updated every frame.
  size_t tableSize() const { return table_.size(); }
  static constexpr size_t kMaxJointBins = 1 << 16;

 private:
  // Per-pixel table[joint bin] of a bin image.
  void mapWith(const std::vector<float> &table, const BinImage &bins, cv::Mat &probability) const;

  BinLayout layout_;
  std::array<int, 3> jointBins_{};                         // bins per channel in the joint table
  std::array<std::array<std::uint8_t, 256>, 3> reduce_{};  // channel bin -> joint-table bin
  std::vector<float> objectCounts_, ringCounts_;           // scratch for learn(), kept between frames
  std::vector<float> objectShare_;  // joint bin -> share of the object's pixels (running mean, as table_)
  std::vector<float> table_;        // joint bin -> P(object | colour), unseen colours 0.5
  std::vector<float> strict_;       // the same with unseen colours 0
  bool learned_ = false;
};

// Sum of `values` (CV_64F integral image from cv::integral) over `rect` in the integral's coordinates.
double boxSum(const cv::Mat &integral, const cv::Rect &rect);

}  // namespace colortrack
