// SPDX-License-Identifier: LGPL-2.1-or-later
// Threshold mode's tracking side: the assignment solver against brute force, tentative tracks, and ids that
// hold through crossings and short exits on rendered ball scenes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <vector>

#include <opencv2/core.hpp>

#include "balls.hpp"
#include "colortrack/blobs.hpp"
#include "colortrack/multi_tracker.hpp"

using namespace colortrack;
using balls::Ball;
using balls::BallScene;
using balls::BallSceneConfig;
using balls::BallTruth;

namespace {

double assignmentCost(const cv::Mat &cost, const std::vector<int> &assignment) {
  double total = 0;
  for (int r = 0; r < cost.rows; ++r)
    if (assignment[r] >= 0) total += cost.at<double>(r, assignment[r]);
  return total;
}

// Minimum over every injective map of the smaller side into the larger.
double bruteForceMinimum(const cv::Mat &cost) {
  const cv::Mat c = cost.rows <= cost.cols ? cost : cv::Mat(cost.t());
  std::vector<int> columns(c.cols);
  std::iota(columns.begin(), columns.end(), 0);
  double best = std::numeric_limits<double>::infinity();
  do {
    double total = 0;
    for (int r = 0; r < c.rows; ++r) total += c.at<double>(r, columns[r]);
    best = std::min(best, total);
  } while (std::next_permutation(columns.begin(), columns.end()));
  return best;
}

Blob blobAt(double x, double y, double side) {
  Blob b;
  b.centroid = {x, y};
  b.box = cv::Rect(cvRound(x - side / 2), cvRound(y - side / 2), cvRound(side), cvRound(side));
  b.area = side * side * CV_PI / 4;
  b.fill = CV_PI / 4;
  return b;
}

// The reported track nearest to `point`, or nullptr when none lies within `radius`.
const TrackedObject *nearest(const std::vector<TrackedObject> &objects, cv::Point2d point, double radius) {
  const TrackedObject *best = nullptr;
  for (const TrackedObject &o : objects)
    if (cv::norm(o.centre - point) < radius &&
        (!best || cv::norm(o.centre - point) < cv::norm(best->centre - point)))
      best = &o;
  return best;
}

const HsvRange kSaturated = [] {
  HsvRange r;
  r.lower = {0, 0.5, 0.25};
  r.upper = {360, 1, 1};
  return r;
}();

}  // namespace

TEST(Assignment, MatchesBruteForceOnRandomMatrices) {
  cv::RNG rng(3);
  for (int trial = 0; trial < 300; ++trial) {
    const int rows = rng.uniform(1, 7), cols = rng.uniform(1, 7);
    cv::Mat cost(rows, cols, CV_64FC1);
    rng.fill(cost, cv::RNG::UNIFORM, 0.0, 10.0);
    if (trial % 3 == 0) cost.at<double>(0, 0) = 1e9;  // a forbidden pair
    const std::vector<int> assignment = solveAssignment(cost);
    ASSERT_EQ(static_cast<int>(assignment.size()), rows);
    std::vector<int> seen;
    int assigned = 0;
    for (int c : assignment) {
      if (c < 0) continue;
      ++assigned;
      EXPECT_EQ(std::count(seen.begin(), seen.end(), c), 0) << "column used twice";
      seen.push_back(c);
    }
    EXPECT_EQ(assigned, std::min(rows, cols));
    EXPECT_NEAR(assignmentCost(cost, assignment), bruteForceMinimum(cost), 1e-9) << rows << "x" << cols;
  }
}

TEST(Assignment, GreedyWouldBeWrong) {
  // Greedy takes the 1 and then pays 100; the optimum pays 2 + 3.
  const cv::Mat cost = (cv::Mat_<double>(2, 2) << 1, 2, 3, 100);
  const std::vector<int> assignment = solveAssignment(cost);
  EXPECT_EQ(assignment, (std::vector<int>{1, 0}));
  EXPECT_TRUE(solveAssignment(cv::Mat(0, 3, CV_64FC1)).empty());
}

