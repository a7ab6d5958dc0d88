// SPDX-License-Identifier: LGPL-2.1-or-later
#include "balls.hpp"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace colortrack::balls {

namespace {

double hueDistance(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

cv::Point2d positionAt(const Ball &ball, int index) {
  const std::vector<Waypoint> &path = ball.path;
  if (path.empty()) return {};
  if (index <= path.front().frame) return path.front().centre;
  for (std::size_t i = 1; i < path.size(); ++i) {
    if (index <= path[i].frame) {
      const Waypoint &a = path[i - 1], &b = path[i];
      const double t = b.frame == a.frame ? 1.0 : static_cast<double>(index - a.frame) / (b.frame - a.frame);
      return a.centre + t * (b.centre - a.centre);
    }
  }
  return path.back().centre;
}

}  // namespace

cv::Vec3b bgrOfHsv(double hue, double saturation, double value) {
  // The standard hexcone inverse of rgbToHsv.
  const double h = std::fmod(std::fmod(hue, 360.0) + 360.0, 360.0) / 60.0;
  const double c = value * saturation, x = c * (1 - std::abs(std::fmod(h, 2.0) - 1)), m = value - c;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(h)) {
    case 0:
      r = c;
      g = x;
      break;
    case 1:
      r = x;
      g = c;
      break;
    case 2:
      g = c;
      b = x;
      break;
    case 3:
      g = x;
      b = c;
      break;
    case 4:
      r = x;
      b = c;
      break;
    default:
      r = c;
      b = x;
      break;
  }
  return cv::Vec3b(cv::saturate_cast<uchar>((b + m) * 255), cv::saturate_cast<uchar>((g + m) * 255),
                   cv::saturate_cast<uchar>((r + m) * 255));
}

BallScene::BallScene(const BallSceneConfig &config, std::vector<Ball> balls)
    : config_(config), balls_(std::move(balls)) {
  cv::RNG rng(config.seed);
  const cv::Size size = config.sceneSize.empty() ? config.frameSize : config.sceneSize;
  // Smooth grey blotches with a faint tint: texture that no sensible range picks up.
  cv::Mat small(std::max(2, size.height / 24), std::max(2, size.width / 24), CV_8UC3);
  for (int y = 0; y < small.rows; ++y)
    for (int x = 0; x < small.cols; ++x)
      small.at<cv::Vec3b>(y, x) =
          bgrOfHsv(rng.uniform(0.0, 360.0), rng.uniform(0.0, 0.12), rng.uniform(0.2, 0.8));
  cv::resize(small, background_, size, 0, 0, cv::INTER_CUBIC);
  cv::Mat grain(size, CV_8UC3);
  rng.fill(grain, cv::RNG::NORMAL, cv::Scalar::all(0), cv::Scalar::all(6));
  cv::add(background_, grain, background_);

  for (int i = 0; i < config.clutterPatches; ++i) {
    double hue = 0;
    bool ok = false;
    for (int attempt = 0; attempt < 100 && !ok; ++attempt) {
      hue = rng.uniform(0.0, 360.0);
      ok = true;
      for (const Ball &b : balls_)
        if (hueDistance(hue, b.hue) < config.clutterHueClearance) ok = false;
    }
    if (!ok) break;
    const int w = rng.uniform(size.width / 40 + 4, size.width / 6 + 5);
    const int h = rng.uniform(size.height / 40 + 4, size.height / 6 + 5);
    const cv::Rect patch(rng.uniform(0, size.width - w), rng.uniform(0, size.height - h), w, h);
    const cv::Vec3b colour =
        bgrOfHsv(hue, rng.uniform(0.3, std::max(0.31, config.clutterSaturation)), rng.uniform(0.3, 0.9));
    background_(patch).setTo(cv::Scalar(colour[0], colour[1], colour[2]));
  }
}

BallTruth BallScene::truthOf(int ball, int index) const {
  const Ball &b = balls_[ball];
  BallTruth t;
  const cv::Matx23d toFrame = sceneToFrame(index);
  const cv::Point2d scene = positionAt(b, index);
  t.centre = cv::Point2d(toFrame(0, 0) * scene.x + toFrame(0, 1) * scene.y + toFrame(0, 2),
                         toFrame(1, 0) * scene.x + toFrame(1, 1) * scene.y + toFrame(1, 2));
  t.radius = b.radius * std::hypot(toFrame(0, 0), toFrame(1, 0));
  const cv::Size s = config_.frameSize;
  t.fullyVisible = t.centre.x - t.radius >= 0 && t.centre.y - t.radius >= 0 &&
                   t.centre.x + t.radius <= s.width - 1 && t.centre.y + t.radius <= s.height - 1;
  t.visible = t.centre.x + t.radius >= 0 && t.centre.y + t.radius >= 0 &&
              t.centre.x - t.radius <= s.width - 1 && t.centre.y - t.radius <= s.height - 1;
  return t;
}

cv::Point BallScene::cameraAt(int index) const {
  const std::vector<cv::Point> &path = config_.cameraPath;
  if (path.empty()) return cv::Point();
  return path[std::clamp(index, 0, static_cast<int>(path.size()) - 1)];
}

namespace {
double valueAt(const std::vector<double> &values, int index, double none) {
  if (values.empty()) return none;
  return values[std::clamp(index, 0, static_cast<int>(values.size()) - 1)];
}
}  // namespace

