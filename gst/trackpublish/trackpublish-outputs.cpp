// SPDX-License-Identifier: LGPL-2.1-or-later
// The table of trackpublish's output kinds: adding one is its file (a DocumentOutput and its open function)
// and a row here.
#include "trackpublish-output.h"

namespace trackpublish {

std::unique_ptr<DocumentOutput> openFileOutput(const OutputContext &context);  // trackpublish-file-output.cpp
std::unique_ptr<DocumentOutput> openMqttOutput(const OutputContext &context);  // trackpublish-mqtt-output.cpp

const std::vector<OutputKind> &outputKinds() {
  static const std::vector<OutputKind> kinds = {
      {"location", [](const Settings &s) { return !s.location.empty(); }, openFileOutput},
      {"address", [](const Settings &s) { return !s.address.empty(); }, openMqttOutput},
  };
  return kinds;
}

}  // namespace trackpublish
