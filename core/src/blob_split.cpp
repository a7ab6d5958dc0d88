#include "colortrack/blob_split.hpp"

#include <algorithm>
#include <limits>

namespace colortrack {

namespace {

struct PartMoments {
  long long count = 0, own = 0;
  double sumX = 0, sumY = 0;
  int minX = std::numeric_limits<int>::max(), maxX = -1, minY = std::numeric_limits<int>::max(), maxY = -1;
};

}  // namespace

std::vector<BlobShare> splitBlob(const Blob &blob, const BlobLabels &labels,
                                 const std::vector<SplitSeed> &seeds) {
  std::vector<BlobShare> parts(seeds.size());
  if (labels.empty() || seeds.empty() || blob.label <= 0) return parts;
  const int d = std::max(1, labels.step);
  // The blob's box on the label grid (the detector scaled the grid box up by d and clipped it to the frame).
  const cv::Rect grid =
      cv::Rect(blob.box.x / d, blob.box.y / d, (blob.box.width + d - 1) / d, (blob.box.height + d - 1) / d) &
      cv::Rect(cv::Point(), labels.labels.size());
  std::vector<PartMoments> moments(seeds.size());
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
      PartMoments &m = moments[nearest];
      ++m.count;
      if (inside <= 1) ++m.own;  // in its own disc only, or in none
      m.sumX += x;
      m.sumY += y;
      m.minX = std::min(m.minX, x);
      m.maxX = std::max(m.maxX, x);
      m.minY = std::min(m.minY, y);
      m.maxY = std::max(m.maxY, y);
    }
  }
  const double cellArea = static_cast<double>(d) * d;
  for (size_t s = 0; s < seeds.size(); ++s) {
    const PartMoments &m = moments[s];
    if (m.count == 0) continue;
    parts[s].ownArea = m.own * cellArea;
    Blob &part = parts[s].blob;
    part.area = m.count * cellArea;
    part.centroid = cv::Point2d(m.sumX / m.count * d, m.sumY / m.count * d);
    const int width = m.maxX - m.minX + 1, height = m.maxY - m.minY + 1;
    part.box = cv::Rect(m.minX * d, m.minY * d, width * d, height * d) & blob.box;
    part.fill = static_cast<double>(m.count) / (static_cast<double>(width) * height);
    part.label = blob.label;
  }
  return parts;
}

}  // namespace colortrack
