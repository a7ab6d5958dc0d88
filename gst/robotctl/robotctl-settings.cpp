// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-settings.h"

#include "colortrack/protocol.hpp"
#include "colortrack/output_file.hpp"
#include "colortrack/udp_port.hpp"

#include <cmath>
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

constexpr bool kVersioned = true;

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
const Def kProperties[] = {
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_string("device", "Device",
                                  "Serial port to send the commands to (e.g. /dev/ttyUSB0, COM3); "
                                  "exclusive with 'location'; read at start",
                                  nullptr, f);
     },
     getTextOrNull<&Settings::device>, setText<&Settings::device>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_uint(
           "baud-rate", "Baud rate",
           "Serial port speed in bit/s; one of the standard rates 50 ... 4000000; read at start", 50, 4000000,
           Settings{}.baudRate, f);
     },
     getValue<&Settings::baudRate>, setValue<&Settings::baudRate>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_int("data-bits", "Data bits", "Serial port data bits; read at start", 5, 8,
                               Settings{}.dataBits, f);
     },
     getValue<&Settings::dataBits>, setValue<&Settings::dataBits>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_enum("parity", "Parity", "Serial port parity; read at start",
                                GST_TYPE_ROBOT_CTL_PARITY, static_cast<gint>(Settings{}.parity), f);
     },
     getValue<&Settings::parity>, setValue<&Settings::parity>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_int("stop-bits", "Stop bits", "Serial port stop bits; read at start", 1, 2,
                               Settings{}.stopBits, f);
     },
     getValue<&Settings::stopBits>, setValue<&Settings::stopBits>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_enum("flow-control", "Flow control", "Serial port flow control; read at start",
                                GST_TYPE_ROBOT_CTL_FLOW_CONTROL, static_cast<gint>(Settings{}.flowControl),
                                f);
     },
     getValue<&Settings::flowControl>, setValue<&Settings::flowControl>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_string("location", "Location",
                                  "File, FIFO or pseudo-terminal to write the commands to, '-' for "
                                  "stdout (dry runs, tests), or udp://HOST:PORT to send each as a datagram; "
                                  "any other SCHEME:... is refused (write ./name for a file with a colon); "
                                  "exclusive with 'device'; read at start",
                                  nullptr, f);
     },
     getTextOrNull<&Settings::location>, setText<&Settings::location>, nullptr, checkLocationValue, true},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_enum("protocol", "Protocol", "How commands are encoded; read at start",
                                GST_TYPE_ROBOT_CTL_PROTOCOL, static_cast<gint>(Settings{}.protocol), f);
     },
     getValue<&Settings::protocol>, setValue<&Settings::protocol>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_string(
           "zone-chars", "Zone characters",
           "The zone-char protocol's characters for forward, backward, left, right and "
           "stop, in that order (five distinct printable characters); read at start",
           Settings{}.zoneChars.c_str(), f);
     },
     getText<&Settings::zoneChars>, setText<&Settings::zoneChars>, nullptr, checkZoneCharsValue, true},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_int(
           "output-scale", "Output scale",
           "Integer sent for full wheel speed by the text and binary protocols; read at start", 1, 32767,
           Settings{}.outputScale, f);
     },
     getValue<&Settings::outputScale>, setValue<&Settings::outputScale>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_enum("mavlink-mode", "MAVLink mode",
                                "protocol=mavlink: what the commands drive: a gimbal (pitch and yaw rates, "
                                "always the proportional law) or a drone (forward velocity and yaw rate); "
                                "read at start",
                                GST_TYPE_ROBOT_CTL_MAVLINK_MODE, static_cast<gint>(Settings{}.mavlinkMode),
                                f);
     },
     getValue<&Settings::mavlinkMode>, setValue<&Settings::mavlinkMode>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_uint("system-id", "System id",
                                "protocol=mavlink: our MAVLink system id, 1-255 (usually the vehicle's); "
                                "read at start",
                                1, 255, Settings{}.systemId, f);
     },
     getValue<&Settings::systemId>, setValue<&Settings::systemId>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_uint("component-id", "Component id",
                                "protocol=mavlink: our MAVLink component id, 1-255 (191: onboard "
                                "computer); read at start",
                                1, 255, Settings{}.componentId, f);
     },
     getValue<&Settings::componentId>, setValue<&Settings::componentId>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_uint("target-system", "Target system",
                                "protocol=mavlink: system id the commands are for, 0-255 (0: all); read at "
                                "start",
                                0, 255, Settings{}.targetSystem, f);
     },
     getValue<&Settings::targetSystem>, setValue<&Settings::targetSystem>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_uint("target-component", "Target component",
                                "protocol=mavlink: component id the commands are for, 0-255 (1: the "
                                "autopilot, which is usually also the gimbal manager; 0: all); read at start",
                                0, 255, Settings{}.targetComponent, f);
     },
     getValue<&Settings::targetComponent>, setValue<&Settings::targetComponent>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_double("hfov", "Horizontal field of view",
                                  "protocol=mavlink: the camera's horizontal field of view in degrees, 1 to "
                                  "170 (the vertical one follows from the frame's aspect ratio); turns a "
                                  "turn of 1.0 into tan(hfov/2) rad/s; read at start",
                                  1.0, 170.0, Settings{}.hfov, f);
     },
     getValue<&Settings::hfov>, setValue<&Settings::hfov>, refuseNotFinite},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_double("max-rate", "Largest rate",
                                  "protocol=mavlink: every pitch and yaw rate sent is clamped to this, deg/s "
                                  "(0.1 to 720); read at start",
                                  0.1, 720.0, Settings{}.maxRate, f);
     },
     getValue<&Settings::maxRate>, setValue<&Settings::maxRate>, refuseNotFinite},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_double("max-speed", "Largest speed",
                                  "protocol=mavlink mavlink-mode=follow: every forward velocity sent is "
                                  "clamped to this, m/s (0.01 to 50); read at start",
                                  0.01, 50.0, Settings{}.maxSpeed, f);
     },
     getValue<&Settings::maxSpeed>, setValue<&Settings::maxSpeed>, refuseNotFinite},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_uint(
           "link-timeout", "Link timeout",
           "protocol=mavlink over udp://: ms without a HEARTBEAT from target-system's target-component "
           "before the link counts as lost (a warning; only stop is sent until one comes "
           "again, then stop first); starts with the first heartbeat heard; 0 (or target-system=0): off; "
           "under about 1500 a 1 Hz heartbeat makes the link flap; read at start",
           0, 60000, Settings{}.linkTimeoutMs, f);
     },
     getValue<&Settings::linkTimeoutMs>, setValue<&Settings::linkTimeoutMs>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_double(
           "rate", "Rate", "Commands per second; the current command is repeated at this rate; read at start",
           0.5, 1000.0, Settings{}.rate, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_double(v, s.rate); },
     [](Settings &s, const GValue *v) { s.rate = g_value_get_double(v); }},

    // How commands are decided: from the next buffer.
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_enum("controller", "Controller",
                                "How commands are decided; zone cannot drive a gimbal (mavlink-mode=gimbal)",
                                GST_TYPE_ROBOT_CTL_CONTROLLER, static_cast<gint>(Settings{}.controller.kind),
                                f);
     },
     getValue<&Settings::controller, &ControllerSettings::kind>,
     setValue<&Settings::controller, &ControllerSettings::kind>, nullptr, checkControllerValue},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_enum("distance-cue", "Distance cue", "What tells how far the target is",
                                GST_TYPE_ROBOT_CTL_DISTANCE_CUE,
                                static_cast<gint>(Settings{}.controller.distanceCue), f);
     },
     getValue<&Settings::controller, &ControllerSettings::distanceCue>,
     setValue<&Settings::controller, &ControllerSettings::distanceCue>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("set-point", "Set-point",
                                  "Wanted distance cue: box height (or box bottom) as a fraction of the "
                                  "frame height",
                                  0.01, 1.0, ControllerSettings{}.setPoint, f);
     },
     getValue<&Settings::controller, &ControllerSettings::setPoint>,
     setValue<&Settings::controller, &ControllerSettings::setPoint>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_boolean("set-point-at-start", "Set-point at start",
                                   "Keep the distance cue the target had when first confirmed (after start, "
                                   "a flush, or turning this on) instead of set-point: the robot holds the "
                                   "distance it was at, whatever share of the object the box covers",
                                   ControllerSettings{}.setPointAtStart, f);
     },
     getValue<&Settings::controller, &ControllerSettings::setPointAtStart>,
     setValue<&Settings::controller, &ControllerSettings::setPointAtStart>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("turn-deadband", "Turn deadband",
                                  "Horizontal offset (fraction of half the frame width) within "
                                  "which the target counts as centred",
                                  0.0, 1.0, ControllerSettings{}.turnDeadband, f);
     },
     getValue<&Settings::controller, &ControllerSettings::turnDeadband>,
     setValue<&Settings::controller, &ControllerSettings::turnDeadband>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("distance-deadband", "Distance deadband",
                                  "Relative distance error within which the distance counts as right", 0.0,
                                  1.0, ControllerSettings{}.distanceDeadband, f);
     },
     getValue<&Settings::controller, &ControllerSettings::distanceDeadband>,
     setValue<&Settings::controller, &ControllerSettings::distanceDeadband>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("hysteresis", "Hysteresis",
                                  "Zone controller: how far inside a deadband the error must come "
                                  "back before a turn or drive ends",
                                  0.0, 1.0, ControllerSettings{}.hysteresis, f);
     },
     getValue<&Settings::controller, &ControllerSettings::hysteresis>,
     setValue<&Settings::controller, &ControllerSettings::hysteresis>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("turn-gain", "Turn gain",
                                  "Proportional controller: angular speed per unit horizontal offset, 0-100",
                                  0.0, 100.0, ControllerSettings{}.turnGain, f);
     },
     getValue<&Settings::controller, &ControllerSettings::turnGain>,
     setValue<&Settings::controller, &ControllerSettings::turnGain>, refuseNotFinite},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("drive-gain", "Drive gain",
                                  "Proportional controller: linear speed per unit relative distance "
                                  "error, 0-100",
                                  0.0, 100.0, ControllerSettings{}.driveGain, f);
     },
     getValue<&Settings::controller, &ControllerSettings::driveGain>,
     setValue<&Settings::controller, &ControllerSettings::driveGain>, refuseNotFinite},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double(
           "turn-integral-gain", "Turn integral gain",
           "Proportional controller: angular speed per unit horizontal offset held for a second, 0-100 "
           "(removes "
           "the lag behind a target moving sideways; frozen while the turn is limited)",
           0.0, 100.0, ControllerSettings{}.turnIntegralGain, f);
     },
     getValue<&Settings::controller, &ControllerSettings::turnIntegralGain>,
     setValue<&Settings::controller, &ControllerSettings::turnIntegralGain>, refuseNotFinite},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double(
           "drive-integral-gain", "Drive integral gain",
           "Proportional controller: linear speed per unit relative distance error held for a second, 0-100 "
           "(removes the lag behind a target moving away or closer; frozen while the speed is limited)",
           0.0, 100.0, ControllerSettings{}.driveIntegralGain, f);
     },
     getValue<&Settings::controller, &ControllerSettings::driveIntegralGain>,
     setValue<&Settings::controller, &ControllerSettings::driveIntegralGain>, refuseNotFinite},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double(
           "turn-rate-gain", "Turn rate gain",
           "Proportional controller: angular speed per unit of horizontal offset change per second, 0-100 "
           "(reacts to the target's sideways motion; damps the turn)",
           0.0, 100.0, ControllerSettings{}.turnRateGain, f);
     },
     getValue<&Settings::controller, &ControllerSettings::turnRateGain>,
     setValue<&Settings::controller, &ControllerSettings::turnRateGain>, refuseNotFinite},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double(
           "drive-rate-gain", "Drive rate gain",
           "Proportional controller: linear speed per unit of relative distance error change per second, "
           "0-100 (reacts to the target moving away or closer; damps the approach)",
           0.0, 100.0, ControllerSettings{}.driveRateGain, f);
     },
     getValue<&Settings::controller, &ControllerSettings::driveRateGain>,
     setValue<&Settings::controller, &ControllerSettings::driveRateGain>, refuseNotFinite},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double(
           "latency", "Latency",
           "Zone controller: seconds from a command to the wheels (the robot's delay plus about half the "
           "send period 1/rate). A turn ends this much early and, near the centre, turns are single "
           "decisions each followed by this long without a turn, so the robot does not swing across the "
           "centre. 0: no such rule (the paper's controller)",
           0.0, 2.0, ControllerSettings{}.latency, f);
     },
     getValue<&Settings::controller, &ControllerSettings::latency>,
     setValue<&Settings::controller, &ControllerSettings::latency>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("max-linear", "Maximum linear speed",
                                  "Largest forward/backward speed (fraction of full speed); the zone "
                                  "controller's driving speed",
                                  0.0, 1.0, ControllerSettings{}.maxLinear, f);
     },
     getValue<&Settings::controller, &ControllerSettings::maxLinear>,
     setValue<&Settings::controller, &ControllerSettings::maxLinear>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("max-angular", "Maximum angular speed",
                                  "Largest turn speed (fraction of full wheel speed); the zone "
                                  "controller's turning speed",
                                  0.0, 1.0, ControllerSettings{}.maxAngular, f);
     },
     getValue<&Settings::controller, &ControllerSettings::maxAngular>,
     setValue<&Settings::controller, &ControllerSettings::maxAngular>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("max-linear-accel", "Maximum linear acceleration",
                                  "Proportional controller: largest change of the linear speed "
                                  "per second (0 = unlimited)",
                                  0.0, 1000.0, ControllerSettings{}.maxLinearAccel, f);
     },
     getValue<&Settings::controller, &ControllerSettings::maxLinearAccel>,
     setValue<&Settings::controller, &ControllerSettings::maxLinearAccel>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("max-angular-accel", "Maximum angular acceleration",
                                  "Proportional controller: largest change of the angular "
                                  "speed per second (0 = unlimited)",
                                  0.0, 1000.0, ControllerSettings{}.maxAngularAccel, f);
     },
     getValue<&Settings::controller, &ControllerSettings::maxAngularAccel>,
     setValue<&Settings::controller, &ControllerSettings::maxAngularAccel>},

    // The failsafe, which target to follow and the messages.
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_uint(
           "lost-timeout", "Lost timeout",
           "Milliseconds without a confirmed target, or without any buffer, before the target counts "
           "as lost and the robot stops (or search-turns); without a confirmed target it keeps its drive "
           "for the first half, then stands still, and never keeps its turn",
           1, 600000, static_cast<guint>(std::lround(FailsafeSettings{}.lostTimeout * 1000)), f);
     },
     [](const Settings &s, GValue *v) {
       g_value_set_uint(v, static_cast<guint>(std::lround(s.failsafe.lostTimeout * 1000)));
     },
     [](Settings &s, const GValue *v) { s.failsafe.lostTimeout = g_value_get_uint(v) / 1000.0; }},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double("min-score", "Minimum score",
                                  "A target with a lower score counts as not seen", 0.0, 1.0,
                                  FailsafeSettings{}.minScore, f);
     },
     getValue<&Settings::failsafe, &FailsafeSettings::minScore>,
     setValue<&Settings::failsafe, &FailsafeSettings::minScore>},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_boolean("search-turn", "Search turn",
                                   "After lost-timeout turn slowly towards where the target was last "
                                   "seen instead of standing still",
                                   FailsafeSettings{}.searchTurn, f);
     },
     [](const Settings &s, GValue *v) { g_value_set_boolean(v, s.failsafe.searchTurn); },
     [](Settings &s, const GValue *v) { s.failsafe.searchTurn = g_value_get_boolean(v); }},
    {Apply::Live, kVersioned,
     [](GParamFlags f) {
       return g_param_spec_double(
           "search-speed", "Search speed",
           "Angular speed of the search turn (fraction of full wheel speed); only used with search-turn=true",
           0.0, 1.0, FailsafeSettings{}.searchSpeed, f);
     },
     getValue<&Settings::failsafe, &FailsafeSettings::searchSpeed>,
     setValue<&Settings::failsafe, &FailsafeSettings::searchSpeed>},
    {Apply::Live, false,
     [](GParamFlags f) {
       return g_param_spec_string("roi-type", "ROI type",
                                  "Type of the region-of-interest meta to follow, not empty "
                                  "(\"object\" for cvtracker)",
                                  Settings{}.roiType.c_str(), f);
     },
     getText<&Settings::roiType>, setText<&Settings::roiType>, refuseEmptyRoiType},
    {Apply::Live, false,
     [](GParamFlags f) {
       return g_param_spec_int("target-id", "Target id",
                               "Id of the region of interest to follow, and no other; -1 = choose by lock-on",
                               -1, G_MAXINT, Settings{}.targetId, f);
     },
     getValue<&Settings::targetId>, setValue<&Settings::targetId>},
    {Apply::Live, false,
     [](GParamFlags f) {
       return g_param_spec_enum("lock-on", "Lock on",
                                "With target-id=-1, which region to follow when there is none yet or the "
                                "followed one is lost or gone (never a region seen beside the followed "
                                "one); the choice is kept while its track lives",
                                GST_TYPE_ROBOT_CTL_LOCK_ON, static_cast<gint>(Settings{}.lockOn), f);
     },
     getValue<&Settings::lockOn>, setValue<&Settings::lockOn>},
    {Apply::AtStart, false,
     [](GParamFlags f) {
       return g_param_spec_boolean(
           "post-messages", "Post messages",
           "Post a \"robotctl\" element message for every command sent; read at start",
           Settings{}.postMessages, f);
     },
     getValue<&Settings::postMessages>, setValue<&Settings::postMessages>},
};

}  // namespace

