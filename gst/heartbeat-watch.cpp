#include "heartbeat-watch.h"

#include "colortrack/mavlink.hpp"

namespace robotctl {

void HeartbeatWatch::feed(const std::uint8_t *bytes, std::size_t size, Clock::time_point now) {
  for (const colortrack::mavlink::Frame &frame : colortrack::mavlink::parseFrames(bytes, size)) {
    // Any component of the system counts (the autopilot, its gimbal manager): the vehicle is there.
    if (frame.messageId != colortrack::mavlink::kHeartbeat.id || frame.systemId != system_) continue;
    heard_ = true;
    lastHeartbeat_ = now;
  }
}

HeartbeatWatch::Link HeartbeatWatch::state(Clock::time_point now) const {
  if (!heard_) return Link::Unknown;
  return now - lastHeartbeat_ > timeout_ ? Link::Lost : Link::Alive;
}

}  // namespace robotctl
