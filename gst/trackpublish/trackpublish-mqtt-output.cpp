// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's MQTT output (address, topic, ...): MqttPublisher's queue and thread, its news as the
// element's warnings, and the settings checked before connecting.
#include <unistd.h>

#include <atomic>
#include <utility>

#include "mqtt-publisher.h"
#include "trackpublish-output.h"

#define GST_CAT_DEFAULT gst_track_publish_debug

namespace trackpublish {

namespace {

using std::chrono::milliseconds;

std::string replaceAll(std::string text, const std::string &what, const std::string &with) {
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + with.size()))
    text.replace(at, what.size(), with);
  return text;
}

// "Cannot reach MQTT broker ADDRESS (the properties at fault): why", or "MQTT broker ADDRESS refused the
// connection (...)" when it answered: what a failed connection says, as a warning or an error.
std::string describeFailure(const std::string &address, const ConnectFailure &failure) {
  const std::string shown = gstglue::validUtf8(address);
  switch (failure.fault) {
    case ConnectFault::Credentials:
      return "MQTT broker " + shown +
             " refused the connection (properties 'username' and 'password'): " + failure.why;
    case ConnectFault::ClientId:
      return "MQTT broker " + shown + " refused the connection (property 'client-id'): " + failure.why;
    case ConnectFault::Broker:
      return "MQTT broker " + shown +
             " refused the connection (the broker at property 'address'): " + failure.why;
    case ConnectFault::Unreachable:
      break;
  }
  // Over TLS a CA that does not sign the broker's certificate, or a certificate that does not match its
  // key, fails the same way as a wrong address: the message names every property that may be at fault.
  const char *suspects = usesTls(address) ? "property 'address', or the TLS settings 'tls-ca-file', "
                                            "'tls-cert-file', 'tls-key-file', 'tls-verify'"
                                          : "property 'address'";
  return "Cannot reach MQTT broker " + shown + " (" + suspects + "): " + failure.why;
}

// The publisher's news as the element's warnings and log.
class ElementMqttListener : public MqttListener {
 public:
  ElementMqttListener(GstElement *element, guint maxQueued) : element_(element), maxQueued_(maxQueued) {}

  void connected(const std::string &address, bool again) override {
    GST_INFO_OBJECT(element_, "%s MQTT broker %s", again ? "reconnected to" : "connected to",
                    address.c_str());
  }
  void connectFailed(const std::string &address, const ConnectFailure &failure, bool first,
                     milliseconds retryIn) override {
    GST_DEBUG_OBJECT(element_, "cannot connect to %s: %s; retrying in %lld ms", address.c_str(),
                     failure.why.c_str(), static_cast<long long>(retryIn.count()));
    if (!first) return;
    GST_ELEMENT_WARNING(element_, RESOURCE, OPEN_WRITE,
                        ("%s. Retrying; documents are queued (up to max-queued=%u).",
                         describeFailure(address, failure).c_str(), maxQueued_),
                        (nullptr));
  }
  void connectionLost(const std::string &address, const std::string &why, std::size_t queued,
                      bool first) override {
    GST_DEBUG_OBJECT(element_, "lost %s: %s", address.c_str(), why.c_str());
    if (!first) return;
    GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                        ("Lost the connection to MQTT broker %s: %s. Reconnecting; %zu documents queued.",
                         gstglue::validUtf8(address).c_str(), why.c_str(), queued),
                        (nullptr));
  }
  void dropped(std::uint64_t total, std::size_t maxQueued) override {
    // One warning a second at most: the count says how many so far.
    const gint64 now = g_get_monotonic_time();
    gint64 last = lastDropWarning_.load();
    if (total > 1 && now - last < G_USEC_PER_SEC) return;
    if (!lastDropWarning_.compare_exchange_strong(last, now)) return;
    GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                        ("MQTT queue full (max-queued=%zu): %" G_GUINT64_FORMAT
                         " documents dropped so far, the oldest first.",
                         maxQueued, total),
                        (nullptr));
  }

 private:
  GstElement *element_;
  const guint maxQueued_;
  std::atomic<gint64> lastDropWarning_{0};
};

