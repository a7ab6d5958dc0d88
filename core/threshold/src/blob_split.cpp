// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/blob_split.hpp"

#include <algorithm>
#include <limits>

namespace colortrack {

std::vector<BlobShare> splitBlob(const Blob &blob, const BlobLabels &labels,
                                 const std::vector<SplitSeed> &seeds) {
  std::vector<BlobShare> parts(seeds.size());
  if (labels.empty() || seeds.empty() || blob.label <= 0) return parts;
  const int d = std::max(1, labels.step);
  // The blob's box on the label grid (the detector scaled the grid box up by d and clipped it to the frame).
  const cv::Rect grid =
      cv::Rect(blob.box.x / d, blob.box.y / d, (blob.box.width + d - 1) / d, (blob.box.height + d - 1) / d) &
      cv::Rect(cv::Point(), labels.labels.size());
  std::vector<GridMoments> moments(seeds.size());
  std::vector<long long> own(seeds.size(), 0);
  for (int y = grid.y; y < grid.y + grid.height; ++y) {
    const int *row = labels.labels.ptr<int>(y);
    for (int x = grid.x; x < grid.x + grid.width; ++x) {
      if (row[x] != blob.label) continue;
      const double px = static_cast<double>(x) * d, py = static_cast<double>(y) * d;
      size_t nearest = 0, inside = 0;
      double best = std::numeric_limits<double>::max();
      for (size_t s = 0; s < seeds.size(); ++s) {
        const double dx = px - seeds[s].centre.x, dy = py - seeds[s].centre.y;
        // Squared distance over squared radius: the same order as distance / radius.
        const double r = std::max(1.0, seeds[s].radius);
        const double relative = (dx * dx + dy * dy) / (r * r);
        if (relative <= 1.0) ++inside;
        if (relative < best) {
          best = relative;
          nearest = s;
        }
      }
      moments[nearest].add(x, y);
      if (inside <= 1) ++own[nearest];  // in its own disc only, or in none
    }
  }
  for (size_t s = 0; s < seeds.size(); ++s) {
    if (moments[s].count == 0) continue;
    parts[s].blob = moments[s].toBlob(d, blob.box);
    parts[s].blob.label = blob.label;
    parts[s].ownArea = static_cast<double>(own[s]) * d * d;
  }
  return parts;
}

}  // namespace colortrack
