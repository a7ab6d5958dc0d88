// SPDX-License-Identifier: LGPL-2.1-or-later
// MAVLink 2 frames of the three messages robotctl sends (bytes out, no I/O), and the parsing of a frame for
// the tests' simulators.
//
// Written here rather than generated: Debian 12 packages no MAVLink C library (the official one is a code
// generator plus generated headers), and robotctl needs three messages, unsigned. Field orders and
// CRC_EXTRA values are those of the MAVLink definitions (minimal.xml, common.xml);
// tests/core/test_mavlink.cpp checks every message byte for byte against an independent implementation
// (node-mavlink).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

namespace colortrack::mavlink {

constexpr std::uint8_t kMagic = 0xFD;      // MAVLink 2 start byte
constexpr std::size_t kHeaderLength = 10;  // magic, len, incompat, compat, seq, sysid, compid, msgid (3)
constexpr std::size_t kChecksumLength = 2;
constexpr std::uint8_t kMagicV1 = 0xFE;     // MAVLink 1, still sent by older autopilots and radios
constexpr std::size_t kHeaderLengthV1 = 6;  // magic, len, seq, sysid, compid, msgid
constexpr std::uint8_t kIncompatSigned = 0x01;
constexpr std::size_t kSignatureLength = 13;

// Who sends: the ids of the frame's header, and its sequence number (+1 per frame, wrapping).
struct Sender {
  std::uint8_t systemId = 1;
  std::uint8_t componentId = 191;  // MAV_COMP_ID_ONBOARD_COMPUTER
  std::uint8_t sequence = 0;
};

// Id and CRC_EXTRA (the hash of the message's definition that the CRC includes) of each message.
struct MessageInfo {
  std::uint32_t id;
  std::uint8_t crcExtra;
  std::uint8_t payloadLength;  // before the trailing zeros are cut
};
constexpr MessageInfo kHeartbeat{0, 50, 9};
constexpr MessageInfo kSetPositionTargetLocalNed{84, 143, 53};
constexpr MessageInfo kGimbalManagerSetPitchyaw{287, 1, 23};
// The CRC_EXTRA of a message id among the three, or none.
std::optional<MessageInfo> messageInfo(std::uint32_t id);

// HEARTBEAT (0): who we are, at 1 Hz, so the flight controller and mavlink-router know the link is alive.
struct Heartbeat {
  std::uint8_t type = 18;      // MAV_TYPE_ONBOARD_CONTROLLER
  std::uint8_t autopilot = 8;  // MAV_AUTOPILOT_INVALID: not a flight controller
  std::uint8_t baseMode = 0;
  std::uint32_t customMode = 0;
  std::uint8_t systemStatus = 4;  // MAV_STATE_ACTIVE
};

// GIMBAL_MANAGER_SET_PITCHYAW (287). Angles in rad, rates in rad/s; NaN = unused (robotctl sends rates only).
struct GimbalManagerSetPitchyaw {
  std::uint8_t targetSystem = 1, targetComponent = 1;
  std::uint32_t flags = 0;
  std::uint8_t gimbalDeviceId = 0;  // 0: all the gimbals of the manager
  float pitch = std::numeric_limits<float>::quiet_NaN();
  float yaw = std::numeric_limits<float>::quiet_NaN();
  float pitchRate = 0;  // > 0 up
  float yawRate = 0;    // > 0 to the right (clockwise seen from above)
};

constexpr std::uint8_t kFrameBodyOffsetNed = 9;  // MAV_FRAME_BODY_OFFSET_NED
// POSITION_TARGET_TYPEMASK: position, acceleration and yaw ignored; the velocity (robotctl sends vy = vz =
// 0: no sideways drift, altitude held) and the yaw rate used. Not vy and vz ignored too: ArduPilot reads
// the velocity as ignored when any of its three bits is set, and with nothing left to follow it stops.
constexpr std::uint16_t kVelocityAndYawRate = 0x0001 | 0x0002 | 0x0004 |  // x, y, z
                                              0x0040 | 0x0080 | 0x0100 |  // afx, afy, afz
                                              0x0400;                     // yaw

// SET_POSITION_TARGET_LOCAL_NED (84). NED: x forward (in the body frames), z down; yaw rate > 0 clockwise
// seen from above.
struct SetPositionTargetLocalNed {
  std::uint32_t timeBootMs = 0;
  std::uint8_t targetSystem = 1, targetComponent = 1;
  std::uint8_t coordinateFrame = kFrameBodyOffsetNed;
  std::uint16_t typeMask = kVelocityAndYawRate;
  float x = 0, y = 0, z = 0, vx = 0, vy = 0, vz = 0, afx = 0, afy = 0, afz = 0, yaw = 0, yawRate = 0;
};

// CRC-16/MCRF4XX as MAVLink uses it ("X.25"): accumulates `size` bytes into `crc` (start with 0xFFFF).
std::uint16_t crcAccumulate(const std::uint8_t *data, std::size_t size, std::uint16_t crc = 0xFFFF);

// A whole frame from a payload laid out in wire order (fields by decreasing size); trailing zero bytes of
// the payload are cut (MAVLink 2), the first byte always stays. Advances sender.sequence.
std::vector<std::uint8_t> frame(const MessageInfo &message, std::vector<std::uint8_t> payload,
                                Sender &sender);

std::vector<std::uint8_t> encode(const Heartbeat &message, Sender &sender);
std::vector<std::uint8_t> encode(const GimbalManagerSetPitchyaw &message, Sender &sender);
std::vector<std::uint8_t> encode(const SetPositionTargetLocalNed &message, Sender &sender);

// One frame read back: its header and its payload, zero-extended to the message's full length.
struct Frame {
  std::uint8_t sequence = 0, systemId = 0, componentId = 0;
  std::uint32_t messageId = 0;
  std::vector<std::uint8_t> payload;
};
// The frame at the start of `bytes` (`size` of them): none when it is not a whole MAVLink 2 or MAVLink 1
// frame of one of the three messages with a valid CRC (a signed frame's signature is not checked).
// `used`: its length.
std::optional<Frame> parseFrame(const std::uint8_t *bytes, std::size_t size, std::size_t *used = nullptr);
// Every such frame in `bytes` (a datagram, or what a serial read gave), skipping anything else.
std::vector<Frame> parseFrames(const std::uint8_t *bytes, std::size_t size);
// A little-endian float of a payload at `offset` (the tests' decoders).
float payloadFloat(const std::vector<std::uint8_t> &payload, std::size_t offset);

}  // namespace colortrack::mavlink
