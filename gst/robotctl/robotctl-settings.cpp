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
using Def = gstglue::PropertyDef<Settings>;
using colortrack::ControllerSettings;
using colortrack::FailsafeSettings;

using Change = Settings::Change;
using Rule = gstglue::StartRule<Settings>;

std::string checkZoneCharsValue(const PropertyStore &, const GValue *v, std::string *) {
  std::string why;
  return colortrack::parseZoneChars(textOf(v), &why) ? "" : why;
}

std::string checkLocationValue(const PropertyStore &, const GValue *v, std::string *) {
  const std::string location = textOf(v);
  const std::string why = checkLocation(location);
  if (!why.empty() || location.empty() || location == "-" || isUdpLocation(location)) return why;
  return colortrack::checkOutputPath(location);
}

// While running (protocol and mavlink-mode are fixed then); before start, start() judges the pair once every
// property has been set, whatever their order.
std::string checkControllerValue(const PropertyStore &store, const GValue *v, std::string *);

// Each numeric property's declared range is the range it accepts (gst-inspect tells the truth), and GLib
// refuses values outside it. GLib's check refuses NaN too (its clamp leaves NaN, which never equals itself);
// this is for a GLib that would not, so that NaN never reaches the controller.
const char *refuseNotFinite(const GValue *v) {
  return std::isfinite(g_value_get_double(v)) ? nullptr : "the value must be a number";
}

const char *refuseEmptyRoiType(const GValue *v) {
  // An empty type matches no region: the robot would never see a target.
  return textOf(v).empty() ? "it names the type of the regions to follow (e.g. colortrack, object)" : nullptr;
}

// Where the commands go and how they are encoded: read at start.
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

std::string nonStandardBaudRate(const Settings &s) {
  if (s.device.empty() || isStandardBaudRate(s.baudRate)) return {};
  return "Unsupported baud rate " + std::to_string(s.baudRate) +
         " (property 'baud-rate'): use a standard rate such as 9600, 19200, 38400, 57600 or 115200.";
}

// A warning when serial-port properties are set away from their defaults while the output is 'location'
// (a file, a pty, a FIFO, UDP or stdout: none of them has a baud rate).
std::string serialSettingsUnused(const Settings &s) {
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
  return "Serial settings " + names +
         " are ignored: only a serial port named by 'device' uses them, and the " +
         "output is 'location' ('" + s.location + "').";
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

std::string noOutput(const Settings &s) {
  if (!s.device.empty() || !s.location.empty()) return {};
  return "No output: set 'device' (a serial port) or 'location' (a file, FIFO, pseudo-terminal, "
         "udp://HOST:PORT, or '-' for stdout).";
}

std::string twoOutputs(const Settings &s) {
  if (s.device.empty() || s.location.empty()) return {};
  return "Set either 'device' ('" + s.device + "') or 'location' ('" + s.location + "'), not both.";
}

std::string badZoneChars(const Settings &s) {
  std::string why;
  if (colortrack::parseZoneChars(s.zoneChars, &why)) return {};
  return "Invalid value '" + s.zoneChars + "' for property 'zone-chars': " + why;
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
          .refusing(refuseNotFinite),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_double(
            "max-rate", "Largest rate",
            "protocol=mavlink: every pitch and yaw rate sent is clamped to this, deg/s "
            "(0.1 to 720); read at start",
            0.1, 720.0, Settings{}.maxRate, f);
      })
          .field<&Settings::maxRate>()
          .refusing(refuseNotFinite),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_double("max-speed", "Largest speed",
                                   "protocol=mavlink mavlink-mode=follow: every forward velocity sent is "
                                   "clamped to this, m/s (0.01 to 50); read at start",
                                   0.01, 50.0, Settings{}.maxSpeed, f);
      })
          .field<&Settings::maxSpeed>()
          .refusing(refuseNotFinite),
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

