// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robot_sim.hpp"

#include <cmath>
#include <cstdio>

#include <opencv2/imgproc.hpp>

namespace colortrack::robot_sim {

RobotSim::RobotSim(const RobotSimConfig &config, const Pose &start)
    : config_(config),
      pose_(start),
      focal_(config.frameSize.width / 2.0 / std::tan(config.horizontalFovDegrees * CV_PI / 360.0)) {}

cv::Point3d RobotSim::toCamera(double x, double y, double z) const {
  const double dx = x - pose_.x, dy = y - pose_.y;
  const double c = std::cos(pose_.heading), s = std::sin(pose_.heading);
  return {dx * c + dy * s, -dx * s + dy * c, z - config_.cameraHeight};
}

cv::Rect2d RobotSim::ballBox() const {
  if (hidden_) return {};
  return boxOf(config_.ball, config_.ballRadius);
}

cv::Rect2d RobotSim::distractorBox() const {
  if (config_.distractorRadius <= 0 || distractorHidden_) return {};
  return boxOf(config_.distractor, config_.distractorRadius);
}

cv::Rect2d RobotSim::boxOf(cv::Point2d position, double r) const {
  const cv::Point3d p = toCamera(position.x, position.y, r);
  if (p.x <= r) return {};
  const double cx = config_.frameSize.width / 2.0, cy = config_.frameSize.height / 2.0;
  const double u = cx - focal_ * p.y / p.x, v = cy - focal_ * p.z / p.x;
  const double radius = focal_ * r / p.x;
  return {u - radius, v - radius, 2 * radius, 2 * radius};
}

void RobotSim::placeDistractor(double bearing, double distance) {
  const double direction = pose_.heading + bearing;
  config_.distractor =
      cv::Point2d(pose_.x + distance * std::cos(direction), pose_.y + distance * std::sin(direction));
}

namespace {

// Smooth noise stretched to 0-255, blurred by `sigma` (x, y) cells.
cv::Mat smoothNoise(cv::Size size, int seed, cv::Size2d sigma) {
  cv::Mat noise(size, CV_8U);
  cv::RNG(seed).fill(noise, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(noise, noise, cv::Size(0, 0), sigma.width, sigma.height, cv::BORDER_WRAP);
  cv::normalize(noise, noise, 0, 255, cv::NORM_MINMAX);
  return noise;
}

// Wraps `i` into [0, n).
int wrap(long i, int n) {
  return static_cast<int>(((i % n) + n) % n);
}

}  // namespace

void RobotSim::setBackdrop(Backdrop backdrop) {
  backdrop_ = backdrop;
  if (backdrop == Backdrop::Mottled && floorTexture_.empty()) {
    floorTexture_ = smoothNoise(cv::Size(1024, 1024), 46, cv::Size2d(8, 8));
    // Vertical streaks, as of boards or panels.
    wallTexture_ = smoothNoise(cv::Size(1024, 64), 47, cv::Size2d(1.5, 12));
  }
}

void RobotSim::moveBall(double dt) {
  config_.ball += config_.ballVelocity * dt;
  config_.distractor += config_.distractorVelocity * dt;
}

double RobotSim::ballBearing() const {
  const cv::Point3d p = toCamera(config_.ball.x, config_.ball.y, config_.ballRadius);
  return std::atan2(p.y, p.x);
}

double RobotSim::ballDistance() const {
  return std::hypot(config_.ball.x - pose_.x, config_.ball.y - pose_.y);
}

double RobotSim::distractorBearing() const {
  const cv::Point3d p = toCamera(config_.distractor.x, config_.distractor.y, config_.distractorRadius);
  return std::atan2(p.y, p.x);
}

double RobotSim::distractorDistance() const {
  return std::hypot(config_.distractor.x - pose_.x, config_.distractor.y - pose_.y);
}

double RobotSim::distanceForSizeCue(double cue) const {
  return 2 * focal_ * config_.ballRadius / (cue * config_.frameSize.height);
}

void drawBall(cv::Mat &image, const cv::Rect2d &box) {
  if (box.empty()) return;
  constexpr int kShift = 4;
  const double scale = 1 << kShift;
  const cv::Point centre(cvRound((box.x + box.width / 2) * scale), cvRound((box.y + box.height / 2) * scale));
  const double radius = box.width / 2;
  cv::circle(image, centre, cvRound(radius * scale), cv::Scalar(25, 25, 170), cv::FILLED, cv::LINE_AA,
             kShift);
  cv::circle(image, centre - cv::Point(cvRound(radius * 0.15 * scale), cvRound(radius * 0.15 * scale)),
             cvRound(radius * 0.7 * scale), cv::Scalar(40, 40, 215), cv::FILLED, cv::LINE_AA, kShift);
  cv::circle(image, centre - cv::Point(cvRound(radius * 0.35 * scale), cvRound(radius * 0.35 * scale)),
             cvRound(radius * 0.25 * scale), cv::Scalar(120, 120, 245), cv::FILLED, cv::LINE_AA, kShift);
}

cv::Point2d RobotSim::floorPoint(double left, double up) const {
  const double c = std::cos(pose_.heading), s = std::sin(pose_.heading);
  const double t = config_.cameraHeight / -up;  // the ray meets the floor at this forward distance
  return {pose_.x + t * (c - left * s), pose_.y + t * (s + left * c)};
}

cv::Vec3b RobotSim::checkered(double left, double up) const {
  if (up >= -1e-6) {
    // Sky: a soft vertical gradient, pale and unsaturated.
    const int shade = static_cast<int>(200 + 40 * std::min(1.0, up * 2));
    return cv::Vec3b(static_cast<uchar>(shade), static_cast<uchar>(shade - 10),
                     static_cast<uchar>(shade - 30));
  }
  constexpr double kTile = 0.5;  // m
  const cv::Point2d p = floorPoint(left, up);
  const bool dark =
      (static_cast<long>(std::floor(p.x / kTile)) + static_cast<long>(std::floor(p.y / kTile))) & 1;
  return dark ? cv::Vec3b(95, 105, 100) : cv::Vec3b(150, 160, 155);
}

cv::Vec3b RobotSim::mottled(double left, double up) const {
  const auto shade = [](double base, double gain, uchar n) { return static_cast<uchar>(base + gain * n); };
  if (up >= -1e-6) {
    // A far wall: its texture turns with the robot (by azimuth) and does not come nearer.
    const double azimuth = pose_.heading + std::atan(left);
    const int column =
        wrap(std::lround(std::floor(azimuth / (2 * CV_PI) * wallTexture_.cols)), wallTexture_.cols);
    const int row = std::min(wallTexture_.rows - 1, static_cast<int>(up * 2 * wallTexture_.rows));
    const uchar n = wallTexture_.at<uchar>(row, column);
    const uchar seam = column % 32 == 0 ? 40 : 0;  // panel joints
    return cv::Vec3b(shade(140 - seam, 0.35, n), shade(125 - seam, 0.3, n), shade(105 - seam, 0.25, n));
  }
  constexpr double kCell = 0.01;  // m per texel: a 10 m patch, repeated
  const cv::Point2d p = floorPoint(left, up);
  const uchar n =
      floorTexture_.at<uchar>(wrap(static_cast<long>(std::floor(p.y / kCell)), floorTexture_.rows),
                              wrap(static_cast<long>(std::floor(p.x / kCell)), floorTexture_.cols));
  return cv::Vec3b(shade(45, 0.25, n), shade(95, 0.45, n), shade(70, 0.3, n));
}

cv::Mat RobotSim::render() const {
  const cv::Size size = config_.frameSize;
  cv::Mat image(size, CV_8UC3);
  const double cx = size.width / 2.0, cy = size.height / 2.0;
  const bool checkeredBackdrop = backdrop_ == Backdrop::Checkered;
  for (int v = 0; v < size.height; ++v) {
    auto *row = image.ptr<cv::Vec3b>(v);
    const double up = -(v + 0.5 - cy) / focal_;
    for (int u = 0; u < size.width; ++u) {
      const double left = -(u + 0.5 - cx) / focal_;
      row[u] = checkeredBackdrop ? checkered(left, up) : mottled(left, up);
    }
  }
  // The farther ball first, so the nearer one covers it.
  const cv::Rect2d ball = ballBox(), distractor = distractorBox();
  const bool distractorFirst = distractorDistance() > ballDistance();
  drawBall(image, distractorFirst ? distractor : ball);
  drawBall(image, distractorFirst ? ball : distractor);
  return image;
}

void RobotSim::drive(double left, double right, double dt) {
  const double v = config_.fullWheelSpeed * (left + right) / 2;
  const double omega = config_.fullWheelSpeed * (right - left) / config_.wheelBase;
  if (std::abs(omega) < 1e-9) {
    pose_.x += v * dt * std::cos(pose_.heading);
    pose_.y += v * dt * std::sin(pose_.heading);
    return;
  }
  const double radius = v / omega, heading = pose_.heading + omega * dt;
  pose_.x += radius * (std::sin(heading) - std::sin(pose_.heading));
  pose_.y -= radius * (std::cos(heading) - std::cos(pose_.heading));
  pose_.heading = heading;
}

// ---------------------------------------------------------------------------------------------------------

CommandDecoder::CommandDecoder(Protocol protocol, double zoneLinear, double zoneAngular, int outputScale)
    : protocol_(protocol), zoneLinear_(zoneLinear), zoneAngular_(zoneAngular), outputScale_(outputScale) {}

std::uint8_t crc8(const std::uint8_t *data, std::size_t size) {
  std::uint8_t crc = 0;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit)
      crc = static_cast<std::uint8_t>(crc & 0x80 ? (crc << 1) ^ 0x07 : crc << 1);
  }
  return crc;
}

