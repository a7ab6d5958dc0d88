// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-output.h"

namespace robotctl {

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
