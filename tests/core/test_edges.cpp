// SPDX-License-Identifier: LGPL-2.1-or-later
// Edge density / energy verification on the synthetic object, and checks of the synthetic scene itself.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "colortrack/edges.hpp"
#include "scene.hpp"

namespace colortrack {
namespace {

using scene::Scene;
using scene::SceneConfig;
using scene::SceneFrame;

// Stated tolerance for the object seen under rotation, rescaling and lighting changes: the window's density
// and energy lie within 25% of the template's.
constexpr double kObjectTolerance = 0.25;
// Tolerance the tracker uses by default; the flat decoy must fail it in every mode.
constexpr double kDecoyTolerance = 0.5;

cv::Mat toGray(const cv::Mat &bgr) {
  cv::Mat gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  return gray;
}

double relativeDifference(double value, double reference) {
  return std::abs(value / reference - 1.0);
}

void report(const char *label, const EdgeSignature &s, const EdgeSignature &t) {
  std::printf("  %-22s density %.4f (%+.1f%%)  energy %.4f (%+.1f%%)  edges %d\n", label, s.density,
              100 * (s.density / t.density - 1), s.energy, 100 * (s.energy / t.energy - 1), s.edgeCount);
}

class EdgesOnSceneObject : public ::testing::Test {
 protected:
  void SetUp() override {
    const Scene scene(SceneConfig{});
    scene.objectTemplate(templateBgr_, templateMask_);
    verifier_.setTemplate(toGray(templateBgr_));
    ASSERT_TRUE(verifier_.hasTemplate());
    ASSERT_TRUE(verifier_.templateSignature().valid());
  }

  // The window must pass in every mode at kObjectTolerance.
  void expectMatchesTemplate(const char *label, const cv::Mat &windowBgr) {
    const EdgeSignature &t = verifier_.templateSignature();
    const EdgeSignature w = verifier_.signature(toGray(windowBgr));
    report(label, w, t);
    EXPECT_LE(relativeDifference(w.density, t.density), kObjectTolerance) << label;
    EXPECT_LE(relativeDifference(w.energy, t.energy), kObjectTolerance) << label;
    EXPECT_TRUE(verifier_.verify(w, VerifyMode::Both, kObjectTolerance)) << label;
    EXPECT_TRUE(verifier_.verify(w, VerifyMode::EdgeDensity, kObjectTolerance)) << label;
    EXPECT_TRUE(verifier_.verify(w, VerifyMode::EdgeEnergy, kObjectTolerance)) << label;
  }