// What MQTT will carry, checked before connecting: the topic after {source} is put in, the client id, and
// TLS files only where TLS is used (with tcp:// they would be ignored, and the link not encrypted).
bool checkMqttSettings(GstElement *self, const Settings &s, const MqttConfig &config,
                       const std::string &topic, const std::string &source) {
  const colortrack::Status topicCheck = checkTopic(topic);
  if (!topicCheck) {
    // Text too long to show is cut; the check's message gives the topic's length.
    const auto shown = [](const std::string &text) {
      return text.size() > 200 ? text.substr(0, 200) + "..." : text;
    };
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Invalid topic '%s' (property 'topic', with source '%s'): %s.",
                       gstglue::validUtf8(shown(topic)).c_str(), gstglue::validUtf8(shown(source)).c_str(),
                       topicCheck.message().c_str()),
                      (nullptr));
    return false;
  }
  const colortrack::Status clientIdCheck = checkClientId(config.clientId);
  if (!clientIdCheck) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Invalid property 'client-id': %s.", clientIdCheck.message().c_str()), (nullptr));
    return false;
  }
  const bool tls = usesTls(s.address);
  for (const auto &[property, file] :
       {std::pair<const char *, const std::string &>{"tls-ca-file", s.tlsCaFile},
        {"tls-cert-file", s.tlsCertFile},
        {"tls-key-file", s.tlsKeyFile}}) {
    if (tls || file.empty()) continue;
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("TLS file '%s' (property '%s') is set but address '%s' does not use TLS: use "
                       "ssl://HOST:PORT, or unset '%s'.",
                       gstglue::validUtf8(file).c_str(), property,
                       gstglue::validUtf8(redactedAddress(s.address)).c_str(), property),
                      (nullptr));
    return false;
  }
  // A private key is only used with its certificate (a certificate may hold its key itself, without
  // tls-key-file).
  if (tls && !s.tlsKeyFile.empty() && s.tlsCertFile.empty()) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Property 'tls-key-file' is set without 'tls-cert-file': a private key is used only "
                       "with its client certificate."),
                      (nullptr));
    return false;
  }
  if (!tls && !s.tlsVerify) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("TLS verification is off (property 'tls-verify') but address '%s' does not use TLS: "
                       "use ssl://HOST:PORT, "
                       "or leave 'tls-verify' alone.",
                       gstglue::validUtf8(redactedAddress(s.address)).c_str()),
                      (nullptr));
    return false;
  }
  // MQTT allows empty levels, but "a//b" is more often a typo than a design: said, not refused.
  if (topic.find("//") != std::string::npos || topic.front() == '/' || topic.back() == '/')
    GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS,
                        ("Topic '%s' (property 'topic') has an empty level (a '/' at an end, or '//'): "
                         "subscribers must use the same empty level.",
                         gstglue::validUtf8(topic).c_str()),
                        (nullptr));
  // MQTT 3.1.1 (3.1.2.9): a password is only sent with a user name.
  if (!s.password.empty() && s.username.empty()) {
    GST_ELEMENT_ERROR(
        self, RESOURCE, SETTINGS,
        ("Property 'password' is set without 'username': MQTT sends a password only with a user "
         "name."),
        (nullptr));
    return false;
  }
  return true;
}

// The default client id: colortrack-<source>-<process id>, the source's characters outside [A-Za-z0-9_-]
// replaced by '_' (some brokers refuse a client id with other characters, and the refusal would be blamed on
// the address).
std::string defaultClientId(const std::string &source) {
  std::string safe = source;
  for (char &c : safe)
    if (!g_ascii_isalnum(c) && c != '_' && c != '-') c = '_';
  return "colortrack-" + safe + "-" + std::to_string(getpid());
}

// What was lost, said once at the end of the stream (EOS) or, in the log, at stop.
void reportLosses(GstElement *self, MqttPublisher &mqtt, const char *when, bool post) {
  const std::uint64_t dropped = mqtt.droppedCount();
  const std::size_t undelivered = mqtt.queued();
  if (dropped == 0 && undelivered == 0) return;
  const std::string text = "MQTT: " + std::to_string(dropped) + " documents dropped in all (queue full), " +
                           std::to_string(undelivered) + " not delivered " + when + "; " +
                           std::to_string(mqtt.delivered()) + " delivered.";
  if (post)
    GST_ELEMENT_WARNING(self, RESOURCE, WRITE, ("%s", text.c_str()), (nullptr));
  else
    GST_WARNING_OBJECT(self, "%s", text.c_str());
}

class MqttOutput : public DocumentOutput {
 public:
  MqttOutput(GstElement *element, const MqttConfig &config, std::string topic, guint maxQueued)
      : element_(element),
        topic_(std::move(topic)),
        listener_(element, maxQueued),
        publisher_(config, listener_) {}
  MqttPublisher &publisher() { return publisher_; }

  GstFlowReturn publish(const std::string &document) override {
    publisher_.publish(topic_, document);
    return GST_FLOW_OK;
  }
  void drainAtEos(milliseconds drain) override {
    publisher_.waitDelivered(drain);
    reportLosses(element_, publisher_, "at EOS after drain-timeout", true);
  }
  void close(milliseconds drain) override {
    publisher_.stop(drain);
    // The bus is flushing by now: the log is where this can still be read.
    reportLosses(element_, publisher_, "when stopping", false);
  }

 private:
  GstElement *element_;
  std::string topic_;
  ElementMqttListener listener_;  // outlives the publisher
  MqttPublisher publisher_;
};

}  // namespace

std::unique_ptr<DocumentOutput> openMqttOutput(const OutputContext &c) {
  const Settings &s = c.settings;
  MqttConfig config;
  config.address = brokerUri(s.address);
  config.clientId = s.clientId.empty() ? defaultClientId(c.source) : s.clientId;
  config.username = s.username;
  config.password = s.password;
  config.caFile = s.tlsCaFile;
  config.certFile = s.tlsCertFile;
  config.keyFile = s.tlsKeyFile;
  config.verifyServer = s.tlsVerify;
  config.qos = s.qos;
  config.maxQueued = s.maxQueued;
  const std::string topic = replaceAll(s.topic, "{source}", c.source);
  if (!checkMqttSettings(c.element, s, config, topic, c.source)) return nullptr;
  auto output = std::make_unique<MqttOutput>(c.element, config, topic, s.maxQueued);
  if (const colortrack::Status started = output->publisher().start(); !started) {
    GST_ELEMENT_ERROR(c.element, RESOURCE, SETTINGS,
                      ("Invalid MQTT address '%s' (property 'address'): %s.",
                       gstglue::validUtf8(redactedAddress(s.address)).c_str(), started.message().c_str()),
                      (nullptr));
    return nullptr;
  }
  // The client's own connect timeout is 5 s; a little more so its answer arrives first.
  ConnectFailure failure;
  if (s.failOnConnect && !output->publisher().waitFirstAttempt(milliseconds(6000), failure)) {
    GST_ELEMENT_ERROR(
        c.element, RESOURCE, OPEN_WRITE,
        ("%s (fail-on-connect=true).", describeFailure(redactedAddress(s.address), failure).c_str()),
        (nullptr));
    output->publisher().stop(milliseconds(0));
    return nullptr;
  }
  return output;
}

}  // namespace trackpublish
