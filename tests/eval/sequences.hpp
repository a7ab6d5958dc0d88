// SPDX-License-Identifier: LGPL-2.1-or-later
// OTB-layout sequence folders (img/<n>.jpg + groundtruth.txt), as both evaluation tools read them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "metrics.hpp"

namespace colortrack::eval {

struct Sequence {
  std::string name;
  std::filesystem::path dir;
  FramePattern pattern;
  std::vector<GroundTruthBox> groundTruth;
  cv::Size frameSize;  // of the first frame
  cv::Rect initBox;    // frame 1's box rounded to whole pixels and clipped to the frame (the OTB start)
};

// Reads one sequence folder; `gtOrigin` is subtracted from ground-truth x and y (1: OTB's 1-based boxes).
// Throws std::runtime_error naming the file and the problem.
Sequence loadSequence(const std::filesystem::path &dir, double gtOrigin);

// Sequence folders, or folders of sequence folders (sorted by name).
std::vector<Sequence> findSequences(const std::vector<std::string> &inputs, double gtOrigin);

// The path of frame `index` (0 = the first) of a sequence.
std::filesystem::path framePath(const Sequence &sequence, int index);

// The shared sequences (../shared/sequences) in two halves, each mixing OTB, VOT, UAV123, DTB70 and UAVDT
// material: parameters are tuned on the first and checked on the second, so a gain that is only
// overfitting shows. Both evaluation tools use these lists.
const std::vector<std::string> &tuneSplit();
const std::vector<std::string> &confirmSplit();
// "tune", "confirm" or "-" (in neither list).
const char *halfOf(const std::string &sequenceName);

}  // namespace colortrack::eval