cv::Matx23d BallScene::sceneToFrame(int index) const {
  const cv::Point2d centre(config_.frameSize.width / 2.0, config_.frameSize.height / 2.0);
  cv::Mat m = cv::getRotationMatrix2D(centre, valueAt(config_.cameraTurn, index, 0),
                                      valueAt(config_.cameraZoom, index, 1));
  cv::Matx23d toFrame(m);
  const cv::Point2d corner(cameraAt(index));
  // First from the scene to the untransformed view (minus the corner), then the turn and zoom.
  toFrame(0, 2) -= toFrame(0, 0) * corner.x + toFrame(0, 1) * corner.y;
  toFrame(1, 2) -= toFrame(1, 0) * corner.x + toFrame(1, 1) * corner.y;
  return toFrame;
}

cv::Rect BallScene::boxOf(int ball, int index) const {
  const BallTruth t = truthOf(ball, index);
  const int x0 = static_cast<int>(std::floor(t.centre.x - t.radius));
  const int y0 = static_cast<int>(std::floor(t.centre.y - t.radius));
  const int x1 = static_cast<int>(std::ceil(t.centre.x + t.radius)) + 1;
  const int y1 = static_cast<int>(std::ceil(t.centre.y + t.radius)) + 1;
  return cv::Rect(cv::Point(x0, y0), cv::Point(x1, y1)) & cv::Rect(cv::Point(), config_.frameSize);
}

cv::Mat BallScene::render(int index, std::vector<BallTruth> *truth) const {
  cv::Mat frame;
  if (config_.cameraTurn.empty() && config_.cameraZoom.empty())
    frame = background_(cv::Rect(cameraAt(index), config_.frameSize)).clone();
  else
    cv::warpAffine(background_, frame, cv::Mat(sceneToFrame(index)), config_.frameSize, cv::INTER_LINEAR,
                   cv::BORDER_REFLECT);
  const cv::Rect inside(cv::Point(), frame.size());
  if (truth) truth->clear();
  for (int i = 0; i < static_cast<int>(balls_.size()); ++i) {
    const Ball &b = balls_[i];
    const BallTruth t = truthOf(i, index);
    if (truth) truth->push_back(t);
    const double radius = t.radius;
    const cv::Rect area = cv::Rect(cv::Point(static_cast<int>(std::floor(t.centre.x - radius - 1)),
                                             static_cast<int>(std::floor(t.centre.y - radius - 1))),
                                   cv::Point(static_cast<int>(std::ceil(t.centre.x + radius + 2)),
                                             static_cast<int>(std::ceil(t.centre.y + radius + 2)))) &
                          inside;
    const cv::Point2d spot = t.centre + cv::Point2d(-0.35 * radius, -0.35 * radius);
    for (int y = area.y; y < area.y + area.height; ++y) {
      cv::Vec3b *row = frame.ptr<cv::Vec3b>(y);
      for (int x = area.x; x < area.x + area.width; ++x) {
        const double r = std::hypot(x - t.centre.x, y - t.centre.y);
        const double coverage = std::clamp(radius + 0.5 - r, 0.0, 1.0);  // anti-aliased rim
        if (coverage <= 0) continue;
        // Shaded towards the rim, like a lit sphere: V varies, hue and saturation do not.
        const double shade = 1.0 - 0.35 * std::min(1.0, (r * r) / (radius * radius));
        cv::Vec3d colour = cv::Vec3d(bgrOfHsv(b.hue, b.saturation, b.value * shade));
        if (b.highlight > 0) {
          const double h = std::clamp(b.highlight + 0.5 - std::hypot(x - spot.x, y - spot.y), 0.0, 1.0);
          colour = (1 - h) * colour + h * cv::Vec3d(250, 250, 250);
        }
        const cv::Vec3d under(row[x]);
        row[x] = cv::Vec3b(coverage * colour + (1 - coverage) * under);
      }
    }
  }

  if (config_.saltPepper > 0 && !balls_.empty()) {
    cv::RNG rng(config_.seed * 7919u + static_cast<std::uint32_t>(index) * 104729u + 17u);
    const cv::Vec3b target = bgrOfHsv(balls_[0].hue, balls_[0].saturation, balls_[0].value);
    const int count = static_cast<int>(config_.saltPepper * frame.total());
    for (int i = 0; i < count; ++i) {
      const int kind = rng.uniform(0, 3);
      frame.at<cv::Vec3b>(rng.uniform(0, frame.rows), rng.uniform(0, frame.cols)) =
          kind == 0   ? target
          : kind == 1 ? cv::Vec3b(255, 255, 255)
                      : cv::Vec3b(0, 0, 0);
    }
  }

  if (config_.brightness != 0) {
    const double factor = 1.0 + config_.brightness * std::sin(2 * CV_PI * index / config_.brightnessPeriod);
    frame.convertTo(frame, -1, factor, 0);
  }
  return frame;
}

BallScene threeCrossingBalls() {
  BallSceneConfig config;
  config.clutterHueClearance = 0;
  config.clutterSaturation = 0.35;  // colourful but below a saturated range
  std::vector<Ball> three(3);
  three[0].hue = 0;
  three[0].path = {{0, {40, 240}}, {90, {600, 240}}};
  three[1].hue = 120;
  three[1].path = {{0, {60, 40}}, {90, {560, 440}}};
  three[2].hue = 240;
  three[2].path = {{0, {580, 60}}, {90, {80, 400}}};
  return BallScene(config, three);
}

}  // namespace colortrack::balls