  cv::Mat templateBgr_, templateMask_;
  EdgeVerifier verifier_;
};

TEST_F(EdgesOnSceneObject, TemplateHasInternalEdges) {
  const EdgeSignature &t = verifier_.templateSignature();
  report("template", t, t);
  // Stripes and blobs: far more edge pixels than the outline alone (a circle of diameter 72 has ~230).
  EXPECT_GT(t.edgeCount, 400);
  EXPECT_GT(t.density, 0.08);
  EXPECT_GT(t.energy, 0.0);
  // With k folded in, the energy is the mean squared radius over the area: below 0.25 (an outline circle)
  // for edges spread over the disc.
  EXPECT_LT(t.energy, 0.25);
}

TEST_F(EdgesOnSceneObject, InvariantToRotation) {
  cv::Mat rotated;
  cv::rotate(templateBgr_, rotated, cv::ROTATE_90_CLOCKWISE);
  expectMatchesTemplate("rotated 90", rotated);
  cv::rotate(templateBgr_, rotated, cv::ROTATE_180);
  expectMatchesTemplate("rotated 180", rotated);
}

TEST_F(EdgesOnSceneObject, InvariantToScale) {
  for (double factor : {0.7, 1.4}) {
    cv::Mat scaled;
    cv::resize(templateBgr_, scaled, cv::Size(), factor, factor,
               factor < 1 ? cv::INTER_AREA : cv::INTER_LINEAR);
    expectMatchesTemplate(("scaled " + std::to_string(factor).substr(0, 3)).c_str(), scaled);
  }
}

TEST_F(EdgesOnSceneObject, InvariantToBrightness) {
  for (double factor : {0.6, 1.4}) {
    cv::Mat lit;
    templateBgr_.convertTo(lit, -1, factor);
    expectMatchesTemplate(("brightness x" + std::to_string(factor).substr(0, 3)).c_str(), lit);
  }
}

TEST_F(EdgesOnSceneObject, FlatDiscOfSameColourFails) {
  // The decoy: the object's outline filled with its mean colour, no texture.
  const cv::Scalar meanColour = cv::mean(templateBgr_, templateMask_);
  cv::Mat flat = cv::Mat::zeros(templateBgr_.size(), CV_8UC3);
  flat.setTo(meanColour, templateMask_);
  const EdgeSignature w = verifier_.signature(toGray(flat));
  report("flat disc", w, verifier_.templateSignature());
  EXPECT_FALSE(verifier_.verify(w, VerifyMode::EdgeDensity, kDecoyTolerance));
  EXPECT_FALSE(verifier_.verify(w, VerifyMode::EdgeEnergy, kDecoyTolerance));
  EXPECT_FALSE(verifier_.verify(w, VerifyMode::Both, kDecoyTolerance));
  EXPECT_TRUE(verifier_.verify(w, VerifyMode::None, kDecoyTolerance));
}

TEST(EdgeVerifier, ObjectInSceneVerifiesAndDecoyDoesNot) {
  // What the tracker sees: the template cut from frame 0 at the init box (background corners included),
  // later windows cut at the ground-truth box while the object turns, grows/shrinks and the light changes.
  SceneConfig config;
  config.decoy = true;
  config.scaleMin = 0.8;
  config.scaleMax = 1.3;
  config.rotationDegrees = 90;
  config.brightness = 0.3;
  const Scene scene(config);
  const SceneFrame first = scene.render(0);
  EdgeVerifier verifier;
  verifier.setTemplate(toGray(first.bgr(scene.initBox())));
  const EdgeSignature &t = verifier.templateSignature();
  ASSERT_TRUE(t.valid());

  int objectPasses = 0, decoyPasses = 0, frames = 0;
  double worstObjectDensity = 0, worstObjectEnergy = 0, bestDecoyDensity = 1e9, bestDecoyEnergy = 1e9;
  for (int index = 0; index < config.frames; index += 8, ++frames) {
    const SceneFrame frame = scene.render(index);
    const cv::Mat gray = toGray(frame.bgr);
    const EdgeSignature object = verifier.signature(gray(cv::Rect(frame.box)));
    // The decoy window is the size the object has in this frame, centred on the decoy.
    const cv::Point2d decoyCentre = (frame.decoyBox.tl() + frame.decoyBox.br()) / 2;
    const cv::Rect decoyWindow = cv::Rect(cv::Point(cvRound(decoyCentre.x - frame.box.width / 2),
                                                    cvRound(decoyCentre.y - frame.box.height / 2)),
                                          frame.box.size()) &
                                 cv::Rect(cv::Point(0, 0), gray.size());
    const EdgeSignature decoy = verifier.signature(gray(decoyWindow));
    objectPasses += verifier.verify(object, VerifyMode::Both, kDecoyTolerance);
    // Density (and so Both) rejects it. Energy alone does not here: the textured background in the window
    // corners dominates the energy of both the template crop and the decoy window.
    decoyPasses += verifier.verify(decoy, VerifyMode::EdgeDensity, kDecoyTolerance) ||
                   verifier.verify(decoy, VerifyMode::Both, kDecoyTolerance);
    worstObjectDensity = std::max(worstObjectDensity, relativeDifference(object.density, t.density));
    worstObjectEnergy = std::max(worstObjectEnergy, relativeDifference(object.energy, t.energy));
    bestDecoyDensity = std::min(bestDecoyDensity, relativeDifference(decoy.density, t.density));
    bestDecoyEnergy = std::min(bestDecoyEnergy, relativeDifference(decoy.energy, t.energy));
  }
  std::printf(
      "  object: worst density diff %.3f, worst energy diff %.3f; decoy: smallest density diff %.3f, "
      "smallest energy diff %.3f (%d frames)\n",
      worstObjectDensity, worstObjectEnergy, bestDecoyDensity, bestDecoyEnergy, frames);
  EXPECT_EQ(objectPasses, frames);
  EXPECT_EQ(decoyPasses, 0);
}

TEST(EdgeVerifier, EdgeCases) {
  EdgeVerifier verifier;
  EXPECT_FALSE(verifier.hasTemplate());

  // A flat template has no edges: nothing to compare against, so any window with edges passes.
  verifier.setTemplate(cv::Mat(40, 40, CV_8UC1, cv::Scalar(120)));
  ASSERT_TRUE(verifier.hasTemplate());
  EXPECT_FALSE(verifier.templateSignature().valid());
  cv::Mat textured(40, 40, CV_8UC1);
  for (int y = 0; y < textured.rows; ++y)
    for (int x = 0; x < textured.cols; ++x) textured.at<uchar>(y, x) = ((x / 8 + y / 8) % 2) ? 200 : 40;
  const EdgeSignature texturedSig = verifier.signature(textured);
  ASSERT_TRUE(texturedSig.valid());
  EXPECT_TRUE(verifier.verify(texturedSig, VerifyMode::Both, 0.1));

  // A window without edges is never verified, except with verification off.
  verifier.setTemplate(textured);
  const EdgeSignature flatSig = verifier.signature(cv::Mat(60, 60, CV_8UC1, cv::Scalar(90)));
  EXPECT_FALSE(flatSig.valid());
  EXPECT_FALSE(verifier.verify(flatSig, VerifyMode::EdgeDensity, 10.0));
  EXPECT_FALSE(verifier.verify(flatSig, VerifyMode::Both, 10.0));
  EXPECT_TRUE(verifier.verify(flatSig, VerifyMode::None, 0.0));

  // Low-amplitude noise on a flat patch is not stretched into edges.
  cv::Mat noisy(60, 60, CV_8UC1);
  cv::RNG rng(5);
  rng.fill(noisy, cv::RNG::UNIFORM, 100, 106);
  EXPECT_EQ(edgeSignature(noisy, 0).edgeCount, 0);

  // The window's own border is not an edge: a patch that is bright up to its border has no edges.
  EXPECT_FALSE(edgeSignature(cv::Mat(3, 3, CV_8UC1, cv::Scalar(255)), 0).valid());

  // k = N_ref / N: the energy does not depend on the reference count (it cancels), the count is kept.
  const EdgeSignature own = edgeSignature(textured, 0),
                      referenced = edgeSignature(textured, 3 * own.edgeCount);
  EXPECT_EQ(own.edgeCount, referenced.edgeCount);
  EXPECT_NEAR(own.energy, referenced.energy, 1e-12);
}

// ---------------------------------------------------------------------------------------------------------
// The synthetic scene itself.

// Pixels where the object changes the frame: the same scene with the object removed has identical background,
// lighting and noise.
cv::Rect objectPixelsBounds(const SceneConfig &config, int index) {
  SceneConfig withoutObject = config;
  withoutObject.leaveFrom = 0;
  withoutObject.leaveTo = -1;
  const cv::Mat with = Scene(config).render(index).bgr, without = Scene(withoutObject).render(index).bgr;
  cv::Mat diff, changed;
  cv::absdiff(with, without, diff);
  cv::cvtColor(diff, diff, cv::COLOR_BGR2GRAY);
  cv::threshold(diff, changed, 0, 255, cv::THRESH_BINARY);
  return cv::boundingRect(changed);
}

TEST(Scene, GroundTruthBoxBoundsTheObjectPixels) {
  SceneConfig config;
  config.scaleMin = 0.7;
  config.scaleMax = 1.3;
  config.rotationDegrees = 120;
  config.brightness = 0.3;
  config.objectSize = cv::Size(80, 56);  // an ellipse, so rotation changes the box
  const Scene scene(config);
  for (int index : {0, 37, 90, 151, 200}) {
    const SceneFrame frame = scene.render(index);
    ASSERT_TRUE(frame.objectVisible);
    const cv::Rect pixels = objectPixelsBounds(config, index);
    const cv::Rect2d box = frame.box;
    // Every changed pixel lies in the box, and the box is tight (no more than a pixel of slack per side).
    EXPECT_EQ((cv::Rect2d(pixels) & box).area(), cv::Rect2d(pixels).area()) << "frame " << index;
    EXPECT_LE(box.width - pixels.width, 2) << "frame " << index;
    EXPECT_LE(box.height - pixels.height, 2) << "frame " << index;
    // The box is within the frame.
    EXPECT_EQ((box & cv::Rect2d(0, 0, frame.bgr.cols, frame.bgr.rows)).area(), box.area());
  }
}

TEST(Scene, ObjectScaleAndLighting) {
  SceneConfig config;
  config.scaleMin = 0.8;
  config.scaleMax = 1.25;
  config.brightness = 0.4;
  const Scene scene(config);
  EXPECT_DOUBLE_EQ(scene.render(0).objectScale, 1.0);  // frame 0 at template scale
  double smallest = 10, largest = 0;
  for (int index = 0; index < config.frames; ++index) {
    const SceneFrame frame = scene.render(index);
    smallest = std::min(smallest, frame.objectScale);
    largest = std::max(largest, frame.objectScale);
    // A disc: the box is the object size times the scale (to a pixel of rasterisation).
    if (index % 10 == 0) {
      EXPECT_NEAR(frame.box.width, config.objectSize.width * frame.objectScale, 2.0);
    }
  }
  EXPECT_NEAR(smallest, config.scaleMin, 0.01);
  EXPECT_NEAR(largest, config.scaleMax, 0.01);

  // Lighting: the frame mean follows 1 + brightness * sin(2 phase): brightest at 1/8 of the pass.
  const double normal = cv::mean(scene.render(0).bgr)[1];
  const double bright = cv::mean(scene.render(config.frames / 8).bgr)[1];
  const double dark = cv::mean(scene.render(3 * config.frames / 8).bgr)[1];
  EXPECT_NEAR(bright / normal, 1.4, 0.05);
  EXPECT_NEAR(dark / normal, 0.6, 0.05);
}

TEST(Scene, Deterministic) {
  SceneConfig config;
  config.decoy = true;
  config.rotationDegrees = 45;
  const Scene a(config), b(config);
  const cv::Mat later = a.render(17).bgr;  // render out of order: no hidden state between frames
  const cv::Mat first = a.render(3).bgr;
  EXPECT_EQ(cv::norm(first, b.render(3).bgr, cv::NORM_INF), 0);
  EXPECT_EQ(cv::norm(later, b.render(17).bgr, cv::NORM_INF), 0);
  EXPECT_GT(cv::norm(first, later, cv::NORM_L1), 0);  // and frames do differ

  SceneConfig other = config;
  other.seed = 2;
  EXPECT_GT(cv::norm(first, Scene(other).render(3).bgr, cv::NORM_L1), 0);
}

TEST(Scene, OddAndSmallFrameSizes) {
  for (const cv::Size size : {cv::Size(321, 241), cv::Size(160, 120), cv::Size(241, 321)}) {
    SceneConfig config;
    config.frameSize = size;
    config.scaleMin = 0.9;
    config.scaleMax = 1.2;
    config.rotationDegrees = 30;
    const Scene scene(config);
    for (int index = 0; index < config.frames; index += 5) {
      const SceneFrame frame = scene.render(index);
      ASSERT_EQ(frame.bgr.size(), size);
      ASSERT_EQ(frame.bgr.type(), CV_8UC3);
      ASSERT_TRUE(frame.objectVisible);
      const cv::Rect2d inside(0, 0, size.width, size.height);
      EXPECT_EQ((frame.box & inside).area(), frame.box.area()) << size << " frame " << index;
    }
    const cv::Rect init = scene.initBox();
    const cv::Rect2d box0 = scene.render(0).box;
    EXPECT_NEAR(init.x, box0.x, 0.5);
    EXPECT_NEAR(init.width, box0.width, 0.5);
  }
}

TEST(Scene, DecoyNeverOverlapsTheObject) {
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(321, 241), cv::Size(480, 640)}) {
    for (double speed : {1.0, 3.0}) {
      SceneConfig config;
      config.frameSize = size;
      config.decoy = true;
      config.speed = speed;
      config.scaleMin = 0.8;
      config.scaleMax = 1.3;
      config.leaveFrom = 100;
      config.leaveTo = 140;
      const Scene scene(config);
      for (int index = 0; index < config.frames; index += 2) {
        const SceneFrame frame = scene.render(index);
        ASSERT_FALSE(frame.decoyBox.empty());
        EXPECT_EQ((frame.box & frame.decoyBox).area(), 0) << size << " speed " << speed << " frame " << index;
      }
    }
  }
}

