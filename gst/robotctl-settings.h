// robotctl's settings, what its properties say, and the table that declares those properties.
#pragma once

#include <string>

#include "colortrack/controller.hpp"
#include "colortrack/target_lock.hpp"
#include "gstrobotctl.h"
#include "property-table.h"

namespace robotctl {

// Copied under the object lock by start() and by the streaming thread; never touched by the writer thread
// (it gets its own copy at start).
struct Settings {
  std::string device, location;
  guint baudRate = 9600;
  gint dataBits = 8;
  GstRobotCtlParity parity = GST_ROBOT_CTL_PARITY_NONE;
  gint stopBits = 1;
  GstRobotCtlFlowControl flowControl = GST_ROBOT_CTL_FLOW_CONTROL_NONE;
  GstRobotCtlProtocol protocol = GST_ROBOT_CTL_PROTOCOL_ZONE_CHAR;
  std::string zoneChars = "FBLRS";  // checked at start
  gint outputScale = 255;
  gdouble rate = 10.0;
  // A change of these (a versioned property) bumps the store's version: the controller takes it.
  colortrack::ControllerSettings controller;
  colortrack::FailsafeSettings failsafe;
  std::string roiType = "colortrack";
  gint targetId = -1;
  colortrack::LockOn lockOn = colortrack::LockOn::FirstConfirmed;
  bool postMessages = false;
};

using PropertyStore = gstglue::PropertyStore<Settings>;

// In the order gst-inspect-1.0 lists them.
const gstglue::PropertyTable<Settings> &properties();

}  // namespace robotctl
