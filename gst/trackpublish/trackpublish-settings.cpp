// SPDX-License-Identifier: LGPL-2.1-or-later
#include "trackpublish-settings.h"

#include "mqtt-publisher.h"
#include <vector>

#include "colortrack/regular_file.hpp"
#include "colortrack/output_file.hpp"
#include "track-document.h"

namespace trackpublish {

namespace {

using gstglue::Apply;
using gstglue::getText;
using gstglue::getTextOrNull;
using gstglue::getValue;
using gstglue::setText;
using gstglue::setValue;
using gstglue::textOf;
using Def = gstglue::PropertyDef<Settings>;

// Every property is read at start (Def::atStart): a change while running warns and applies from the next
// start, so no row marks a change.

colortrack::Status checkLocationValue(const PropertyStore &, const GValue *v) {
  const std::string location = textOf(v);
  if (location.empty() || location == "-") return {};
  if (colortrack::looksLikeUrl(location))
    return colortrack::Status::failure(
        "it looks like a URL (or a drive letter), but location names a file (an MQTT broker goes in "
        "'address'); a file whose name has a colon is written ./" +
        location);
  return colortrack::checkOutputPath(location);
}

colortrack::Status checkAddressValue(const PropertyStore &, const GValue *v) {
  const std::string address = textOf(v);
  return address.empty() ? colortrack::Status() : checkAddress(address);
}

// Only {source} is replaced in a topic: any other {name} would be published as written.
colortrack::Status checkTopicValue(const PropertyStore &, const GValue *v) {
  const std::string topic = textOf(v);
  for (std::size_t open = topic.find('{'); open != std::string::npos; open = topic.find('{', open + 1)) {
    const std::size_t close = topic.find('}', open);
    const std::string name =
        topic.substr(open, close == std::string::npos ? std::string::npos : close - open + 1);
    if (name != "{source}")
      return colortrack::Status::failure("'" + name +
                                         "' is not replaced by anything: the only placeholder is {source}");
  }
  return checkTopic(topic);
}

// The source goes into every document and into the topic: a control character (a newline) would split a
// line-per-document file for some readers and is refused by brokers in a topic.
colortrack::Status checkSourceValue(const PropertyStore &, const GValue *v) {
  for (const unsigned char c : textOf(v))
    if (c < 0x20 || c == 0x7F)
      return colortrack::Status::failure(
          "a source name must not contain control characters (a newline, a tab, ...)");
  return {};
}

colortrack::Status checkClientIdValue(const PropertyStore &, const GValue *v) {
  return checkClientId(textOf(v));
}

// A PEM file holding `what` ("CERTIFICATE", "PRIVATE KEY"), read without waiting: a FIFO or a directory
// would hold Paho's thread (and the pipeline's stop) for ever, and a missing or garbled file would only show
// as "cannot reach the broker", blamed on the address.
colortrack::Status checkPemFile(const std::string &path, const char *what) {
  if (path.empty()) return {};
  const colortrack::Result<std::vector<unsigned char>> bytes = colortrack::readRegularFile(path, 1 << 20);
  if (!bytes) return bytes.status();
  const std::string text(bytes->begin(), bytes->end());
  if (text.find("-----BEGIN ") == std::string::npos || text.find(what) == std::string::npos)
    return colortrack::Status::failure(std::string("'") + path + "' is not a PEM file with a " + what +
                                       " (-----BEGIN ..." + what + "-----)");
  return {};
}

// tls-ca-file and tls-cert-file both hold certificates.
colortrack::Status checkCertificateFileValue(const PropertyStore &, const GValue *v) {
  return checkPemFile(textOf(v), "CERTIFICATE");
}

colortrack::Status checkKeyFileValue(const PropertyStore &, const GValue *v) {
  return checkPemFile(textOf(v), "PRIVATE KEY");
}

colortrack::Status checkUsernameValue(const PropertyStore &, const GValue *v) {
  return checkMqttString(textOf(v), "the user name");
}

colortrack::Status checkPasswordValue(const PropertyStore &, const GValue *v) {
  return checkMqttString(textOf(v), "the password");
}

colortrack::Status checkTagsValue(const PropertyStore &, const GValue *v) {
  const std::string tags = textOf(v);
  return tags.empty() ? colortrack::Status() : checkTags(tags);
}

colortrack::Status refuseEmptyRoiType(const GValue *v) {
  if (!textOf(v).empty()) return {};
  return colortrack::Status::failure("it names the type of the regions to publish (e.g. colortrack, object)");
}

// Where documents go, and what they hold.
std::vector<Def> outputRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("location", "Location",
                                   "File to append one JSON document per line to (a regular file, created if "
                                   "missing, a character device or a FIFO that a reader has open), or \"-\" "
                                   "for stdout; may be combined with address",
                                   nullptr, f);
      })
          .textOrNull<&Settings::location>()
          .checking(checkLocationValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string(
            "address", "Address",
            "MQTT broker to publish to, tcp://HOST:PORT or ssl://HOST:PORT (1883 and 8883 "
            "are the usual ports; HOST:PORT alone means tcp://, as in gvametapublish); setting it selects "
            "MQTT",
            nullptr, f);
      })
          .textOrNull<&Settings::address>()
          .checking(checkAddressValue)
          .keepingRefused()
          .showing([](const GValue *v) { return "'" + redactedAddress(textOf(v)) + "'"; }),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("topic", "Topic",
                                   "MQTT topic; {source} is replaced by the source name; no wildcards, not "
                                   "starting with $ (the broker's), at most 65535 bytes of UTF-8",
                                   Settings{}.topic.c_str(), f);
      })
          .text<&Settings::topic>()
          .checking(checkTopicValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("tags", "Tags",
                                   "A JSON object put in every document as \"tags\" (as gvametapublish's "
                                   "tags), e.g. {\"site\":\"dock-3\"}; NULL = none",
                                   nullptr, f);
      })
          .textOrNull<&Settings::tags>()
          .checking(checkTagsValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_boolean("add-empty-results", "Add empty results",
                                    "Also publish a document for a frame with no object (as gvametaconvert's "
                                    "add-empty-results: by default such frames give none)",
                                    Settings{}.addEmptyResults, f);
      }).field<&Settings::addEmptyResults>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("source", "Source",
                                   "Name of this camera or stream in every document (and in the topic); "
                                   "NULL = the element's name",
                                   nullptr, f);
      })
          .textOrNull<&Settings::source>()
          .checking(checkSourceValue),
  };
}

