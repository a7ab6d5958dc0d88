// SPDX-License-Identifier: LGPL-2.1-or-later
// Dynamic scale: pick the best box size around a detection.
#pragma once

#include <opencv2/core.hpp>

#include "colortrack/color.hpp"
#include "colortrack/histogram.hpp"

namespace colortrack {

struct ScaleParams {
  double minFactor = 0.94;  // relative to the current box size
  double maxFactor = 1.06;
  double step = 0.02;
  double ringWidth = 0.25;  // width of the surrounding ring, as a fraction of the box's smaller side
};

struct ScaleResult {
  cv::Rect2d box;        // chosen box, same centre as the input
  double factor = 1.0;   // chosen size relative to the input box
  double match = 0;      // match value of the chosen window
  double criterion = 0;  // what was maximised
};

// Tries the sizes factor * box.size for factor in [minFactor, maxFactor] at the box's centre. A raw
// intersection maximum would favour windows smaller than the object (a part of a uniform object is "purer"
// than the whole with its border), so the criterion rewards covering the object: match(window) minus
// match(ring around it). The ring is clipped to the bin image; a window that leaves it is skipped.
ScaleResult refineScale(const BinImage &bins, const cv::Rect2d &box, const Histogram &model,
                        const ChannelWeights &weights, const ScaleParams &params);

}  // namespace colortrack