TEST(MultiTracker, TentativeUntilConfirmedAndNoiseMakesNoTrack) {
  MultiTrackerSettings settings;
  settings.confirmFrames = 3;
  MultiTracker tracker(settings);
  cv::RNG rng(5);
  const cv::Size frame(640, 480);
  for (int i = 0; i < 40; ++i) {
    // One steady object plus two specks somewhere new every frame.
    std::vector<Blob> blobs = {blobAt(100 + 2 * i, 200, 30),
                               blobAt(rng.uniform(0, 640), rng.uniform(0, 480), 8),
                               blobAt(rng.uniform(0, 640), rng.uniform(0, 480), 8)};
    const std::vector<TrackedObject> reported = tracker.update(blobs, frame);
    if (i < 2) {
      EXPECT_TRUE(reported.empty()) << "frame " << i;
    } else {
      ASSERT_EQ(reported.size(), 1u) << "frame " << i;
      EXPECT_EQ(reported[0].id, 1);
      EXPECT_EQ(reported[0].state, TrackState::Tracking);
      EXPECT_NEAR(reported[0].centre.x, 100 + 2 * i, 1.5);
    }
  }
  EXPECT_GT(tracker.allTracks().size(), 1u);  // the specks do start tentative tracks
}

TEST(MultiTracker, PrimaryIsTheLargest) {
  std::vector<TrackedObject> objects(3);
  objects[0].area = 10;
  objects[1].area = 30;
  objects[2].area = 20;
  EXPECT_EQ(primaryIndex(objects), 1);
  EXPECT_EQ(primaryIndex({}), -1);
}

// Three balls of different colours whose straight paths cross (two of them overlap for several frames):
// every ball keeps the id it got, and no extra track appears.
TEST(MultiTracker, IdsHoldThroughCrossings) {
  const BallScene scene = colortrack::balls::threeCrossingBalls();

  BlobSettings blobSettings;
  blobSettings.range = kSaturated;
  BlobDetector detector(blobSettings);
  MultiTracker tracker;
  std::map<int, int> idOfBall;
  int overlapFrames = 0, checked = 0;
  double errorSum = 0;
  for (int i = 0; i <= 90; ++i) {
    std::vector<BallTruth> truth;
    const cv::Mat frame = scene.render(i, &truth);
    const std::vector<TrackedObject> reported =
        tracker.update(detector.detect(MatImageSource(frame)), frame.size());
    if (i < 3) continue;
    EXPECT_EQ(reported.size(), 3u) << "frame " << i;
    for (int b = 0; b < 3; ++b) {
      bool overlapping = false;
      for (int o = 0; o < 3; ++o)
        if (o != b && cv::norm(truth[b].centre - truth[o].centre) < 2 * truth[b].radius + 4)
          overlapping = true;
      if (overlapping) {
        ++overlapFrames;
        continue;
      }
      const TrackedObject *track = nearest(reported, truth[b].centre, truth[b].radius);
      ASSERT_NE(track, nullptr) << "ball " << b << " frame " << i;
      if (!idOfBall.count(b)) idOfBall[b] = track->id;
      EXPECT_EQ(track->id, idOfBall[b]) << "ball " << b << " frame " << i;
      errorSum += cv::norm(track->centre - truth[b].centre);
      ++checked;
    }
  }
  std::printf("crossing: %d ball-frames overlapping, %d checked, mean filtered error %.2f px, ids %d %d %d\n",
              overlapFrames, checked, errorSum / checked, idOfBall[0], idOfBall[1], idOfBall[2]);
  EXPECT_GT(overlapFrames, 10);  // the paths really cross
  EXPECT_LT(errorSum / checked, 2.0);
  EXPECT_EQ(idOfBall.size(), 3u);
}

namespace {

// A ball that runs out of the right edge, waits outside for `waitFrames`, and comes back. Returns the ids it
// was reported with before leaving and after returning, and the frames it was fully out.
struct ExitResult {
  int before = 0, after = 0, framesOut = 0;
};
ExitResult leaveAndReturn(int waitFrames, int maxCoastFrames) {
  BallSceneConfig config;
  Ball ball;
  ball.hue = 200;
  ball.radius = 20;
  ball.path = {
      {0, {300, 240}}, {40, {700, 240}}, {40 + waitFrames, {700, 240}}, {80 + waitFrames, {300, 240}}};
  const BallScene scene(config, {ball});
  BlobSettings blobSettings;
  blobSettings.range = kSaturated;
  blobSettings.range.lower.h = 170;
  blobSettings.range.upper.h = 230;
  BlobDetector detector(blobSettings);
  MultiTrackerSettings settings;
  settings.maxCoastFrames = maxCoastFrames;
  MultiTracker tracker(settings);
  ExitResult result;
  for (int i = 0; i <= 90 + waitFrames; ++i) {
    const cv::Mat frame = scene.render(i);
    const BallTruth truth = scene.truthOf(0, i);
    const std::vector<TrackedObject> reported =
        tracker.update(detector.detect(MatImageSource(frame)), frame.size());
    if (!truth.visible) ++result.framesOut;
    if (!truth.fullyVisible) continue;
    const TrackedObject *track = nearest(reported, truth.centre, truth.radius);
    if (!track) continue;
    (i < 40 ? result.before : result.after) = track->id;
  }
  return result;
}

}  // namespace