// The MQTT session.
std::vector<Def> mqttRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_int("mqtt-qos", "MQTT QoS",
                                "MQTT quality of service: 0 at most once, 1 at least once (a document may "
                                "arrive twice after a reconnect), 2 exactly once",
                                0, 2, Settings{}.qos, f);
      }).field<&Settings::qos>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("client-id", "Client id",
                                   "MQTT client id, unique per broker, at most 65535 bytes of UTF-8; NULL = "
                                   "colortrack-<source>-<process id>",
                                   nullptr, f);
      })
          .textOrNull<&Settings::clientId>()
          .checking(checkClientIdValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("username", "User name", "MQTT user name; NULL = none", nullptr, f);
      })
          .textOrNull<&Settings::username>()
          .checking(checkUsernameValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("password", "Password", "MQTT password; NULL = none", nullptr, f);
      })
          .textOrNull<&Settings::password>()
          .checking(checkPasswordValue)
          .keepingRefused()
          .showing([](const GValue *) { return std::string("'***'"); }),
  };
}

// TLS to the broker.
std::vector<Def> tlsRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string(
            "tls-ca-file", "TLS CA file",
            "PEM file of the certificate authorities to trust (ssl:// only: refused with "
            "tcp://); NULL = the system's",
            nullptr, f);
      })
          .textOrNull<&Settings::tlsCaFile>()
          .checking(checkCertificateFileValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("tls-cert-file", "TLS certificate file",
                                   "PEM client certificate (ssl:// only); NULL = none", nullptr, f);
      })
          .textOrNull<&Settings::tlsCertFile>()
          .checking(checkCertificateFileValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string("tls-key-file", "TLS key file",
                                   "PEM private key of the client certificate (ssl:// only); NULL = in the "
                                   "certificate file",
                                   nullptr, f);
      })
          .textOrNull<&Settings::tlsKeyFile>()
          .checking(checkKeyFileValue)
          .keepingRefused(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_boolean("tls-verify", "TLS verify",
                                    "Check the broker's certificate and host name (ssl:// only)",
                                    Settings{}.tlsVerify, f);
      }).field<&Settings::tlsVerify>(),
  };
}

// Delivery, and the metadata read.
std::vector<Def> deliveryRows() {
  return {
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint("max-queued", "Maximum queued",
                                 "Documents kept while the broker is unreachable or the file (location) "
                                 "is behind; beyond this the oldest are dropped (counted in a warning)",
                                 1, 10000000, Settings{}.maxQueued, f);
      }).field<&Settings::maxQueued>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_boolean("fail-on-connect", "Fail on connect",
                                    "Fail to start when the broker cannot be reached (else warn and keep "
                                    "retrying, queueing documents)",
                                    Settings{}.failOnConnect, f);
      }).field<&Settings::failOnConnect>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_uint("drain-timeout", "Drain timeout",
                                 "Milliseconds to keep delivering queued documents (to the broker and to "
                                 "the file) at EOS and when stopping",
                                 0, 600000, Settings{}.drainTimeoutMs, f);
      }).field<&Settings::drainTimeoutMs>(),
      Def::atStart([](GParamFlags f) {
        return g_param_spec_string(
            "roi-type", "ROI type",
            "Type of the region-of-interest metas to publish, not empty (\"object\" for "
            "cvtracker)",
            Settings{}.roiType.c_str(), f);
      })
          .text<&Settings::roiType>()
          .refusing(refuseEmptyRoiType),
  };
}

}  // namespace

std::vector<gstglue::PropertyDef<Settings>> settingRows() {
  return gstglue::rowsOf<Def>(outputRows(), mqttRows(), tlsRows(), deliveryRows());
}

}  // namespace trackpublish
