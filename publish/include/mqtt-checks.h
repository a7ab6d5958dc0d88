// SPDX-License-Identifier: LGPL-2.1-or-later
// What MQTT and Paho accept, checked before anything is sent: the broker's address, topics, client ids and
// MQTT's strings; and the address as it may be shown. No GStreamer here (GLib checks UTF-8).
#pragma once

#include <string>

#include "colortrack/status.hpp"

namespace trackpublish {

// An address Paho accepts, or why not: SCHEME://HOST:PORT (tcp, ssl, mqtt, mqtts), or HOST:PORT, which
// means tcp:// as in DL Streamer's gvametapublish.
colortrack::Status checkAddress(const std::string &address);
// The address as Paho takes it: HOST:PORT becomes tcp://HOST:PORT, anything else is kept.
std::string brokerUri(const std::string &address);
// A topic a publisher may use (UTF-8 of at most 65,535 bytes, not empty, no NUL, no wildcards, not the
// broker's own $...), or why not.
colortrack::Status checkTopic(const std::string &topic);
// Whether `text` is an MQTT "UTF-8 encoded string" (at most 65,535 bytes of UTF-8, no NUL), or why not,
// naming it as `what`.
colortrack::Status checkMqttString(const std::string &text, const char *what);
// A client id MQTT can carry (UTF-8 of at most 65,535 bytes, no NUL), or why not.
colortrack::Status checkClientId(const std::string &clientId);
// Whether the address's scheme is a TLS one (ssl://, mqtts://).
bool usesTls(const std::string &address);
// The address as it may be shown: a password in it (tcp://user:password@host:port) becomes ***.
std::string redactedAddress(const std::string &address);

}  // namespace trackpublish
