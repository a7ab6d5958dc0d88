// Re-acquisition by the default (fused) method: the target is taken back soon after it is in view again,
// and nothing else is taken for it meanwhile (issue 21).
#include <gtest/gtest.h>

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
int reacquiredAt(const Scene &scene, int hiddenFrom, int backFrom, bool confirmed = true) {
  TrackerSettings s;
  s.method = Method::Fused;
  Tracker tracker(s);
  tracker.setTemplateFromBox(MatImageSource(scene.render(0).bgr), scene.initBox());
  for (int i = 1; i <= backFrom + kReacquireFrames; ++i) {
    const SceneFrame f = scene.render(i);
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
