// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/udp_port.hpp"

#include <gio/gio.h>

#include "colortrack/output_file.hpp"

#include <cstdlib>

namespace robotctl {

namespace {

bool fail(GError *error, std::string &why) {
  why = error ? error->message : "unknown error";
  g_clear_error(&error);
  return false;
}

// Commands go to one robot: a multicast group would hand them to every listener on the network.
bool isMulticast(GInetAddress *address) {
  return g_inet_address_get_is_multicast(address);
}

const char *const kMulticastRefused =
    "is a multicast address: every host in the group would take the robot's commands; give the robot's own "
    "address";

}  // namespace

bool isUdpLocation(const std::string &location) {
  return location.rfind(kUdpScheme, 0) == 0;
}

colortrack::Status checkLocation(const std::string &location) {
  if (isUdpLocation(location)) return parseUdpLocation(location).status();
  if (!colortrack::looksLikeUrl(location)) return {};
  return colortrack::Status::failure(
      "it looks like a URL (or a drive letter), but the only address robotctl sends to is udp://HOST:PORT "
      "(e.g. udp://127.0.0.1:14550); a file whose name has a colon is written ./" +
      location);
}

colortrack::Result<UdpEndpoint> parseUdpLocation(const std::string &location) {
  const std::string rest = location.substr(std::string(kUdpScheme).size());
  UdpEndpoint endpoint;
  std::string port;
  if (!rest.empty() && rest[0] == '[') {
    const std::size_t close = rest.find(']');
    if (close == std::string::npos || close + 1 >= rest.size() || rest[close + 1] != ':') {
      return colortrack::Status::failure("expected udp://[IPV6-ADDRESS]:PORT");
    }
    endpoint.host = rest.substr(1, close - 1);
    port = rest.substr(close + 2);
  } else {
    const std::size_t colon = rest.rfind(':');
    if (colon == std::string::npos) {
      return colortrack::Status::failure("expected udp://HOST:PORT (e.g. udp://127.0.0.1:14550): no port");
    }
    endpoint.host = rest.substr(0, colon);
    port = rest.substr(colon + 1);
    if (endpoint.host.find(':') != std::string::npos) {
      return colortrack::Status::failure("an IPv6 address goes in brackets: udp://[ADDRESS]:PORT");
    }
  }
  if (endpoint.host.empty()) {
    return colortrack::Status::failure("expected udp://HOST:PORT: no host");
  }
  if (port.empty() || port.size() > 5 || port.find_first_not_of("0123456789") != std::string::npos ||
      std::atoi(port.c_str()) < 1 || std::atoi(port.c_str()) > 65535) {
    return colortrack::Status::failure("the port '" + port + "' is not a number from 1 to 65535");
  }
  endpoint.port = static_cast<std::uint16_t>(std::atoi(port.c_str()));
  if (GInetAddress *literal = g_inet_address_new_from_string(endpoint.host.c_str())) {
    const bool multicast = isMulticast(literal);
    g_object_unref(literal);
    if (multicast) {
      return colortrack::Status::failure("'" + endpoint.host + "' " + kMulticastRefused);
    }
  }
  return endpoint;
}

colortrack::Status UdpPort::open() {
  std::string why;
  return openWithReason(why) ? colortrack::Status() : colortrack::Status::failure(why);
}

bool UdpPort::openWithReason(std::string &why) {
  const colortrack::Result<UdpEndpoint> endpoint = parseUdpLocation(location_);
  if (!endpoint) {
    why = endpoint.error();
    return false;
  }
  GError *error = nullptr;
  GSocketConnectable *connectable = g_network_address_new(endpoint->host.c_str(), endpoint->port);
  GSocketAddressEnumerator *addresses = g_socket_connectable_enumerate(connectable);
  GSocketAddress *address = g_socket_address_enumerator_next(addresses, nullptr, &error);
  g_object_unref(addresses);
  g_object_unref(connectable);
  if (!address) {
    if (!error) why = "the host '" + endpoint->host + "' has no address";
    return error ? fail(error, why) : false;
  }
  // A host name may resolve to a group too.
  if (G_IS_INET_SOCKET_ADDRESS(address) &&
      isMulticast(g_inet_socket_address_get_address(G_INET_SOCKET_ADDRESS(address)))) {
    why = "the host '" + endpoint->host + "' " + kMulticastRefused;
    g_object_unref(address);
    return false;
  }
  // A connected socket: the kernel finds the route now (a host nothing leads to is an error here, not
  // datagrams silently dropped later), and a peer that is not listening (ICMP port unreachable) makes the
  // next send fail, so the writer sees the link go and sends stop first when it is back.
  GSocket *socket = g_socket_new(g_socket_address_get_family(address), G_SOCKET_TYPE_DATAGRAM,
                                 G_SOCKET_PROTOCOL_UDP, &error);
  const bool connected = socket && g_socket_connect(socket, address, nullptr, &error);
  g_object_unref(address);
  if (!connected) {
    if (socket) g_object_unref(socket);
    return fail(error, why);
  }
  g_socket_set_blocking(socket, FALSE);
  socket_ = socket;
  return true;
}

void UdpPort::close() {
  if (socket_) g_object_unref(socket_);
  socket_ = nullptr;
}

WriteResult UdpPort::write(const std::vector<std::uint8_t> &bytes, int timeoutMs, std::size_t &written,
                           std::string &why) {
  written = 0;
  const gchar *data = reinterpret_cast<const gchar *>(bytes.data());
  GError *error = nullptr;
  gssize sent = g_socket_send(socket_, data, bytes.size(), nullptr, &error);
  if (sent < 0 && g_error_matches(error, G_IO_ERROR, G_IO_ERROR_WOULD_BLOCK)) {
    // The send buffer is full: wait for room, at most the write's timeout.
    g_clear_error(&error);
    if (!g_socket_condition_timed_wait(socket_, G_IO_OUT, static_cast<gint64>(timeoutMs) * 1000, nullptr,
                                       nullptr))
      return WriteResult::Busy;
    sent = g_socket_send(socket_, data, bytes.size(), nullptr, &error);
    if (sent < 0 && g_error_matches(error, G_IO_ERROR, G_IO_ERROR_WOULD_BLOCK)) {
      g_clear_error(&error);
      return WriteResult::Busy;
    }
  }
  if (sent < 0) {
    fail(error, why);
    return WriteResult::Failed;
  }
  // A datagram goes whole or not at all.
  written = static_cast<std::size_t>(sent);
  return WriteResult::Written;
}

bool UdpPort::receive(std::uint8_t *buffer, std::size_t capacity, std::size_t &received, std::string &why) {
  received = 0;
  GError *error = nullptr;
  const gssize n = g_socket_receive(socket_, reinterpret_cast<gchar *>(buffer), capacity, nullptr, &error);
  if (n >= 0) {
    received = static_cast<std::size_t>(n);
    return true;
  }
  if (g_error_matches(error, G_IO_ERROR, G_IO_ERROR_WOULD_BLOCK)) {
    g_clear_error(&error);
    return true;
  }
  return fail(error, why);
}

}  // namespace robotctl
