// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-output.h"

#include <algorithm>
#include <iterator>

namespace robotctl {

namespace {

// The rates a serial port can be set to portably (termios' Bxxx constants).
constexpr guint kStandardBaudRates[] = {50,      75,      110,     134,     150,     200,    300,     600,
                                        1200,    1800,    2400,    4800,    9600,    19200,  38400,   57600,
                                        115200,  230400,  460800,  500000,  576000,  921600, 1000000, 1152000,
                                        1500000, 2000000, 2500000, 3000000, 3500000, 4000000};

}  // namespace

bool isStandardBaudRate(guint rate) {
  return std::find(std::begin(kStandardBaudRates), std::end(kStandardBaudRates), rate) !=
         std::end(kStandardBaudRates);
}

SerialConfig toSerialConfig(const Settings &s) {
  return SerialConfig{s.device, s.baudRate, s.dataBits, s.stopBits, s.parity, s.flowControl};
}

colortrack::MavlinkSettings toMavlinkSettings(const Settings &s) {
  colortrack::MavlinkSettings m;
  m.mode = s.mavlinkMode;
  // Each checked to be within a byte (robotctl-settings.cpp).
  m.systemId = static_cast<std::uint8_t>(s.systemId);
  m.componentId = static_cast<std::uint8_t>(s.componentId);
  m.targetSystem = static_cast<std::uint8_t>(s.targetSystem);
  m.targetComponent = static_cast<std::uint8_t>(s.targetComponent);
  m.rateScale = colortrack::mavlinkRateScale(s.hfov);
  m.maxRate = s.maxRate * G_PI / 180;
  m.maxSpeed = s.maxSpeed;
  return m;
}

}  // namespace robotctl
