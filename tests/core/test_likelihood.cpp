// SPDX-License-Identifier: LGPL-2.1-or-later
// Object-versus-surroundings colour likelihood: hand-computed cases.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "colortrack/color.hpp"
#include "colortrack/likelihood.hpp"

using namespace colortrack;

namespace {

const cv::Vec3b kRed(0, 0, 255), kGreen(0, 200, 0), kBlue(255, 0, 0), kYellow(0, 255, 255);

// 40x40 green surroundings, a 20x20 object at (10,10): red except a blue column of 20 px (5%), and 20 blue
// pixels out in the surroundings.
cv::Mat makeImage() {
  cv::Mat img(40, 40, CV_8UC3, cv::Scalar(kGreen[0], kGreen[1], kGreen[2]));
  img(cv::Rect(10, 10, 20, 20)).setTo(cv::Scalar(kRed[0], kRed[1], kRed[2]));
  img(cv::Rect(10, 10, 1, 20)).setTo(cv::Scalar(kBlue[0], kBlue[1], kBlue[2]));
  img(cv::Rect(0, 0, 20, 1)).setTo(cv::Scalar(kBlue[0], kBlue[1], kBlue[2]));
  return img;
}

struct Fixture {
  BinMapper mapper{ColorSpace::Hsv, BinLayout{}};
  ColorLikelihood likelihood{BinLayout{}};
  BinImage bins;
  Fixture() { mapper.map(makeImage(), bins.bins); }
  float p(const cv::Vec3b &bgr) {
    cv::Mat px(1, 1, CV_8UC3, cv::Scalar(bgr[0], bgr[1], bgr[2])), b;
    mapper.map(px, b);
    return likelihood.probability(likelihood.jointBin(b.at<cv::Vec3b>(0, 0)));
  }
};

}  // namespace

TEST(Likelihood, UnlearntIsOneHalf) {
  Fixture f;
  EXPECT_TRUE(f.likelihood.empty());
  EXPECT_FLOAT_EQ(f.p(kRed), 0.5f);
}

TEST(Likelihood, LearnsObjectAgainstSurroundings) {
  Fixture f;
  f.likelihood.learn(f.bins, cv::Rect(10, 10, 20, 20), cv::Rect(0, 0, 40, 40), 1.0);
  EXPECT_FALSE(f.likelihood.empty());
  EXPECT_FLOAT_EQ(f.p(kRed), 1.0f);     // only in the object
  EXPECT_FLOAT_EQ(f.p(kGreen), 0.0f);   // only around it
  EXPECT_FLOAT_EQ(f.p(kBlue), 0.5f);    // 20 pixels in each: H_O / (H_O + H_S)
  EXPECT_FLOAT_EQ(f.p(kYellow), 0.5f);  // never seen
}

TEST(Likelihood, SlowUpdateBlends) {
  Fixture f;
  f.likelihood.learn(f.bins, cv::Rect(10, 10, 20, 20), cv::Rect(0, 0, 40, 40), 1.0);
  // Learn again with the object box on pure surroundings: green now belongs to the object.
  f.likelihood.learn(f.bins, cv::Rect(30, 30, 10, 10), cv::Rect(30, 30, 10, 10), 0.1);
  EXPECT_NEAR(f.p(kGreen), 0.1, 1e-6);  // 0.9 * 0 + 0.1 * 1
  EXPECT_NEAR(f.p(kRed), 0.95, 1e-6);   // unseen in the new sample (0.5) blended in at 0.1
}

TEST(Likelihood, MapsEveryPixelAndClipsLearning) {
  Fixture f;
  // Surroundings beyond the image are clipped, not read.
  f.likelihood.learn(f.bins, cv::Rect(10, 10, 20, 20), cv::Rect(-20, -20, 80, 80), 1.0);
  cv::Mat probability;
  f.likelihood.map(f.bins, probability);
  ASSERT_EQ(probability.type(), CV_32FC1);
  ASSERT_EQ(probability.size(), cv::Size(40, 40));
  EXPECT_FLOAT_EQ(probability.at<float>(20, 20), 1.0f);
  EXPECT_FLOAT_EQ(probability.at<float>(35, 35), 0.0f);
  cv::Mat integral;
  cv::integral(probability, integral, CV_64F);
  EXPECT_NEAR(boxSum(integral, cv::Rect(11, 10, 19, 20)), 19 * 20, 1e-9);  // the red part of the object
}

