// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/round_split.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack {

namespace {

// A neck this narrow (its half width against the smaller disc's radius) separates two objects; one body
// that is merely long (a capsule, an ellipse) has a ridge of nearly even width between its peaks. 0.85 missed
// a small ball a third over a big one (neck 11.0 px, radius 13.6); 0.95 splits red balls with orange ones
// drawn over them (docs/benchmarks-history.md, issue 47).
constexpr double kNeck = 0.9;
// The discs must cover this part of the blob: what they leave is not round objects.
constexpr double kCoverage = 0.9;
// A blob that fills the disc inscribed in its (nearly square) box is one round object, which is what most
// blobs are in most frames: it is passed over without a distance transform. Several objects touching fill
// less of their box, or make it oblong.
constexpr double kOneDiscFill = 0.9;
constexpr double kOneDiscAspect = 1.1;
// Discs are drawn this much (grid px) larger than the distance transform's value at their centre, which
// undershoots a disc's radius by about a pixel.
constexpr double kRadiusMargin = 1.0;

// The smallest distance-transform value on the segment from a to b.
float neckWidth(const cv::Mat &dist, cv::Point a, cv::Point b) {
  float narrowest = dist.at<float>(a);
  for (cv::LineIterator it(dist, a, b, 8); it.pos() != b; ++it)
    narrowest = std::min(narrowest, *reinterpret_cast<const float *>(*it));
  return narrowest;
}

}  // namespace

std::vector<SplitSeed> roundParts(const Blob &blob, const BlobLabels &labels, double minRadius) {
  if (labels.empty() || blob.label <= 0 || blob.box.empty()) return {};
  const double longSide = std::max(blob.box.width, blob.box.height);
  const double shortSide = std::min(blob.box.width, blob.box.height);
  if (longSide <= kOneDiscAspect * shortSide && blob.area >= kOneDiscFill * CV_PI / 4 * blob.box.area())
    return {};
  const int d = std::max(1, labels.step);
  const cv::Rect grid =
      cv::Rect(blob.box.x / d, blob.box.y / d, (blob.box.width + d - 1) / d, (blob.box.height + d - 1) / d) &
      cv::Rect(cv::Point(), labels.labels.size());
  if (grid.width < 3 || grid.height < 3) return {};
  // The blob alone, with a background border so that the distance transform sees its edge everywhere.
  cv::Mat mask;
  cv::compare(labels.labels(grid), blob.label, mask, cv::CMP_EQ);
  cv::copyMakeBorder(mask, mask, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  cv::Mat dist;
  cv::distanceTransform(mask, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE);

  // Peaks: local maxima of the distance transform, strongest first.
  cv::Mat dilated, isPeak;
  cv::dilate(dist, dilated, cv::Mat());
  cv::compare(dist, dilated, isPeak, cv::CMP_GE);
  const float floorRadius = static_cast<float>(std::max(1.0, minRadius / d));
  cv::Mat bigEnough;
  cv::compare(dist, floorRadius, bigEnough, cv::CMP_GE);
  cv::bitwise_and(isPeak, bigEnough, isPeak);
  std::vector<cv::Point> candidates;
  cv::findNonZero(isPeak, candidates);
  if (candidates.size() < 2) return {};
  std::sort(candidates.begin(), candidates.end(),
            [&](cv::Point a, cv::Point b) { return dist.at<float>(a) > dist.at<float>(b); });

  // Each peak outside the stronger peaks' discs, and parted from each by a neck, is another object.
  std::vector<cv::Point> centres;
  for (const cv::Point p : candidates) {
    const float r = dist.at<float>(p);
    bool own = true;
    for (const cv::Point c : centres) {
      const float rc = dist.at<float>(c);
      if (cv::norm(p - c) <= rc || neckWidth(dist, c, p) >= kNeck * std::min(r, rc)) {
        own = false;
        break;
      }
    }
    if (own) centres.push_back(p);
  }
  if (centres.size() < 2) return {};

  // The discs must explain the blob: a shape they leave much of is something else.
  cv::Mat discs = cv::Mat::zeros(mask.size(), CV_8U);
  for (const cv::Point c : centres)
    cv::circle(discs, c, cvRound(dist.at<float>(c) + kRadiusMargin), cv::Scalar(255), cv::FILLED);
  cv::bitwise_and(discs, mask, discs);
  if (cv::countNonZero(discs) < kCoverage * cv::countNonZero(mask)) return {};

  std::vector<SplitSeed> seeds;
  for (const cv::Point c : centres) {
    // Back to frame coordinates (the crop started at grid.tl() less the border).
    const cv::Point2d centre((c.x - 1 + grid.x) * d, (c.y - 1 + grid.y) * d);
    seeds.push_back(SplitSeed{centre, (dist.at<float>(c) + kRadiusMargin) * d});
  }
  return seeds;
}

std::vector<Blob> splitRound(const Blob &blob, const BlobLabels &labels, int minArea) {
  const std::vector<SplitSeed> seeds = roundParts(blob, labels, std::sqrt(std::max(1, minArea) / CV_PI));
  const std::vector<BlobShare> shares = splitBlob(blob, labels, seeds);
  std::vector<Blob> parts;
  for (size_t i = 0; i < seeds.size(); ++i) {
    if (shares[i].blob.area < minArea) continue;
    // Where the object is, and how big, is its disc's: the share's centroid and box are pulled towards the
    // neck, and cut where a neighbour covers the object.
    Blob part = shares[i].blob;
    const double r = seeds[i].radius;
    part.centroid = seeds[i].centre;
    part.box = cv::Rect(cvRound(seeds[i].centre.x - r), cvRound(seeds[i].centre.y - r), cvRound(2 * r) + 1,
                        cvRound(2 * r) + 1) &
               blob.box;
    parts.push_back(part);
  }
  if (parts.size() < 2) parts.clear();
  return parts;
}

}  // namespace colortrack
