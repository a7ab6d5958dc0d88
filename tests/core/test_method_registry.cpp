// SPDX-License-Identifier: LGPL-2.1-or-later
// The detection-method registry: every Method value makes its method, and a made method follows a target
// it was started on, through the DetectionMethod interface alone.
#include <gtest/gtest.h>

#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "colortrack/detection_method.hpp"

using namespace colortrack;

namespace {

// A red disc on a grey background, at `centre`.
cv::Mat discFrame(cv::Point centre) {
  cv::Mat frame(240, 320, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::circle(frame, centre, 20, cv::Scalar(30, 30, 220), cv::FILLED);
  return frame;
}

class Registry : public ::testing::TestWithParam<Method> {};

TEST_P(Registry, MadeMethodFollowsTheTargetItStartedOn) {
  TrackerSettings settings;
  settings.method = GetParam();
  TemplateModel model;
  KalmanTrack track;
  const MethodContext context{settings, model, track};
  const std::unique_ptr<DetectionMethod> method = createDetectionMethod(settings.method, context);
  ASSERT_TRUE(method);

  const cv::Rect box(100, 80, 40, 40);
  const MatImageSource first(discFrame(cv::Point(120, 100)));
  cv::Mat bgr;
  first.bgr(box, bgr);
  model.setTemplate(bgr, cv::Mat(), settings);
  track.newTemplate(bgr.size());
  track.start(box, settings.kalman);
  method->start(first, box);

  const MatImageSource moved(discFrame(cv::Point(124, 102)));
  TrackOutput out;
  method->process(moved, 1.0, out);
  track.report(out);
  EXPECT_EQ(out.state, TrackState::Tracking);
  EXPECT_EQ(out.id, 1);
  EXPECT_NEAR(out.box.x + out.box.width / 2, 124, 3);
  EXPECT_NEAR(out.box.y + out.box.height / 2, 102, 3);
}

INSTANTIATE_TEST_SUITE_P(EveryMethod, Registry,
                         ::testing::Values(Method::Indexing, Method::Discriminative, Method::Fused));

TEST(Registry, UnregisteredValueIsRefused) {
  TrackerSettings settings;
  TemplateModel model;
  KalmanTrack track;
  EXPECT_THROW(createDetectionMethod(static_cast<Method>(99), MethodContext{settings, model, track}),
               std::logic_error);
}

}  // namespace
