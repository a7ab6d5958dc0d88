// SPDX-License-Identifier: LGPL-2.1-or-later
// Which port a robot's settings name, decided in one place: a serial device when one is given, else a UDP
// destination (udp://HOST:PORT), else a file, FIFO, pty or stdout ("-").
#pragma once

#include <memory>
#include <string>

#include "colortrack/robot_port.hpp"

namespace robotctl {

enum class PortKind { Serial, Udp, File };

PortKind portKind(const std::string &device, const std::string &location);

// The port of that kind, not yet opened.
std::unique_ptr<Port> makePort(const std::string &device, const SerialConfig &serial,
                               const std::string &location);

}  // namespace robotctl
