// SPDX-License-Identifier: LGPL-2.1-or-later
// protocol=zone-char: one byte per command, the command's character (the paper's robot).
#include "colortrack/protocol.hpp"

namespace colortrack {

namespace {

class ZoneCharEncoder : public CommandEncoder {
 public:
  explicit ZoneCharEncoder(const ZoneChars &chars) : chars_(chars) {}
  std::vector<std::uint8_t> encode(const DriveOutput &output, std::uint8_t &) override {
    return {static_cast<std::uint8_t>(chars_.of(output.command))};
  }

 private:
  ZoneChars chars_;
};

}  // namespace

std::unique_ptr<CommandEncoder> makeZoneCharEncoder(const ProtocolSettings &settings) {
  return std::make_unique<ZoneCharEncoder>(settings.zoneChars);
}

}  // namespace colortrack
