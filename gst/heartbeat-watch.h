// Whether the vehicle at the other end of a MAVLink link still answers: the MAVLink convention that a link
// is lost when no HEARTBEAT came from that system for a while (3 s is usual). Bytes and clock in, state out;
// no I/O, no GStreamer.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>

namespace robotctl {

class HeartbeatWatch {
 public:
  using Clock = std::chrono::steady_clock;

  // Watches the heartbeats of `system` (robotctl's target-system); a link lost after `timeout`.
  HeartbeatWatch(std::uint8_t system, Clock::duration timeout) : system_(system), timeout_(timeout) {}

  // What the port received at `now` (one datagram, or what a read gave; any other bytes are skipped).
  void feed(const std::uint8_t *bytes, std::size_t size, Clock::time_point now);

  // Unknown until the first heartbeat: a vehicle that never answered (one that sends no heartbeat back, a
  // one-way radio) is no evidence of a lost link, so the watch stays out of the way.
  enum class Link { Unknown, Alive, Lost };
  Link state(Clock::time_point now) const;

  Clock::duration timeout() const { return timeout_; }
  std::uint8_t system() const { return system_; }

 private:
  std::uint8_t system_;
  Clock::duration timeout_;
  bool heard_ = false;
  Clock::time_point lastHeartbeat_;
};

}  // namespace robotctl
