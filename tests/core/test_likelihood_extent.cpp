// SPDX-License-Identifier: LGPL-2.1-or-later
// The colour extent vote: on a likelihood map holding one object-like rectangle, the box it picks.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "colortrack/likelihood_extent.hpp"

using namespace colortrack;

namespace {

// A 200x200 likelihood map at 0.2 with a 60x40 rectangle at 0.9 centred at (100, 100), as an integral image.
cv::Mat integralOfRectangle(cv::Size object) {
  cv::Mat map(200, 200, CV_32F, cv::Scalar(0.2));
  map(cv::Rect(100 - object.width / 2, 100 - object.height / 2, object.width, object.height)).setTo(0.9);
  cv::Mat integral;
  cv::integral(map, integral, CV_64F);
  return integral;
}

std::vector<double> factors() {
  return {0.8, 0.85, 0.9, 0.95, 1.05, 1.1, 1.15, 1.2};
}

}  // namespace

TEST(LikelihoodExtent, ShrinksATooLargeBoxToTheObject) {
  const ExtentVote vote =
      likelihoodExtent(integralOfRectangle({60, 40}), {100, 100}, {72, 48}, factors(), {}, 0.25);
  EXPECT_NEAR(72 * vote.factor.width, 60, 3);
  EXPECT_NEAR(48 * vote.factor.height, 40, 3);
  EXPECT_GT(vote.contrast, 0.5);
}

TEST(LikelihoodExtent, GrowsEachAxisOnItsOwn) {
  // Width right, height too small: the height grows by 15 %, the width stays within a step (whole-pixel
  // rounding of the boxes).
  const ExtentVote vote =
      likelihoodExtent(integralOfRectangle({60, 40}), {100, 100}, {60, 34}, factors(), {}, 0.25);
  EXPECT_NEAR(vote.factor.width, 1.0, 0.05 + 1e-9);
  EXPECT_NEAR(34 * vote.factor.height, 40, 2);
}

TEST(LikelihoodExtent, KeepsTheSizeOnAFlatMap) {
  cv::Mat flat(200, 200, CV_32F, cv::Scalar(0.5)), integral;
  cv::integral(flat, integral, CV_64F);
  const ExtentVote vote = likelihoodExtent(integral, {100, 100}, {60, 40}, factors(), {}, 0.25);
  EXPECT_EQ(vote.factor, cv::Size2d(1, 1));
  EXPECT_NEAR(vote.contrast, 0, 1e-9);
}

TEST(LikelihoodExtent, NeverTriesABoxOffTheMap) {
  // The object touches the map's left edge: a wider box would reach past it, where nothing can be measured.
  cv::Mat map(200, 200, CV_32F, cv::Scalar(0.2)), integral;
  map(cv::Rect(0, 80, 60, 40)).setTo(0.9);
  cv::integral(map, integral, CV_64F);
  const ExtentVote vote = likelihoodExtent(integral, {30, 100}, {52, 40}, factors(), {}, 0.25);
  EXPECT_GT(52 * vote.factor.width, 52);
  EXPECT_LE(52 * vote.factor.width, 60);
}

TEST(LikelihoodExtent, MovesABoxPlacedOffTheObjectOntoIt) {
  // Tried 6 px right and 4 px below the rectangle's centre (a tenth of its size): the vote moves it back.
  const ExtentVote vote = likelihoodExtent(integralOfRectangle({60, 40}), {106, 104}, {60, 40}, factors(),
                                           {-0.1, -0.05, 0.05, 0.1}, 0.25);
  EXPECT_NEAR(106 + 60 * vote.shift.x, 100, 1e-9);
  EXPECT_NEAR(104 + 40 * vote.shift.y, 100, 1e-9);
  EXPECT_NEAR(vote.factor.width, 1.0, 1e-9);
  EXPECT_NEAR(vote.factor.height, 1.0, 1e-9);
}

TEST(LikelihoodExtent, KeepsABoxOnTheObjectWhereItIs) {
  const ExtentVote vote = likelihoodExtent(integralOfRectangle({60, 40}), {100, 100}, {60, 40}, factors(),
                                           {-0.1, -0.05, 0.05, 0.1}, 0.25);
  EXPECT_EQ(vote.shift, cv::Point2d(0, 0));
}
