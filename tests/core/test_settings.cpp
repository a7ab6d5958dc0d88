// SPDX-License-Identifier: LGPL-2.1-or-later
// Parsing and formatting of the user-facing setting strings.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "colortrack/settings.hpp"
#include "support/status_helpers.hpp"

using namespace colortrack;

TEST(ParseBins, AcceptsThreeIntegersWithSpaces) {
  auto bins = parseBins("16,16,8");
  ASSERT_TRUE(bins);
  EXPECT_EQ(bins->bins, (std::array<int, 3>{16, 16, 8}));
  bins = parseBins(" 1 , 256,\t7 ");
  ASSERT_TRUE(bins);
  EXPECT_EQ(bins->bins, (std::array<int, 3>{1, 256, 7}));
}

TEST(ParseBins, RejectsMalformedWithAReason) {
  for (const char *bad : {"", "16", "16,16", "16,16,8,4", "16,x,8", "16,,8", "16,16,8,", "0,16,8", "16,257,8",
                          "-1,16,8", "16.5,16,8", "16 16 8", "1e1,16,8", "16,16,8x", "99999999999,1,1"}) {
    std::string error;
    EXPECT_FALSE(okOr(parseBins(bad), error)) << '"' << bad << '"';
    EXPECT_FALSE(error.empty()) << '"' << bad << '"';
  }
  std::string error;
  okOr(parseBins("16,x"), error);
  EXPECT_EQ(error, "expected three integers 1..256 separated by commas, got \"16,x\"");
  okOr(parseBins("16,300,8"), error);
  EXPECT_NE(error.find("300"), std::string::npos) << error;
  EXPECT_FALSE(parseBins("0,1,1"));  // no error pointer: still fine
}

TEST(ParseWeights, AcceptsNumbersInUnitInterval) {
  auto w = parseWeights("1,1,0.3");
  ASSERT_TRUE(w);
  EXPECT_EQ(w->w, (std::array<double, 3>{1.0, 1.0, 0.3}));
  w = parseWeights(" 0 , .5 ,1e-1");
  ASSERT_TRUE(w);
  EXPECT_EQ(w->w, (std::array<double, 3>{0.0, 0.5, 0.1}));
}

TEST(ParseWeights, RejectsMalformedWithAReason) {
  for (const char *bad : {"", "1,1", "1,1,1,1", "1,,1", "1,1,a", "1,1,1.5", "-0.1,1,1", "1,1,nan", "1,1,inf",
                          "1;1;1", "0,5,1,1"}) {
    std::string error;
    EXPECT_FALSE(okOr(parseWeights(bad), error)) << '"' << bad << '"';
    EXPECT_FALSE(error.empty()) << '"' << bad << '"';
  }
  std::string error;
  okOr(parseWeights("1,2,0"), error);
  EXPECT_NE(error.find("[0, 1]"), std::string::npos) << error;
  // As good as zero: refused like all zero.
  for (const char *zero : {"0,0,0", "-0,0,1e-320", "0.0001,0.0001,0.0001"}) {
    EXPECT_FALSE(okOr(parseWeights(zero), error)) << zero;
    EXPECT_NE(error.find("add up"), std::string::npos) << error;
  }
  const auto negativeZero = parseWeights("-0,0,1");
  ASSERT_TRUE(negativeZero);
  EXPECT_FALSE(std::signbit(negativeZero->w[0]));
}

TEST(ParseBox, AcceptsFourIntegers) {
  auto box = parseBox("10, 20, 30, 40");
  ASSERT_TRUE(box);
  EXPECT_EQ(*box, cv::Rect(10, 20, 30, 40));
  box = parseBox("0,0,1,1");
  ASSERT_TRUE(box);
  EXPECT_EQ(*box, cv::Rect(0, 0, 1, 1));
}

TEST(ParseBox, RejectsMalformedWithAReason) {
  for (const char *bad : {"", "1,2,3", "1,2,3,4,5", "-1,0,5,5", "0,-1,5,5", "0,0,0,5", "0,0,5,0", "0,0,-5,5",
                          "a,0,5,5", "0,0,5.5,5", "0 0 5 5", "2147483647,0,1,1"}) {
    std::string error;
    EXPECT_FALSE(okOr(parseBox(bad), error)) << '"' << bad << '"';
    EXPECT_FALSE(error.empty()) << '"' << bad << '"';
  }
  std::string error;
  okOr(parseBox("0,0,0,5"), error);
  EXPECT_NE(error.find("width"), std::string::npos) << error;
  okOr(parseBox("-3,0,5,5"), error);
  EXPECT_NE(error.find(">= 0"), std::string::npos) << error;
}

TEST(Format, RoundTrips) {
  for (const BinLayout &layout : {BinLayout{{16, 16, 8}}, BinLayout{{1, 256, 37}}}) {
    const std::string text = formatBins(layout);
    const auto back = parseBins(text);
    ASSERT_TRUE(back) << text;
    EXPECT_EQ(*back, layout);
  }
  EXPECT_EQ(formatBins(BinLayout{{16, 16, 8}}), "16,16,8");

  ChannelWeights w;
  EXPECT_EQ(formatWeights(w), "1,1,0.3");
  w.w = {0.0, 0.125, 0.999};
  EXPECT_EQ(formatWeights(w), "0,0.125,0.999");
  for (const auto &values : {std::array<double, 3>{0.0, 0.5, 1.0}, std::array<double, 3>{0.3, 0.25, 0.001},
                             std::array<double, 3>{0.12345, 0.00001, 0.6789}}) {
    w.w = values;
    const std::string text = formatWeights(w);
    const auto back = parseWeights(text);
    ASSERT_TRUE(back) << text;
    for (int c = 0; c < 3; ++c)  // three significant digits
      EXPECT_NEAR(back->w[c], values[c], 0.005 * values[c] + 1e-12) << text;
  }

  for (const cv::Rect &box : {cv::Rect(0, 0, 1, 1), cv::Rect(12, 34, 56, 78)}) {
    const auto back = parseBox(formatBox(box));
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, box);
  }
  EXPECT_EQ(formatBox(cv::Rect(1, 2, 3, 4)), "1,2,3,4");
}
