// SPDX-License-Identifier: LGPL-2.1-or-later
// Re-acquisition by the default (fused) method: the target is taken back soon after it is in view again,
// and nothing else is taken for it meanwhile (issue 21).
#include <functional>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "colortrack/tracker.hpp"
#include "scene.hpp"

using namespace colortrack;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;
using colortrack::scene::SceneFrame;

namespace {

// Frames allowed between the target being back in view and the track being on it again.
constexpr int kReacquireFrames = 15;

SceneConfig movingConfig() {
  SceneConfig c;
  c.frameSize = {640, 480};
  c.frames = 200;
  c.rotationDegrees = 90;
  c.scaleMin = 0.7;
  c.scaleMax = 1.4;
  c.brightness = 0.4;
  return c;
}

// Runs the fused tracker over `scene` until `backFrom + kReacquireFrames`: the target is hidden during
// [hiddenFrom, backFrom). Returns the first frame from backFrom on whose box is on it (IoU >= 0.5), or -1;
// with `confirmed`, the first such frame reported `tracking`.
// `paint`, if given, draws on each frame before the tracker sees it.
int reacquiredAt(const Scene &scene, int hiddenFrom, int backFrom, bool confirmed = true,
                 const std::function<void(int, cv::Mat &)> &paint = nullptr) {
  TrackerSettings s;
  s.method = Method::Fused;
  Tracker tracker(s);
  tracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
  for (int i = 1; i <= backFrom + kReacquireFrames; ++i) {
    SceneFrame f = scene.render(i);
    if (paint) paint(i, f.bgr);
    const TrackOutput out = tracker.process(MatImageSource(f.bgr));
    if (i >= hiddenFrom && i < backFrom) {
      EXPECT_FALSE(f.objectVisible) << "frame " << i;
      EXPECT_NE(out.state, TrackState::Tracking) << "frame " << i << ": tracking while the target is hidden";
    }
    const bool reported = out.state == TrackState::Tracking || (!confirmed && out.hasBox);
    if (i >= backFrom && reported && scene::iou(out.box, f.box) >= 0.5) return i;
  }
  return -1;
}

}  // namespace

TEST(Reacquisition, TargetLeavesAndReturnsElsewhereSixtyFramesLater) {
  SceneConfig c = movingConfig();
  c.leaveFrom = 60;
  c.leaveTo = 120;
  const Scene scene(c);
  const int at = reacquiredAt(scene, 60, 120);
  EXPECT_GE(at, 120) << "not re-acquired within " << kReacquireFrames << " frames";
}

// A flat board in the target's colours covers it for 40 frames: the colour cue alone would take the board.
// The target turns by at most 9 degrees while hidden (rotation 30 over a 400-frame pass): the correlation
// filter knows it again.
TEST(Reacquisition, TargetHiddenByBoardOfItsColours) {
  SceneConfig c = movingConfig();
  c.frames = 400;  // slower, so the board that covers the whole hidden path stays smaller than the frame
  c.rotationDegrees = 30;
  c.occludeFrom = 60;
  c.occludeTo = 100;
  const Scene scene(c);
  EXPECT_FALSE(scene.render(80).boardBox.empty());
  const int at = reacquiredAt(scene, 60, 100);
  EXPECT_GE(at, 100) << "not re-acquired within " << kReacquireFrames << " frames";
}

// A target that turns 26 degrees while hidden (rotation 90) comes back with a fused PSR of 4.3-6.4, under the
// bar of 6 that confirms a re-detection: it is proposed at half that bar and followed, reported `coasting`
// until a frame reaches the bar. Before guesses were followed it was not found again within 15 frames.
TEST(Reacquisition, TurnedTargetIsFollowedBeforeItIsConfirmed) {
  SceneConfig c = movingConfig();
  c.frames = 400;
  c.rotationDegrees = 90;
  c.occludeFrom = 60;
  c.occludeTo = 100;
  const Scene scene(c);
  const int at = reacquiredAt(scene, 60, 100, false);
  EXPECT_GE(at, 100) << "no box on the target within " << kReacquireFrames << " frames";
}

// While the target is away, a large board of one of its colours (light orange) stands at the top right. The
// likelihood against the target's last surroundings rates that colour as highly as the target's own mix, so
// the board holds the strongest colour places; against the whole frame the colour is common and the target's
// others are not, and the target ranks first once it is back. Before the candidate against the whole frame
// (redetection.cpp) it was not found again at all, with boards of any of three of its colours and sizes from
// 240 x 180 to 340 x 240 px; with it, it is followed from frame 123 in each.
TEST(Reacquisition, TargetReturnsWhileABoardOfOneOfItsColoursIsInView) {
  SceneConfig c = movingConfig();
  c.leaveFrom = 60;
  c.leaveTo = 120;
  const Scene scene(c);
  const auto board = [](int frame, cv::Mat &bgr) {
    if (frame >= 60) bgr(cv::Rect(360, 0, 280, 220)).setTo(cv::Scalar(45, 140, 235));
  };
  const int at = reacquiredAt(scene, 60, 120, false, board);
  EXPECT_GE(at, 120) << "no box on the target within " << kReacquireFrames << " frames";
}
