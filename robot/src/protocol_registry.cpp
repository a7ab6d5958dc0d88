// SPDX-License-Identifier: LGPL-2.1-or-later
// The registry of robot protocols: adding a protocol is a value of Protocol, its encoder's file (with its
// factory) and a row below (the factory's declaration and the descriptor).
#include "colortrack/protocol.hpp"

namespace colortrack {

std::unique_ptr<CommandEncoder> makeZoneCharEncoder(
    const ProtocolSettings &settings);                                                // encoder_zone_char.cpp
std::unique_ptr<CommandEncoder> makeTextEncoder(const ProtocolSettings &settings);    // encoder_text.cpp
std::unique_ptr<CommandEncoder> makeBinaryEncoder(const ProtocolSettings &settings);  // encoder_binary.cpp
std::unique_ptr<CommandEncoder> makeMavlinkEncoder(const ProtocolSettings &settings);  // encoder_mavlink.cpp

const std::vector<ProtocolDescriptor> &protocolDescriptors() {
  static const std::vector<ProtocolDescriptor> protocols = {
      {Protocol::ZoneChar, "zone-char", "One character per command (zone-chars)", makeZoneCharEncoder},
      {Protocol::Text, "text", "One line \"L=<int> R=<int>\" per command", makeTextEncoder},
      {Protocol::Binary, "binary", "Framed packet with sequence number and CRC-8", makeBinaryEncoder},
      {Protocol::Mavlink, "mavlink", "MAVLink 2 (mavlink-mode), with a 1 Hz heartbeat", makeMavlinkEncoder},
  };
  return protocols;
}

}  // namespace colortrack
