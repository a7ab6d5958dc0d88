// SPDX-License-Identifier: LGPL-2.1-or-later
#include "mot_scenes.hpp"

#include <algorithm>
#include <functional>
#include <cmath>
#include <cstdint>
#include <string>

#include <opencv2/imgproc.hpp>

namespace colortrack::eval {

namespace {

constexpr double kRed = 0, kOrange = 32, kMagenta = 300;
constexpr int kHeldOutRandomScenes = 8;

balls::Ball ball(double hue, double radius, std::vector<balls::Waypoint> path) {
  balls::Ball b;
  b.hue = hue;
  b.radius = radius;
  b.path = std::move(path);
  return b;
}

MotScene makeScene(std::string name, balls::BallSceneConfig config, std::vector<balls::Ball> list,
                   std::vector<bool> isTarget) {
  return MotScene{std::move(name), balls::BallScene(config, std::move(list)), std::move(isTarget), cv::Rect(),
                  cv::Rect()};
}

MotScene crossing() {
  balls::BallSceneConfig config;
  config.seed = 11;
  // A small ball passes over a big one (frame 120, middle of the frame); two equal balls cross earlier,
  // higher up (frame 60).
  return makeScene("crossing", config,
                   {ball(kRed, 42, {{0, {100, 320}}, {240, {540, 320}}}),
                    ball(kRed, 14, {{0, {540, 305}}, {240, {100, 305}}}),
                    ball(kRed, 24, {{0, {320, -20}}, {120, {320, 240}}}),
                    ball(kRed, 24, {{0, {180, 40}}, {120, {460, 180}}})},
                   {true, true, true, true});
}

// Eight balls on random straight paths that turn every 40 frames. Seed 1234 is the scene issue 12 was tuned
// on ("eight-random"); the others ("random-eight-N") were first run in issue 47 and are the held-out check.
MotScene eightAtRandom(const std::string &name, uint64_t pathSeed) {
  balls::BallSceneConfig config;
  config.seed = 12;
  cv::RNG rng(pathSeed);
  std::vector<balls::Ball> list;
  for (int i = 0; i < 8; ++i) {
    std::vector<balls::Waypoint> path;
    for (int f = 0; f <= 240; f += 40)
      path.push_back({f, cv::Point2d(rng.uniform(60.0, 580.0), rng.uniform(60.0, 420.0))});
    list.push_back(ball(kRed, rng.uniform(10.0, 32.0), path));
  }
  return makeScene(name, config, list, std::vector<bool>(8, true));
}

MotScene enterLeaveBehindBoard() {
  balls::BallSceneConfig config;
  config.seed = 13;
  std::vector<balls::Ball> list;
  for (int i = 0; i < 5; ++i) {
    const int start = i * 40;
    const double y = 90 + 75 * i;
    list.push_back(ball(kRed, 18 + 3 * i, {{start, {-60, y}}, {start + 120, {700, y + (i % 2 ? 30 : -30)}}}));
  }
  MotScene s = makeScene("enter-leave-board", config, list, std::vector<bool>(5, true));
  s.board = cv::Rect(290, 0, 60, 480);
  return s;
}

MotScene lightingAndShadow() {
  balls::BallSceneConfig config;
  config.seed = 14;
  config.brightness = 0.3;
  config.brightnessPeriod = 120;
  MotScene s = makeScene("light-shadow", config,
                         {ball(kRed, 28, {{0, {60, 120}}, {120, {580, 360}}, {240, {60, 360}}}),
                          ball(kRed, 20, {{0, {580, 100}}, {120, {80, 200}}, {240, {560, 420}}}),
                          ball(kRed, 16, {{0, {320, 440}}, {120, {320, 40}}, {240, {320, 440}}})},
                         {true, true, true});
  s.shadow = cv::Rect(0, 200, 640, 90);
  return s;
}

MotScene distractors() {
  balls::BallSceneConfig config;
  config.seed = 15;
  config.saltPepper = 0.0015;  // specks of the first ball's red
  MotScene s = makeScene("distractors", config,
                         {ball(kRed, 24, {{0, {80, 100}}, {240, {560, 380}}}),
                          ball(kRed, 18, {{0, {560, 100}}, {240, {100, 400}}}),
                          ball(kRed, 30, {{0, {320, 420}}, {120, {320, 80}}, {240, {330, 420}}}),
                          ball(kOrange, 26, {{0, {100, 300}}, {240, {540, 200}}}),
                          ball(kOrange, 20, {{0, {480, 440}}, {240, {200, 60}}}),
                          ball(kMagenta, 28, {{0, {600, 260}}, {240, {60, 240}}}),
                          ball(kMagenta, 16, {{0, {200, 40}}, {240, {420, 460}}})},
                         {true, true, true, false, false, false, false});
  return s;
}

// Bounces off the walls of `arena` at a constant speed: one waypoint a frame.
std::vector<balls::Waypoint> bouncingPath(cv::RNG &rng, cv::Rect arena, double radius, int frames) {
  const double x0 = arena.x + radius, x1 = arena.br().x - radius;
  const double y0 = arena.y + radius, y1 = arena.br().y - radius;
  cv::Point2d p(rng.uniform(x0, x1), rng.uniform(y0, y1));
  const double speed = rng.uniform(2.0, 5.0), angle = rng.uniform(0.0, 2 * CV_PI);
  cv::Point2d v(speed * std::cos(angle), speed * std::sin(angle));
  std::vector<balls::Waypoint> path;
  for (int f = 0; f <= frames; ++f) {
    path.push_back({f, p});
    p += v;
    if (p.x < x0 || p.x > x1) v.x = -v.x;
    if (p.y < y0 || p.y > y1) v.y = -v.y;
  }
  return path;
}

// Still spells of 4-15 frames and bursts of 4-10 frames at 6-14 px a frame in a random direction, turned
// back at the scene's edge: a hand-held or robot camera that jerks.
std::vector<cv::Point> jerkyCamera(cv::RNG &rng, cv::Size scene, cv::Size frame, int frames) {
  const cv::Point limit(scene.width - frame.width, scene.height - frame.height);
  cv::Point2d p(limit.x / 2.0, limit.y / 2.0);
  std::vector<cv::Point> path;
  while (static_cast<int>(path.size()) < frames) {
    for (int still = rng.uniform(4, 16); still > 0; --still) path.push_back(cv::Point(p));
    const double speed = rng.uniform(6.0, 14.0), angle = rng.uniform(0.0, 2 * CV_PI);
    cv::Point2d v(std::round(speed * std::cos(angle)), std::round(speed * std::sin(angle)));
    for (int burst = rng.uniform(4, 11); burst > 0; --burst) {
      if (p.x + v.x < 0 || p.x + v.x > limit.x) v.x = -v.x;
      if (p.y + v.y < 0 || p.y + v.y > limit.y) v.y = -v.y;
      p += v;
      path.push_back(cv::Point(p));
    }
  }
  path.resize(frames);
  return path;
}

// The same camera with a shake of up to 1.5 px (rounded to whole px) on every frame, still spells included:
// a robot's camera on a vibrating base (issue 47).
std::vector<cv::Point> shakyCamera(cv::RNG &rng, cv::Size scene, cv::Size frame, int frames) {
  std::vector<cv::Point> path = jerkyCamera(rng, scene, frame, frames);
  const cv::Point limit(scene.width - frame.width, scene.height - frame.height);
  for (cv::Point &p : path) {
    p.x = std::clamp(p.x + cvRound(rng.uniform(-1.5, 1.5)), 0, limit.x);
    p.y = std::clamp(p.y + cvRound(rng.uniform(-1.5, 1.5)), 0, limit.y);
  }
  return path;
}

// A slow pan (0.4 px a frame to the right) with two jerks of a quarter of the frame each way in one frame
// (a bump, a gimbal that snaps): there at frame 100, back at frame 200 (issue 47).
std::vector<cv::Point> snappingCamera(cv::Size frame, int frames) {
  const cv::Point jerk(frame.width / 4, frame.height / 4);
  std::vector<cv::Point> path;
  for (int f = 0; f < frames; ++f)
    path.push_back(cv::Point(cvRound(0.4 * f), 0) + (f >= 100 && f < 200 ? jerk : cv::Point()));
  return path;
}

// Six red balls bounce in a scene larger than the frame while the camera moves over it (`cameraPath` of the
// scene size and frame count), within the part of the scene every view of the camera holds: an object that
// changes id changed it because the camera moved, not because it left the view.
MotScene movingCamera(
    const std::string &name, int seed, cv::Size sceneSize,
    const std::function<std::vector<cv::Point>(cv::RNG &, const balls::BallSceneConfig &, int)> &cameraPath,
    const std::function<void(balls::BallSceneConfig &, int)> &turnAndZoom = {}) {
  balls::BallSceneConfig config;
  config.seed = 16 + seed;
  config.sceneSize = sceneSize;
  constexpr int kFrames = 300;
  cv::RNG rng(seed);
  config.cameraPath = cameraPath(rng, config, kFrames);
  if (turnAndZoom) turnAndZoom(config, kFrames);
  const cv::Size travel = config.sceneSize - config.frameSize;
  const cv::Rect arena(cv::Point(travel), config.frameSize - travel);
  std::vector<balls::Ball> list;
  for (int i = 0; i < 6; ++i) {
    const double radius = rng.uniform(14.0, 26.0);
    list.push_back(ball(kRed, radius, bouncingPath(rng, arena, radius, kFrames)));
  }
  MotScene s = makeScene(name, config, list, std::vector<bool>(6, true));
  s.frames = kFrames;
  return s;
}

// A drone's camera: the bursts of jerkyCamera, a yaw that swings +-4 degrees (a period of 120 frames) and a
// climb that zooms out and back, 1.2 times to 1 and back to 1.2 at 0.5 % a frame (issue 47).
MotScene turningCameraScene(int seed) {
  return movingCamera(
      "turning-camera-" + std::to_string(seed), seed, cv::Size(760, 570),
      [](cv::RNG &rng, const balls::BallSceneConfig &c, int frames) {
        return jerkyCamera(rng, c.sceneSize, c.frameSize, frames);
      },
      [](balls::BallSceneConfig &c, int frames) {
        for (int f = 0; f < frames; ++f) {
          c.cameraTurn.push_back(4.0 * std::sin(2 * CV_PI * f / 120.0));
          const double climb = std::clamp(std::abs(f - frames / 2.0) / 40.0, 0.0, 1.0);  // 0 at the middle
          c.cameraZoom.push_back(1.0 + 0.2 * climb);
        }
      });
}

MotScene panningCamera(int seed) {
  return movingCamera("panning-camera-" + std::to_string(seed), seed, cv::Size(760, 570),
                      [](cv::RNG &rng, const balls::BallSceneConfig &c, int frames) {
                        return jerkyCamera(rng, c.sceneSize, c.frameSize, frames);
                      });
}

MotScene shakyCameraScene(int seed) {
  return movingCamera("shaky-camera-" + std::to_string(seed), seed, cv::Size(760, 570),
                      [](cv::RNG &rng, const balls::BallSceneConfig &c, int frames) {
                        return shakyCamera(rng, c.sceneSize, c.frameSize, frames);
                      });
}

MotScene snappingCameraScene() {
  // The scene is as large as the path's reach (pan 120 px, jerk 160 px across and 120 down).
  return movingCamera("snapping-camera", 4, cv::Size(640 + 240, 480 + 120),
                      [](cv::RNG &, const balls::BallSceneConfig &c, int frames) {
                        return snappingCamera(c.frameSize, frames);
                      });
}

}  // namespace

cv::Mat MotScene::render(int index, MotFrame &truth, double minVisibleFraction, int minArea) const {
  std::vector<balls::BallTruth> balls;
  cv::Mat frame = this->balls.render(index, &balls);
  const cv::Rect frameRect(cv::Point(), frame.size());
  if (!shadow.empty()) {
    cv::Mat band = frame(shadow & frameRect);
    band.convertTo(band, -1, shadowFactor);
  }
  if (!board.empty()) frame(board & frameRect).setTo(cv::Scalar(128, 128, 128));

  truth = MotFrame();
  for (size_t i = 0; i < balls.size(); ++i) {
    if (!isTarget[i]) continue;
    const balls::BallTruth &b = balls[i];
    // The visible pixels: the disc inside the frame and not behind the board.
    const cv::Rect disc(cvFloor(b.centre.x - b.radius), cvFloor(b.centre.y - b.radius),
                        cvCeil(2 * b.radius) + 1, cvCeil(2 * b.radius) + 1);
    int visible = 0, total = 0;
    int x0 = frame.cols, y0 = frame.rows, x1 = -1, y1 = -1;
    for (int y = disc.y; y < disc.y + disc.height; ++y)
      for (int x = disc.x; x < disc.x + disc.width; ++x) {
        if (std::hypot(x + 0.5 - b.centre.x, y + 0.5 - b.centre.y) > b.radius) continue;
        ++total;
        const cv::Point p(x, y);
        if (!frameRect.contains(p) || board.contains(p)) continue;
        // Balls are drawn in order: a later one covers this one.
        bool covered = false;
        for (size_t j = i + 1; j < balls.size() && !covered; ++j)
          covered = std::hypot(x + 0.5 - balls[j].centre.x, y + 0.5 - balls[j].centre.y) <= balls[j].radius;
        if (covered) continue;
        ++visible;
        x0 = std::min(x0, x);
        y0 = std::min(y0, y);
        x1 = std::max(x1, x);
        y1 = std::max(y1, y);
      }
    const int id = static_cast<int>(i) + 1;
    if (total > 0 && visible >= minArea && visible >= minVisibleFraction * total)
      truth.truth.push_back({id, cv::Rect2d(x0, y0, x1 - x0 + 1, y1 - y0 + 1)});
    else if (visible > 0)
      truth.ignored.push_back({id, cv::Rect2d(x0, y0, x1 - x0 + 1, y1 - y0 + 1)});
    else if (board.contains(cv::Point(cvRound(b.centre.x), cvRound(b.centre.y))))
      truth.ignored.push_back({id, cv::Rect2d(disc)});  // wholly behind the board
  }
  return frame;
}

std::vector<MotScene> motScenes() {
  std::vector<MotScene> scenes = {crossing(),
                                  eightAtRandom("eight-random", 1234),
                                  enterLeaveBehindBoard(),
                                  lightingAndShadow(),
                                  distractors(),
                                  panningCamera(1),
                                  panningCamera(2),
                                  panningCamera(3),
                                  shakyCameraScene(1),
                                  shakyCameraScene(2),
                                  snappingCameraScene(),
                                  turningCameraScene(1),
                                  turningCameraScene(2)};
  for (int seed = 1; seed <= kHeldOutRandomScenes; ++seed)
    scenes.push_back(eightAtRandom("random-eight-" + std::to_string(seed), static_cast<uint64_t>(seed)));
  return scenes;
}

}  // namespace colortrack::eval
