// SPDX-License-Identifier: LGPL-2.1-or-later
#include "mot_metrics.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "colortrack/multi_tracker.hpp"  // solveAssignment (Hungarian method)
#include "metrics.hpp"

namespace colortrack::eval {

namespace {

constexpr double kNoMatch = 1e6;  // the cost of a pair whose IoU is below the threshold

// Maximum-IoU one-to-one matching between `rows` and `cols` boxes, pairs below `minIou` left out: for each
// row, the matched column or -1.
std::vector<int> matchByIou(const std::vector<cv::Rect2d> &rows, const std::vector<cv::Rect2d> &cols,
                            double minIou) {
  std::vector<int> match(rows.size(), -1);
  if (rows.empty() || cols.empty()) return match;
  cv::Mat cost(static_cast<int>(rows.size()), static_cast<int>(cols.size()), CV_64FC1);
  for (int r = 0; r < cost.rows; ++r)
    for (int c = 0; c < cost.cols; ++c) {
      const double iou = overlap(rows[r], cols[c]);
      cost.at<double>(r, c) = iou >= minIou ? 1.0 - iou : kNoMatch;
    }
  // solveAssignment wants no more rows than columns; transpose otherwise.
  if (cost.rows <= cost.cols) {
    const std::vector<int> a = solveAssignment(cost);
    for (int r = 0; r < cost.rows; ++r)
      if (a[r] >= 0 && cost.at<double>(r, a[r]) < kNoMatch) match[r] = a[r];
  } else {
    const cv::Mat t = cost.t();
    const std::vector<int> a = solveAssignment(t);
    for (int c = 0; c < t.rows; ++c)
      if (a[c] >= 0 && t.at<double>(c, a[c]) < kNoMatch) match[a[c]] = c;
  }
  return match;
}

std::vector<cv::Rect2d> boxesOf(const std::vector<MotBox> &objects) {
  std::vector<cv::Rect2d> boxes;
  for (const MotBox &o : objects) boxes.push_back(o.box);
  return boxes;
}

}  // namespace

MotScore scoreMot(const std::vector<MotFrame> &frames, double minIou) {
  MotScore s;
  s.frames = static_cast<int>(frames.size());
  std::map<int, int> lastTrackOf;            // ground-truth id -> the track id it matched last
  std::map<std::pair<int, int>, int> pairs;  // (truth id, track id) -> frames overlapping (IDF1)
  std::map<int, int> truthFrames, trackFrames;
  double iouSum = 0;
  for (const MotFrame &f : frames) {
    // Track boxes on "don't care" objects are set aside first.
    std::vector<MotBox> tracks;
    {
      const std::vector<int> onIgnored = matchByIou(boxesOf(f.tracks), boxesOf(f.ignored), minIou);
      for (size_t t = 0; t < f.tracks.size(); ++t)
        if (onIgnored[t] < 0) tracks.push_back(f.tracks[t]);
    }
    s.truthBoxes += static_cast<int>(f.truth.size());
    for (const MotBox &g : f.truth) ++truthFrames[g.id];
    for (const MotBox &t : tracks) ++trackFrames[t.id];
    // IDF1 counts every qualifying overlap, whatever CLEAR-MOT matched.
    for (const MotBox &g : f.truth)
      for (const MotBox &t : tracks)
        if (overlap(g.box, t.box) >= minIou) ++pairs[{g.id, t.id}];

    // CLEAR-MOT: correspondences kept from the last frame first.
    std::vector<int> truthMatch(f.truth.size(), -1);
    std::vector<char> trackUsed(tracks.size(), 0);
    for (size_t g = 0; g < f.truth.size(); ++g) {
      const auto last = lastTrackOf.find(f.truth[g].id);
      if (last == lastTrackOf.end()) continue;
      for (size_t t = 0; t < tracks.size(); ++t)
        if (!trackUsed[t] && tracks[t].id == last->second &&
            overlap(f.truth[g].box, tracks[t].box) >= minIou) {
          truthMatch[g] = static_cast<int>(t);
          trackUsed[t] = 1;
          break;
        }
    }
    std::vector<int> freeTruth, freeTracks;
    for (size_t g = 0; g < f.truth.size(); ++g)
      if (truthMatch[g] < 0) freeTruth.push_back(static_cast<int>(g));
    for (size_t t = 0; t < tracks.size(); ++t)
      if (!trackUsed[t]) freeTracks.push_back(static_cast<int>(t));
    std::vector<cv::Rect2d> a, b;
    for (int g : freeTruth) a.push_back(f.truth[g].box);
    for (int t : freeTracks) b.push_back(tracks[t].box);
    const std::vector<int> m = matchByIou(a, b, minIou);
    for (size_t i = 0; i < freeTruth.size(); ++i)
      if (m[i] >= 0) {
        truthMatch[freeTruth[i]] = freeTracks[m[i]];
        trackUsed[freeTracks[m[i]]] = 1;
      }

    for (size_t g = 0; g < f.truth.size(); ++g) {
      if (truthMatch[g] < 0) {
        ++s.misses;
        continue;
      }
      const MotBox &t = tracks[truthMatch[g]];
      ++s.matches;
      iouSum += overlap(f.truth[g].box, t.box);
      const auto last = lastTrackOf.find(f.truth[g].id);
      if (last != lastTrackOf.end() && last->second != t.id) ++s.idSwitches;
      lastTrackOf[f.truth[g].id] = t.id;
    }
    for (size_t t = 0; t < tracks.size(); ++t)
      if (!trackUsed[t]) ++s.falsePositives;
  }
  s.mota = s.truthBoxes > 0
               ? 1.0 - static_cast<double>(s.misses + s.falsePositives + s.idSwitches) / s.truthBoxes
               : 1.0;
  s.motp = s.matches > 0 ? iouSum / s.matches : 0;

  // IDF1: the pairing of identities that maximises the overlapping frames.
  std::vector<int> truthIds, trackIds;
  for (const auto &[id, n] : truthFrames) truthIds.push_back(id);
  for (const auto &[id, n] : trackFrames) trackIds.push_back(id);
  int totalTruth = 0, totalTracks = 0;
  for (const auto &[id, n] : truthFrames) totalTruth += n;
  for (const auto &[id, n] : trackFrames) totalTracks += n;
  int idtp = 0;
  if (!truthIds.empty() && !trackIds.empty()) {
    // Square, with dummy rows and columns so that any identity may stay unpaired: every entry costs `best`
    // except a real pair, which costs `best` less its overlapping frames. The total is then a constant minus
    // the overlap of the pairs chosen, and pairing two identities that never overlap changes nothing.
    int best = 0;
    for (const auto &[key, count] : pairs) best = std::max(best, count);
    const int n = static_cast<int>(truthIds.size() + trackIds.size());
    cv::Mat cost(n, n, CV_64FC1, cv::Scalar(best));
    for (size_t g = 0; g < truthIds.size(); ++g)
      for (size_t t = 0; t < trackIds.size(); ++t) {
        const auto it = pairs.find({truthIds[g], trackIds[t]});
        if (it != pairs.end()) cost.at<double>(static_cast<int>(g), static_cast<int>(t)) = best - it->second;
      }
    const std::vector<int> a = solveAssignment(cost);
    for (size_t g = 0; g < truthIds.size(); ++g) {
      const int t = a[g];
      if (t < 0 || t >= static_cast<int>(trackIds.size())) continue;
      const auto it = pairs.find({truthIds[g], trackIds[t]});
      if (it != pairs.end()) idtp += it->second;
    }
  }
  s.idTruePositives = idtp;
  s.idFalsePositives = totalTracks - idtp;
  s.idFalseNegatives = totalTruth - idtp;
  s.idPrecision = totalTracks > 0 ? static_cast<double>(idtp) / totalTracks : 1.0;
  s.idRecall = totalTruth > 0 ? static_cast<double>(idtp) / totalTruth : 1.0;
  s.idf1 = totalTruth + totalTracks > 0 ? 2.0 * idtp / (totalTruth + totalTracks) : 1.0;
  return s;
}

}  // namespace colortrack::eval
