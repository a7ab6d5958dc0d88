// SPDX-License-Identifier: LGPL-2.1-or-later
// Wire formats of drive commands (bytes out; no I/O). Layouts are documented in docs/robotctl.md.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "colortrack/choice.hpp"
#include "colortrack/status.hpp"
#include "colortrack/controller.hpp"
#include "colortrack/mavlink.hpp"

namespace colortrack {

enum class Protocol {
  ZoneChar,  // one byte per command: the command's character
  Text,      // "L=<int> R=<int>\n", wheel speeds scaled by outputScale
  Binary,    // framed packet: start byte, sequence, length, payload, CRC-8
  Mavlink,   // MAVLink 2 (see MavlinkSettings), with a heartbeat
};

// What the MAVLink commands drive.
enum class MavlinkMode {
  Gimbal,  // GIMBAL_MANAGER_SET_PITCHYAW: pitch and yaw rates (DriveOutput tilt and angular)
  Follow,  // SET_POSITION_TARGET_LOCAL_NED, body frame: forward velocity and yaw rate (linear and angular)
};
inline constexpr Choice<MavlinkMode> kMavlinkModes[] = {
    {MavlinkMode::Gimbal, "gimbal", "GIMBAL_MANAGER_SET_PITCHYAW: pitch and yaw rates"},
    {MavlinkMode::Follow, "follow",
     "SET_POSITION_TARGET_LOCAL_NED, body frame: forward velocity and yaw rate"},
};

struct MavlinkSettings {
  MavlinkMode mode = MavlinkMode::Gimbal;
  std::uint8_t systemId = 1, componentId = 191;        // ours: an onboard computer's usual ids
  std::uint8_t targetSystem = 1, targetComponent = 1;  // the autopilot (also the usual gimbal manager)
  // rad/s at angular (or tilt) 1.0: tan(hfov / 2), the rate at which a target near the centre crosses half
  // the frame width per second (mavlinkRateScale), so a turn gain means the same whatever the lens.
  double rateScale = 0.57735;
  double speedScale = 1.0;  // m/s at linear 1.0
  // Every command is clamped to these: what a hobby gimbal or copter takes without harm, whatever the gains
  // and the lens make of the controller's output.
  double maxRate = 60.0 * 3.14159265358979323846 / 180;  // rad/s, pitch and yaw
  double maxSpeed = 2.0;                                 // m/s, forward
};
// tan(hfov / 2) for a horizontal field of view in degrees.
double mavlinkRateScale(double hfovDegrees);

// What a MAVLink command carries, in MAVLink's units and signs: rates in rad/s, the yaw rate > 0 turning
// clockwise seen from above (to the right, the opposite of DriveOutput::angular), the pitch rate > 0 up;
// the forward speed in m/s. Bounded by maxRate and maxSpeed, exactly zero on a stop.
struct MavlinkCommand {
  float pitchRate = 0, yawRate = 0, forwardSpeed = 0;
};
MavlinkCommand mavlinkCommand(const DriveOutput &output, const MavlinkSettings &settings);

// Characters for stop, forward, backward, left, right, in the order of the `zone-chars` text "FBLRS".
struct ZoneChars {
  char forward = 'F', backward = 'B', left = 'L', right = 'R', stop = 'S';
  char of(DriveCommand command) const;
};
// Exactly five distinct printable characters in the order forward, backward, left, right, stop.
Result<ZoneChars> parseZoneChars(const std::string &text);
std::string formatZoneChars(const ZoneChars &chars);

struct ProtocolSettings {
  Protocol protocol = Protocol::ZoneChar;
  ZoneChars zoneChars;
  int outputScale = 255;  // wheel speed 1.0 in the text and binary protocols
  MavlinkSettings mavlink;
};

namespace binary {
constexpr std::uint8_t kStart = 0xA5;
constexpr std::uint8_t kPayloadLength = 6;  // command, flags, left (int16 LE), right (int16 LE)
constexpr std::size_t kPacketLength = 4 + kPayloadLength;  // start, sequence, length, payload, crc
constexpr std::uint8_t kFlagTargetVisible = 0x01;
// Command codes in the payload.
std::uint8_t commandCode(DriveCommand command);
}  // namespace binary

// CRC-8, polynomial 0x07, initial value 0, no reflection (CRC-8/SMBUS): small enough for any microcontroller.
std::uint8_t crc8(const std::uint8_t *data, std::size_t size);

// A wheel speed in [-1, 1] as the integer sent: round(speed * scale), clamped to +-scale.
int scaledSpeed(double speed, int scale);

// The wheel speeds of `output` as sent: each scaled by scaledSpeed(), and exactly zero on a stop whatever
// rounding the speeds had.
struct SentSpeeds {
  int left = 0, right = 0;
};
SentSpeeds sentSpeeds(const DriveOutput &output, int scale);

// One protocol's wire format: the bytes of one command, and of what the protocol sends once a second
// whatever the commands (MAVLink's HEARTBEAT). `sequence` is the number the protocol's packets carry (binary
// packets, MAVLink frames), kept by the caller so that it runs on across a change of settings.
class CommandEncoder {
 public:
  virtual ~CommandEncoder() = default;
  virtual std::vector<std::uint8_t> encode(const DriveOutput &output, std::uint8_t &sequence) = 0;
  virtual bool hasHeartbeat() const { return false; }
  virtual std::vector<std::uint8_t> heartbeat(std::uint8_t & /*sequence*/) { return {}; }
};

// One protocol: its value, the name a user types, what it sends, and its encoder's factory. The registry's
// table (robot/src/protocol_registry.cpp) is the one list of protocols; robotctl's enum type is made from it.
// Adding a protocol is a value of Protocol, its encoder's file (robot/src/encoder_<name>.cpp) and a row.
struct ProtocolDescriptor {
  Protocol value;
  const char *nick;
  const char *description;
  std::unique_ptr<CommandEncoder> (*make)(const ProtocolSettings &settings);
};
// In Protocol's order (each row's value is its position).
const std::vector<ProtocolDescriptor> &protocolDescriptors();

// The encoder of settings.protocol (whose settings it keeps), numbering its packets.
class ProtocolEncoder {
 public:
  explicit ProtocolEncoder(const ProtocolSettings &settings = ProtocolSettings());
  // A new protocol or new settings; the packet numbering runs on.
  void setSettings(const ProtocolSettings &settings);
  const ProtocolSettings &settings() const { return settings_; }

  // The bytes of one command. The binary protocol numbers its packets (wrapping at 256) so a receiver can
  // tell lost packets; every call is one packet (MAVLink: one frame, numbered with the heartbeats).
  std::vector<std::uint8_t> encode(const DriveOutput &output) { return encoder_->encode(output, sequence_); }
  // What the protocol sends once a second whatever the commands (MAVLink's HEARTBEAT); empty for the others.
  std::vector<std::uint8_t> heartbeat() { return encoder_->heartbeat(sequence_); }
  bool hasHeartbeat() const { return encoder_->hasHeartbeat(); }
  std::uint8_t nextSequence() const { return sequence_; }

 private:
  ProtocolSettings settings_;
  std::unique_ptr<CommandEncoder> encoder_;
  std::uint8_t sequence_ = 0;
};

}  // namespace colortrack
