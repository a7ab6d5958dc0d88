// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's outputs behind one interface: each kind (a file, an MQTT broker) is one file and one row of
// outputKinds(); the element opens every kind its settings ask for and hands each document to all of them.
#pragma once

#include <gst/gst.h>

#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "colortrack/status.hpp"

#include "trackpublish-settings.h"

GST_DEBUG_CATEGORY_EXTERN(gst_track_publish_debug);

namespace trackpublish {

// One open output. None waits on the streaming thread: each queues and delivers from its own thread.
class DocumentOutput {
 public:
  virtual ~DocumentOutput() = default;
  // Hands a document over; GST_FLOW_ERROR, with an error posted, once the output has failed for good.
  virtual GstFlowReturn publish(const std::string &document) = 0;
  // At EOS: waits up to `drain` for what is queued, and warns of what is left.
  virtual void drainAtEos(std::chrono::milliseconds drain) = 0;
  // At stop: delivers what it can within `drain`, closes, and logs what is left (the bus is flushing).
  virtual void close(std::chrono::milliseconds drain) = 0;
};

// What opening an output needs; `source` is the source name the documents carry.
struct OutputContext {
  GstElement *element;
  const Settings &settings;
  const std::string &source;
};

struct OutputKind {
  const char *property;                      // the property that asks for it
  const char *what;                          // what the property names, for the "no output" error
  bool (*wanted)(const Settings &settings);  // asked for by these settings
  // The output, or null with an error posted that names what to fix.
  std::unique_ptr<DocumentOutput> (*open)(const OutputContext &context);
};

// The table of output kinds (trackpublish-outputs.cpp).
const std::vector<OutputKind> &outputKinds();
// Whether some kind is asked for; the start's error when none is, naming each kind's property.
colortrack::Status checkSomeOutput(const Settings &settings);

}  // namespace trackpublish
