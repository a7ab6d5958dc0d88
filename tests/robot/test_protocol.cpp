// SPDX-License-Identifier: LGPL-2.1-or-later
// Wire formats: exact bytes of every protocol.
#include <gtest/gtest.h>

#include <stdexcept>

#include <string>
#include <vector>

#include "colortrack/protocol.hpp"
#include "support/status_helpers.hpp"

namespace colortrack {
namespace {

using Bytes = std::vector<std::uint8_t>;

DriveOutput command(DriveCommand c, double left, double right, bool visible = true) {
  DriveOutput out;
  out.command = c;
  out.left = left;
  out.right = right;
  out.targetVisible = visible;
  return out;
}

std::string text(const Bytes &bytes) {
  return std::string(bytes.begin(), bytes.end());
}

TEST(Protocol, ZoneCharDefaultAndCustom) {
  ProtocolEncoder encoder;
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Forward, 0.5, 0.5))), "F");
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Backward, -0.5, -0.5))), "B");
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Left, -0.3, 0.3))), "L");
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Right, 0.3, -0.3))), "R");
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Stop, 0, 0))), "S");

  ProtocolSettings s;
  s.zoneChars = *parseZoneChars("wsadx");
  encoder.setSettings(s);
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Left, -0.3, 0.3))), "a");
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Stop, 0, 0))), "x");
  EXPECT_EQ(formatZoneChars(s.zoneChars), "wsadx");
}

TEST(Protocol, ZoneCharsRejected) {
  std::string why;
  EXPECT_FALSE(okOr(parseZoneChars("FBLR"), why));
  EXPECT_NE(why.find("five"), std::string::npos);
  EXPECT_FALSE(okOr(parseZoneChars("FFLRS"), why));
  EXPECT_NE(why.find("differ"), std::string::npos);
  EXPECT_FALSE(okOr(parseZoneChars("F LRS"), why));
  EXPECT_TRUE(parseZoneChars("12345"));
  // Five letters of ten UTF-8 bytes: refused as not one byte each, not as "got 10".
  EXPECT_FALSE(okOr(parseZoneChars("\u0109\u011d\u0125\u0135\u015d"), why));
  EXPECT_NE(why.find("ASCII"), std::string::npos) << why;
  EXPECT_EQ(why.find("10"), std::string::npos) << why;
}

TEST(Protocol, TextLines) {
  ProtocolSettings s;
  s.protocol = Protocol::Text;
  ProtocolEncoder encoder(s);
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Forward, 0.45, 0.15))),
            "L=115 R=38\n");  // 114.75, 38.25
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Left, -0.2, 0.6))), "L=-51 R=153\n");
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Stop, 0.001, 0))), "L=0 R=0\n");  // a stop is zero
  s.outputScale = 1000;
  encoder.setSettings(s);
  EXPECT_EQ(text(encoder.encode(command(DriveCommand::Backward, -1.5, -0.25))), "L=-1000 R=-250\n");
}

TEST(Protocol, Crc8CheckValue) {
  // The published check value of CRC-8/SMBUS.
  const std::string check = "123456789";
  EXPECT_EQ(crc8(reinterpret_cast<const std::uint8_t *>(check.data()), check.size()), 0xF4);
}

TEST(Protocol, BinaryPackets) {
  ProtocolSettings s;
  s.protocol = Protocol::Binary;
  ProtocolEncoder encoder(s);
  EXPECT_EQ(encoder.encode(command(DriveCommand::Forward, 0.5, 0.5)),
            (Bytes{0xA5, 0x00, 0x06, 0x01, 0x01, 0x80, 0x00, 0x80, 0x00, 0x00}));  // 127.5 rounds to 128
  EXPECT_EQ(encoder.encode(command(DriveCommand::Right, 0.3, -0.3)),
            (Bytes{0xA5, 0x01, 0x06, 0x04, 0x01, 0x4D, 0x00, 0xB3, 0xFF, 0xFF}));  // +77, -77
  EXPECT_EQ(encoder.encode(command(DriveCommand::Stop, 0, 0, false)),
            (Bytes{0xA5, 0x02, 0x06, 0x00, 0x00, 0x00, 0x00, 0x00, 0x00, 0xEA}));
  EXPECT_EQ(binary::kPacketLength, 10u);
}

TEST(Protocol, BinarySequenceWrapsAndCrcCoversPacket) {
  ProtocolSettings s;
  s.protocol = Protocol::Binary;
  ProtocolEncoder encoder(s);
  Bytes last;
  for (int i = 0; i < 257; ++i) last = encoder.encode(command(DriveCommand::Left, -0.2, 0.6));
  EXPECT_EQ(last[1], 0x00);  // packet 256 (the 257th) wraps
  EXPECT_EQ(last.back(), crc8(last.data() + 1, last.size() - 2));
  // Any single-bit error is caught.
  for (std::size_t byte = 1; byte + 1 < last.size(); ++byte) {
    Bytes corrupt = last;
    corrupt[byte] ^= 0x10;
    EXPECT_NE(crc8(corrupt.data() + 1, corrupt.size() - 2), last.back()) << byte;
  }
}

// Each protocol's encoder comes from the registry (protocolDescriptors()); a new setting keeps the packet
// numbering, and a value without a registration is refused, keeping the encoder it had.
TEST(Protocol, EncodersComeFromTheRegistry) {
  ProtocolSettings s;
  s.protocol = Protocol::Binary;
  ProtocolEncoder encoder(s);
  encoder.encode(command(DriveCommand::Stop, 0, 0));
  encoder.encode(command(DriveCommand::Stop, 0, 0));
  s.outputScale = 100;
  encoder.setSettings(s);
  EXPECT_EQ(encoder.encode(command(DriveCommand::Stop, 0, 0))[1], 2);  // the third packet
  ProtocolSettings bad = s;
  bad.protocol = static_cast<Protocol>(99);
  EXPECT_THROW(encoder.setSettings(bad), std::logic_error);
  EXPECT_EQ(encoder.settings().protocol, Protocol::Binary);
  EXPECT_EQ(encoder.encode(command(DriveCommand::Stop, 0, 0)).size(), binary::kPacketLength);
  EXPECT_THROW(ProtocolEncoder{bad}, std::logic_error);
  for (const ProtocolDescriptor &d : protocolDescriptors()) {
    s.protocol = d.value;
    EXPECT_FALSE(ProtocolEncoder(s).encode(command(DriveCommand::Forward, 0.5, 0.5)).empty()) << d.nick;
    EXPECT_EQ(ProtocolEncoder(s).hasHeartbeat(), d.value == Protocol::Mavlink) << d.nick;
  }
}

}  // namespace
}  // namespace colortrack
