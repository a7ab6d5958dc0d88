// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/port_choice.hpp"

#include "colortrack/udp_port.hpp"

namespace robotctl {

PortKind portKind(const std::string &device, const std::string &location) {
  if (!device.empty()) return PortKind::Serial;
  return isUdpLocation(location) ? PortKind::Udp : PortKind::File;
}

std::unique_ptr<Port> makePort(const std::string &device, const SerialConfig &serial,
                               const std::string &location) {
  switch (portKind(device, location)) {
    case PortKind::Serial:
      return std::make_unique<SerialPort>(serial);
    case PortKind::Udp:
      return std::make_unique<UdpPort>(location);
    case PortKind::File:
      break;
  }
  return std::make_unique<FilePort>(location);
}

}  // namespace robotctl
