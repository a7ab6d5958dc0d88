// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-settings.h"

#include "colortrack/protocol.hpp"
#include "colortrack/output_file.hpp"
#include "colortrack/udp_port.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <type_traits>

namespace robotctl {

namespace {

using gstglue::Apply;
using gstglue::getText;
using gstglue::getTextOrNull;
using gstglue::getValue;
using gstglue::setText;
using gstglue::setValue;
using gstglue::textOf;
using Def = Row;
using colortrack::ControllerSettings;
using colortrack::FailsafeSettings;

using Change = Settings::Change;
using Rule = gstglue::StartRule<Settings>;

colortrack::Status checkZoneCharsValue(const PropertyStore &, const GValue *v) {
  return colortrack::parseZoneChars(textOf(v)).status();
}

colortrack::Status checkLocationValue(const PropertyStore &, const GValue *v) {
  const std::string location = textOf(v);
  const colortrack::Status written = checkLocation(location);
  if (!written || location.empty() || location == "-" || isUdpLocation(location)) return written;
  return colortrack::checkOutputPath(location);
}

colortrack::Status refuseEmptyRoiType(const GValue *v) {
  // An empty type matches no region: the robot would never see a target.
  if (!textOf(v).empty()) return {};
  return colortrack::Status::failure("it names the type of the regions to follow (e.g. colortrack, object)");
}

// The serial port (read at start).
std::vector<Def> serialRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("device", "Device",
                                   "Serial port to send the commands to (e.g. /dev/ttyUSB0, COM3); "
                                   "exclusive with 'location'; read at start",
                                   nullptr, f);
      }).textOrNull<&Settings::device>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint(
            "baud-rate", "Baud rate",
            "Serial port speed in bit/s; one of the standard rates 50 ... 4000000; read at start", 50,
            4000000, Settings{}.baudRate, f);
      }).field<&Settings::baudRate>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_int("data-bits", "Data bits", "Serial port data bits; read at start", 5, 8,
                                Settings{}.dataBits, f);
      }).field<&Settings::dataBits>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_enum("parity", "Parity", "Serial port parity; read at start",
                                 GST_TYPE_ROBOT_CTL_PARITY, static_cast<gint>(Settings{}.parity), f);
      }).field<&Settings::parity>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_int("stop-bits", "Stop bits", "Serial port stop bits; read at start", 1, 2,
                                Settings{}.stopBits, f);
      }).field<&Settings::stopBits>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_enum("flow-control", "Flow control", "Serial port flow control; read at start",
                                 GST_TYPE_ROBOT_CTL_FLOW_CONTROL, static_cast<gint>(Settings{}.flowControl),
                                 f);
      }).field<&Settings::flowControl>(),
  };
}

// The rates a serial port can be set to portably (termios' Bxxx constants).
constexpr guint kStandardBaudRates[] = {50,      75,      110,     134,     150,     200,    300,     600,
                                        1200,    1800,    2400,    4800,    9600,    19200,  38400,   57600,
                                        115200,  230400,  460800,  500000,  576000,  921600, 1000000, 1152000,
                                        1500000, 2000000, 2500000, 3000000, 3500000, 4000000};

colortrack::Status nonStandardBaudRate(const Settings &s) {
  if (s.device.empty() || isStandardBaudRate(s.baudRate)) return {};
  return colortrack::Status::failure(
      "Unsupported baud rate " + std::to_string(s.baudRate) +
      " (property 'baud-rate'): use a standard rate such as 9600, 19200, 38400, 57600 or 115200.");
}

// A warning when serial-port properties are set away from their defaults while the output is 'location'
// (a file, a pty, a FIFO, UDP or stdout: none of them has a baud rate).
colortrack::Status serialSettingsUnused(const Settings &s) {
  if (s.location.empty()) return {};
  const Settings defaults;
  std::string names;
  const auto note = [&names](bool changed, const char *name) {
    if (changed) names += std::string(names.empty() ? "" : ", ") + "'" + name + "'";
  };
  note(s.baudRate != defaults.baudRate, "baud-rate");
  note(s.dataBits != defaults.dataBits, "data-bits");
  note(s.stopBits != defaults.stopBits, "stop-bits");
  note(s.parity != defaults.parity, "parity");
  note(s.flowControl != defaults.flowControl, "flow-control");
  if (names.empty()) return {};
  return colortrack::Status::failure(
      "Serial settings " + names + " are ignored: only a serial port named by 'device' uses them, and the " +
      "output is 'location' ('" + s.location + "').");
}

