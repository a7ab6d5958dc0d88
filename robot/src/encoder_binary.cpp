// SPDX-License-Identifier: LGPL-2.1-or-later
// protocol=binary: a framed, numbered packet per command: start byte, sequence, length, payload (command,
// flags, left and right as int16 little-endian), CRC-8 of everything after the start byte.
#include "colortrack/protocol.hpp"

namespace colortrack {

namespace {

std::uint8_t le16(int value, int byte) {
  return static_cast<std::uint8_t>(
      (static_cast<std::uint16_t>(static_cast<std::int16_t>(value)) >> (8 * byte)) & 0xFF);
}

class BinaryEncoder : public CommandEncoder {
 public:
  explicit BinaryEncoder(int scale) : scale_(scale) {}
  std::vector<std::uint8_t> encode(const DriveOutput &output, std::uint8_t &sequence) override {
    const auto [left, right] = sentSpeeds(output, scale_);
    std::vector<std::uint8_t> packet = {
        binary::kStart,
        sequence++,
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

 private:
  int scale_;
};

}  // namespace

std::unique_ptr<CommandEncoder> makeBinaryEncoder(const ProtocolSettings &settings) {
  return std::make_unique<BinaryEncoder>(settings.outputScale);
}

}  // namespace colortrack
