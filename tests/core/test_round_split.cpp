// SPDX-License-Identifier: LGPL-2.1-or-later
// Telling several round objects in one blob from one object: balls that touch or overlap are split into a
// disc each; one ball, a ball cut by an edge, and long or irregular shapes are not.
#include <gtest/gtest.h>

#include <vector>

#include <opencv2/imgproc.hpp>

#include "colortrack/round_split.hpp"

using namespace colortrack;

namespace {

// The mask's blobs, labelled and measured as BlobDetector does (the mask is on a grid of the given step).
struct Labelled {
  std::vector<Blob> blobs;
  BlobLabels labels;
};

Labelled labelAll(const cv::Mat &mask, int step = 1) {
  Labelled out;
  const int count = cv::connectedComponents(mask, out.labels.labels, 8, CV_32S);
  out.labels.step = step;
  for (int label = 1; label < count; ++label) {
    GridMoments m;
    for (int y = 0; y < mask.rows; ++y)
      for (int x = 0; x < mask.cols; ++x)
        if (out.labels.labels.at<int>(y, x) == label) m.add(x, y);
    Blob b = m.toBlob(step, cv::Rect(0, 0, mask.cols * step, mask.rows * step));
    b.label = label;
    out.blobs.push_back(b);
  }
  return out;
}

std::vector<Blob> partsOf(const cv::Mat &mask, int step = 1) {
  const Labelled l = labelAll(mask, step);
  EXPECT_EQ(l.blobs.size(), 1u);
  return splitRound(l.blobs.front(), l.labels, 50);
}

}  // namespace

TEST(RoundSplit, TwoOverlappingBallsBecomeOneBlobEach) {
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8U);
  cv::circle(mask, {100, 100}, 30, 255, cv::FILLED);
  cv::circle(mask, {135, 120}, 16, 255, cv::FILLED);  // overlaps the large one
  std::vector<Blob> parts = partsOf(mask);
  ASSERT_EQ(parts.size(), 2u);
  std::sort(parts.begin(), parts.end(), [](const Blob &a, const Blob &b) { return a.area > b.area; });
  // Placed and sized by their discs, though the small one's share is cut where the large one covers it.
  EXPECT_NEAR(parts[0].centroid.x, 100, 2);
  EXPECT_NEAR(parts[0].centroid.y, 100, 2);
  EXPECT_NEAR(parts[0].box.width, 61, 3);
  EXPECT_NEAR(parts[1].centroid.x, 135, 2);
  EXPECT_NEAR(parts[1].centroid.y, 120, 2);
  EXPECT_NEAR(parts[1].box.width, 33, 3);
  EXPECT_EQ(parts[0].label, parts[1].label);
}

TEST(RoundSplit, BallsJoinedByANarrowBridgeAreSplitOnADecimatedGrid) {
  // Two balls a few pixels apart that the closing joined, on a grid of every second pixel.
  cv::Mat mask = cv::Mat::zeros(120, 160, CV_8U);
  cv::circle(mask, {50, 60}, 20, 255, cv::FILLED);
  cv::circle(mask, {83, 60}, 11, 255, cv::FILLED);
  cv::rectangle(mask, cv::Rect(68, 57, 6, 6), 255, cv::FILLED);
  const std::vector<Blob> parts = partsOf(mask, 2);
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_NEAR(parts[0].centroid.x, 100, 4);  // frame coordinates: twice the grid's
  EXPECT_NEAR(parts[1].centroid.x, 166, 4);
}

TEST(RoundSplit, OneBallIsNotSplit) {
  cv::Mat mask = cv::Mat::zeros(200, 200, CV_8U);
  cv::circle(mask, {100, 100}, 40, 255, cv::FILLED);
  EXPECT_TRUE(partsOf(mask).empty());
}

TEST(RoundSplit, ABallCutByAnEdgeIsNotSplit) {
  // A ball half behind a board, and one with a notch: one object each.
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8U);
  cv::circle(mask, {100, 100}, 40, 255, cv::FILLED);
  mask(cv::Rect(100, 0, 200, 200)).setTo(0);
  EXPECT_TRUE(partsOf(mask).empty());
  mask.setTo(0);
  cv::circle(mask, {150, 100}, 40, 255, cv::FILLED);
  cv::circle(mask, {150, 140}, 15, 0, cv::FILLED);
  EXPECT_TRUE(partsOf(mask).empty());
}

TEST(RoundSplit, LongShapesAreNotSplit) {
  // An ellipse, a capsule and a bar: peaks along a ridge with no neck between them.
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8U);
  cv::ellipse(mask, {150, 100}, {80, 30}, 20, 0, 360, 255, cv::FILLED);
  EXPECT_TRUE(partsOf(mask).empty());
  mask.setTo(0);
  cv::line(mask, {80, 100}, {220, 100}, 255, 40);  // round caps
  EXPECT_TRUE(partsOf(mask).empty());
  mask.setTo(0);
  mask(cv::Rect(50, 80, 200, 30)).setTo(255);
  EXPECT_TRUE(partsOf(mask).empty());
}

TEST(RoundSplit, ShapesTheDiscsDoNotExplainAreNotSplit) {
  // Two balls joined by a thick band: discs at the two peaks leave much of the blob.
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8U);
  cv::circle(mask, {60, 100}, 25, 255, cv::FILLED);
  cv::circle(mask, {240, 100}, 25, 255, cv::FILLED);
  mask(cv::Rect(60, 85, 180, 30)).setTo(255);
  EXPECT_TRUE(partsOf(mask).empty());
}

TEST(RoundSplit, PartsUnderTheMinimumAreaOrWithoutLabelsAreNoSplit) {
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8U);
  cv::circle(mask, {100, 100}, 30, 255, cv::FILLED);
  cv::circle(mask, {135, 120}, 16, 255, cv::FILLED);
  const Labelled l = labelAll(mask);
  ASSERT_EQ(l.blobs.size(), 1u);
  EXPECT_EQ(splitRound(l.blobs.front(), l.labels, 50).size(), 2u);
  EXPECT_TRUE(splitRound(l.blobs.front(), l.labels, 1000).empty());  // the small ball is under it
  EXPECT_TRUE(splitRound(l.blobs.front(), BlobLabels(), 50).empty());
}