// How commands are decided: from the next buffer.
std::vector<Def> controllerRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_enum("controller", "Controller",
                                 "How commands are decided; zone cannot drive a gimbal (mavlink-mode=gimbal)",
                                 GST_TYPE_ROBOT_CTL_CONTROLLER, static_cast<gint>(Settings{}.controller.kind),
                                 f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::kind>()
          .checking(checkControllerValue),
      Def::live([](GParamFlags f) {
        return g_param_spec_enum("distance-cue", "Distance cue", "What tells how far the target is",
                                 GST_TYPE_ROBOT_CTL_DISTANCE_CUE,
                                 static_cast<gint>(Settings{}.controller.distanceCue), f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::distanceCue>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("set-point", "Set-point",
                                   "Wanted distance cue: box height (or box bottom) as a fraction of the "
                                   "frame height",
                                   0.01, 1.0, ControllerSettings{}.setPoint, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::setPoint>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean("set-point-at-start", "Set-point at start",
                                    "Keep the distance cue the target had when first confirmed (after start, "
                                    "a flush, or turning this on) instead of set-point: the robot holds the "
                                    "distance it was at, whatever share of the object the box covers",
                                    ControllerSettings{}.setPointAtStart, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::setPointAtStart>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("turn-deadband", "Turn deadband",
                                   "Horizontal offset (fraction of half the frame width) within "
                                   "which the target counts as centred",
                                   0.0, 1.0, ControllerSettings{}.turnDeadband, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnDeadband>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("distance-deadband", "Distance deadband",
                                   "Relative distance error within which the distance counts as right", 0.0,
                                   1.0, ControllerSettings{}.distanceDeadband, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::distanceDeadband>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("hysteresis", "Hysteresis",
                                   "Zone controller: how far inside a deadband the error must come "
                                   "back before a turn or drive ends",
                                   0.0, 1.0, ControllerSettings{}.hysteresis, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::hysteresis>(),
  };
}

// The proportional controller's gains.
std::vector<Def> gainRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_double("turn-gain", "Turn gain",
                                   "Proportional controller: angular speed per unit horizontal offset, 0-100",
                                   0.0, 100.0, ControllerSettings{}.turnGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnGain>()
          .refusing(refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("drive-gain", "Drive gain",
                                   "Proportional controller: linear speed per unit relative distance "
                                   "error, 0-100",
                                   0.0, 100.0, ControllerSettings{}.driveGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::driveGain>()
          .refusing(refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "turn-integral-gain", "Turn integral gain",
            "Proportional controller: angular speed per unit horizontal offset held for a second, 0-100 "
            "(removes "
            "the lag behind a target moving sideways; frozen while the turn is limited)",
            0.0, 100.0, ControllerSettings{}.turnIntegralGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnIntegralGain>()
          .refusing(refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "drive-integral-gain", "Drive integral gain",
            "Proportional controller: linear speed per unit relative distance error held for a second, 0-100 "
            "(removes the lag behind a target moving away or closer; frozen while the speed is limited)",
            0.0, 100.0, ControllerSettings{}.driveIntegralGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::driveIntegralGain>()
          .refusing(refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "turn-rate-gain", "Turn rate gain",
            "Proportional controller: angular speed per unit of horizontal offset change per second, 0-100 "
            "(reacts to the target's sideways motion; damps the turn)",
            0.0, 100.0, ControllerSettings{}.turnRateGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::turnRateGain>()
          .refusing(refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "drive-rate-gain", "Drive rate gain",
            "Proportional controller: linear speed per unit of relative distance error change per second, "
            "0-100 (reacts to the target moving away or closer; damps the approach)",
            0.0, 100.0, ControllerSettings{}.driveRateGain, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::driveRateGain>()
          .refusing(refuseNotFinite),
      Def::live([](GParamFlags f) {
        return g_param_spec_double(
            "latency", "Latency",
            "Zone controller: seconds from a command to the wheels (the robot's delay plus about half the "
            "send period 1/rate). A turn ends this much early and, near the centre, turns are single "
            "decisions each followed by this long without a turn, so the robot does not swing across the "
            "centre. 0: no such rule (the paper's controller)",
            0.0, 2.0, ControllerSettings{}.latency, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::latency>(),
  };
}

// The limits of every command.
std::vector<Def> limitRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-linear", "Maximum linear speed",
                                   "Largest forward/backward speed (fraction of full speed); the zone "
                                   "controller's driving speed",
                                   0.0, 1.0, ControllerSettings{}.maxLinear, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxLinear>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-angular", "Maximum angular speed",
                                   "Largest turn speed (fraction of full wheel speed); the zone "
                                   "controller's turning speed",
                                   0.0, 1.0, ControllerSettings{}.maxAngular, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxAngular>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-linear-accel", "Maximum linear acceleration",
                                   "Proportional controller: largest change of the linear speed "
                                   "per second (0 = unlimited)",
                                   0.0, 1000.0, ControllerSettings{}.maxLinearAccel, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxLinearAccel>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("max-angular-accel", "Maximum angular acceleration",
                                   "Proportional controller: largest change of the angular "
                                   "speed per second (0 = unlimited)",
                                   0.0, 1000.0, ControllerSettings{}.maxAngularAccel, f);
      })
          .marks({Change::Controller})
          .field<&Settings::controller, &ControllerSettings::maxAngularAccel>(),
  };
}

// The failsafe.
std::vector<Def> failsafeRows() {
  return {
      Def::live([](GParamFlags f) {
        return g_param_spec_uint(
            "lost-timeout", "Lost timeout",
            "Milliseconds without a confirmed target, or without any buffer, before the target counts "
            "as lost and the robot stops (or search-turns); without a confirmed target it keeps its drive "
            "for the first half, then stands still, and never keeps its turn",
            1, 600000, static_cast<guint>(std::lround(FailsafeSettings{}.lostTimeout * 1000)), f);
      })
          .marks({Change::Controller})
          .accessors(
              [](const Settings &s, GValue *v) {
                g_value_set_uint(v, static_cast<guint>(std::lround(s.failsafe.lostTimeout * 1000)));
              },
              [](Settings &s, const GValue *v) { s.failsafe.lostTimeout = g_value_get_uint(v) / 1000.0; }),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("min-score", "Minimum score",
                                   "A target with a lower score counts as not seen", 0.0, 1.0,
                                   FailsafeSettings{}.minScore, f);
      })
          .marks({Change::Controller})
          .field<&Settings::failsafe, &FailsafeSettings::minScore>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_boolean("search-turn", "Search turn",
                                    "After lost-timeout turn slowly towards where the target was last "
                                    "seen instead of standing still",
                                    FailsafeSettings{}.searchTurn, f);
      })
          .marks({Change::Controller})
          .field<&Settings::failsafe, &colortrack::FailsafeSettings::searchTurn>(),
      Def::live([](GParamFlags f) {
        return g_param_spec_double("search-speed", "Search speed",
                                   "Angular speed of the search turn (fraction of full wheel speed); only "
                                   "used with search-turn=true",
                                   0.0, 1.0, FailsafeSettings{}.searchSpeed, f);
      })
          .marks({Change::Controller})
          .field<&Settings::failsafe, &FailsafeSettings::searchSpeed>(),
  };
}

// Which target to follow, and the messages.
std::vector<Def> targetRows() {
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

namespace {

// Why `controller` cannot drive what the protocol drives (zone and a gimbal), or empty: a start rule, and
// checked again when `controller` is set while running.
std::string controllerMismatch(const Settings &s) {
  const colortrack::ControllerSettings c = controllerSettings(s);
  if (colortrack::lawFits(c.kind, c.axes)) return {};
  return "controller=zone cannot drive a gimbal (protocol=mavlink mavlink-mode=gimbal): its commands are one "
         "motion at a time at a fixed speed. Use controller=auto (the default) or controller=proportional";
}

std::string checkControllerValue(const PropertyStore &store, const GValue *v, std::string *) {
  if (!store.running) return {};
  Settings s = store.settings;
  s.controller.kind = static_cast<colortrack::ControllerKind>(g_value_get_enum(v));
  return controllerMismatch(s);
}
}  // namespace

bool isStandardBaudRate(guint rate) {
  return std::find(std::begin(kStandardBaudRates), std::end(kStandardBaudRates), rate) !=
         std::end(kStandardBaudRates);
}

const gstglue::PropertyTable<Settings> &properties() {
  static const gstglue::PropertyTable<Settings> table(
      gstglue::rowsOf<Def>(serialRows(), outputRows(), mavlinkRows(), mavlinkLimitRows(), controllerRows(),
                           gainRows(), limitRows(), failsafeRows(), targetRows()),
      {{noOutput, Rule::Severity::Error, GST_RESOURCE_ERROR_NOT_FOUND},
       {twoOutputs},
       {nonStandardBaudRate},
       {controllerMismatch},
       {serialSettingsUnused, Rule::Severity::Warning},
       {badZoneChars}});
  return table;
}

}  // namespace robotctl
