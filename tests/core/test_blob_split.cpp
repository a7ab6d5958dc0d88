// SPDX-License-Identifier: LGPL-2.1-or-later
// Sharing one blob between touching objects: each share follows the pixels nearest its seed, and the pixels
// no other seed could claim tell a visible object from one wholly behind another.
#include <gtest/gtest.h>

#include <vector>

#include <opencv2/imgproc.hpp>

#include "colortrack/blob_split.hpp"

using namespace colortrack;

namespace {

// The one blob of a mask, labelled as BlobDetector labels it.
struct LabelledBlob {
  Blob blob;
  BlobLabels labels;
};

LabelledBlob labelOf(const cv::Mat &mask, int step = 1) {
  LabelledBlob out;
  cv::connectedComponents(mask, out.labels.labels, 8, CV_32S);
  out.labels.step = step;
  const cv::Rect grid = cv::boundingRect(mask);
  std::vector<cv::Point> pixels;
  cv::findNonZero(mask, pixels);
  out.blob.label = out.labels.labels.at<int>(pixels.front());
  out.blob.box = cv::Rect(grid.x * step, grid.y * step, grid.width * step, grid.height * step);
  out.blob.area = static_cast<double>(pixels.size()) * step * step;
  return out;
}

}  // namespace

TEST(BlobSplit, TwoTouchingDiscsGetTheirOwnPixels) {
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8U);
  cv::circle(mask, {100, 100}, 30, 255, cv::FILLED);
  cv::circle(mask, {150, 100}, 30, 255, cv::FILLED);  // overlaps the first by 10 px
  const LabelledBlob lb = labelOf(mask);
  // Seeds a few pixels off, as predictions are.
  const std::vector<BlobShare> shares = splitBlob(lb.blob, lb.labels, {{{103, 98}, 30}, {{147, 102}, 30}});
  ASSERT_EQ(shares.size(), 2u);
  for (int s = 0; s < 2; ++s) {
    EXPECT_NEAR(shares[s].blob.area, lb.blob.area / 2, 0.05 * lb.blob.area) << s;
    EXPECT_GT(shares[s].ownArea, 0.7 * shares[s].blob.area) << s;
    EXPECT_EQ(shares[s].blob.box.height, 61) << s;  // the whole disc's height: the split is vertical
  }
  // Each share's outer edge is its own disc's.
  EXPECT_EQ(shares[0].blob.box.x, 70);
  EXPECT_EQ(shares[1].blob.box.x + shares[1].blob.box.width - 1, 180);
  EXPECT_NEAR(shares[0].blob.area + shares[1].blob.area, lb.blob.area, 1e-9);
}

TEST(BlobSplit, AnObjectWhollyBehindAnotherHasNoPixelsOfItsOwn) {
  cv::Mat mask = cv::Mat::zeros(200, 300, CV_8U);
  cv::circle(mask, {150, 100}, 40, 255, cv::FILLED);
  const LabelledBlob lb = labelOf(mask);
  // A small object's prediction inside the large one: it may take the pixels around it, but none of them lies
  // outside the large object's disc.
  const std::vector<BlobShare> shares = splitBlob(lb.blob, lb.labels, {{{150, 100}, 40}, {{170, 100}, 12}});
  EXPECT_GT(shares[1].blob.area, 0);
  EXPECT_EQ(shares[1].ownArea, 0);
  EXPECT_GT(shares[0].ownArea, 0);
}

TEST(BlobSplit, WorksOnADecimatedGridInFrameCoordinates) {
  cv::Mat grid = cv::Mat::zeros(100, 150, CV_8U);  // a 300 x 200 frame segmented every 2nd pixel
  cv::circle(grid, {50, 50}, 15, 255, cv::FILLED);
  cv::circle(grid, {75, 50}, 15, 255, cv::FILLED);
  const LabelledBlob lb = labelOf(grid, 2);
  const std::vector<BlobShare> shares = splitBlob(lb.blob, lb.labels, {{{100, 100}, 30}, {{150, 100}, 30}});
  EXPECT_NEAR(shares[0].blob.centroid.x, 96, 3);  // a disc at 100 less the sliver beyond the middle
  EXPECT_NEAR(shares[0].blob.centroid.y, 100, 1);
  EXPECT_NEAR(shares[1].blob.centroid.x, 154, 3);
  EXPECT_NEAR(shares[0].blob.area + shares[1].blob.area, lb.blob.area, 1e-9);
}

TEST(BlobSplit, NothingWithoutLabels) {
  Blob blob;
  blob.area = 100;
  blob.box = cv::Rect(0, 0, 10, 10);
  const std::vector<BlobShare> shares = splitBlob(blob, BlobLabels(), {{{5, 5}, 5}, {{8, 8}, 5}});
  ASSERT_EQ(shares.size(), 2u);
  EXPECT_EQ(shares[0].blob.area, 0);
  EXPECT_EQ(shares[1].blob.area, 0);
}
