// SPDX-License-Identifier: LGPL-2.1-or-later
// The fast window search (coarse cell grid, then running histograms) against the brute-force reference.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>

#include <opencv2/core.hpp>

#include "colortrack/search.hpp"

using namespace colortrack;

namespace {

const BinLayout kLayout{{16, 16, 8}};

// Uniform random bins in every channel: a background with no structure.
cv::Mat noiseBins(cv::Size size, cv::RNG &rng) {
  cv::Mat bins(size, CV_8UC3);
  for (int y = 0; y < size.height; ++y)
    for (int x = 0; x < size.width; ++x)
      bins.at<cv::Vec3b>(y, x) = cv::Vec3b(rng.uniform(0, kLayout.bins[0]), rng.uniform(0, kLayout.bins[1]),
                                           rng.uniform(0, kLayout.bins[2]));
  return bins;
}

// A colour mixture: a few bins per channel, each picked at random per pixel.
struct Mixture {
  std::array<std::array<int, 3>, 3> choices;  // [channel][k]
  explicit Mixture(cv::RNG &rng) {
    for (int c = 0; c < 3; ++c)
      for (int &bin : choices[c]) bin = rng.uniform(0, kLayout.bins[c]);
  }
  void paint(cv::Mat &bins, const cv::Rect &rect, cv::RNG &rng) const {
    for (int y = rect.y; y < rect.br().y; ++y)
      for (int x = rect.x; x < rect.br().x; ++x)
        bins.at<cv::Vec3b>(y, x) = cv::Vec3b(choices[0][rng.uniform(0, 3)], choices[1][rng.uniform(0, 3)],
                                             choices[2][rng.uniform(0, 3)]);
  }
};

// A model histogram of the mixture, from its own sample (so it never matches any window perfectly).
Histogram mixtureModel(const Mixture &mixture, cv::Size size, cv::RNG &rng) {
  BinImage sample{cv::Mat(size, CV_8UC3), cv::Point()};
  mixture.paint(sample.bins, cv::Rect(cv::Point(), size), rng);
  return histogramOf(sample, kLayout, cv::Rect(cv::Point(), size));
}

struct Comparison {
  SearchResult fast, brute;
};

Comparison compare(const BinImage &image, const cv::Rect &region, cv::Size window, const Histogram &model,
                   const SearchParams &params = SearchParams(),
                   const ChannelWeights &weights = ChannelWeights()) {
  return {searchWindow(image, region, window, model, weights, params),
          searchWindowBruteForce(image, region, window, model, weights)};
}

// The fast result must be the brute-force one, or (tied scores) another position with the same score;
// its reported score must be the exact value of its box.
void expectSameAsBruteForce(const BinImage &image, const Comparison &r, const Histogram &model,
                            const std::string &what, const ChannelWeights &weights = ChannelWeights()) {
  SCOPED_TRACE(what);
  ASSERT_TRUE(r.brute.found);
  ASSERT_TRUE(r.fast.found);
  EXPECT_EQ(r.fast.box.size(), r.brute.box.size());
  EXPECT_NEAR(r.fast.score, windowMatch(image, r.fast.box, model, weights), 1e-12);
  if (r.fast.box != r.brute.box)
    EXPECT_NEAR(r.fast.score, r.brute.score, 1e-9) << "fast " << r.fast.box << " brute " << r.brute.box;
  else
    EXPECT_EQ(r.fast.score, r.brute.score);
}

}  // namespace