TEST(MultiTracker, ShortExitKeepsTheIdLongExitGetsANewOne) {
  const ExitResult shortExit = leaveAndReturn(0, 10);
  std::printf("short exit: %d frames out, id %d -> %d\n", shortExit.framesOut, shortExit.before,
              shortExit.after);
  EXPECT_LT(shortExit.framesOut, 10);
  EXPECT_GT(shortExit.framesOut, 3);
  EXPECT_EQ(shortExit.before, 1);
  EXPECT_EQ(shortExit.after, 1);

  const ExitResult longExit = leaveAndReturn(12, 10);
  std::printf("long exit: %d frames out, id %d -> %d\n", longExit.framesOut, longExit.before, longExit.after);
  EXPECT_GT(longExit.framesOut, 10);
  EXPECT_EQ(longExit.before, 1);
  EXPECT_EQ(longExit.after, 2);
}

// A small object passes behind a large one (only the large one's blob is seen while it is hidden), and a
// third object far away turns back meanwhile. The hidden track must not take the third object's blob:
// without a measurement the filter's uncertainty grows like t^2.5, and a gate built on it spans the frame
// within ten frames (issue 12: "a parked or stale track never grabs a far-away newcomer").
TEST(MultiTracker, ATrackHiddenInAnotherBlobNeverTakesAFarAwayOne) {
  MultiTracker tracker;
  const cv::Size frame(640, 480);
  const cv::Point2d large(200, 200);
  constexpr double kLargeSide = 60, kSmallSide = 20;
  int farId = 0, hiddenId = 0, hiddenFrames = 0;
  for (int i = 0; i < 45; ++i) {
    const cv::Point2d small(80 + 4.0 * i, 200);  // behind the large one for x in 170-230
    const cv::Point2d far(360, 260 + (i < 35 ? -3.0 * i : -105 + 3.0 * (i - 35)));  // turns back at 35
    const bool hidden = std::abs(small.x - large.x) < kLargeSide / 2;
    hiddenFrames += hidden;
    std::vector<Blob> blobs = {blobAt(large.x, large.y, kLargeSide), blobAt(far.x, far.y, kSmallSide)};
    if (!hidden) blobs.push_back(blobAt(small.x, small.y, kSmallSide));
    const std::vector<TrackedObject> reported = tracker.update(blobs, frame);
    if (i < 3) continue;  // confirming
    const TrackedObject *onFar = nearest(reported, far, 5);
    ASSERT_NE(onFar, nullptr) << "frame " << i;
    if (farId == 0) farId = onFar->id;
    EXPECT_EQ(onFar->id, farId) << "frame " << i << ": the far object's blob went to another track";
    if (hiddenId == 0 && !hidden)
      hiddenId = nearest(reported, small, 5) ? nearest(reported, small, 5)->id : 0;
    for (const TrackedObject &o : reported) {
      if (o.id == hiddenId) {
        EXPECT_LT(cv::norm(o.centre - small), 30) << "frame " << i << ": the hidden track is off its object";
      }
    }
  }
  EXPECT_GE(hiddenFrames, 14);
  EXPECT_NE(hiddenId, 0);
}

