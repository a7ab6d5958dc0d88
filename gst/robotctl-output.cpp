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

Parity toParity(GstRobotCtlParity parity) {
  switch (parity) {
    case GST_ROBOT_CTL_PARITY_ODD:
      return Parity::Odd;
    case GST_ROBOT_CTL_PARITY_EVEN:
      return Parity::Even;
    case GST_ROBOT_CTL_PARITY_MARK:
      return Parity::Mark;
    case GST_ROBOT_CTL_PARITY_SPACE:
      return Parity::Space;
    case GST_ROBOT_CTL_PARITY_NONE:
      break;
  }
  return Parity::None;
}

FlowControl toFlowControl(GstRobotCtlFlowControl flow) {
  switch (flow) {
    case GST_ROBOT_CTL_FLOW_CONTROL_XONXOFF:
      return FlowControl::XonXoff;
    case GST_ROBOT_CTL_FLOW_CONTROL_RTSCTS:
      return FlowControl::RtsCts;
    case GST_ROBOT_CTL_FLOW_CONTROL_DTRDSR:
      return FlowControl::DtrDsr;
    case GST_ROBOT_CTL_FLOW_CONTROL_NONE:
      break;
  }
  return FlowControl::None;
}

colortrack::MavlinkMode toMavlinkMode(GstRobotCtlMavlinkMode mode) {
  switch (mode) {
    case GST_ROBOT_CTL_MAVLINK_MODE_FOLLOW:
      return colortrack::MavlinkMode::Follow;
    case GST_ROBOT_CTL_MAVLINK_MODE_GIMBAL:
      break;
  }
  return colortrack::MavlinkMode::Gimbal;
}

}  // namespace

bool isStandardBaudRate(guint rate) {
  return std::find(std::begin(kStandardBaudRates), std::end(kStandardBaudRates), rate) !=
         std::end(kStandardBaudRates);
}

SerialConfig toSerialConfig(const Settings &s) {
  return SerialConfig{s.device,   s.baudRate,         s.dataBits,
                      s.stopBits, toParity(s.parity), toFlowControl(s.flowControl)};
}

// No default: -Wswitch names a protocol added to the property but not mapped here.
colortrack::Protocol toProtocol(GstRobotCtlProtocol protocol) {
  switch (protocol) {
    case GST_ROBOT_CTL_PROTOCOL_TEXT:
      return colortrack::Protocol::Text;
    case GST_ROBOT_CTL_PROTOCOL_BINARY:
      return colortrack::Protocol::Binary;
    case GST_ROBOT_CTL_PROTOCOL_MAVLINK:
      return colortrack::Protocol::Mavlink;
    case GST_ROBOT_CTL_PROTOCOL_ZONE_CHAR:
      break;
  }
  return colortrack::Protocol::ZoneChar;
}

colortrack::MavlinkSettings toMavlinkSettings(const Settings &s) {
  colortrack::MavlinkSettings m;
  m.mode = toMavlinkMode(s.mavlinkMode);
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