// Random scenes with a pasted patch of a distinct mixture: many sizes, odd widths, non-square windows,
// image origins and sub-regions.
TEST(SearchWindow, FindsThePastedPatchLikeBruteForce) {
  struct Case {
    cv::Size image, window;
    int step;
  };
  const Case cases[] = {
      {{97, 61}, {20, 20}, 0}, {{151, 83}, {31, 17}, 0}, {{64, 64}, {9, 25}, 0},   {{120, 90}, {40, 12}, 0},
      {{75, 55}, {13, 13}, 3}, {{75, 55}, {13, 13}, 7},  {{99, 71}, {24, 18}, 1},  {{81, 47}, {15, 21}, 40},
      {{53, 41}, {53, 7}, 0},  {{53, 41}, {6, 41}, 0},   {{201, 37}, {45, 30}, 0},
  };
  int seed = 1, differentPixel = 0, runs = 0;
  for (const Case &c : cases)
    for (int repeat = 0; repeat < 3; ++repeat, ++seed) {
      cv::RNG rng(seed);
      BinImage image{noiseBins(c.image, rng), cv::Point(rng.uniform(-50, 50), rng.uniform(-50, 50))};
      const Mixture mixture(rng);
      const cv::Rect patch(rng.uniform(0, c.image.width - c.window.width + 1),
                           rng.uniform(0, c.image.height - c.window.height + 1), c.window.width,
                           c.window.height);
      mixture.paint(image.bins, patch, rng);
      const Histogram model = mixtureModel(mixture, c.window, rng);
      SearchParams params;
      params.coarseStep = c.step;
      // Each repeat uses other channel weights: the default (V down), all equal, and one channel off.
      const ChannelWeights weights[] = {ChannelWeights(), ChannelWeights{{1.0, 1.0, 1.0}},
                                        ChannelWeights{{0.5, 0.0, 1.0}}};
      const Comparison r = compare(image, image.frameRect(), c.window, model, params, weights[repeat]);
      const std::string what = cv::format("image %dx%d window %dx%d step %d seed %d", c.image.width,
                                          c.image.height, c.window.width, c.window.height, c.step, seed);
      expectSameAsBruteForce(image, r, model, what, weights[repeat]);
      // The patch was found: the best box overlaps it by most of its area.
      const cv::Rect patchInFrame = patch + image.origin;
      EXPECT_GT((r.fast.box & patchInFrame).area(), patch.area() / 2) << what;
      differentPixel += r.fast.box != r.brute.box;
      ++runs;
    }
  std::printf("pasted patch: fast box differs from brute force (equal score) in %d of %d runs\n",
              differentPixel, runs);
}

TEST(SearchWindow, SubRegionsAndRegionsPastTheImage) {
  cv::RNG rng(77);
  BinImage image{noiseBins({90, 70}, rng), cv::Point(100, 200)};
  const Mixture mixture(rng);
  mixture.paint(image.bins, cv::Rect(50, 30, 15, 11), rng);
  const Histogram model = mixtureModel(mixture, {15, 11}, rng);
  const cv::Rect regions[] = {
      {120, 210, 60, 45},    // inside, patch at frame (150,230) included
      {140, 220, 29, 23},    // tight around the patch
      {60, 150, 500, 500},   // covers the whole image and more: clipped
      {170, 240, 100, 100},  // hangs off the bottom-right corner
  };
  for (const cv::Rect &region : regions) {
    const Comparison r = compare(image, region, {15, 11}, model);
    expectSameAsBruteForce(image, r, model,
                           cv::format("region %d,%d %dx%d", region.x, region.y, region.width, region.height));
    const cv::Rect allowed = region & image.frameRect();
    EXPECT_EQ(r.fast.box & allowed, r.fast.box) << "box must lie inside region and image";
  }
}

TEST(SearchWindow, EdgeCases) {
  cv::RNG rng(3);
  BinImage image{noiseBins({40, 30}, rng), cv::Point(5, -5)};
  const Histogram model = histogramOf(image, kLayout, cv::Rect(20, 0, 8, 6));
  const ChannelWeights w;

  // The window is the region: one position.
  const SearchResult whole = searchWindow(image, image.frameRect(), {40, 30}, model, w);
  ASSERT_TRUE(whole.found);
  EXPECT_EQ(whole.box, image.frameRect());
  EXPECT_NEAR(whole.score, windowMatch(image, image.frameRect(), model, w), 1e-12);

  // The window is larger than the (clipped) region, zero-sized, or the region misses the image.
  EXPECT_FALSE(searchWindow(image, image.frameRect(), {41, 10}, model, w).found);
  EXPECT_FALSE(searchWindow(image, image.frameRect(), {10, 31}, model, w).found);
  EXPECT_FALSE(searchWindow(image, cv::Rect(0, 0, 100, 100), {10, 31}, model, w).found);
  EXPECT_FALSE(searchWindow(image, image.frameRect(), {0, 5}, model, w).found);
  EXPECT_FALSE(searchWindow(image, cv::Rect(-100, -100, 50, 50), {3, 3}, model, w).found);
  EXPECT_FALSE(searchWindowBruteForce(image, image.frameRect(), {41, 10}, model, w).found);

  // One-pixel windows (step 1: the coarse pass is already exact) and one-pixel-wide strips.
  for (const cv::Size window : {cv::Size(1, 1), cv::Size(1, 12), cv::Size(17, 1)}) {
    const Comparison r = compare(image, image.frameRect(), window, model);
    expectSameAsBruteForce(image, r, model, cv::format("window %dx%d", window.width, window.height));
  }
  // The model's own window scores 1 (to float precision: model values are floats) and nothing beats it.
  const Comparison own = compare(image, image.frameRect(), {8, 6}, model);
  EXPECT_NEAR(own.brute.score, 1.0, 1e-6);
  EXPECT_EQ(own.fast.box, own.brute.box);
  EXPECT_EQ(own.fast.score, own.brute.score);
}

