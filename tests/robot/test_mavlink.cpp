// SPDX-License-Identifier: LGPL-2.1-or-later
// MAVLink 2 frames: byte for byte against node-mavlink (an independent implementation, see
// tests/support/node_mavlink.hpp), the CRC's check value, the protocol encoder's signs, units and stops, and
// the parser the simulators use. Without node the node-mavlink test is skipped and the run reports "skipped"
// (exit 77) after the others pass.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "colortrack/mavlink.hpp"
#include "colortrack/protocol.hpp"
#include "node_mavlink.hpp"

namespace colortrack {
namespace {

using Bytes = std::vector<std::uint8_t>;

std::string hex(const Bytes &bytes) {
  std::string text;
  char byte[3];
  for (std::uint8_t b : bytes) {
    std::snprintf(byte, sizeof byte, "%02x", b);
    text += byte;
  }
  return text;
}

bool nodeMissing = false;

TEST(Mavlink, CrcCheckValue) {
  // CRC-16/MCRF4XX (MAVLink's X.25): the catalogue's check value of "123456789".
  const std::string check = "123456789";
  EXPECT_EQ(mavlink::crcAccumulate(reinterpret_cast<const std::uint8_t *>(check.data()), check.size()),
            0x6F91);
}

// One message encoded by both sides.
struct Case {
  std::string json;  // for node-mavlink
  Bytes ours;
};

Case heartbeat(std::uint8_t sysid, std::uint8_t compid, std::uint8_t seq) {
  char json[256];
  std::snprintf(json, sizeof json,
                R"({"message":"heartbeat","sysid":%d,"compid":%d,"seq":%d,"type":18,"autopilot":8,)"
                R"("baseMode":0,"customMode":0,"systemStatus":4,"mavlinkVersion":3})",
                sysid, compid, seq);
  mavlink::Sender sender{sysid, compid, seq};
  return {json, mavlink::encode(mavlink::Heartbeat(), sender)};
}

Case gimbal(std::uint8_t seq, double pitchRate, double yawRate, std::uint8_t target) {
  char json[320];
  std::snprintf(json, sizeof json,
                R"({"message":"gimbal","sysid":1,"compid":191,"seq":%d,"targetSystem":%d,)"
                R"("targetComponent":%d,"flags":0,"gimbalDeviceId":0,"pitch":"NaN","yaw":"NaN",)"
                R"("pitchRate":%.17g,"yawRate":%.17g})",
                seq, target, target, pitchRate, yawRate);
  mavlink::GimbalManagerSetPitchyaw m;
  m.targetSystem = m.targetComponent = target;
  m.pitchRate = static_cast<float>(pitchRate);
  m.yawRate = static_cast<float>(yawRate);
  mavlink::Sender sender{1, 191, seq};
  return {json, mavlink::encode(m, sender)};
}

Case position(std::uint8_t seq, double vx, double yawRate, std::uint32_t timeBootMs) {
  char json[512];
  std::snprintf(json, sizeof json,
                R"({"message":"position","sysid":1,"compid":191,"seq":%d,"timeBootMs":%u,"targetSystem":1,)"
                R"("targetComponent":1,"coordinateFrame":9,"typeMask":1479,"x":0,"y":0,"z":0,"vx":%.17g,)"
                R"("vy":0,"vz":0,"afx":0,"afy":0,"afz":0,"yaw":0,"yawRate":%.17g})",
                seq, timeBootMs, vx, yawRate);
  mavlink::SetPositionTargetLocalNed m;
  m.timeBootMs = timeBootMs;
  m.vx = static_cast<float>(vx);
  m.yawRate = static_cast<float>(yawRate);
  mavlink::Sender sender{1, 191, seq};
  return {json, mavlink::encode(m, sender)};
}

TEST(Mavlink, EveryMessageMatchesNodeMavlink) {
  std::string why;
  if (!node_mavlink::available(why)) {
    nodeMissing = true;
    GTEST_SKIP() << why;
  }
  // 1479 = the ignore bits of x, y, z (1, 2, 4), afx, afy, afz (64, 128, 256) and yaw (1024); velocity and
  // yaw rate used, FORCE_SET (512) clear.
  ASSERT_EQ(mavlink::kVelocityAndYawRate, 1479);
  const std::vector<Case> cases = {
      heartbeat(1, 191, 0),
      heartbeat(42, 1, 255),
      gimbal(1, 0.25, -0.5, 1),
      gimbal(2, -0.1, 0.3, 0),  // broadcast targets: the trailing zero bytes are cut
      gimbal(7, 0, 0, 1),       // the stop form
      position(3, 0.8, -0.3, 0),
      position(4, 0, 0, 0),  // the stop form
      position(200, -0.25, 0.125, 123456),
  };
  std::vector<std::string> json;
  for (const Case &c : cases) json.push_back(c.json);
  const std::vector<Bytes> theirs = node_mavlink::encode(json);
  ASSERT_EQ(theirs.size(), cases.size()) << "node-mavlink failed";
  for (std::size_t i = 0; i < cases.size(); ++i) {
    EXPECT_EQ(hex(cases[i].ours), hex(theirs[i])) << cases[i].json;
    std::printf("%s\n", hex(cases[i].ours).c_str());
  }
}

// What a vehicle sends back: its heartbeat, in MAVLink 1 (older autopilots and radios) and MAVLink 2,
// encoded by node-mavlink, read by parseFrames() among other bytes (robotctl's link-timeout).
TEST(Mavlink, ParsesTheVehiclesHeartbeatInBothVersions) {
  std::string why;
  if (!node_mavlink::available(why)) {
    nodeMissing = true;
    GTEST_SKIP() << why;
  }
  const std::string fields = R"("message":"heartbeat","type":2,"autopilot":3,"baseMode":81,"customMode":4,)"
                             R"("systemStatus":4,"mavlinkVersion":3)";
  const std::vector<Bytes> theirs =
      node_mavlink::encode({"{" + fields + R"(,"sysid":7,"compid":1,"seq":9,"version":1})",
                            "{" + fields + R"(,"sysid":8,"compid":1,"seq":10})"});
  ASSERT_EQ(theirs.size(), 2u) << "node-mavlink failed";
  EXPECT_EQ(theirs[0][0], mavlink::kMagicV1);
  Bytes stream = {0x00, 0xFE, 0x55};  // noise, and a start byte that begins no frame
  for (const Bytes &frame : theirs) stream.insert(stream.end(), frame.begin(), frame.end());
  const std::vector<mavlink::Frame> frames = mavlink::parseFrames(stream.data(), stream.size());
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[0].systemId, 7);
  EXPECT_EQ(frames[0].sequence, 9);
  EXPECT_EQ(frames[1].systemId, 8);
  for (const mavlink::Frame &f : frames) {
    EXPECT_EQ(f.messageId, mavlink::kHeartbeat.id);
    EXPECT_EQ(f.payload[0], 4);  // custom_mode, first on the wire
    EXPECT_EQ(f.payload[4], 2);  // type: a quadrotor
  }
  // A corrupted MAVLink 1 frame is not taken.
  Bytes bad = theirs[0];
  bad[8] ^= 0x01;
  EXPECT_TRUE(mavlink::parseFrames(bad.data(), bad.size()).empty());
}

// A signed MAVLink 2 frame (incompatibility flag 1): 13 bytes of signature after the CRC, taken whole.
TEST(Mavlink, TakesASignedFrameWhole) {
  mavlink::Sender sender{9, 1, 0};
  Bytes bytes = mavlink::encode(mavlink::Heartbeat(), sender);
  bytes[2] = mavlink::kIncompatSigned;
  const std::uint16_t crc = mavlink::crcAccumulate(
      &mavlink::kHeartbeat.crcExtra, 1, mavlink::crcAccumulate(bytes.data() + 1, bytes.size() - 3));
  bytes[bytes.size() - 2] = crc & 0xFF;
  bytes[bytes.size() - 1] = crc >> 8;
  bytes.insert(bytes.end(), mavlink::kSignatureLength, 0xAB);
  std::size_t used = 0;
  ASSERT_TRUE(mavlink::parseFrame(bytes.data(), bytes.size(), &used));
  EXPECT_EQ(used, bytes.size());
  EXPECT_FALSE(mavlink::parseFrame(bytes.data(), bytes.size() - 1));  // the signature cut
  bytes[2] = 0x02;                                                    // a flag nobody defined
  EXPECT_FALSE(mavlink::parseFrame(bytes.data(), bytes.size()));
}

ProtocolEncoder mavlinkEncoder(MavlinkMode mode) {
  ProtocolSettings s;
  s.protocol = Protocol::Mavlink;
  s.mavlink.mode = mode;
  s.mavlink.rateScale = mavlinkRateScale(60);
  return ProtocolEncoder(s);
}

DriveOutput output(double linear, double angular, double tilt) {
  DriveOutput out = makeOutput(linear, angular, true);
  out.tilt = tilt;
  return out;
}

mavlink::Frame parsed(const Bytes &bytes) {
  std::size_t used = 0;
  const std::optional<mavlink::Frame> frame = mavlink::parseFrame(bytes.data(), bytes.size(), &used);
  EXPECT_TRUE(frame);
  EXPECT_EQ(used, bytes.size());
  return frame ? *frame : mavlink::Frame();
}

TEST(Mavlink, GimbalRatesSignsUnitsAndStop) {
  ProtocolEncoder encoder = mavlinkEncoder(MavlinkMode::Gimbal);
  const double scale = std::tan(30 * M_PI / 180);  // rad/s at 1.0 with a 60 degree lens
  EXPECT_EQ(parsed(encoder.heartbeat()).messageId, 0u);
  // Turning left (angular > 0) is a negative yaw rate; tilting up a positive pitch rate.
  const mavlink::Frame turn = parsed(encoder.encode(output(0, 0.5, 0.2)));
  EXPECT_EQ(turn.messageId, 287u);
  EXPECT_EQ(turn.sequence, 1);
  EXPECT_EQ(turn.systemId, 1);
  EXPECT_EQ(turn.componentId, 191);
  EXPECT_TRUE(std::isnan(mavlink::payloadFloat(turn.payload, 4)));  // pitch angle unused
  EXPECT_TRUE(std::isnan(mavlink::payloadFloat(turn.payload, 8)));  // yaw angle unused
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(turn.payload, 12), static_cast<float>(0.2 * scale));
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(turn.payload, 16), static_cast<float>(-0.5 * scale));
  const mavlink::Frame stop = parsed(encoder.encode(DriveOutput()));
  EXPECT_EQ(stop.sequence, 2);
  EXPECT_EQ(mavlink::payloadFloat(stop.payload, 12), 0.0f);
  EXPECT_EQ(mavlink::payloadFloat(stop.payload, 16), 0.0f);
  // A tilt alone is not a stop (the pan's command name says stop).
  EXPECT_GT(mavlink::payloadFloat(parsed(encoder.encode(output(0, 0, 0.1))).payload, 12), 0.0f);
  EXPECT_EQ(parsed(encoder.heartbeat()).sequence, 4);
}

