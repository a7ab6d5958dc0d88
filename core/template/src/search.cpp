// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <vector>

namespace colortrack {

namespace {

// Cell-row ring buffers above this size are replaced by recounting the leaving pixels (slower, O(1) memory).
constexpr std::size_t kMaxRingBytes = std::size_t(32) << 20;

// The part of the region where a window can be placed: region clipped to the bin image, in bin-image
// coordinates. Empty when the window does not fit.
struct Placement {
  cv::Rect area;       // clipped region, bin-image coordinates
  int positionsX = 0;  // window positions per row
  int positionsY = 0;  // window positions per column
  bool fits() const { return positionsX > 0 && positionsY > 0; }
};

Placement placementOf(const BinImage &bins, const cv::Rect &region, cv::Size window) {
  Placement p;
  if (window.width <= 0 || window.height <= 0 || bins.bins.empty()) return p;
  p.area = (region & bins.frameRect()) - bins.origin;
  p.positionsX = std::max(0, p.area.width - window.width + 1);
  p.positionsY = std::max(0, p.area.height - window.height + 1);
  return p;
}

// Keeps the best (score, raster position) seen; ties go to the earlier raster position (smaller y, then
// x) so that the fast search and the brute force agree whenever the best score is unique or tied.
struct Best {
  double score = -1;
  cv::Point pos;
  void offer(double s, cv::Point p) {
    if (s > score || (s == score && (p.y < pos.y || (p.y == pos.y && p.x < pos.x)))) {
      score = s;
      pos = p;
    }
  }
};

// Per-channel bin offsets, so that counting a pixel is three increments with no branching.
struct BinOffsets {
  int c1, c2, total;
  explicit BinOffsets(const BinLayout &l) : c1(l.offset(1)), c2(l.offset(2)), total(l.total()) {}
};

inline void addPixel(int *counts, const cv::Vec3b &p, const BinOffsets &o, int sign) {
  counts[p[0]] += sign;
  counts[o.c1 + p[1]] += sign;
  counts[o.c2 + p[2]] += sign;
}

// Per-cell counts of bands of pixel rows. Neighbouring pixels often share bins, and incrementing the same
// counter back to back stalls on the previous increment; so with cells wide enough to pay for the final
// sum (8 px and more), four interleaved copies of each cell's counters take consecutive pixel columns and
// are summed once per band.
class CellCounter {
 public:
  CellCounter(const cv::Mat &binMat, const cv::Rect &area, int step, const BinOffsets &o)
      : binMat_(binMat),
        area_(area),
        o_(o),
        cells_((area.width + step - 1) / step),
        copies_(step >= 8 ? 4 : 1) {
    columnBase_.resize(area.width);
    for (int x = 0; x < area.width; ++x) columnBase_[x] = ((x / step) * copies_ + x % copies_) * o.total;
    if (copies_ > 1) scratch_.resize(std::size_t(cells_) * copies_ * o.total);
  }

  // Adds (sign +1) or removes (-1) the counts of pixel rows [y0, y1) to `cells` (cells x total ints).
  void add(int y0, int y1, int sign, int *cells) {
    if (copies_ == 1) {  // narrow cells: summing copies would cost more than the stalls it saves
      accumulate(y0, y1, sign, cells);
      return;
    }
    std::fill(scratch_.begin(), scratch_.end(), 0);
    accumulate(y0, y1, +1, scratch_.data());
    const int total = o_.total;
    for (int cell = 0; cell < cells_; ++cell) {
      const int *copy = &scratch_[std::size_t(cell) * copies_ * total];
      int *out = cells + std::size_t(cell) * total;
      for (int k = 0; k < copies_; ++k, copy += total)
        for (int i = 0; i < total; ++i) out[i] += sign * copy[i];
    }
  }

 private:
  void accumulate(int y0, int y1, int sign, int *counters) const {
    for (int y = y0; y < y1; ++y) {
      const cv::Vec3b *row = binMat_.ptr<cv::Vec3b>(area_.y + y) + area_.x;
      for (int x = 0; x < area_.width; ++x) addPixel(counters + columnBase_[x], row[x], o_, sign);
    }
  }