bool drivesGimbal(const Settings &s) {
  return s.protocol == colortrack::Protocol::Mavlink && s.mavlinkMode == colortrack::MavlinkMode::Gimbal;
}

colortrack::ControllerSettings controllerSettings(const Settings &s) {
  colortrack::ControllerSettings controller = s.controller;
  controller.axes = drivesGimbal(s) ? colortrack::ControlAxes::PanTilt : colortrack::ControlAxes::TurnDrive;
  return controller;
}

std::string controllerMismatch(const Settings &s) {
  const colortrack::ControllerSettings c = controllerSettings(s);
  if (colortrack::lawFits(c.kind, c.axes)) return {};
  return "controller=zone cannot drive a gimbal (protocol=mavlink mavlink-mode=gimbal): its commands are one "
         "motion at a time at a fixed speed. Use controller=auto (the default) or controller=proportional";
}

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
         " are ignored: only a serial port named by 'device' uses them, and the "
         "output is 'location' ('" +
         s.location + "')";
}

namespace {

std::string checkControllerValue(const PropertyStore &store, const GValue *v, std::string *) {
  if (!store.running) return {};
  Settings s = store.settings;
  s.controller.kind = static_cast<colortrack::ControllerKind>(g_value_get_enum(v));
  return controllerMismatch(s);
}

}  // namespace

const gstglue::PropertyTable<Settings> &properties() {
  static const gstglue::PropertyTable<Settings> table(kProperties);
  return table;
}

}  // namespace robotctl