// Any other output, and what is written to it (read at start).
std::vector<Def> outputRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("location", "Location",
                                   "File, FIFO or pseudo-terminal to write the commands to, '-' for "
                                   "stdout (dry runs, tests), or udp://HOST:PORT to send each as a datagram; "
                                   "any other SCHEME:... is refused (write ./name for a file with a colon); "
                                   "exclusive with 'device'; read at start",
                                   nullptr, f);
      })
          .textOrNull<&Settings::location>()
          .checking(checkLocationValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_enum("protocol", "Protocol", "How commands are encoded; read at start",
                                 GST_TYPE_ROBOT_CTL_PROTOCOL, static_cast<gint>(Settings{}.protocol), f);
      }).field<&Settings::protocol>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string(
            "zone-chars", "Zone characters",
            "The zone-char protocol's characters for forward, backward, left, right and "
            "stop, in that order (five distinct printable characters); read at start",
            Settings{}.zoneChars.c_str(), f);
      })
          .text<&Settings::zoneChars>()
          .checking(checkZoneCharsValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_int(
            "output-scale", "Output scale",
            "Integer sent for full wheel speed by the text and binary protocols; read at start", 1, 32767,
            Settings{}.outputScale, f);
      }).field<&Settings::outputScale>(),
  };
}

colortrack::Status noOutput(const Settings &s) {
  if (!s.device.empty() || !s.location.empty()) return {};
  return colortrack::Status::failure(
      "No output: set 'device' (a serial port) or 'location' (a file, FIFO, pseudo-terminal, "
      "udp://HOST:PORT, or '-' for stdout).");
}

colortrack::Status twoOutputs(const Settings &s) {
  if (s.device.empty() || s.location.empty()) return {};
  return colortrack::Status::failure("Set either 'device' ('" + s.device + "') or 'location' ('" +
                                     s.location + "'), not both.");
}

colortrack::Status badZoneChars(const Settings &s) {
  const colortrack::Result<colortrack::ZoneChars> chars = colortrack::parseZoneChars(s.zoneChars);
  if (chars) return {};
  return colortrack::Status::failure("Invalid value '" + s.zoneChars +
                                     "' for property 'zone-chars': " + chars.error());
}

// MAVLink ids and what the commands drive (read at start).
std::vector<Def> mavlinkRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_enum("mavlink-mode", "MAVLink mode",
                                 "protocol=mavlink: what the commands drive: a gimbal (pitch and yaw rates, "
                                 "always the proportional law) or a drone (forward velocity and yaw rate); "
                                 "read at start",
                                 GST_TYPE_ROBOT_CTL_MAVLINK_MODE, static_cast<gint>(Settings{}.mavlinkMode),
                                 f);
      }).field<&Settings::mavlinkMode>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint("system-id", "System id",
                                 "protocol=mavlink: our MAVLink system id, 1-255 (usually the vehicle's); "
                                 "read at start",
                                 1, 255, Settings{}.systemId, f);
      }).field<&Settings::systemId>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint("component-id", "Component id",
                                 "protocol=mavlink: our MAVLink component id, 1-255 (191: onboard "
                                 "computer); read at start",
                                 1, 255, Settings{}.componentId, f);
      }).field<&Settings::componentId>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint("target-system", "Target system",
                                 "protocol=mavlink: system id the commands are for, 0-255 (0: all); read at "
                                 "start",
                                 0, 255, Settings{}.targetSystem, f);
      }).field<&Settings::targetSystem>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint(
            "target-component", "Target component",
            "protocol=mavlink: component id the commands are for, 0-255 (1: the "
            "autopilot, which is usually also the gimbal manager; 0: all); read at start",
            0, 255, Settings{}.targetComponent, f);
      }).field<&Settings::targetComponent>(),
  };
}