TEST(Mavlink, FollowVelocityYawRateAndStop) {
  ProtocolEncoder encoder = mavlinkEncoder(MavlinkMode::Follow);
  const double scale = std::tan(30 * M_PI / 180);
  const mavlink::Frame go = parsed(encoder.encode(output(0.4, -0.2, 0)));  // forward, turning right
  EXPECT_EQ(go.messageId, 84u);
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(go.payload, 16), 0.4f);                             // vx, m/s
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(go.payload, 44), static_cast<float>(0.2 * scale));  // yaw rate
  EXPECT_EQ(go.payload[48] | (go.payload[49] << 8), 1479);                                  // type_mask
  EXPECT_EQ(go.payload[52], 9);  // MAV_FRAME_BODY_OFFSET_NED
  const mavlink::Frame stop = parsed(encoder.encode(DriveOutput()));
  EXPECT_EQ(mavlink::payloadFloat(stop.payload, 16), 0.0f);
  EXPECT_EQ(mavlink::payloadFloat(stop.payload, 44), 0.0f);
  EXPECT_EQ(stop.payload[52], 9);
}

TEST(Mavlink, EveryCommandIsBounded) {
  ProtocolSettings s;
  s.protocol = Protocol::Mavlink;
  s.mavlink.rateScale = mavlinkRateScale(170);  // a very wide lens: 11.4 rad/s at 1.0
  s.mavlink.maxRate = 1.0;
  s.mavlink.maxSpeed = 2.0;
  s.mavlink.mode = MavlinkMode::Gimbal;
  ProtocolEncoder gimbal(s);
  const mavlink::Frame fast = parsed(gimbal.encode(output(0, 1e6, -1e6)));
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(fast.payload, 16), -1.0f);  // yaw
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(fast.payload, 12), -1.0f);  // pitch
  const mavlink::Frame nan = parsed(gimbal.encode(output(0, std::nan(""), 0.1)));
  EXPECT_EQ(mavlink::payloadFloat(nan.payload, 16), 0.0f);
  s.mavlink.mode = MavlinkMode::Follow;
  ProtocolEncoder follow(s);
  const mavlink::Frame go = parsed(follow.encode(output(100, -1e6, 0)));
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(go.payload, 16), 2.0f);  // vx
  EXPECT_FLOAT_EQ(mavlink::payloadFloat(go.payload, 44), 1.0f);  // yaw rate
}

TEST(Mavlink, ParseRejectsCorruptAndCutFrames) {
  mavlink::Sender sender;
  Bytes bytes = mavlink::encode(mavlink::Heartbeat(), sender);
  EXPECT_TRUE(mavlink::parseFrame(bytes.data(), bytes.size()));
  EXPECT_FALSE(mavlink::parseFrame(bytes.data(), bytes.size() - 1));
  bytes[12] ^= 0x01;
  EXPECT_FALSE(mavlink::parseFrame(bytes.data(), bytes.size()));
}

}  // namespace
}  // namespace colortrack

int main(int argc, char **argv) {
  testing::InitGoogleTest(&argc, argv);
  const int result = RUN_ALL_TESTS();
  return result == 0 && colortrack::nodeMissing ? colortrack::node_mavlink::kSkip : result;
}
