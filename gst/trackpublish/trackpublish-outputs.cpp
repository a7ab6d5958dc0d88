// SPDX-License-Identifier: LGPL-2.1-or-later
// The table of trackpublish's output kinds: adding one is its file (a DocumentOutput and its open function)
// and a row here.
#include "trackpublish-output.h"

namespace trackpublish {

std::unique_ptr<DocumentOutput> openFileOutput(const OutputContext &context);  // trackpublish-file-output.cpp
std::unique_ptr<DocumentOutput> openMqttOutput(const OutputContext &context);  // trackpublish-mqtt-output.cpp

const std::vector<OutputKind> &outputKinds() {
  static const std::vector<OutputKind> kinds = {
      {"location", "a file, or '-' for stdout", [](const Settings &s) { return !s.location.empty(); },
       openFileOutput},
      {"address", "an MQTT broker, tcp://HOST:PORT", [](const Settings &s) { return !s.address.empty(); },
       openMqttOutput},
  };
  return kinds;
}

colortrack::Status checkSomeOutput(const Settings &settings) {
  std::string asked;
  for (const OutputKind &kind : outputKinds()) {
    if (kind.wanted(settings)) return {};
    asked += std::string(asked.empty() ? "" : " and/or ") + "'" + kind.property + "' (" + kind.what + ")";
  }
  return colortrack::Status::failure("No output: set " + asked + ".");
}

}  // namespace trackpublish
