// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's UDP transport (location=udp://HOST:PORT): each command a datagram to a flight controller,
// mavlink-router or a ground station, through GIO's sockets. No GStreamer, like the other ports.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "colortrack/robot_port.hpp"
#include "colortrack/status.hpp"

typedef struct _GSocket GSocket;

namespace robotctl {

constexpr const char *kUdpScheme = "udp://";

// True when `location` names a UDP destination (it starts with udp://).
bool isUdpLocation(const std::string &location);

// Whether `location` can be used as written, or why not: a valid udp://HOST:PORT, or a path. A
// string that starts like a URL or a drive letter (looksLikeUrl: "udp:127.0.0.1:14550", "C:\\robot.txt")
// but is not a valid udp:// one is refused rather than taken as a file name, which would quietly write the
// robot's commands into a new file; a file whose name really has a colon is written "./udp:x".
colortrack::Status checkLocation(const std::string &location);

// HOST and PORT of "udp://HOST:PORT" (HOST a name, an IPv4 address or an IPv6 address in brackets; PORT
// 1-65535), or why not. Resolves nothing.
struct UdpEndpoint {
  std::string host;
  std::uint16_t port = 0;
};
colortrack::Result<UdpEndpoint> parseUdpLocation(const std::string &location);

// Sends from an ephemeral local port (nothing is bound, so no local port can be in use) to the first address
// the host resolves to. UDP is fire-and-forget, as MAVLink over UDP expects: whether anything listens there
// is not known (a flight controller or mavlink-router that starts later simply begins to hear us; our
// heartbeat is how it knows we are there). What is known is checked: a host that does not resolve or that
// no route leads to fails the open, and a send that fails (the route went away) fails the write (a
// warning, then reopen with back-off, like an unplugged serial adapter). Non-blocking: a full send buffer
// waits at most the write's timeout, then the datagram is dropped (Busy).
class UdpPort : public Port {
 public:
  explicit UdpPort(std::string location) : location_(std::move(location)) {}
  ~UdpPort() override { close(); }

  // Resolves the host (blocking: at start, or in the writer thread on a reopen; never the streaming
  // thread).
  colortrack::Status open() override;
  void close() override;
  bool isOpen() const override { return socket_ != nullptr; }
  WriteResult write(const std::vector<std::uint8_t> &bytes, int timeoutMs, std::size_t &written,
                    std::string &why) override;
  // One datagram the destination sent back (only it: the socket is connected to it).
  bool receive(std::uint8_t *buffer, std::size_t capacity, std::size_t &received, std::string &why) override;
  std::string describe() const override { return "'" + location_ + "' (property 'location')"; }

 private:
  bool openWithReason(std::string &why);

  std::string location_;
  GSocket *socket_ = nullptr;  // connected to the destination
};

}  // namespace robotctl
