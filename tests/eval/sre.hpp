// SPDX-License-Identifier: LGPL-2.1-or-later
// Spatial robustness evaluation (SRE, Wu, Lim, Yang, CVPR 2013): the same sequence started from slightly
// wrong boxes, so a score does not rest on one lucky initialisation.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace colortrack::eval {

// One start of a sequence: the one-pass start (OPE) or one of the perturbed ones.
struct StartBox {
  std::string name;  // "ope", "left", "right", "up", "down", "up-left", "down-right", "scale0.9", "scale1.1"
  cv::Rect box;      // rounded to whole pixels and clipped to the frame
};

// The number of perturbed starts startBoxes adds after the OPE one.
constexpr int kSreStarts = 8;

// The box as a start: rounded to whole pixels, clipped to the frame (empty when it lies outside).
cv::Rect startRect(const cv::Rect2d &box, cv::Size frame);

// The OPE start (`groundTruth`, frame 1's box) and, with `sre`, the eight perturbed ones after it: shifted
// by 10 % of the width left and right, 10 % of the height up and down, diagonally by 10 % up-left and
// down-right, and scaled about the centre by 0.9 and 1.1. All rounded and clipped to `frame`.
std::vector<StartBox> startBoxes(const cv::Rect2d &groundTruth, cv::Size frame, bool sre);

// A start offset as the tools take it ("DX,DY", whole pixels, e.g. "-1,2"); nullopt for anything else.
std::optional<cv::Point> parseStartOffset(const std::string &text);

}  // namespace colortrack::eval
