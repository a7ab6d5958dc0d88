#include "mot_scenes.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack::eval {

namespace {

constexpr double kRed = 0, kOrange = 32, kMagenta = 300;

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

MotScene eightAtRandom() {
  balls::BallSceneConfig config;
  config.seed = 12;
  cv::RNG rng(1234);
  std::vector<balls::Ball> list;
  for (int i = 0; i < 8; ++i) {
    std::vector<balls::Waypoint> path;
    for (int f = 0; f <= 240; f += 40)
      path.push_back({f, cv::Point2d(rng.uniform(60.0, 580.0), rng.uniform(60.0, 420.0))});
    list.push_back(ball(kRed, rng.uniform(10.0, 32.0), path));
  }
  return makeScene("eight-random", config, list, std::vector<bool>(8, true));
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
  return {crossing(), eightAtRandom(), enterLeaveBehindBoard(), lightingAndShadow(), distractors()};
}

}  // namespace colortrack::eval