std::vector<WheelCommand> CommandDecoder::feed(const std::uint8_t *data, std::size_t size) {
  std::vector<WheelCommand> out;
  pending_.insert(pending_.end(), data, data + size);
  switch (protocol_) {
    case Protocol::ZoneChar:
      for (std::uint8_t byte : pending_) {
        WheelCommand c;
        c.zone = static_cast<char>(byte);
        switch (c.zone) {
          case 'F':
            c.left = c.right = zoneLinear_;
            break;
          case 'B':
            c.left = c.right = -zoneLinear_;
            break;
          case 'L':
            c.left = -zoneAngular_, c.right = zoneAngular_;
            break;
          case 'R':
            c.left = zoneAngular_, c.right = -zoneAngular_;
            break;
          case 'S':
            break;
          default:
            ++rejected_;
            continue;
        }
        out.push_back(c);
      }
      pending_.clear();
      break;
    case Protocol::Text: {
      std::size_t start = 0;
      for (std::size_t i = 0; i < pending_.size(); ++i) {
        if (pending_[i] != '\n') continue;
        const std::string line(pending_.begin() + static_cast<long>(start),
                               pending_.begin() + static_cast<long>(i));
        start = i + 1;
        int left = 0, right = 0;
        char tail = 0;
        if (std::sscanf(line.c_str(), "L=%d R=%d%c", &left, &right, &tail) != 2) {
          ++rejected_;
          continue;
        }
        WheelCommand c;
        c.left = static_cast<double>(left) / outputScale_;
        c.right = static_cast<double>(right) / outputScale_;
        out.push_back(c);
      }
      pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(start));
      break;
    }
    case Protocol::Binary: {
      constexpr std::size_t kLength = 10;
      std::size_t i = 0;
      while (pending_.size() - i >= kLength) {
        const std::uint8_t *p = pending_.data() + i;
        if (p[0] != 0xA5 || p[2] != 6 || crc8(p + 1, kLength - 2) != p[kLength - 1]) {
          ++rejected_;
          ++i;  // resynchronise on the next start byte
          continue;
        }
        WheelCommand c;
        c.sequence = p[1];
        c.left = static_cast<std::int16_t>(p[5] | p[6] << 8) / static_cast<double>(outputScale_);
        c.right = static_cast<std::int16_t>(p[7] | p[8] << 8) / static_cast<double>(outputScale_);
        out.push_back(c);
        i += kLength;
      }
      pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(i));
      break;
    }
  }
  return out;
}

}  // namespace colortrack::robot_sim