// The other side of the same rule: a small object that turns back while it is hidden behind a large one comes
// out where it went in, further from its coasting prediction than a gate that never grows would reach. Its
// track takes it back, and no second track is started on it.
TEST(MultiTracker, AnObjectThatTurnsBackWhileHiddenKeepsItsId) {
  MultiTracker tracker;
  const cv::Size frame(640, 480);
  const cv::Point2d large(200, 200);
  constexpr double kLargeSide = 60, kSmallSide = 20;
  int id = 0, hiddenFrames = 0;
  for (int i = 0; i < 50; ++i) {
    // Rightwards at 4 px/frame, behind the large one from x = 172, back at 2 px/frame from frame 30 (x =
    // 200).
    const cv::Point2d small(i < 30 ? 80 + 4.0 * i : 200 - 2.0 * (i - 30), 200);
    const bool hidden = std::abs(small.x - large.x) < kLargeSide / 2;
    hiddenFrames += hidden;
    std::vector<Blob> blobs = {blobAt(large.x, large.y, kLargeSide)};
    if (!hidden) blobs.push_back(blobAt(small.x, small.y, kSmallSide));
    const std::vector<TrackedObject> reported = tracker.update(blobs, frame);
    if (i < 3 || hidden) continue;
    const TrackedObject *onSmall = nearest(reported, small, 5);
    ASSERT_NE(onSmall, nullptr) << "frame " << i;
    if (id == 0) id = onSmall->id;
    EXPECT_EQ(onSmall->id, id) << "frame " << i;
    EXPECT_EQ(reported.size(), 2u) << "frame " << i;  // the large one and the small one, no third track
  }
  EXPECT_GE(hiddenFrames, 20);
}

// An object at rest jumps in the image (the camera turned once) and is lost a moment later: its track coasts
// near where it was seen, not on the jump, which the filter's velocity has followed. One lost while moving
// steadily is followed at its speed.
TEST(MultiTracker, CoastingDoesNotFollowAOneFrameJump) {
  const cv::Size frame(640, 480);
  for (const bool jump : {true, false}) {
    const double speed = jump ? 0 : 3;
    MultiTracker tracker;
    double x = 300;
    for (int i = 0; i < 20; ++i, x += speed) tracker.update({blobAt(x, 200, 40)}, frame);
    if (jump) x -= 13;  // then seen on two frames
    for (int i = 0; i < 2; ++i, x += speed) tracker.update({blobAt(x, 200, 40)}, frame);
    const double lostAt = x - speed;
    std::vector<TrackedObject> reported;
    for (int i = 0; i < 8; ++i) reported = tracker.update({}, frame);
    ASSERT_EQ(reported.size(), 1u) << "jump " << jump;
    EXPECT_EQ(reported[0].state, TrackState::Coasting);
    EXPECT_NEAR(reported[0].centre.x, lostAt + 8 * speed, 20) << "jump " << jump;  // half its size
  }
}

// Two balls 60 px apart moving right at 2 px a frame; the camera jerks 60 px left in one frame, so in the
// picture both jump 60 px right: the left ball lands where the right one was. Told how the picture moved,
// each track keeps its ball (not told, the right ball's track takes the left ball: printed).
TEST(MultiTracker, FollowsTheCameraThroughAJerk) {
  for (const bool told : {true, false}) {
    MultiTracker tracker;
    std::vector<TrackedObject> out;
    cv::Point2d left(200, 240), right(260, 240);
    for (int i = 0; i < 10; ++i) {
      out = tracker.update({blobAt(left.x, left.y, 20), blobAt(right.x, right.y, 20)}, cv::Size(640, 480));
      left.x += 2;
      right.x += 2;
    }
    ASSERT_EQ(out.size(), 2u);
    const int leftId = nearest(out, left, 10)->id, rightId = nearest(out, right, 10)->id;
    const cv::Point2d jerk(60, 0);
    for (int i = 0; i < 5; ++i) {
      if (told && i == 0) tracker.followCamera(jerk);
      const cv::Point2d l = left + jerk, r = right + jerk;
      out = tracker.update({blobAt(l.x, l.y, 20), blobAt(r.x, r.y, 20)}, cv::Size(640, 480));
      left.x += 2;
      right.x += 2;
    }
    const TrackedObject *l = nearest(out, left + jerk, 4), *r = nearest(out, right + jerk, 4);
    if (told) {
      ASSERT_TRUE(l && r);
      EXPECT_EQ(l->id, leftId);
      EXPECT_EQ(r->id, rightId);
      EXPECT_NEAR(l->vx, 2, 0.5);  // the ball's own motion: the jerk is not in the velocity
    } else {
      // Not told (today the right ball's track takes the left ball): shown, not required.
      std::printf("not told of the jerk: left ball's track id %d (was %d), right ball's %d (was %d)\n",
                  l ? l->id : -1, leftId, r ? r->id : -1, rightId);
    }
  }
}
