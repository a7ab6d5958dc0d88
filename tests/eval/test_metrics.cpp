// SPDX-License-Identifier: LGPL-2.1-or-later
// The evaluation metrics on hand-made boxes, with the expected figures worked out by hand from the OTB
// definitions (success: IoU > t for t = 0, 0.05, ..., 1; precision: centre error <= t px).
#include <gtest/gtest.h>

#include <limits>

#include "metrics.hpp"

namespace colortrack::eval {
namespace {

TEST(GroundTruth, ParsesEverySeparatorCrlfAndNan) {
  const std::string text =
      "10,20,30,40\r\n11\t21\t31\t41\r\n12 22 32 42\nNaN,NaN,NaN,NaN\n1.5, 2.5, 3.5, 4.5\n\n";
  std::vector<GroundTruthBox> boxes;
  std::string error;
  ASSERT_TRUE(parseGroundTruth(text, 1.0, boxes, &error)) << error;
  ASSERT_EQ(boxes.size(), 5u);
  EXPECT_EQ(*boxes[0], cv::Rect2d(9, 19, 30, 40));  // 1-based to 0-based: x and y move, w and h do not
  EXPECT_EQ(*boxes[1], cv::Rect2d(10, 20, 31, 41));
  EXPECT_EQ(*boxes[2], cv::Rect2d(11, 21, 32, 42));
  EXPECT_FALSE(boxes[3].has_value());
  EXPECT_EQ(*boxes[4], cv::Rect2d(0.5, 1.5, 3.5, 4.5));

  ASSERT_TRUE(parseGroundTruth("10,20,30,40\n", 0.0, boxes, &error));
  EXPECT_EQ(*boxes[0], cv::Rect2d(10, 20, 30, 40));
}

TEST(GroundTruth, RejectsMalformedLinesAndKeepsEmptyBoxesOut) {
  std::vector<GroundTruthBox> boxes;
  std::string error;
  EXPECT_FALSE(parseGroundTruth("1,2,3\n", 1.0, boxes, &error));
  EXPECT_NE(error.find("line 1"), std::string::npos);
  EXPECT_FALSE(parseGroundTruth("1,2,3,4\n1,2,x,4\n", 1.0, boxes, &error));
  EXPECT_NE(error.find("line 2"), std::string::npos);
  EXPECT_FALSE(parseGroundTruth("1,2,3,4\n\n1,2,3,4\n", 1.0, boxes, &error));
  ASSERT_TRUE(parseGroundTruth("1,2,0,4\n", 1.0, boxes, &error));
  ASSERT_EQ(boxes.size(), 1u);
  EXPECT_FALSE(boxes[0].has_value());
}

TEST(Boxes, OverlapAndCentreDistance) {
  const cv::Rect2d a(0, 0, 10, 10);
  EXPECT_DOUBLE_EQ(overlap(a, a), 1.0);
  EXPECT_DOUBLE_EQ(overlap(a, cv::Rect2d(5, 0, 10, 10)), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(overlap(a, cv::Rect2d(2.5, 2.5, 5, 5)), 25.0 / 100.0);
  EXPECT_DOUBLE_EQ(overlap(a, cv::Rect2d(10, 0, 10, 10)), 0.0);  // touching edges share no area
  EXPECT_DOUBLE_EQ(overlap(a, cv::Rect2d(0, 0, 0, 10)), 0.0);
  EXPECT_DOUBLE_EQ(centreDistance(a, cv::Rect2d(3, 4, 10, 10)), 5.0);
}

TEST(Score, HandMadeSequence) {
  const cv::Rect2d box(100, 100, 10, 10);
  // Frame 0 exact, frame 1 shifted by half a width (IoU 1/3, centre error 5 px), frame 2 a miss, frame 3
  // without ground truth (not scored even though the tracker has a box), frame 4 past the tracker's output.
  const std::vector<GroundTruthBox> gt = {box, box, box, std::nullopt, box};
  const std::vector<std::optional<cv::Rect2d>> tracked = {box, cv::Rect2d(105, 100, 10, 10), std::nullopt,
                                                          box};
  const SequenceScore s = scoreSequence(gt, tracked);
  EXPECT_EQ(s.scoredFrames, 4);
  ASSERT_EQ(s.success.size(), static_cast<std::size_t>(kSuccessSteps));
  ASSERT_EQ(s.precision.size(), static_cast<std::size_t>(kPrecisionSteps));
  EXPECT_DOUBLE_EQ(s.success[0], 2.0 / 4);  // IoU > 0: the exact and the shifted frame
  EXPECT_DOUBLE_EQ(s.success[6], 2.0 / 4);  // 1/3 > 0.30
  EXPECT_DOUBLE_EQ(s.success[7], 1.0 / 4);  // 1/3 < 0.35
  EXPECT_DOUBLE_EQ(s.success[20], 0.0);     // nothing is strictly above IoU 1
  // The exact frame passes 20 thresholds (0 ... 0.95), the shifted one 7 (0 ... 0.30).
  EXPECT_NEAR(s.auc, (20.0 + 7.0) / (4 * 21), 1e-12);
  EXPECT_DOUBLE_EQ(s.precision[0], 1.0 / 4);
  EXPECT_DOUBLE_EQ(s.precision[4], 1.0 / 4);
  EXPECT_DOUBLE_EQ(s.precision[5], 2.0 / 4);  // 5 px <= 5 px
  EXPECT_DOUBLE_EQ(s.precisionAt20, 2.0 / 4);
  EXPECT_DOUBLE_EQ(s.precision[50], 2.0 / 4);  // misses never count, however lenient the threshold
}

TEST(Score, AverageWeighsSequencesEqually) {
  const cv::Rect2d box(0, 0, 10, 10);
  const SequenceScore perfect = scoreSequence({box}, {box});
  const SequenceScore lost = scoreSequence({box, box, box}, {std::nullopt, std::nullopt, std::nullopt});
  EXPECT_NEAR(perfect.auc, 20.0 / 21, 1e-12);
  EXPECT_DOUBLE_EQ(lost.auc, 0.0);
  const SequenceScore mean = averageScores({perfect, lost});
  EXPECT_NEAR(mean.auc, 10.0 / 21, 1e-12);
  EXPECT_DOUBLE_EQ(mean.precisionAt20, 0.5);
  EXPECT_EQ(mean.scoredFrames, 4);
}

TEST(FramePattern, DetectsThePaddingAndStartOfEachBenchmark) {
  FramePattern p;
  std::string error;
  ASSERT_TRUE(detectFramePattern({"0002.jpg", "0001.jpg", "0003.jpg", "notes.txt"}, p, &error)) << error;
  EXPECT_EQ(p.printfPattern(), "%04d.jpg");
  EXPECT_EQ(p.startIndex, 1);
  EXPECT_EQ(p.count, 3);
  ASSERT_TRUE(detectFramePattern({"00000001.jpg", "00000002.jpg"}, p, &error)) << error;
  EXPECT_EQ(p.printfPattern(), "%08d.jpg");
  ASSERT_TRUE(detectFramePattern({"000300.jpg", "000301.jpg"}, p, &error)) << error;
  EXPECT_EQ(p.printfPattern(), "%06d.jpg");
  EXPECT_EQ(p.startIndex, 300);
  ASSERT_TRUE(detectFramePattern({"img9.JPG", "img10.JPG", "img11.JPG"}, p, &error)) << error;
  EXPECT_EQ(p.printfPattern(), "img%d.JPG");
  EXPECT_EQ(p.startIndex, 9);
}

TEST(FramePattern, RejectsGapsAndMixedNames) {
  FramePattern p;
  std::string error;
  EXPECT_FALSE(detectFramePattern({"0001.jpg", "0003.jpg"}, p, &error));
  EXPECT_NE(error.find("consecutive"), std::string::npos);
  EXPECT_FALSE(detectFramePattern({"a0001.jpg", "b0002.jpg"}, p, &error));
  EXPECT_FALSE(detectFramePattern({"readme.txt"}, p, &error));
  EXPECT_FALSE(detectFramePattern({"0009.jpg", "00010.jpg"}, p, &error));
}

TEST(Alarms, WrongFramesReportedAsTracking) {
  const cv::Rect2d truth(100, 100, 10, 10), far(300, 300, 10, 10);
  // Frame 0 is the start and never counts. Frames 1-2 on target; 3 wrong but "tracking" (a false report);
  // 4 wrong and "coasting"; 5 without a box; 6 without ground truth.
  const std::vector<GroundTruthBox> gt = {truth, truth, truth, truth, truth, truth, std::nullopt};
  const std::vector<std::optional<cv::Rect2d>> boxes = {truth, truth, truth, far, far, std::nullopt, far};
  const std::vector<std::string> states = {"init",     "tracking",  "tracking", "tracking",
                                           "coasting", "searching", "tracking"};
  const AlarmFigures f = alarmFigures(gt, boxes, states, cv::Size(640, 480));
  EXPECT_EQ(f.wrongFrames, 3);
  EXPECT_EQ(f.wrongTracking, 1);
  EXPECT_EQ(f.runs, 1);
  EXPECT_EQ(f.lossRuns, 1);
  EXPECT_EQ(f.reacquiredRuns, 0);
  EXPECT_EQ(f.afterLossFrames, 0);  // frame 6, the only one after the loss, has no ground truth
}

TEST(Alarms, ReacquisitionAfterTheFirstLossAndInView) {
  const cv::Size frame(200, 200);
  const cv::Rect2d truth(50, 50, 20, 20), leaving(190, 50, 20, 20);  // half of `leaving` outside: in view
  const cv::Rect2d gone(195, 50, 20, 20);                            // a quarter inside: out of view
  // Frame 1 declares the loss ("lost"); frames 2.. are after it: 2 found, 3 missed in view, 4 found out of
  // view, 5 a second loss (changes nothing), 6 found.
  const std::vector<GroundTruthBox> gt = {truth, truth, truth, leaving, gone, truth, truth};
  const std::vector<std::optional<cv::Rect2d>> boxes = {truth, std::nullopt, truth, std::nullopt,
                                                        gone,  std::nullopt, truth};
  const std::vector<std::string> states = {"init",     "lost",      "tracking", "lost",
                                           "tracking", "searching", "tracking"};
  const AlarmFigures f = alarmFigures(gt, boxes, states, frame);
  EXPECT_EQ(f.lossRuns, 1);
  EXPECT_EQ(f.reacquiredRuns, 1);
  EXPECT_EQ(f.afterLossFrames, 5);
  EXPECT_EQ(f.afterLossFound, 3);
  EXPECT_EQ(f.afterLossInView, 4);
  EXPECT_EQ(f.afterLossInViewFound, 2);

  // States missing (a tracker that reports none): no loss is ever declared.
  const AlarmFigures none = alarmFigures(gt, boxes, {}, frame);
  EXPECT_EQ(none.lossRuns, 0);
  EXPECT_EQ(none.wrongTracking, 0);
  EXPECT_EQ(none.wrongFrames, 3);

  AlarmFigures pooled = f;
  pooled += none;
  EXPECT_EQ(pooled.runs, 2);
  EXPECT_EQ(pooled.lossRuns, 1);
  EXPECT_EQ(pooled.afterLossFrames, 5);
}

}  // namespace
}  // namespace colortrack::eval
