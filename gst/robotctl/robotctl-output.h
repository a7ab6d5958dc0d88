// SPDX-License-Identifier: LGPL-2.1-or-later
// What robotctl's properties say about its output, in the terms of the core's encoder and the serial port:
// the mapping from the property units (degrees, per-property ids) to the encoder's, in one place.
#pragma once

#include "colortrack/protocol.hpp"
#include "colortrack/robot_port.hpp"
#include "robotctl-settings.h"

namespace robotctl {

SerialConfig toSerialConfig(const Settings &s);
// The MAVLink ids, mode and bounds (hfov, max-rate in deg/s, max-speed) as the encoder takes them.
colortrack::MavlinkSettings toMavlinkSettings(const Settings &s);

}  // namespace robotctl
