// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's settings, what its properties say, and the table that declares those properties. All are
// read at start.
#pragma once

#include <string>
#include <vector>

#include "element-core.h"

namespace trackpublish {

struct Settings {
  enum class Change : unsigned {};  // every property is read at start: nothing changes while running

  std::string location;  // a file of JSON lines, "-" for stdout; empty: none
  std::string address;   // MQTT broker, tcp://HOST:PORT or ssl://HOST:PORT; empty: none
  std::string topic = "colortrack/{source}";
  std::string source;  // empty: the element's name
  gint qos = 1;
  std::string clientId;  // empty: colortrack-<source>-<process id>
  std::string username, password;
  std::string tlsCaFile, tlsCertFile, tlsKeyFile;
  bool tlsVerify = true;
  guint maxQueued = 1000;
  bool failOnConnect = false;
  guint drainTimeoutMs = 5000;
  std::string roiType = "colortrack";
  std::string tags;              // a JSON object put in every document as "tags"; empty: none
  bool addEmptyResults = false;  // a document also for a frame with no object (gvametaconvert's default: no)
};

using PropertyStore = gstglue::PropertyStore<Settings>;
using ElementCore = gstglue::ElementCore<Settings>;

// Every property's row, in the order gst-inspect-1.0 lists them (the table: trackpublish-properties.h).
std::vector<gstglue::PropertyDef<Settings>> settingRows();

}  // namespace trackpublish
