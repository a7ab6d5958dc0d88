// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's view of its command writer: the writer's events as the element's bus messages, warnings and log.
#pragma once

#include <gst/gst.h>

#include <chrono>
#include <string>

#include "colortrack/command_writer.hpp"

namespace robotctl {

class ElementListener : public WriterListener {
 public:
  // Logs in `category`, the element's. With `postMessages`, each command sent is posted as a "robotctl"
  // element message: with `mavlink`, the rates and speed of the MAVLink message sent; otherwise the wheel
  // speeds times the protocol's output scale.
  ElementListener(GstElement *element, GstDebugCategory *category, bool postMessages,
                  const colortrack::ProtocolSettings &protocol)
      : element_(element), category_(category), postMessages_(postMessages), protocol_(protocol) {}

  void sent(const Command &command) override;
  void stalled(double timeout) override;
  void busy(const std::string &port, bool tail, std::size_t left) override;
  void connectionLost(const std::string &port, const std::string &why) override;
  void linkLost(const std::string &port, const std::string &why) override;
  void reopenFailed(const std::string &port, const std::string &why, bool newReason,
                    std::chrono::milliseconds retryIn) override;
  void reconnected(const std::string &port) override;

 private:
  void post(const Command &command);

  GstElement *element_;
  GstDebugCategory *category_;
  const bool postMessages_;
  const colortrack::ProtocolSettings protocol_;
};

}  // namespace robotctl