  const cv::Mat &binMat_;
  cv::Rect area_;
  BinOffsets o_;
  int cells_, copies_;
  std::vector<int> columnBase_;  // counter block of each pixel column
  std::vector<int> scratch_;     // cells x copies x total
};

// Ranking score of the coarse pass: the logarithm of the match value, in float with precomputed model
// sums. The coarse windows are approximations anyway; exact values come from matchCounts() later.
class CoarseScorer {
 public:
  CoarseScorer(const Histogram &model, const ChannelWeights &weights) : layout_(model.layout) {
    for (int c = 0; c < 3; ++c) {
      weight_[c] = static_cast<float>(weights.w[c]);
      double sum = 0;
      for (int j = 0; j < layout_.bins[c]; ++j) sum += model.channel(c)[j];
      inverseModelSum_[c] = sum > 0 ? static_cast<float>(1.0 / sum) : 0.0f;
    }
    model_ = model.values;
  }

  float logScore(const int *counts, int pixels) const {
    const float inverseArea = 1.0f / static_cast<float>(pixels);
    float total = 0;
    for (int c = 0; c < 3; ++c) {
      if (weight_[c] == 0) continue;
      const int offset = layout_.offset(c);
      const int n = layout_.bins[c];
      float common[4] = {};  // partial sums: lets the compiler vectorise
      int j = 0;
      for (; j + 4 <= n; j += 4)
        for (int k = 0; k < 4; ++k)
          common[k] +=
              std::min(static_cast<float>(counts[offset + j + k]) * inverseArea, model_[offset + j + k]);
      for (; j < n; ++j)
        common[0] += std::min(static_cast<float>(counts[offset + j]) * inverseArea, model_[offset + j]);
      const float channelValue = ((common[0] + common[1]) + (common[2] + common[3])) * inverseModelSum_[c];
      total += weight_[c] * std::log(std::max(channelValue, 1e-30f));
    }
    return total;
  }

