// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode: sharing one blob between several tracked objects. Two balls of one colour that touch or
// pass over each other make one connected blob; each ball's pixels are still the ones nearest it.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/blobs.hpp"

namespace colortrack {

// Where one object is expected: a disc.
struct SplitSeed {
  cv::Point2d centre;
  double radius = 1;
};

// One seed's share of a blob.
struct BlobShare {
  Blob blob;  // its pixels, in frame coordinates like the detector's (area 0: none)
  double ownArea =
      0;  // of those, the ones outside every other seed's disc: evidence that this object is seen
};

// Gives each pixel of `blob` (found through `labels`) to the seed it is nearest to relative to that seed's
// radius, so a small object over a large one keeps the pixels around it. Returns one share per seed.
std::vector<BlobShare> splitBlob(const Blob &blob, const BlobLabels &labels,
                                 const std::vector<SplitSeed> &seeds);

}  // namespace colortrack
