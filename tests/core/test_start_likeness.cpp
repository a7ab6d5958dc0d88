// SPDX-License-Identifier: LGPL-2.1-or-later
// The never-updated start appearance (issue 46): the template's histogram matches the object where it started
// and not the background beside it, and StartLikeness turns the match into a factor on the score that falls
// with the match, relative to the start's own and never above 1.
#include <gtest/gtest.h>

#include <cmath>

#include "colortrack/settings.hpp"
#include "colortrack/start_likeness.hpp"
#include "colortrack/template_model.hpp"
#include "scene.hpp"

using namespace colortrack;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;

TEST(StartLikeness, TheStartMatchesItselfAndNotTheBackground) {
  const Scene scene{SceneConfig{}};
  const scene::SceneFrame first = scene.render(0);
  const cv::Rect box(first.box);
  TrackerSettings settings;
  TemplateModel model;
  model.setTemplate(first.bgr(box).clone(), cv::Mat(), settings);
  const MatImageSource frame(first.bgr);
  const double onObject = model.matchStart(frame, box, settings);
  // The same size two object sides away (inside the frame): background only.
  const cv::Rect beside = box + cv::Point(box.x > 320 ? -2 * box.width : 2 * box.width, 0);
  const double onBackground = model.matchStart(frame, beside, settings);
  std::printf("match on the object %.3f, beside it %.3f\n", onObject, onBackground);
  EXPECT_GT(onObject, 0.95);
  EXPECT_LT(onBackground, 0.5 * onObject);
  EXPECT_EQ(model.matchStart(frame, cv::Rect(-50, -50, 10, 10), settings), 0.0);  // outside the frame
}

TEST(StartLikeness, FactorFallsWithTheMatchAndNeverRises) {
  StartLikeness likeness;
  EXPECT_EQ(likeness.factor(), 1.0);  // nothing seen yet
  for (int i = 0; i < 40; ++i) likeness.observe(0.8);
  EXPECT_DOUBLE_EQ(likeness.factor(), 1.0);
  likeness.observe(0.95);
  EXPECT_DOUBLE_EQ(likeness.factor(), 1.0);  // more like the start than usual: capped
  likeness.observe(0.2);
  EXPECT_NEAR(likeness.factor(), std::sqrt(0.25), 1e-9);
}

TEST(StartLikeness, TheReferenceIsTheStartNotTheLatest) {
  StartLikeness likeness;
  for (int i = 0; i < 40; ++i) likeness.observe(0.8);
  // A box that has slid onto something else for a long time is still compared with the start.
  for (int i = 0; i < 200; ++i) likeness.observe(0.4);
  EXPECT_NEAR(likeness.factor(), std::sqrt(0.5), 1e-9);
  likeness.reset();  // a new start
  EXPECT_EQ(likeness.factor(), 1.0);
  likeness.observe(0.4);
  EXPECT_DOUBLE_EQ(likeness.factor(), 1.0);
}
