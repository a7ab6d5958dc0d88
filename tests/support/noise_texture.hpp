// SPDX-License-Identifier: LGPL-2.1-or-later
// Smooth random texture for detector tests: uniform noise blurred and stretched to the full grey range.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace colortrack::test {

// CV_8UC3 noise of `size` from `seed`, blurred by a Gaussian of `sigma` px: gradients in every direction,
// finer for a smaller sigma.
inline cv::Mat noiseTexture(cv::Size size, int seed, double sigma) {
  cv::RNG rng(seed);
  cv::Mat noise(size, CV_8UC3);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), sigma);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  return noise;
}

}  // namespace colortrack::test
