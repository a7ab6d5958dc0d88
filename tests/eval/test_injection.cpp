// SPDX-License-Identifier: LGPL-2.1-or-later
// The injected failures (injection.hpp) and the honesty figures (honesty.hpp), on a synthetic sequence whose
// target is a red square on grey and a second sequence that is plain blue.
#include <gtest/gtest.h>

#include <cmath>

#include <opencv2/imgproc.hpp>

#include "honesty.hpp"
#include "injection.hpp"
#include "metrics.hpp"

namespace colortrack::eval {
namespace {

constexpr int kFrames = 200;
const cv::Size kFrame(320, 240);
const cv::Scalar kRed(0, 0, 255), kGrey(128, 128, 128), kBlue(255, 0, 0);

// The target drifts right by half a pixel a frame.
cv::Rect2d targetAt(int i) {
  return {60 + 0.5 * i, 100, 30, 30};
}

std::vector<Sequence> makeSequences() {
  std::vector<Sequence> sequences(2);
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    sequences[s].name = s == 0 ? "red" : "blue";
    sequences[s].frameSize = kFrame;
    sequences[s].pattern.count = kFrames;
    for (int i = 0; i < kFrames; ++i) sequences[s].groundTruth.push_back(targetAt(i));
  }
  return sequences;
}

cv::Mat readSynthetic(std::size_t sequence, int i) {
  cv::Mat image(kFrame, CV_8UC3, sequence == 0 ? kGrey : kBlue);
  if (sequence == 0) cv::rectangle(image, cv::Rect(targetAt(i)), kRed, cv::FILLED);
  return image;
}

int redPixels(const cv::Mat &image, const cv::Rect &area) {
  cv::Mat mask;
  cv::inRange(image(area & cv::Rect(cv::Point(), image.size())), kRed, kRed, mask);
  return cv::countNonZero(mask);
}

Injection findKind(const std::vector<Injection> &plan, InjectionKind kind, int length = 0,
                   bool beside = false) {
  for (const Injection &injection : plan)
    if (injection.kind == kind && (length == 0 || injection.length == length) && injection.beside == beside)
      return injection;
  ADD_FAILURE() << "no such injection planned";
  return {};
}

TEST(Injection, PlansEveryKindWithFramesLeftAfterIt) {
  const std::vector<Sequence> sequences = makeSequences();
  const std::vector<Injection> plan = planInjections(sequences, 0);
  ASSERT_EQ(plan.size(), 8u);  // two cuts, three covers, three crossings
  for (const Injection &injection : plan) {
    EXPECT_GE(injection.first, 1) << injection.name;
    EXPECT_LE(injection.last() + kFramesAfter, kFrames - 1) << injection.name;
  }
  EXPECT_EQ(findKind(plan, InjectionKind::Cut).otherSequence, 1u);
  // A sequence too short for anything gets nothing.
  std::vector<Sequence> shortOnes = makeSequences();
  shortOnes[0].groundTruth.resize(30);
  EXPECT_TRUE(planInjections(shortOnes, 0).empty());
}

TEST(Injection, CutShowsTheOtherSceneAndMarksTheTargetAbsent) {
  const std::vector<Sequence> sequences = makeSequences();
  InjectedRun run(sequences, 0, findKind(planInjections(sequences, 0), InjectionKind::Cut));
  const Injection &cut = run.injection();
  const std::vector<FrameTruth> truth = run.truth();
  const cv::Mat during = run.frame(cut.first + 3, readSynthetic);
  EXPECT_LT(cv::norm(cv::mean(during) - kBlue), 1e-6);
  EXPECT_TRUE(truth[cut.first].absent && truth[cut.first].grace && !truth[cut.first].target);
  EXPECT_TRUE(truth[cut.first + kCutGrace].absent && !truth[cut.first + kCutGrace].grace);
  EXPECT_FALSE(truth[cut.last() + 1].absent);
  EXPECT_GT(redPixels(run.frame(cut.last() + 1, readSynthetic), cv::Rect(targetAt(cut.last() + 1))), 800);
}

TEST(Injection, CoverHidesEveryPixelOfTheTarget) {
  const std::vector<Sequence> sequences = makeSequences();
  InjectedRun run(sequences, 0, findKind(planInjections(sequences, 0), InjectionKind::Cover, 15));
  const Injection &cover = run.injection();
  for (int i = cover.first; i <= cover.last(); ++i)
    EXPECT_EQ(redPixels(run.frame(i, readSynthetic), cv::Rect(0, 0, kFrame.width, kFrame.height)), 0) << i;
  EXPECT_TRUE(run.truth()[cover.first].absent);
  EXPECT_FALSE(run.truth()[cover.first].grace);
  EXPECT_GT(redPixels(run.frame(cover.last() + 1, readSynthetic), cv::Rect(targetAt(cover.last() + 1))), 800);
}

TEST(Injection, CopyCrossesInFrontOfTheTargetFromOneSideToTheOther) {
  const std::vector<Sequence> sequences = makeSequences();
  InjectedRun run(sequences, 0, findKind(planInjections(sequences, 0), InjectionKind::Copy, kCopySlowFrames));
  const Injection &copy = run.injection();
  const std::vector<FrameTruth> truth = run.truth();
  for (int i : {copy.first, copy.last()}) {
    ASSERT_TRUE(truth[i].copy && truth[i].target);
    const cv::Mat image = run.frame(i, readSynthetic);
    EXPECT_EQ(redPixels(image, cv::Rect(*truth[i].copy)), 900) << i;  // the whole copy, in the frame
    EXPECT_NEAR(std::abs(truth[i].copy->x - truth[i].target->x), kCopyReach * 30, 1.0) << i;
    EXPECT_NEAR(truth[i].copy->y, truth[i].target->y, 1.0) << i;
  }
  EXPECT_LT(truth[copy.first].copy->x, truth[copy.first].target->x);    // from the left ...
  EXPECT_GT(truth[copy.last()].copy->x, truth[copy.last()].target->x);  // ... to the right
  EXPECT_FALSE(truth[copy.first].absent);
  EXPECT_FALSE(truth[copy.last() + 1].copy);

  InjectedRun beside(sequences, 0,
                     findKind(planInjections(sequences, 0), InjectionKind::Copy, kCopySlowFrames, true));
  const FrameTruth middle = beside.truth()[beside.injection().first + kCopySlowFrames / 2];
  EXPECT_EQ(overlap(*middle.copy, *middle.target), 0.0);  // beside: never over it
}

TEST(Honesty, AurocCountsTiesAsHalf) {
  EXPECT_DOUBLE_EQ(auroc({{0.9, true}, {0.8, true}, {0.1, false}, {0.2, false}}), 1.0);
  EXPECT_DOUBLE_EQ(auroc({{0.1, true}, {0.9, false}}), 0.0);
  EXPECT_DOUBLE_EQ(auroc({{1.0, true}, {1.0, false}, {1.0, true}}), 0.5);
  EXPECT_DOUBLE_EQ(auroc({{0.9, true}, {0.5, false}, {0.5, true}, {0.1, false}}), 0.875);
  EXPECT_TRUE(std::isnan(auroc({{0.5, true}})));
}

TEST(Honesty, TrackingOnAnAbsentTargetIsAnAlarmAfterTheGrace) {
  std::vector<FrameTruth> truth(6);
  for (int i = 0; i < 6; ++i) truth[i].target = cv::Rect2d(10, 10, 20, 20);
  truth[2] = {std::nullopt, true, true, std::nullopt};  // a cut's grace frame: not counted
  truth[3] = {std::nullopt, true, false, std::nullopt};
  const cv::Rect2d on(10, 10, 20, 20), off(100, 100, 20, 20);
  const std::vector<FrameReport> reports = {{on, "init", 0},        {on, "tracking", 0.9},
                                            {off, "tracking", 0.8}, {off, "tracking", 0.7},
                                            {off, "coasting", 0.2}, {std::nullopt, "lost", 0}};
  const HonestyFigures f = honestyFigures(truth, reports);
  EXPECT_EQ(f.offTarget, 3);  // frames 3 (absent, a box), 4 (off), 5 (no box)
  EXPECT_EQ(f.offTargetTracking, 1);
  EXPECT_EQ(f.tracking, 2);
  EXPECT_EQ(f.trackingOnTarget, 1);
  EXPECT_EQ(f.onTarget, 1);
  ASSERT_EQ(f.scores.size(), 3u);  // frames 1, 3 and 4: the lost frame has no box
  EXPECT_DOUBLE_EQ(auroc(f.scores), 1.0);
}

TEST(Honesty, OutcomeOfACutAndOfACrossing) {
  Injection cut{InjectionKind::Cut, "cut@3", 2, 4};
  std::vector<FrameTruth> truth(2 + 4 + kFramesAfter);
  for (FrameTruth &t : truth) t.target = cv::Rect2d(10, 10, 20, 20);
  for (int i = 2; i < 6; ++i) truth[i] = {std::nullopt, true, i - 2 < kCutGrace, std::nullopt};
  std::vector<FrameReport> reports(truth.size(), {cv::Rect2d(10, 10, 20, 20), "tracking", 1});
  reports[4] = {std::nullopt, "lost", 0};
  reports[5] = reports[6] = reports[7] = {std::nullopt, "lost", 0};
  InjectionOutcome o = injectionOutcome(cut, truth, reports);
  EXPECT_EQ(o.declaredAfter, 3);
  EXPECT_EQ(o.absentFrames, 0);  // all four in the grace
  EXPECT_EQ(o.backAfter, 3);     // frame 8 is the third after the cut's last frame (5)

  Injection copy{InjectionKind::Copy, "copy-front3@3", 2, 3};
  for (FrameTruth &t : truth) t = {cv::Rect2d(10, 10, 20, 20), false, false, std::nullopt};
  truth[2].copy = cv::Rect2d(0, 10, 20, 20);
  truth[3].copy = cv::Rect2d(10, 10, 20, 20);
  truth[4].copy = cv::Rect2d(60, 10, 20, 20);
  reports.assign(truth.size(), {cv::Rect2d(10, 10, 20, 20), "tracking", 1});
  reports[3].score = 0.4;
  reports[4] = {cv::Rect2d(60, 10, 20, 20), "tracking", 0.9};
  o = injectionOutcome(copy, truth, reports);
  EXPECT_FALSE(o.endsOnTarget);
  EXPECT_TRUE(o.endsOnCopyTracking);
  EXPECT_DOUBLE_EQ(o.scoreBefore, 1.0);
  EXPECT_DOUBLE_EQ(o.scoreConfusable, 0.7);  // frames 2 and 3 are within 1.5 sides; frame 4 is not
}

}  // namespace
}  // namespace colortrack::eval