// Plain noise, model from another noise sample: scores are flat, so the coarse pass may pick a
// neighbourhood that is not the global best; the loss must stay small.
TEST(SearchWindow, PlainNoiseLosesLittle) {
  int differentPixel = 0, runs = 0;
  double worstLoss = 0;
  for (int seed = 100; seed < 112; ++seed) {
    cv::RNG rng(seed);
    const cv::Size window(rng.uniform(8, 30), rng.uniform(8, 30));
    BinImage image{noiseBins({rng.uniform(60, 110), rng.uniform(50, 90)}, rng), cv::Point()};
    BinImage other{noiseBins(window, rng), cv::Point()};
    const Histogram model = histogramOf(other, kLayout, other.frameRect());
    const Comparison r = compare(image, image.frameRect(), window, model);
    ASSERT_TRUE(r.fast.found);
    EXPECT_LE(r.fast.score, r.brute.score + 1e-12);
    EXPECT_GE(r.fast.score, r.brute.score - 0.05) << "seed " << seed;
    EXPECT_NEAR(r.fast.score, windowMatch(image, r.fast.box, model, ChannelWeights()), 1e-12);
    worstLoss = std::max(worstLoss, r.brute.score - r.fast.score);
    differentPixel += r.fast.box != r.brute.box;
    ++runs;
  }
  std::printf("plain noise: fast box differs from brute force in %d of %d runs, worst score loss %.4f\n",
              differentPixel, runs, worstLoss);
}

// The greedy candidate list for k is a prefix of the one for k + 1, so the refined set only grows.
TEST(SearchWindow, MoreCandidatesNeverHurt) {
  cv::RNG rng(42);
  BinImage image{noiseBins({120, 80}, rng), cv::Point()};
  BinImage other{noiseBins({24, 24}, rng), cv::Point()};
  const Histogram model = histogramOf(other, kLayout, other.frameRect());
  double previous = -1;
  for (int candidates : {1, 3, 10, 1000}) {
    SearchParams params;
    params.candidates = candidates;
    const SearchResult r = searchWindow(image, image.frameRect(), {24, 24}, model, ChannelWeights(), params);
    ASSERT_TRUE(r.found);
    EXPECT_GE(r.score, previous);
    previous = r.score;
  }
  EXPECT_LE(previous,
            searchWindowBruteForce(image, image.frameRect(), {24, 24}, model, ChannelWeights()).score);
}

// Not a timing assertion: prints the cost of a whole-frame search for the report.
TEST(SearchWindow, FullHdTiming) {
  cv::RNG rng(9);
  BinImage image{noiseBins({1920, 1080}, rng), cv::Point()};
  const Mixture mixture(rng);
  const cv::Rect patch(1234, 567, 80, 80);
  mixture.paint(image.bins, patch, rng);
  const Histogram model = mixtureModel(mixture, {80, 80}, rng);
  SearchResult r = searchWindow(image, image.frameRect(), {80, 80}, model, ChannelWeights());  // warm-up
  const int runs = 10;
  const auto start = std::chrono::steady_clock::now();
  for (int i = 0; i < runs; ++i)
    r = searchWindow(image, image.frameRect(), {80, 80}, model, ChannelWeights());
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / runs;
  std::printf("searchWindow 80x80 over 1920x1080 (bins 16,16,8): %.2f ms, box %d,%d score %.4f\n", ms,
              r.box.x, r.box.y, r.score);
  ASSERT_TRUE(r.found);
  EXPECT_GT((r.box & patch).area(), patch.area() / 2);
}
