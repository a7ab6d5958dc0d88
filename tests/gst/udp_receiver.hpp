// SPDX-License-Identifier: LGPL-2.1-or-later
// A UDP socket on loopback for the MAVLink tests: robotctl sends to its port (location=udp://127.0.0.1:PORT)
// and the test takes the datagrams with their arrival times.
#pragma once

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "node_mavlink.hpp"

namespace colortrack::gst_test_util {

class UdpReceiver {
 public:
  // Bound to `port` of 127.0.0.1 (0: an ephemeral one); non-blocking.
  explicit UdpReceiver(int port = 0) {
    fd_ = socket(AF_INET, SOCK_DGRAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    socklen_t length = sizeof address;
    if (fd_ >= 0 && bind(fd_, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0 &&
        getsockname(fd_, reinterpret_cast<sockaddr *>(&address), &length) == 0)
      port_ = ntohs(address.sin_port);
  }
  ~UdpReceiver() {
    if (fd_ >= 0) close(fd_);
  }
  UdpReceiver(const UdpReceiver &) = delete;
  UdpReceiver &operator=(const UdpReceiver &) = delete;

  int port() const { return port_; }  // 0: the socket could not be made
  std::string location() const { return "udp://127.0.0.1:" + std::to_string(port_); }

  // The datagrams waiting now, each stamped with the time it was taken (s, steady clock).
  std::vector<node_mavlink::Datagram> drain() {
    std::vector<node_mavlink::Datagram> datagrams;
    std::uint8_t buffer[2048];
    ssize_t n;
    socklen_t length = sizeof sender_;
    while ((n = recvfrom(fd_, buffer, sizeof buffer, 0, reinterpret_cast<sockaddr *>(&sender_), &length)) >
           0) {
      datagrams.push_back({now(), std::vector<std::uint8_t>(buffer, buffer + n)});
      length = sizeof sender_;
    }
    return datagrams;
  }
  // Sends `bytes` back to whoever sent the last datagram drain() took (as a flight controller answers);
  // false before anything came.
  bool reply(const std::vector<std::uint8_t> &bytes) const {
    if (sender_.sin_port == 0) return false;
    return sendto(fd_, bytes.data(), bytes.size(), 0, reinterpret_cast<const sockaddr *>(&sender_),
                  sizeof sender_) == static_cast<ssize_t>(bytes.size());
  }

  static double now() {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }

 private:
  int fd_ = -1;
  int port_ = 0;
  sockaddr_in sender_{};
};

}  // namespace colortrack::gst_test_util
