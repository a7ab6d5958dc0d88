// SPDX-License-Identifier: LGPL-2.1-or-later
// Multi-object tracking metrics: CLEAR-MOT (Bernardin & Stiefelhagen 2008: MOTA, MOTP, identity switches)
// and the identity measures of Ristani et al. 2016 (IDF1, IDP, IDR). No GStreamer here, so the unit test
// checks the figures on hand-made tracks.
#pragma once

#include <vector>

#include <opencv2/core.hpp>

namespace colortrack::eval {

// One object in one frame: an id and its box.
struct MotBox {
  int id = 0;
  cv::Rect2d box;
};

// One frame: the ground truth, the tracker's boxes, and ground-truth objects too hidden to count ("don't
// care": a tracker box on one is neither a hit nor a false positive, as in the MOT benchmarks).
struct MotFrame {
  std::vector<MotBox> truth;
  std::vector<MotBox> tracks;
  std::vector<MotBox> ignored;
};

struct MotScore {
  int frames = 0;
  int truthBoxes = 0;  // ground-truth boxes that count
  int matches = 0, misses = 0, falsePositives = 0, idSwitches = 0;
  double mota = 0;  // 1 - (misses + false positives + id switches) / truth boxes
  double motp = 0;  // mean IoU of the matches
  int idTruePositives = 0, idFalsePositives = 0, idFalseNegatives = 0;
  double idf1 = 0, idPrecision = 0, idRecall = 0;
};

// Scores a sequence; a ground-truth box and a track box can match when their IoU is at least `minIou`.
// CLEAR-MOT: a ground-truth object keeps the track it matched last while their IoU still qualifies; the
// rest are assigned by maximum total IoU; a match whose track differs from the object's previous match is an
// identity switch. IDF1: each ground-truth identity is paired with at most one track identity so that the
// frames in which the pair overlaps (IoU >= minIou) are as many as possible.
MotScore scoreMot(const std::vector<MotFrame> &frames, double minIou = 0.3);

}  // namespace colortrack::eval
