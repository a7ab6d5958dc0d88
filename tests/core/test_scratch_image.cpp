// SPDX-License-Identifier: LGPL-2.1-or-later
// ScratchImage: views of the asked size and type, in memory that is kept while it is large enough.
#include <gtest/gtest.h>

#include <opencv2/core.hpp>

#include "colortrack/scratch_image.hpp"

using colortrack::ScratchImage;

TEST(ScratchImage, ViewHasTheAskedSizeAndTypeAndIsContinuous) {
  ScratchImage scratch;
  const cv::Mat a = scratch.view(cv::Size(37, 11), CV_8UC3);
  EXPECT_EQ(a.size(), cv::Size(37, 11));
  EXPECT_EQ(a.type(), CV_8UC3);
  EXPECT_TRUE(a.isContinuous());
  const cv::Mat b = scratch.view(cv::Size(5, 3), CV_32FC1);
  EXPECT_EQ(b.size(), cv::Size(5, 3));
  EXPECT_EQ(b.type(), CV_32FC1);
  EXPECT_TRUE(b.isContinuous());
}

TEST(ScratchImage, SmallerOrSlightlyLargerViewsReuseTheMemory) {
  ScratchImage scratch;
  const uchar *first = scratch.view(cv::Size(100, 100), CV_8UC3).data;
  EXPECT_EQ(scratch.view(cv::Size(60, 90), CV_8UC3).data, first);
  EXPECT_EQ(scratch.view(cv::Size(100, 75), CV_32FC1).data, first);  // the same number of bytes
  // A quarter more than first asked is kept, so a region growing a little does not reallocate.
  EXPECT_EQ(scratch.view(cv::Size(110, 110), CV_8UC3).data, first);
  const cv::Mat larger = scratch.view(cv::Size(200, 200), CV_8UC3);
  EXPECT_EQ(larger.size(), cv::Size(200, 200));
  EXPECT_EQ(scratch.view(cv::Size(100, 100), CV_8UC3).data, larger.data);
}

TEST(ScratchImage, OpenCvWritesIntoTheView) {
  ScratchImage scratch;
  cv::Mat out = scratch.view(cv::Size(8, 4), CV_8UC1);
  const uchar *where = out.data;
  cv::Mat source(4, 8, CV_8UC1, cv::Scalar(7));
  source.copyTo(out);  // size and type match: no new allocation
  EXPECT_EQ(out.data, where);
  EXPECT_EQ(cv::countNonZero(scratch.view(cv::Size(8, 4), CV_8UC1) == 7), 32);
}
