// SPDX-License-Identifier: LGPL-2.1-or-later
// A simulated differential-drive robot with a forward camera, in a flat world with one coloured ball (and,
// optionally, a second ball of the same colour that rolls across: a distractor), seen against a checkered
// floor and the sky or, after a cut, against another place's mottled floor and wall. It renders what the
// camera sees (pinhole model) and drives from wheel speeds, so robotctl can be tested in a closed loop. It
// also decodes robotctl's three protocols, independently of core/ (from docs/robotctl.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace colortrack::robot_sim {

struct RobotSimConfig {
  cv::Size frameSize{320, 240};
  double horizontalFovDegrees = 60;
  double cameraHeight = 0.25;      // m above the floor, looking level
  double ballRadius = 0.15;        // m; the ball rests on the floor
  cv::Point2d ball{3.0, 0.0};      // m, world position of the ball
  cv::Point2d ballVelocity{0, 0};  // m/s, applied by moveBall
  double fullWheelSpeed = 1.0;     // m/s at wheel speed 1
  double wheelBase = 0.4;          // m between the wheels
  // A second ball of the ball's colour (none while distractorRadius is 0), also resting on the floor and
  // rolling at its own velocity (moveBall moves both).
  double distractorRadius = 0;           // m
  cv::Point2d distractor{0, 0};          // m, world position
  cv::Point2d distractorVelocity{0, 0};  // m/s
};

// Position (m) and heading (rad, 0 = +x, counter-clockwise).
struct Pose {
  double x = 0, y = 0, heading = 0;
};

// What the balls are seen against: the checkered floor under the sky, or another place (for a cut): a
// mottled green floor and a blue-grey wall, both textured and anchored to the world so they move with the
// robot, and nowhere near the balls' red.
enum class Backdrop { Checkered, Mottled };

class RobotSim {
 public:
  RobotSim(const RobotSimConfig &config, const Pose &start);

  // The camera view: the backdrop, the ball and the distractor, the nearer one drawn over the other (BGR,
  // CV_8UC3).
  cv::Mat render() const;
  // Where the ball appears (ground truth); empty when hidden or behind the camera.
  cv::Rect2d ballBox() const;
  // Where the distractor appears, whole (not cut where the ball is in front); empty without one or hidden.
  cv::Rect2d distractorBox() const;
  void setBallHidden(bool hidden) { hidden_ = hidden; }
  void setDistractorHidden(bool hidden) { distractorHidden_ = hidden; }
  void setBackdrop(Backdrop backdrop);
  // Moves the distractor to `bearing` (rad from the camera's axis, > 0 to the left) and `distance` (m on the
  // floor from the camera), so that a test can put it where it wants it in the image.
  void placeDistractor(double bearing, double distance);
  // Rolls the ball and the distractor for dt seconds at their velocities.
  void moveBall(double dt);

  // Ground truth for scoring a run: the ball's bearing from the camera's axis (rad, > 0 to the left) and
  // its distance on the floor (m, camera to ball centre).
  double ballBearing() const;
  double ballDistance() const;
  // The same for the distractor.
  double distractorBearing() const;
  double distractorDistance() const;
  // The distance at which the ball's box is `cue` of the frame height (robotctl's distance-cue=size):
  // box height = 2 * focal * radius / distance, exactly (ballBox).
  double distanceForSizeCue(double cue) const;

  // Moves for dt seconds with wheel speeds in [-1, 1] (exact arc of a differential drive).
  void drive(double left, double right, double dt);

  const Pose &pose() const { return pose_; }
  double focalLength() const { return focal_; }
  const RobotSimConfig &config() const { return config_; }

 private:
  // World point to camera coordinates: forward, left, up (m).
  cv::Point3d toCamera(double x, double y, double z) const;
  // Where a ball of `radius` resting at `position` appears; empty when behind the camera.
  cv::Rect2d boxOf(cv::Point2d position, double radius) const;
  // Where the ray `left` and `up` (camera coordinates, per unit forward; up < 0) meets the floor.
  cv::Point2d floorPoint(double left, double up) const;
  // The backdrop's colour seen along the ray `left` and `up` (camera coordinates, per unit forward).
  cv::Vec3b checkered(double left, double up) const;
  cv::Vec3b mottled(double left, double up) const;

  RobotSimConfig config_;
  Pose pose_;
  double focal_;
  bool hidden_ = false, distractorHidden_ = false;
  Backdrop backdrop_ = Backdrop::Checkered;
  cv::Mat floorTexture_, wallTexture_;  // CV_8U, made when the mottled backdrop is first set
};

// A shaded red ball with a highlight, filling `box` (nothing when empty); sub-pixel centre (shift) so it
// moves smoothly. The simulators' target.
void drawBall(cv::Mat &image, const cv::Rect2d &box);

// One decoded command: wheel speeds in [-1, 1] (and the character of zone-char).
struct WheelCommand {
  char zone = 0;
  double left = 0, right = 0;
  int sequence = -1;  // binary only
  bool stop() const { return left == 0 && right == 0; }
};

class CommandDecoder {
 public:
  enum class Protocol { ZoneChar, Text, Binary };
  // zoneLinear / zoneAngular: the wheel speeds the robot's firmware uses for the zone characters "FBLRS";
  // outputScale: the integer of full wheel speed in the text and binary protocols.
  CommandDecoder(Protocol protocol, double zoneLinear, double zoneAngular, int outputScale);
  std::vector<WheelCommand> feed(const std::uint8_t *data, std::size_t size);
  int rejected() const { return rejected_; }  // bad characters, lines or packets

 private:
  Protocol protocol_;
  double zoneLinear_, zoneAngular_;
  int outputScale_;
  std::vector<std::uint8_t> pending_;
  int rejected_ = 0;
};

// CRC-8/SMBUS (polynomial 0x07, initial 0) as a robot checks robotctl's binary packets: written here apart
// from core's crc8, so that the tests check robotctl's packets against a second reading of the rule.
std::uint8_t crc8(const std::uint8_t *data, std::size_t size);

}  // namespace colortrack::robot_sim
