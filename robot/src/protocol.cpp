// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/protocol.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

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

Result<ZoneChars> parseZoneChars(const std::string &text) {
  const auto fail = [](const std::string &why) { return Status::failure(why); };
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

double mavlinkRateScale(double hfovDegrees) {
  return std::tan(hfovDegrees * M_PI / 360.0);
}

ProtocolEncoder::ProtocolEncoder(const ProtocolSettings &settings) {
  setSettings(settings);
}

void ProtocolEncoder::setSettings(const ProtocolSettings &settings) {
  std::unique_ptr<CommandEncoder> made;
  for (const ProtocolDescriptor &d : protocolDescriptors())
    if (d.value == settings.protocol) made = d.make(settings);
  if (!made)
    throw std::logic_error("no encoder registered for Protocol value " +
                           std::to_string(static_cast<int>(settings.protocol)));
  settings_ = settings;
  encoder_ = std::move(made);
}

}  // namespace colortrack