 private:
  BinLayout layout_;
  std::vector<float> model_;
  std::array<float, 3> weight_{}, inverseModelSum_{};
};

// Coarse pass: ranking scores of the window approximated by whole cells of step x step pixels, at every
// grid position (multiples of `step` from the area's corner). Returns the scores row-major, gridX x gridY.
std::vector<float> coarseScores(const BinImage &bins, const Placement &pl, cv::Size window, int step,
                                const Histogram &model, const ChannelWeights &weights, int gridX, int gridY) {
  const BinOffsets o(model.layout);
  const cv::Rect &area = pl.area;
  const int cellsX = (area.width + step - 1) / step;
  const int cellsY = (area.height + step - 1) / step;
  // Window size in cells: the nearest whole number, at least one, never more than the area holds.
  const int winCellsX = std::clamp(static_cast<int>(std::lround(double(window.width) / step)), 1, cellsX);
  const int winCellsY = std::clamp(static_cast<int>(std::lround(double(window.height) / step)), 1, cellsY);

  CellCounter counter(bins.bins, area, step, o);

  // columnSums: counts of the window's cell rows, per cell column. A ring of the last winCellsY cell rows
  // lets a cell row leave the window without recounting its pixels.
  std::vector<int> columnSums(std::size_t(cellsX) * o.total, 0);
  const std::size_t rowInts = std::size_t(cellsX) * o.total;
  // The ring costs three passes over a cell row's counts per cell row; recounting costs touching the
  // pixels twice. Small steps (many cells, few pixels each) favour recounting.
  const bool ringIsCheaper = 3 * rowInts < std::size_t(2) * 3 * step * area.width;
  const bool useRing = ringIsCheaper && rowInts * winCellsY * sizeof(int) <= kMaxRingBytes;
  std::vector<int> ring(useRing ? rowInts * winCellsY : 0);
  auto pixelRowsOf = [&](int cellRow, int &y0, int &y1) {
    y0 = cellRow * step;
    y1 = std::min(area.height, y0 + step);
  };
  auto addCellRow = [&](int cellRow) {
    int y0, y1;
    if (useRing) {
      int *slot = ring.data() + rowInts * (cellRow % winCellsY);
      if (cellRow >= winCellsY)  // the slot holds the row leaving the window
        for (std::size_t i = 0; i < rowInts; ++i) columnSums[i] -= slot[i];
      std::fill(slot, slot + rowInts, 0);
      pixelRowsOf(cellRow, y0, y1);
      counter.add(y0, y1, +1, slot);
      for (std::size_t i = 0; i < rowInts; ++i) columnSums[i] += slot[i];
    } else {
      if (cellRow >= winCellsY) {
        pixelRowsOf(cellRow - winCellsY, y0, y1);
        counter.add(y0, y1, -1, columnSums.data());
      }
      pixelRowsOf(cellRow, y0, y1);
      counter.add(y0, y1, +1, columnSums.data());
    }
  };

  const CoarseScorer scorer(model, weights);
  std::vector<float> scores(std::size_t(gridX) * gridY);
  std::vector<int> windowSums(o.total);
  int nextCellRow = 0;  // first cell row not yet added
  for (int gy = 0; gy < gridY; ++gy) {
    // Grid positions near the bottom edge reuse the last full band of cells.
    const int topCell = std::min(gy, cellsY - winCellsY);
    while (nextCellRow < topCell + winCellsY) addCellRow(nextCellRow++);

    std::fill(windowSums.begin(), windowSums.end(), 0);
    int leftCell = 0;
    for (int cx = 0; cx < winCellsX; ++cx)
      for (int i = 0; i < o.total; ++i) windowSums[i] += columnSums[std::size_t(cx) * o.total + i];
    for (int gx = 0; gx < gridX; ++gx) {
      const int wantLeft = std::min(gx, cellsX - winCellsX);
      while (leftCell < wantLeft) {  // slide right by one cell column
        const int *leaving = &columnSums[std::size_t(leftCell) * o.total];
        const int *entering = &columnSums[std::size_t(leftCell + winCellsX) * o.total];
        for (int i = 0; i < o.total; ++i) windowSums[i] += entering[i] - leaving[i];
        ++leftCell;
      }
      // Every pixel counts once per channel, so channel 0 sums to the pixel count (edge cells are partial).
      int pixels = 0;
      for (int i = 0; i < model.layout.bins[0]; ++i) pixels += windowSums[i];
      scores[std::size_t(gy) * gridX + gx] = scorer.logScore(windowSums.data(), pixels);
    }
  }
  return scores;
}

// Up to `count` best grid positions, each at least two grid steps (Chebyshev) from the others, so the
// refinements look at different places instead of the shoulders of one peak.
std::vector<cv::Point> bestSeparated(const std::vector<float> &scores, int gridX, int gridY, int count) {
  std::vector<cv::Point> picked;
  std::vector<std::uint8_t> suppressed(scores.size(), 0);
  auto pick = [&](std::size_t index) {
    const cv::Point g(int(index % gridX), int(index / gridX));
    picked.push_back(g);
    for (int y = std::max(0, g.y - 1); y <= std::min(gridY - 1, g.y + 1); ++y)
      for (int x = std::max(0, g.x - 1); x <= std::min(gridX - 1, g.x + 1); ++x)
        suppressed[std::size_t(y) * gridX + x] = 1;
  };
  constexpr int kFewCandidates = 16;
  if (count <= kFewCandidates) {  // a pass per candidate beats sorting every grid position
    for (int k = 0; k < count; ++k) {
      std::ptrdiff_t bestIndex = -1;
      for (std::size_t i = 0; i < scores.size(); ++i)
        if (!suppressed[i] && (bestIndex < 0 || scores[i] > scores[bestIndex])) bestIndex = std::ptrdiff_t(i);
      if (bestIndex < 0) break;
      pick(std::size_t(bestIndex));
    }
    return picked;
  }
  std::vector<std::size_t> order(scores.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return scores[a] > scores[b]; });
  for (std::size_t index : order) {
    if (int(picked.size()) == count) break;
    if (!suppressed[index]) pick(index);
  }
  return picked;
}

// Exact scores of every window position in `positions` (top-left corners, area coordinates) with running
// histograms: one histogram per pixel column of the window's height, slid down a row at a time (two
// pixels per column), and the window's histogram slid right by swapping one column histogram for the
// next. A position costs O(bins) instead of O(window area).
void refine(const BinImage &bins, const Placement &pl, cv::Size window, const cv::Rect &positions,
            const Histogram &model, const ChannelWeights &weights, Best &best) {
  const BinOffsets o(model.layout);
  const cv::Mat &binMat = bins.bins;
  const cv::Point base = pl.area.tl() + positions.tl();  // first window's corner, bin-image coordinates
  const int columns = positions.width + window.width - 1;
  const double pixels = double(window.width) * window.height;

  std::vector<int> columnCounts(std::size_t(columns) * o.total, 0);
  for (int y = base.y; y < base.y + window.height; ++y) {
    const cv::Vec3b *row = binMat.ptr<cv::Vec3b>(y) + base.x;
    for (int x = 0; x < columns; ++x) addPixel(&columnCounts[std::size_t(x) * o.total], row[x], o, +1);
  }
  std::vector<int> counts(o.total);
  for (int py = 0; py < positions.height; ++py) {
    if (py > 0) {
      const cv::Vec3b *leaving = binMat.ptr<cv::Vec3b>(base.y + py - 1) + base.x;
      const cv::Vec3b *entering = binMat.ptr<cv::Vec3b>(base.y + py + window.height - 1) + base.x;
      for (int x = 0; x < columns; ++x) {
        int *column = &columnCounts[std::size_t(x) * o.total];
        addPixel(column, leaving[x], o, -1);
        addPixel(column, entering[x], o, +1);
      }
    }
    std::fill(counts.begin(), counts.end(), 0);
    for (int x = 0; x < window.width; ++x)
      for (int i = 0; i < o.total; ++i) counts[i] += columnCounts[std::size_t(x) * o.total + i];
    for (int px = 0; px < positions.width; ++px) {
      if (px > 0) {
        const int *leaving = &columnCounts[std::size_t(px - 1) * o.total];
        const int *entering = &columnCounts[std::size_t(px + window.width - 1) * o.total];
        for (int i = 0; i < o.total; ++i) counts[i] += entering[i] - leaving[i];
      }
      best.offer(matchCounts(counts.data(), pixels, model, weights), positions.tl() + cv::Point(px, py));
    }
  }
}

SearchResult resultOf(const Best &best, const Placement &pl, const BinImage &bins, cv::Size window) {
  SearchResult r;
  r.found = true;
  r.box = cv::Rect(best.pos + pl.area.tl() + bins.origin, window);
  r.score = best.score;
  return r;
}

}  // namespace

