// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/edges.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

constexpr double kMaxNormalisedSide = 96;  // largest side edges are compared at

// Canny thresholds on the contrast-stretched, lightly blurred patch (gradient magnitude, L2 norm of the 3x3
// Sobel). Stretching makes the patch span 0..255, so fixed thresholds behave the same in dim and bright
// light.
constexpr double kCannyLow = 90;
constexpr double kCannyHigh = 220;
// A patch whose gray range is below this is flat: stretching it would only amplify noise into "edges".
constexpr double kFlatRange = 12;
// The window's own border is where the crop cut the image, not an edge of the object.
constexpr int kIgnoredBorder = 2;

cv::Mat toGray(const cv::Mat &patch) {
  if (patch.channels() == 1) return patch;
  cv::Mat gray;
  cv::cvtColor(patch, gray, patch.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
  return gray;
}

}  // namespace

EdgeSignature edgeSignature(const cv::Mat &gray, int referenceCount) {
  EdgeSignature sig;
  if (gray.empty() || gray.cols <= 2 * kIgnoredBorder || gray.rows <= 2 * kIgnoredBorder) return sig;

  cv::Mat patch = toGray(gray);
  if (patch.depth() != CV_8U) patch.convertTo(patch, CV_8U);

  double minVal = 0, maxVal = 0;
  cv::minMaxLoc(patch, &minVal, &maxVal);
  cv::Mat stretched;
  if (maxVal - minVal >= kFlatRange)
    cv::normalize(patch, stretched, 0, 255, cv::NORM_MINMAX);
  else
    stretched = patch;

  cv::Mat smoothed, edges;
  cv::GaussianBlur(stretched, smoothed, cv::Size(3, 3), 0.8);
  cv::Canny(smoothed, edges, kCannyLow, kCannyHigh, 3, /*L2gradient=*/true);

  const cv::Rect inner(kIgnoredBorder, kIgnoredBorder, edges.cols - 2 * kIgnoredBorder,
                       edges.rows - 2 * kIgnoredBorder);
  const cv::Moments m = cv::moments(edges(inner), /*binaryImage=*/true);
  const int count = static_cast<int>(std::lround(m.m00));
  const double area = static_cast<double>(patch.total());
  sig.edgeCount = count;
  sig.density = count / area;
  if (count == 0) return sig;

  // mu20 + mu02 of the binary edge map is the sum of squared distances of the edge pixels to their centroid.
  const double spread = m.mu20 + m.mu02;
  const double reference = referenceCount > 0 ? referenceCount : count;
  const double k = reference / count;
  // k compensates for a window having more or fewer edge pixels than the template; with k folded in, the
  // value is the mean squared radius over the area, which does not depend on the patch size.
  sig.energy = k * spread / (reference * area);
  return sig;
}

void EdgeVerifier::setTemplate(const cv::Mat &templateGray) {
  if (templateGray.empty()) {
    normSize_ = cv::Size();
    template_ = EdgeSignature();
    return;
  }
  // Compared at the template's size, capped: a large template's edges say no more about texture than the
  // same template at ~96 px, and the check runs on every detection.
  const double shrink = std::min(1.0, kMaxNormalisedSide / std::max(templateGray.cols, templateGray.rows));
  normSize_ = cv::Size(std::max(1, cvRound(templateGray.cols * shrink)),
                       std::max(1, cvRound(templateGray.rows * shrink)));
  cv::Mat normalised = templateGray;
  if (normSize_ != templateGray.size()) cv::resize(templateGray, normalised, normSize_, 0, 0, cv::INTER_AREA);
  template_ = edgeSignature(normalised, 0);
}

EdgeSignature EdgeVerifier::signature(const cv::Mat &windowGray) const {
  if (windowGray.empty()) return EdgeSignature();
  if (!hasTemplate()) return edgeSignature(windowGray, 0);
  cv::Mat resized;
  if (windowGray.size() == normSize_) {
    resized = windowGray;
  } else {
    // INTER_AREA averages when shrinking (no aliasing into false edges); bilinear when enlarging.
    const bool shrinking = windowGray.total() > static_cast<size_t>(normSize_.area());
    cv::resize(windowGray, resized, normSize_, 0, 0, shrinking ? cv::INTER_AREA : cv::INTER_LINEAR);
  }
  return edgeSignature(resized, template_.edgeCount);
}

bool EdgeVerifier::verify(const EdgeSignature &window, VerifyMode mode, double tolerance) const {
  if (mode == VerifyMode::None) return true;
  if (!window.valid()) return false;
  // A template without edges gives nothing to compare against: the check cannot reject, so it passes.
  if (!template_.valid()) return true;

  const auto within = [tolerance](double windowValue, double templateValue) {
    return templateValue > 0 && std::abs(windowValue / templateValue - 1.0) <= tolerance;
  };
  const bool densityOk = within(window.density, template_.density);
  const bool energyOk = within(window.energy, template_.energy);
  switch (mode) {
    case VerifyMode::EdgeDensity:
      return densityOk;
    case VerifyMode::EdgeEnergy:
      return energyOk;
    case VerifyMode::Both:
      return densityOk && energyOk;
    case VerifyMode::None:
      break;
  }
  return true;
}

}  // namespace colortrack
