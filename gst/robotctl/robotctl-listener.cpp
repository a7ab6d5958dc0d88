// SPDX-License-Identifier: LGPL-2.1-or-later
#include "robotctl-listener.h"

#include "colortrack-meta.h"
#include "property-table.h"

#define GST_CAT_DEFAULT category_

namespace robotctl {

void ElementListener::sent(const Command &command) {
  if (postMessages_) post(command);
}

void ElementListener::stalled(double timeout) {
  GST_INFO_OBJECT(element_, "no buffer for %.0f ms: stopping", timeout * 1000);
}

void ElementListener::busy(const std::string &port, bool tail, std::size_t left) {
  if (tail)
    GST_LOG_OBJECT(element_, "%s is not taking data: %zu bytes of a command still to send", port.c_str(),
                   left);
  else
    GST_LOG_OBJECT(element_, "%s is not taking data: %s", port.c_str(),
                   left > 0 ? "the rest of the command goes first on the next tick" : "command dropped");
}

void ElementListener::connectionLost(const std::string &port, const std::string &why) {
  GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                      ("Lost the connection to %s: %s. Retrying.", gstglue::validUtf8(port).c_str(),
                       gstglue::validUtf8(why).c_str()),
                      (nullptr));
}

void ElementListener::linkLost(const std::string &port, const std::string &why) {
  GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                      ("Lost the link to %s: %s. Sending only stop until it answers again.",
                       gstglue::validUtf8(port).c_str(), gstglue::validUtf8(why).c_str()),
                      (nullptr));
}

void ElementListener::reopenFailed(const std::string &port, const std::string &why, bool newReason,
                                   std::chrono::milliseconds retryIn) {
  if (newReason)
    GST_ELEMENT_WARNING(element_, RESOURCE, OPEN_WRITE,
                        ("Cannot reopen %s: %s. Retrying.", gstglue::validUtf8(port).c_str(),
                         gstglue::validUtf8(why).c_str()),
                        (nullptr));
  GST_DEBUG_OBJECT(element_, "could not reopen %s: %s (next try in %lld ms)", port.c_str(), why.c_str(),
                   static_cast<long long>(retryIn.count()));
}

void ElementListener::reconnected(const std::string &port) {
  GST_ELEMENT_INFO(element_, RESOURCE, WRITE, ("Reconnected to %s.", gstglue::validUtf8(port).c_str()),
                   (nullptr));
}

void ElementListener::post(const Command &command) {
  const colortrack::DriveOutput &out = command.output;
  GstStructure *s = gst_structure_new(
      ROBOTCTL_MESSAGE_NAME, ROBOTCTL_MESSAGE_COMMAND, G_TYPE_STRING, colortrack::toString(out.command),
      ROBOTCTL_MESSAGE_LINEAR, G_TYPE_DOUBLE, out.linear, ROBOTCTL_MESSAGE_ANGULAR, G_TYPE_DOUBLE,
      out.angular, ROBOTCTL_MESSAGE_TARGET_VISIBLE, G_TYPE_BOOLEAN, static_cast<gboolean>(out.targetVisible),
      ROBOTCTL_MESSAGE_TIMESTAMP, G_TYPE_UINT64, static_cast<guint64>(command.timestamp),
      ROBOTCTL_MESSAGE_REASON, G_TYPE_STRING, command.reason, nullptr);
  if (protocol_.protocol == colortrack::Protocol::Mavlink) {
    // What the MAVLink message carried, so that a log of the bus reads like one of the vehicle's link.
    const colortrack::MavlinkCommand sent = colortrack::mavlinkCommand(out, protocol_.mavlink);
    if (protocol_.mavlink.mode == colortrack::MavlinkMode::Gimbal)
      gst_structure_set(s, ROBOTCTL_MESSAGE_PITCH_RATE, G_TYPE_DOUBLE, double{sent.pitchRate}, nullptr);
    else
      gst_structure_set(s, ROBOTCTL_MESSAGE_VX, G_TYPE_DOUBLE, double{sent.forwardSpeed}, nullptr);
    gst_structure_set(s, ROBOTCTL_MESSAGE_YAW_RATE, G_TYPE_DOUBLE, double{sent.yawRate}, nullptr);
  } else {
    const colortrack::SentSpeeds speeds = colortrack::sentSpeeds(out, protocol_.outputScale);
    gst_structure_set(s, ROBOTCTL_MESSAGE_LEFT, G_TYPE_INT, speeds.left, ROBOTCTL_MESSAGE_RIGHT, G_TYPE_INT,
                      speeds.right, nullptr);
  }
  gst_element_post_message(element_, gst_message_new_element(GST_OBJECT(element_), s));
}

}  // namespace robotctl