// MAVLink bounds and the link watch, and the command rate.
std::vector<Def> mavlinkLimitRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_double("hfov", "Horizontal field of view",
                                   "protocol=mavlink: the camera's horizontal field of view in degrees, 1 to "
                                   "170 (the vertical one follows from the frame's aspect ratio); turns a "
                                   "turn of 1.0 into tan(hfov/2) rad/s; read at start",
                                   1.0, 170.0, Settings{}.hfov, f);
      })
          .field<&Settings::hfov>()
          .refusing(gstglue::refuseNotFinite),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_double(
            "max-rate", "Largest rate",
            "protocol=mavlink: every pitch and yaw rate sent is clamped to this, deg/s "
            "(0.1 to 720); read at start",
            0.1, 720.0, Settings{}.maxRate, f);
      })
          .field<&Settings::maxRate>()
          .refusing(gstglue::refuseNotFinite),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_double("max-speed", "Largest speed",
                                   "protocol=mavlink mavlink-mode=follow: every forward velocity sent is "
                                   "clamped to this, m/s (0.01 to 50); read at start",
                                   0.01, 50.0, Settings{}.maxSpeed, f);
      })
          .field<&Settings::maxSpeed>()
          .refusing(gstglue::refuseNotFinite),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint(
            "link-timeout", "Link timeout",
            "protocol=mavlink over udp://: ms without a HEARTBEAT from target-system's target-component "
            "before the link counts as lost (a warning; only stop is sent until one comes "
            "again, then stop first); starts with the first heartbeat heard; 0 (or target-system=0): off; "
            "under about 1500 a 1 Hz heartbeat makes the link flap; read at start",
            0, 60000, Settings{}.linkTimeoutMs, f);
      }).field<&Settings::linkTimeoutMs>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_double(
            "rate", "Rate",
            "Commands per second; the current command is repeated at this rate; read at start", 0.5, 1000.0,
            Settings{}.rate, f);
      }).field<&Settings::rate>(),
  };
}

// Which target to follow, and the messages.
std::vector<Def> followRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_string("roi-type", "ROI type",
                                   "Type of the region-of-interest meta to follow, not empty "
                                   "(\"object\" for cvtracker)",
                                   Settings{}.roiType.c_str(), f);
      })
          .text<&Settings::roiType>()
          .refusing(refuseEmptyRoiType),
      Def::live([](GParamFlags f) {
        return g_param_spec_int(
            "target-id", "Target id",
            "Id of the region of interest to follow, and no other; -1 = choose by lock-on", -1, G_MAXINT,
            Settings{}.targetId, f);
      }).field<&Settings::targetId>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_enum("lock-on", "Lock on",
                                 "With target-id=-1, which region to follow when there is none yet or the "
                                 "followed one is lost or gone (never a region seen beside the followed "
                                 "one); the choice is kept while its track lives",
                                 GST_TYPE_ROBOT_CTL_LOCK_ON, static_cast<gint>(Settings{}.lockOn), f);
      }).field<&Settings::lockOn>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_boolean(
            "post-messages", "Post messages",
            "Post a \"robotctl\" element message for every command sent; read at start",
            Settings{}.postMessages, f);
      }).field<&Settings::postMessages>(),
  };
}

}  // namespace

bool drivesGimbal(const Settings &s) {
  return s.protocol == colortrack::Protocol::Mavlink && s.mavlinkMode == colortrack::MavlinkMode::Gimbal;
}

colortrack::ControllerSettings controllerSettings(const Settings &s) {
  colortrack::ControllerSettings controller = s.controller;
  controller.axes = drivesGimbal(s) ? colortrack::ControlAxes::PanTilt : colortrack::ControlAxes::TurnDrive;
  return controller;
}

bool isStandardBaudRate(guint rate) {
  return std::find(std::begin(kStandardBaudRates), std::end(kStandardBaudRates), rate) !=
         std::end(kStandardBaudRates);
}

std::vector<Row> linkRows() {
  return gstglue::rowsOf<Def>(serialRows(), outputRows(), mavlinkRows(), mavlinkLimitRows());
}

std::vector<Row> targetRows() {
  return followRows();
}

std::vector<gstglue::StartRule<Settings>> linkRules() {
  return {{noOutput, Rule::Severity::Error, GST_RESOURCE_ERROR_NOT_FOUND},
          {twoOutputs},
          {nonStandardBaudRate},
          {serialSettingsUnused, Rule::Severity::Warning},
          {badZoneChars}};
}

}  // namespace robotctl