TEST(Likelihood, FineBinsAreCoarsenedToABoundedTable) {
  const BinLayout fine{{256, 256, 256}};
  ColorLikelihood likelihood(fine);
  EXPECT_LE(likelihood.tableSize(), ColorLikelihood::kMaxJointBins);
  EXPECT_GE(likelihood.tableSize(), ColorLikelihood::kMaxJointBins / 8);
  // Still learns: the object's colour against the surroundings'.
  BinMapper mapper(ColorSpace::Hsv, fine);
  BinImage bins;
  mapper.map(makeImage(), bins.bins);
  likelihood.learn(bins, cv::Rect(10, 10, 20, 20), cv::Rect(0, 0, 40, 40), 1.0);
  cv::Mat probability;
  likelihood.map(bins, probability);
  EXPECT_FLOAT_EQ(probability.at<float>(20, 20), 1.0f);  // red, only in the object
  EXPECT_FLOAT_EQ(probability.at<float>(35, 35), 0.0f);  // green, only around it
}

// Against a whole image: the object's learnt colour shares (red 380 / 400, blue 20 / 400 px) at the given
// object area, against each colour's count in the image itself.
TEST(Likelihood, AgainstTheWholeImage) {
  Fixture f;
  f.likelihood.learn(f.bins, cv::Rect(10, 10, 20, 20), cv::Rect(0, 0, 40, 40), 1.0);
  // Another frame: yellow, a 10x10 red patch and a 20x20 blue one.
  cv::Mat frame(40, 40, CV_8UC3, cv::Scalar(kYellow[0], kYellow[1], kYellow[2]));
  frame(cv::Rect(0, 0, 10, 10)).setTo(cv::Scalar(kRed[0], kRed[1], kRed[2]));
  frame(cv::Rect(20, 20, 20, 20)).setTo(cv::Scalar(kBlue[0], kBlue[1], kBlue[2]));
  BinImage bins;
  f.mapper.map(frame, bins.bins);
  cv::Mat probability;
  ImageColours image;
  f.likelihood.countImageColours(bins, image);
  f.likelihood.mapAgainstImage(bins, 100, image, probability);
  ASSERT_EQ(probability.type(), CV_32FC1);
  ASSERT_EQ(probability.size(), frame.size());
  EXPECT_NEAR(probability.at<float>(5, 5), 95.0 / (95 + 100), 1e-6);  // red: 0.95 * 100 against 100 px
  EXPECT_NEAR(probability.at<float>(30, 30), 5.0 / (5 + 400), 1e-6);  // blue: 0.05 * 100 against 400 px
  // A colour the object never showed is background here; the map against the surroundings calls it unknown.
  EXPECT_FLOAT_EQ(probability.at<float>(5, 30), 0.0f);
  f.likelihood.map(bins, probability);
  EXPECT_FLOAT_EQ(probability.at<float>(5, 30), 0.5f);
  EXPECT_FLOAT_EQ(probability.at<float>(30, 30), 0.5f);
}

TEST(Likelihood, AgainstTheWholeImageBlendsTheObjectsColours) {
  Fixture f;
  f.likelihood.learn(f.bins, cv::Rect(10, 10, 20, 20), cv::Rect(0, 0, 40, 40), 1.0);
  // The object turns green (a box on the surroundings), learnt at rate 0.1: red keeps 0.9 of its share.
  f.likelihood.learn(f.bins, cv::Rect(30, 30, 10, 10), cv::Rect(30, 30, 10, 10), 0.1);
  cv::Mat red(4, 4, CV_8UC3, cv::Scalar(kRed[0], kRed[1], kRed[2]));
  BinImage bins;
  f.mapper.map(red, bins.bins);
  cv::Mat probability;
  ImageColours image;
  f.likelihood.countImageColours(bins, image);
  f.likelihood.mapAgainstImage(bins, 16, image, probability);
  const double object = 16 * 0.9 * 0.95;
  EXPECT_NEAR(probability.at<float>(0, 0), object / (object + 16), 1e-5);
}
