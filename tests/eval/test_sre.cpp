// SPDX-License-Identifier: LGPL-2.1-or-later
// The SRE start boxes, worked out by hand on a box whose 10 % steps are whole pixels, and the start offset
// the tools take.
#include <gtest/gtest.h>

#include "sre.hpp"

namespace colortrack::eval {
namespace {

TEST(Sre, EightPerturbedStartsAfterTheOpeOne) {
  const cv::Rect2d box(100, 200, 40, 60);  // 10 %: 4 px across, 6 px down
  const std::vector<StartBox> starts = startBoxes(box, cv::Size(640, 480), true);
  ASSERT_EQ(starts.size(), 1u + kSreStarts);
  EXPECT_EQ(starts[0].name, "ope");
  EXPECT_EQ(starts[0].box, cv::Rect(100, 200, 40, 60));
  EXPECT_EQ(starts[1].box, cv::Rect(96, 200, 40, 60));   // left
  EXPECT_EQ(starts[2].box, cv::Rect(104, 200, 40, 60));  // right
  EXPECT_EQ(starts[3].box, cv::Rect(100, 194, 40, 60));  // up
  EXPECT_EQ(starts[4].box, cv::Rect(100, 206, 40, 60));  // down
  EXPECT_EQ(starts[5].box, cv::Rect(96, 194, 40, 60));   // up-left
  EXPECT_EQ(starts[6].box, cv::Rect(104, 206, 40, 60));  // down-right
  EXPECT_EQ(starts[7].box, cv::Rect(102, 203, 36, 54));  // 0.9 about the centre (120, 230)
  EXPECT_EQ(starts[8].box, cv::Rect(98, 197, 44, 66));   // 1.1
  EXPECT_EQ(startBoxes(box, cv::Size(640, 480), false).size(), 1u);
}

TEST(Sre, StartsAreClippedToTheFrame) {
  const cv::Rect2d corner(0, 0, 40, 60);
  const std::vector<StartBox> starts = startBoxes(corner, cv::Size(200, 100), true);
  EXPECT_EQ(starts[1].box, cv::Rect(0, 0, 36, 60));  // left: the 4 px past the edge are cut off
  EXPECT_EQ(starts[5].box, cv::Rect(0, 0, 36, 54));  // up-left
  EXPECT_EQ(starts[8].box, cv::Rect(0, 0, 42, 63));  // 1.1 from (-2, -3, 44, 66)
}

TEST(StartOffset, ParsesWholePixelsAndRefusesTheRest) {
  EXPECT_EQ(parseStartOffset("1,0"), cv::Point(1, 0));
  EXPECT_EQ(parseStartOffset("-1,-2"), cv::Point(-1, -2));
  for (const char *bad : {"1", "1,", ",1", "1,z", "1.5,0", "1,0,0", ""})
    EXPECT_FALSE(parseStartOffset(bad).has_value()) << "'" << bad << "'";
}

}  // namespace
}  // namespace colortrack::eval
