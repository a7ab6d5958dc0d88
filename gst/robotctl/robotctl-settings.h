// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's settings (the property values), and the rows of its table for where commands go and which target
// to follow with their start rules (the table itself: robotctl-properties.h).
#pragma once

#include <string>
#include <vector>

#include "colortrack/controller.hpp"
#include "colortrack/protocol.hpp"
#include "colortrack/target_lock.hpp"
#include "robotctl-enums.h"
#include "element-core.h"
#include "colortrack/robot_port.hpp"

namespace robotctl {

// Copied under the object lock by start() and by the streaming thread; never touched by the writer thread
// (it gets its own copy at start).
struct Settings {
  // What a change of a property marks (PropertyDef::changes).
  enum class Change : unsigned {
    Controller,  // `controller` or `failsafe`: the controller takes them from the next buffer
  };

  std::string device, location;
  guint baudRate = 9600;
  gint dataBits = 8;
  Parity parity = Parity::None;
  gint stopBits = 1;
  FlowControl flowControl = FlowControl::None;
  colortrack::Protocol protocol = colortrack::Protocol::ZoneChar;
  std::string zoneChars = "FBLRS";  // checked at start
  gint outputScale = 255;
  // MAVLink (read at start): ours and the receiver's ids, what the commands drive, the camera's field of
  // view, the bounds of every command.
  colortrack::MavlinkMode mavlinkMode = colortrack::MavlinkMode::Gimbal;
  guint systemId = 1, componentId = 191;  // an onboard computer: MAV_COMP_ID_ONBOARD_COMPUTER
  guint targetSystem = 1, targetComponent = 1;
  gdouble hfov = 60.0;         // degrees
  gdouble maxRate = 60.0;      // deg/s, every pitch and yaw rate sent
  gdouble maxSpeed = 2.0;      // m/s, every forward velocity sent
  guint linkTimeoutMs = 3000;  // without the vehicle's HEARTBEAT (0: off); MAVLink's usual 3 s
  gdouble rate = 10.0;
  // A change of these marks Change::Controller.
  colortrack::ControllerSettings controller;
  colortrack::FailsafeSettings failsafe;
  std::string roiType = "colortrack";
  gint targetId = -1;
  colortrack::LockOn lockOn = colortrack::LockOn::FirstConfirmed;
  bool postMessages = false;
  bool hold = false;  // a person's STOP: only stop is sent until released
};

class CommandWriter;

// What the threads share besides the values: the writer of a started element (null otherwise), so that
// `hold` acts at once rather than from the next buffer, which may never come.
struct Shared {
  CommandWriter *writer = nullptr;
};

using PropertyStore = gstglue::PropertyStore<Settings, Shared>;
using ElementCore = gstglue::ElementCore<Settings, Shared>;
using Row = gstglue::PropertyDef<Settings, Shared>;

// The MAVLink commands drive a gimbal: the controller pans and tilts (and is proportional).
bool drivesGimbal(const Settings &settings);
// The controller's settings as the protocol needs them (a gimbal: PanTilt).
colortrack::ControllerSettings controllerSettings(const Settings &settings);
// A rate a serial port can be set to portably (termios' Bxxx constants).
bool isStandardBaudRate(guint rate);

// The rows of robotctl's table for where commands go and how (read at start), and for which target to follow;
// and the start rules between them (robotctl-properties.cpp assembles the table).
std::vector<Row> linkRows();
std::vector<Row> targetRows();
std::vector<gstglue::StartRule<Settings>> linkRules();

}  // namespace robotctl
