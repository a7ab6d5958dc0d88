#include "colortrack/protocol.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>

namespace colortrack {

char ZoneChars::of(DriveCommand command) const {
  switch (command) {
    case DriveCommand::Forward:
      return forward;
    case DriveCommand::Backward:
      return backward;
    case DriveCommand::Left:
      return left;
    case DriveCommand::Right:
      return right;
    case DriveCommand::Stop:
      break;
  }
  return stop;
}

std::optional<ZoneChars> parseZoneChars(const std::string &text, std::string *error) {
  auto fail = [&](const std::string &why) -> std::optional<ZoneChars> {
    if (error) *error = why;
    return std::nullopt;
  };
  // Each command goes out as one byte: anything but printable ASCII (a UTF-8 letter is several bytes) is
  // refused before the count, which is then a count of characters.
  for (unsigned char c : text)
    if (c >= 0x80 || !std::isgraph(c))
      return fail("the characters must be printable ASCII and not blank (each is sent as one byte)");
  if (text.size() != 5)
    return fail("expected five characters (forward, backward, left, right, stop), got " +
                std::to_string(text.size()));
  if (std::set<char>(text.begin(), text.end()).size() != 5) return fail("the five characters must differ");
  ZoneChars chars;
  chars.forward = text[0];
  chars.backward = text[1];
  chars.left = text[2];
  chars.right = text[3];
  chars.stop = text[4];
  return chars;
}

std::string formatZoneChars(const ZoneChars &chars) {
  return {chars.forward, chars.backward, chars.left, chars.right, chars.stop};
}

std::uint8_t binary::commandCode(DriveCommand command) {
  switch (command) {
    case DriveCommand::Forward:
      return 1;
    case DriveCommand::Backward:
      return 2;
    case DriveCommand::Left:
      return 3;
    case DriveCommand::Right:
      return 4;
    case DriveCommand::Stop:
      break;
  }
  return 0;
}

std::uint8_t crc8(const std::uint8_t *data, std::size_t size) {
  std::uint8_t crc = 0;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int bit = 0; bit < 8; ++bit)
      crc = (crc & 0x80) ? static_cast<std::uint8_t>((crc << 1) ^ 0x07) : crc << 1;
  }
  return crc;
}

int scaledSpeed(double speed, int scale) {
  const long value = std::lround(std::clamp(speed, -1.0, 1.0) * scale);
  return static_cast<int>(std::clamp<long>(value, -scale, scale));
}

SentSpeeds sentSpeeds(const DriveOutput &output, int scale) {
  if (output.command == DriveCommand::Stop) return SentSpeeds{};
  return SentSpeeds{scaledSpeed(output.left, scale), scaledSpeed(output.right, scale)};
}

namespace {

// `value` within +-`limit`; 0 for anything not finite (a command that cannot be trusted is no motion).
float bounded(double value, double limit) {
  return std::isfinite(value) ? static_cast<float>(std::clamp(value, -limit, limit)) : 0.0f;
}

}  // namespace

double mavlinkRateScale(double hfovDegrees) {
  return std::tan(hfovDegrees * M_PI / 360.0);
}

std::vector<std::uint8_t> ProtocolEncoder::heartbeat() {
  if (!hasHeartbeat()) return {};
  mavlink::Sender sender{settings_.mavlink.systemId, settings_.mavlink.componentId, sequence_};
  std::vector<std::uint8_t> bytes = mavlink::encode(mavlink::Heartbeat(), sender);
  sequence_ = sender.sequence;
  return bytes;
}

MavlinkCommand mavlinkCommand(const DriveOutput &output, const MavlinkSettings &m) {
  MavlinkCommand c;
  if (isStill(output)) return c;  // exactly zero
  c.pitchRate = bounded(output.tilt * m.rateScale, m.maxRate);
  c.yawRate = bounded(-output.angular * m.rateScale, m.maxRate);
  c.forwardSpeed = bounded(output.linear * m.speedScale, m.maxSpeed);
  return c;
}

std::vector<std::uint8_t> ProtocolEncoder::encodeMavlink(const DriveOutput &output) {
  const MavlinkSettings &m = settings_.mavlink;
  mavlink::Sender sender{m.systemId, m.componentId, sequence_};
  const MavlinkCommand command = mavlinkCommand(output, m);
  std::vector<std::uint8_t> bytes;
  if (m.mode == MavlinkMode::Gimbal) {
    mavlink::GimbalManagerSetPitchyaw message;
    message.targetSystem = m.targetSystem;
    message.targetComponent = m.targetComponent;
    message.pitchRate = command.pitchRate;
    message.yawRate = command.yawRate;
    bytes = mavlink::encode(message, sender);
  } else {
    mavlink::SetPositionTargetLocalNed message;
    message.targetSystem = m.targetSystem;
    message.targetComponent = m.targetComponent;
    message.vx = command.forwardSpeed;
    message.yawRate = command.yawRate;
    bytes = mavlink::encode(message, sender);
  }
  sequence_ = sender.sequence;
  return bytes;
}

std::vector<std::uint8_t> ProtocolEncoder::encode(const DriveOutput &output) {
  if (settings_.protocol == Protocol::Mavlink) return encodeMavlink(output);
  const auto [left, right] = sentSpeeds(output, settings_.outputScale);

  switch (settings_.protocol) {
    case Protocol::ZoneChar:
      return {static_cast<std::uint8_t>(settings_.zoneChars.of(output.command))};
    case Protocol::Text: {
      char line[32];
      const int n = std::snprintf(line, sizeof line, "L=%d R=%d\n", left, right);
      return std::vector<std::uint8_t>(line, line + n);
    }
    case Protocol::Binary:
    case Protocol::Mavlink:  // encodeMavlink()
      break;
  }

  const auto le16 = [](int v, int byte) {
    return static_cast<std::uint8_t>(
        (static_cast<std::uint16_t>(static_cast<std::int16_t>(v)) >> (8 * byte)) & 0xFF);
  };
  std::vector<std::uint8_t> packet = {
      binary::kStart,
      sequence_++,
      binary::kPayloadLength,
      binary::commandCode(output.command),
      static_cast<std::uint8_t>(output.targetVisible ? binary::kFlagTargetVisible : 0),
      le16(left, 0),
      le16(left, 1),
      le16(right, 0),
      le16(right, 1),
  };
  // The CRC covers everything after the start byte, so a receiver can resynchronise on 0xA5.
  packet.push_back(crc8(packet.data() + 1, packet.size() - 1));
  return packet;
}

}  // namespace colortrack