TEST(Scene, DecoyHasTheObjectsColoursButNoTexture) {
  SceneConfig config;
  config.decoy = true;
  const Scene scene(config);
  const SceneFrame frame = scene.render(0);
  cv::Mat bgrTemplate, mask;
  scene.objectTemplate(bgrTemplate, mask);
  cv::Mat edges;
  cv::Canny(toGray(frame.bgr), edges, 50, 150);
  // Edge pixels in the inner part of each disc (away from its outline).
  auto innerEdgeFraction = [&edges](const cv::Rect2d &box) {
    const cv::Rect inner(
        cv::Rect2d(box.x + box.width * 0.25, box.y + box.height * 0.25, box.width * 0.5, box.height * 0.5));
    return cv::countNonZero(edges(inner)) / double(inner.area());
  };
  const double decoyEdges = innerEdgeFraction(frame.decoyBox), objectEdges = innerEdgeFraction(frame.box);
  std::printf("inner edge fraction: decoy %.4f, object %.4f\n", decoyEdges, objectEdges);
  EXPECT_LT(decoyEdges, 0.01);   // smooth gradients only
  EXPECT_GT(objectEdges, 0.05);  // stripes and blobs
  // Same colours: the hue histograms of the decoy disc and of the object overlap mostly.
  auto hueHistogram = [](const cv::Mat &bgr, const cv::Mat &m) {
    cv::Mat hsv, hist;
    cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV_FULL);
    const int channels[] = {0}, bins[] = {16};
    const float range[] = {0, 256};
    const float *ranges[] = {range};
    cv::calcHist(&hsv, 1, channels, m, hist, 1, bins, ranges);
    return cv::Mat(hist / cv::sum(hist)[0]);
  };
  const cv::Rect decoyRect(frame.decoyBox);
  cv::Mat decoyMask(decoyRect.size(), CV_8UC1, cv::Scalar(0));
  cv::circle(decoyMask, cv::Point(decoyRect.width / 2, decoyRect.height / 2), decoyRect.width / 2 - 2, 255,
             cv::FILLED);
  const cv::Mat decoyHue = hueHistogram(frame.bgr(decoyRect), decoyMask);
  const cv::Mat objectHue = hueHistogram(bgrTemplate, mask);
  double overlap = 0;
  for (int j = 0; j < 16; ++j) overlap += std::min(decoyHue.at<float>(j), objectHue.at<float>(j));
  EXPECT_GT(overlap, 0.7);
}

