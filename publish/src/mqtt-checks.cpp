// SPDX-License-Identifier: LGPL-2.1-or-later
#include "mqtt-checks.h"

#include <glib.h>

#include <algorithm>
#include <cstdlib>

namespace trackpublish {

std::string brokerUri(const std::string &address) {
  return address.find("://") == std::string::npos ? "tcp://" + address : address;
}

colortrack::Status checkAddress(const std::string &address) {
  const std::string uri = brokerUri(address);
  const std::size_t scheme = uri.find("://");
  const std::string kind = uri.substr(0, scheme);
  if (kind != "tcp" && kind != "ssl" && kind != "mqtt" && kind != "mqtts")
    return colortrack::Status::failure("unknown scheme '" + kind +
                                       "://' (use tcp:// or ssl://, or HOST:PORT for tcp://)");
  const std::string rest = uri.substr(scheme + 3);
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string::npos || colon == 0)
    return colortrack::Status::failure(
        "it needs a host and a port: HOST:PORT, tcp://HOST:PORT or ssl://HOST:PORT");
  // Not a host: what a typo of the scheme leaves ("tcp:/host:1883" read as HOST:PORT).
  // (Shown from after a user:password@, which must not appear in a message.)
  const std::size_t at = rest.rfind('@', colon);
  const std::size_t hostFrom = at == std::string::npos ? 0 : at + 1;
  if (rest.find('/') != std::string::npos)
    return colortrack::Status::failure("'" + rest.substr(hostFrom, colon - std::min(colon, hostFrom)) +
                                       "' is not a host");
  const std::string port = rest.substr(colon + 1);
  char *end = nullptr;
  const long number = std::strtol(port.c_str(), &end, 10);
  if (port.empty() || *end != '\0' || number < 1 || number > 65535)
    return colortrack::Status::failure("the port '" + port + "' is not a number from 1 to 65535");
  return {};
}

// MQTT's "UTF-8 encoded string": at most 65,535 bytes, well-formed UTF-8, no U+0000 (MQTT 3.1.1, 1.5.3).
colortrack::Status checkMqttString(const std::string &text, const char *what) {
  if (text.size() > 65535)
    return colortrack::Status::failure(std::string(what) + " is " + std::to_string(text.size()) +
                                       " bytes; MQTT allows at most 65535");
  if (text.find('\0') != std::string::npos)
    return colortrack::Status::failure(std::string(what) + " must not contain NUL");
  if (!g_utf8_validate(text.data(), static_cast<gssize>(text.size()), nullptr))
    return colortrack::Status::failure(std::string(what) + " is not valid UTF-8");
  return {};
}

colortrack::Status checkTopic(const std::string &topic) {
  if (topic.empty()) return colortrack::Status::failure("a topic must not be empty");
  if (topic.find_first_not_of(' ') == std::string::npos)
    return colortrack::Status::failure("a topic of only spaces is surely a mistake");
  if (colortrack::Status bad = checkMqttString(topic, "the topic"); !bad) return bad;
  if (topic.find_first_of("+#") != std::string::npos)
    return colortrack::Status::failure("a topic to publish to must not contain the wildcards + or #");
  // MQTT 3.1.1, 1.5.3: control characters should not be in a topic, and brokers (mosquitto) drop the
  // connection of a client that publishes one; that would show only as a lost connection.
  for (const unsigned char c : topic)
    if (c < 0x20 || c == 0x7F)
      return colortrack::Status::failure(
          "a topic must not contain control characters (a newline, a tab, ...)");
  // Brokers keep topics starting with $ ($SYS/...) for themselves and refuse publishes to them silently.
  if (topic[0] == '$')
    return colortrack::Status::failure("topics starting with $ belong to the broker ($SYS/...)");
  return {};
}

bool usesTls(const std::string &address) {
  return address.rfind("ssl://", 0) == 0 || address.rfind("mqtts://", 0) == 0;
}

colortrack::Status checkClientId(const std::string &clientId) {
  return checkMqttString(clientId, "the client id");
}

std::string redactedAddress(const std::string &address) {
  const std::size_t scheme = address.find("://");
  const std::size_t hostStart = scheme == std::string::npos ? 0 : scheme + 3;
  const std::size_t at = address.find('@', hostStart);
  if (at == std::string::npos) return address;
  const std::size_t colon = address.find(':', hostStart);
  const std::size_t userEnd = colon != std::string::npos && colon < at ? colon : at;
  return address.substr(0, userEnd) + (userEnd < at ? ":***" : "") + address.substr(at);
}

}  // namespace trackpublish