SearchResult searchWindow(const BinImage &bins, const cv::Rect &region, cv::Size window,
                          const Histogram &model, const ChannelWeights &weights, const SearchParams &params) {
  const Placement pl = placementOf(bins, region, window);
  if (!pl.fits()) return SearchResult();
  CV_Assert(bins.bins.type() == CV_8UC3);

  const int step =
      params.coarseStep > 0 ? params.coarseStep : std::max(1, std::min(window.width, window.height) / 6);
  // Grid positions: multiples of step; the last real position lies less than one step past the last one.
  const int gridX = (pl.positionsX - 1) / step + 1;
  const int gridY = (pl.positionsY - 1) / step + 1;
  const std::vector<float> scores = coarseScores(bins, pl, window, step, model, weights, gridX, gridY);
  const std::vector<cv::Point> candidates =
      bestSeparated(scores, gridX, gridY, std::max(1, params.candidates));

  Best best;
  const cv::Rect allPositions(0, 0, pl.positionsX, pl.positionsY);
  for (const cv::Point &g : candidates) {
    const cv::Point center = g * step;
    const cv::Rect around =
        cv::Rect(center.x - step, center.y - step, 2 * step + 1, 2 * step + 1) & allPositions;
    refine(bins, pl, window, around, model, weights, best);
  }
  return resultOf(best, pl, bins, window);
}

SearchResult searchWindowBruteForce(const BinImage &bins, const cv::Rect &region, cv::Size window,
                                    const Histogram &model, const ChannelWeights &weights) {
  const Placement pl = placementOf(bins, region, window);
  if (!pl.fits()) return SearchResult();
  Best best;
  for (int py = 0; py < pl.positionsY; ++py)
    for (int px = 0; px < pl.positionsX; ++px) {
      const cv::Rect frameWindow(pl.area.tl() + bins.origin + cv::Point(px, py), window);
      best.offer(windowMatch(bins, frameWindow, model, weights), cv::Point(px, py));
    }
  return resultOf(best, pl, bins, window);
}

}  // namespace colortrack