TEST(Scene, LeavesAndComesBackElsewhere) {
  for (const cv::Size size : {cv::Size(640, 480), cv::Size(160, 120), cv::Size(321, 241)}) {
    for (int leaveFrom : {30, 100, 170}) {
      SceneConfig config;
      config.frameSize = size;
      config.leaveFrom = leaveFrom;
      config.leaveTo = leaveFrom + 25;
      const Scene scene(config);
      for (int index = config.leaveFrom; index < config.leaveTo; ++index) {
        const SceneFrame frame = scene.render(index);
        EXPECT_FALSE(frame.objectVisible);
        EXPECT_TRUE(frame.box.empty());
      }
      const SceneFrame before = scene.render(config.leaveFrom - 1), after = scene.render(config.leaveTo);
      ASSERT_TRUE(before.objectVisible);
      ASSERT_TRUE(after.objectVisible);
      const double jump = scene::centreError(before.box, after.box);
      std::printf("  %dx%d leave %d: reappears %.0f px away\n", size.width, size.height, leaveFrom, jump);
      EXPECT_GE(jump, 0.25 * size.width) << size << " leave " << leaveFrom;
      // It then moves smoothly again.
      EXPECT_LT(scene::centreError(after.box, scene.render(config.leaveTo + 1).box), 10.0);
    }
  }
}

