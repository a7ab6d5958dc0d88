// SPDX-License-Identifier: LGPL-2.1-or-later
// protocol=text: one line "L=<int> R=<int>\n" per command, the wheel speeds scaled by outputScale.
#include <cstdio>

#include "colortrack/protocol.hpp"

namespace colortrack {

namespace {

class TextEncoder : public CommandEncoder {
 public:
  explicit TextEncoder(int scale) : scale_(scale) {}
  std::vector<std::uint8_t> encode(const DriveOutput &output, std::uint8_t &) override {
    const auto [left, right] = sentSpeeds(output, scale_);
    char line[32];
    const int n = std::snprintf(line, sizeof line, "L=%d R=%d\n", left, right);
    return std::vector<std::uint8_t>(line, line + n);
  }

 private:
  int scale_;
};

}  // namespace

std::unique_ptr<CommandEncoder> makeTextEncoder(const ProtocolSettings &settings) {
  return std::make_unique<TextEncoder>(settings.outputScale);
}

}  // namespace colortrack
