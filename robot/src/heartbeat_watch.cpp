// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/heartbeat_watch.hpp"

#include "colortrack/mavlink.hpp"

namespace robotctl {

void HeartbeatWatch::feed(const std::uint8_t *bytes, std::size_t size, Clock::time_point now) {
  for (const colortrack::mavlink::Frame &frame : colortrack::mavlink::parseFrames(bytes, size)) {
    if (frame.messageId != colortrack::mavlink::kHeartbeat.id || frame.systemId != system_) continue;
    // The autopilot (target-component), not another program that shares the vehicle's system id (a camera
    // manager, a second robotctl behind mavlink-router), and never our own heartbeat echoed back.
    if (component_ != 0 && frame.componentId != component_) continue;
    if (frame.systemId == self_ && frame.componentId == selfComponent_) continue;
    heard_ = true;
    stale_ = false;
    lastHeartbeat_ = now;
  }
}

HeartbeatWatch::Link HeartbeatWatch::state(Clock::time_point now) const {
  if (!heard_) return Link::Unknown;
  return stale_ || now - lastHeartbeat_ > timeout_ ? Link::Lost : Link::Alive;
}

}  // namespace robotctl