// Saturated orange/red (OpenCV hue 0..25 or 170..180): the colour family of the object.
cv::Mat objectHueMask(const cv::Mat &bgr) {
  cv::Mat hsv, low, high;
  cv::cvtColor(bgr, hsv, cv::COLOR_BGR2HSV);
  cv::inRange(hsv, cv::Scalar(0, 60, 40), cv::Scalar(25, 255, 255), low);
  cv::inRange(hsv, cv::Scalar(170, 60, 40), cv::Scalar(180, 255, 255), high);
  return low | high;
}

TEST(Scene, BackgroundHoldsLittleOfTheObjectColour) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    SceneConfig config;
    config.seed = seed;
    const Scene scene(config);
    const SceneFrame frame = scene.render(0);
    cv::Mat background = objectHueMask(frame.bgr);
    background(cv::Rect(frame.box)).setTo(0);
    const double backgroundFraction = cv::countNonZero(background) / static_cast<double>(background.total());

    cv::Mat bgrTemplate, mask;
    scene.objectTemplate(bgrTemplate, mask);
    const double objectFraction =
        cv::countNonZero(objectHueMask(bgrTemplate) & mask) / static_cast<double>(cv::countNonZero(mask));
    std::printf("  seed %u: object-coloured pixels: background %.4f, object %.3f\n", seed, backgroundFraction,
                objectFraction);
    EXPECT_LT(backgroundFraction, 0.01);
    EXPECT_GT(objectFraction, 0.95);
  }
}

TEST(Scene, BoxHelpers) {
  const cv::Rect2d a(0, 0, 10, 10), b(5, 0, 10, 10), far(100, 100, 5, 5);
  EXPECT_DOUBLE_EQ(scene::iou(a, a), 1.0);
  EXPECT_DOUBLE_EQ(scene::iou(a, b), 50.0 / 150.0);
  EXPECT_DOUBLE_EQ(scene::iou(a, far), 0.0);
  EXPECT_DOUBLE_EQ(scene::iou(a, cv::Rect2d()), 0.0);
  EXPECT_DOUBLE_EQ(scene::centreError(a, b), 5.0);
  EXPECT_DOUBLE_EQ(scene::centreError(a, cv::Rect2d(3, 4, 10, 10)), 5.0);
}

}  // namespace
}  // namespace colortrack
