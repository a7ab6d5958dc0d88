// SPDX-License-Identifier: LGPL-2.1-or-later
// protocol=mavlink: MAVLink 2 frames (robot/src/mavlink.cpp), a gimbal's pitch and yaw rates or a drone's
// forward velocity and yaw rate per command (mavlink-mode), and a HEARTBEAT once a second.
#include <algorithm>
#include <cmath>

#include "colortrack/protocol.hpp"

namespace colortrack {

namespace {

// `value` within +-`limit`; 0 for anything not finite (a command that cannot be trusted is no motion).
float bounded(double value, double limit) {
  return std::isfinite(value) ? static_cast<float>(std::clamp(value, -limit, limit)) : 0.0f;
}

class MavlinkEncoder : public CommandEncoder {
 public:
  explicit MavlinkEncoder(const MavlinkSettings &settings) : m_(settings) {}

  std::vector<std::uint8_t> encode(const DriveOutput &output, std::uint8_t &sequence) override {
    mavlink::Sender sender{m_.systemId, m_.componentId, sequence};
    const MavlinkCommand command = mavlinkCommand(output, m_);
    std::vector<std::uint8_t> bytes;
    if (m_.mode == MavlinkMode::Gimbal) {
      mavlink::GimbalManagerSetPitchyaw message;
      message.targetSystem = m_.targetSystem;
      message.targetComponent = m_.targetComponent;
      message.pitchRate = command.pitchRate;
      message.yawRate = command.yawRate;
      bytes = mavlink::encode(message, sender);
    } else {
      mavlink::SetPositionTargetLocalNed message;
      message.targetSystem = m_.targetSystem;
      message.targetComponent = m_.targetComponent;
      message.vx = command.forwardSpeed;
      message.yawRate = command.yawRate;
      bytes = mavlink::encode(message, sender);
    }
    sequence = sender.sequence;
    return bytes;
  }

  bool hasHeartbeat() const override { return true; }

  std::vector<std::uint8_t> heartbeat(std::uint8_t &sequence) override {
    mavlink::Sender sender{m_.systemId, m_.componentId, sequence};
    std::vector<std::uint8_t> bytes = mavlink::encode(mavlink::Heartbeat(), sender);
    sequence = sender.sequence;
    return bytes;
  }

 private:
  MavlinkSettings m_;
};

}  // namespace

MavlinkCommand mavlinkCommand(const DriveOutput &output, const MavlinkSettings &m) {
  MavlinkCommand c;
  if (isStill(output)) return c;  // exactly zero
  c.pitchRate = bounded(output.tilt * m.rateScale, m.maxRate);
  c.yawRate = bounded(-output.angular * m.rateScale, m.maxRate);
  c.forwardSpeed = bounded(output.linear * m.speedScale, m.maxSpeed);
  return c;
}

std::unique_ptr<CommandEncoder> makeMavlinkEncoder(const ProtocolSettings &settings) {
  return std::make_unique<MavlinkEncoder>(settings.mavlink);
}

}  // namespace colortrack
