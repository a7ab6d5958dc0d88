// SPDX-License-Identifier: LGPL-2.1-or-later
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

  // Watches the heartbeats of `system`'s `component` (robotctl's target-system and target-component; a
  // component 0 is any of the system's), never counting our own (`self`, `selfComponent`); a link lost
  // after `timeout`.
  HeartbeatWatch(std::uint8_t system, std::uint8_t component, std::uint8_t self, std::uint8_t selfComponent,
                 Clock::duration timeout)
      : system_(system),
        component_(component),
        self_(self),
        selfComponent_(selfComponent),
        timeout_(timeout) {}

  // What the port received at `now` (one datagram, or what a read gave; any other bytes are skipped).
  void feed(const std::uint8_t *bytes, std::size_t size, Clock::time_point now);

  // Unknown until the first heartbeat: a vehicle that never answered (one that sends no heartbeat back, a
  // one-way radio) is no evidence of a lost link, so the watch stays out of the way.
  enum class Link { Unknown, Alive, Lost };
  Link state(Clock::time_point now) const;
  // The port went away: what was heard before says nothing about now. Lost until a heartbeat comes again
  // (Unknown stays Unknown).
  void forget() { stale_ = heard_; }

  Clock::duration timeout() const { return timeout_; }
  std::uint8_t system() const { return system_; }

 private:
  std::uint8_t system_, component_, self_, selfComponent_;
  Clock::duration timeout_;
  bool heard_ = false;
  bool stale_ = false;  // heard before a port loss, not since
  Clock::time_point lastHeartbeat_;
};

}  // namespace robotctl
