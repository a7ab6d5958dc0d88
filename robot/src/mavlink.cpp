// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/mavlink.hpp"

#include <cstring>

namespace colortrack::mavlink {

namespace {

// A payload in wire order: little-endian fields, appended one after the other.
class Payload {
 public:
  explicit Payload(const MessageInfo &message) { bytes_.reserve(message.payloadLength); }
  Payload &u8(std::uint8_t v) {
    bytes_.push_back(v);
    return *this;
  }
  Payload &u16(std::uint16_t v) { return u8(v & 0xFF).u8(v >> 8); }
  Payload &u32(std::uint32_t v) { return u16(v & 0xFFFF).u16(v >> 16); }
  Payload &f32(float v) {
    std::uint32_t bits;
    std::memcpy(&bits, &v, sizeof bits);
    return u32(bits);
  }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

}  // namespace

std::optional<MessageInfo> messageInfo(std::uint32_t id) {
  for (const MessageInfo &m : {kHeartbeat, kSetPositionTargetLocalNed, kGimbalManagerSetPitchyaw})
    if (m.id == id) return m;
  return std::nullopt;
}

std::uint16_t crcAccumulate(const std::uint8_t *data, std::size_t size, std::uint16_t crc) {
  for (std::size_t i = 0; i < size; ++i) {
    std::uint8_t tmp = data[i] ^ static_cast<std::uint8_t>(crc & 0xFF);
    tmp ^= static_cast<std::uint8_t>(tmp << 4);
    crc = static_cast<std::uint16_t>((crc >> 8) ^ (tmp << 8) ^ (tmp << 3) ^ (tmp >> 4));
  }
  return crc;
}

std::vector<std::uint8_t> frame(const MessageInfo &message, std::vector<std::uint8_t> payload,
                                Sender &sender) {
  // MAVLink 2 sends no trailing zeros (the receiver fills them back in); one byte always remains.
  while (payload.size() > 1 && payload.back() == 0) payload.pop_back();
  std::vector<std::uint8_t> bytes;
  bytes.reserve(kHeaderLength + payload.size() + kChecksumLength);
  for (std::uint8_t b :
       {kMagic, static_cast<std::uint8_t>(payload.size()),
        std::uint8_t{0},  // incompatibility flags: not signed
        std::uint8_t{0},  // compatibility flags
        sender.sequence++, sender.systemId, sender.componentId, static_cast<std::uint8_t>(message.id & 0xFF),
        static_cast<std::uint8_t>((message.id >> 8) & 0xFF),
        static_cast<std::uint8_t>((message.id >> 16) & 0xFF)})
    bytes.push_back(b);
  for (std::uint8_t b : payload) bytes.push_back(b);
  // Over everything after the magic, then the message's CRC_EXTRA: a receiver with another definition of
  // the message sees a bad CRC instead of misreading the fields.
  std::uint16_t crc = crcAccumulate(bytes.data() + 1, bytes.size() - 1);
  crc = crcAccumulate(&message.crcExtra, 1, crc);
  bytes.push_back(crc & 0xFF);
  bytes.push_back(crc >> 8);
  return bytes;
}

// Fields by decreasing size, and in the order of the definition among those of one size (MAVLink's wire
// order); the extension fields (none here) would come last.
std::vector<std::uint8_t> encode(const Heartbeat &m, Sender &sender) {
  constexpr std::uint8_t kMavlinkVersion = 3;
  return frame(kHeartbeat,
               Payload(kHeartbeat)
                   .u32(m.customMode)
                   .u8(m.type)
                   .u8(m.autopilot)
                   .u8(m.baseMode)
                   .u8(m.systemStatus)
                   .u8(kMavlinkVersion)
                   .take(),
               sender);
}

std::vector<std::uint8_t> encode(const GimbalManagerSetPitchyaw &m, Sender &sender) {
  return frame(kGimbalManagerSetPitchyaw,
               Payload(kGimbalManagerSetPitchyaw)
                   .u32(m.flags)
                   .f32(m.pitch)
                   .f32(m.yaw)
                   .f32(m.pitchRate)
                   .f32(m.yawRate)
                   .u8(m.targetSystem)
                   .u8(m.targetComponent)
                   .u8(m.gimbalDeviceId)
                   .take(),
               sender);
}

std::vector<std::uint8_t> encode(const SetPositionTargetLocalNed &m, Sender &sender) {
  return frame(kSetPositionTargetLocalNed,
               Payload(kSetPositionTargetLocalNed)
                   .u32(m.timeBootMs)
                   .f32(m.x)
                   .f32(m.y)
                   .f32(m.z)
                   .f32(m.vx)
                   .f32(m.vy)
                   .f32(m.vz)
                   .f32(m.afx)
                   .f32(m.afy)
                   .f32(m.afz)
                   .f32(m.yaw)
                   .f32(m.yawRate)
                   .u16(m.typeMask)
                   .u8(m.targetSystem)
                   .u8(m.targetComponent)
                   .u8(m.coordinateFrame)
                   .take(),
               sender);
}

namespace {

// The header fields and lengths of a frame of either version (MAVLink 1: no flags, a one-byte message id).
struct Layout {
  std::size_t headerLength, total;
  std::uint32_t messageId;
  std::uint8_t sequence, systemId, componentId;
};

std::optional<Layout> layoutOf(const std::uint8_t *bytes, std::size_t size) {
  if (size < 2) return std::nullopt;
  const std::size_t length = bytes[1];
  Layout l{};
  if (bytes[0] == kMagicV1) {
    if (size < kHeaderLengthV1) return std::nullopt;
    l = {kHeaderLengthV1, kHeaderLengthV1 + length + kChecksumLength, bytes[5], bytes[2], bytes[3], bytes[4]};
  } else if (bytes[0] == kMagic) {
    // Only the signing flag exists; a signed frame carries 13 more bytes, taken but not verified.
    if (size < kHeaderLength || (bytes[2] & ~kIncompatSigned) != 0) return std::nullopt;
    const std::size_t signature = (bytes[2] & kIncompatSigned) ? kSignatureLength : 0;
    l = {kHeaderLength,
         kHeaderLength + length + kChecksumLength + signature,
         static_cast<std::uint32_t>(bytes[7] | (bytes[8] << 8) | (bytes[9] << 16)),
         bytes[4],
         bytes[5],
         bytes[6]};
  } else {
    return std::nullopt;
  }
  if (size < l.total) return std::nullopt;
  return l;
}

}  // namespace

std::optional<Frame> parseFrame(const std::uint8_t *bytes, std::size_t size, std::size_t *used) {
  const std::optional<Layout> l = layoutOf(bytes, size);
  if (!l) return std::nullopt;
  const std::size_t length = bytes[1];
  const std::optional<MessageInfo> message = messageInfo(l->messageId);
  if (!message || length > message->payloadLength) return std::nullopt;
  // MAVLink 1 sends the whole payload, zeros and all.
  if (bytes[0] == kMagicV1 && length != message->payloadLength) return std::nullopt;
  std::uint16_t crc = crcAccumulate(bytes + 1, l->headerLength - 1 + length);
  crc = crcAccumulate(&message->crcExtra, 1, crc);
  const std::size_t crcAt = l->headerLength + length;
  if ((bytes[crcAt] | (bytes[crcAt + 1] << 8)) != crc) return std::nullopt;
  Frame f;
  f.sequence = l->sequence;
  f.systemId = l->systemId;
  f.componentId = l->componentId;
  f.messageId = l->messageId;
  f.payload.assign(bytes + l->headerLength, bytes + l->headerLength + length);
  f.payload.resize(message->payloadLength, 0);
  if (used) *used = l->total;
  return f;
}

std::vector<Frame> parseFrames(const std::uint8_t *bytes, std::size_t size) {
  std::vector<Frame> frames;
  for (std::size_t at = 0; at < size;) {
    std::size_t used = 0;
    if (std::optional<Frame> f = parseFrame(bytes + at, size - at, &used)) {
      frames.push_back(std::move(*f));
      at += used;
    } else {
      ++at;  // not a frame we know here: look for the next start byte
    }
  }
  return frames;
}

float payloadFloat(const std::vector<std::uint8_t> &payload, std::size_t offset) {
  std::uint32_t bits = 0;
  for (int i = 3; i >= 0; --i) bits = (bits << 8) | payload.at(offset + static_cast<std::size_t>(i));
  float v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

}  // namespace colortrack::mavlink
