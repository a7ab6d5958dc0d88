// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's writer: a thread that sends the newest drive command to a Port at a fixed rate (and the
// protocol's heartbeat once a second, MAVLink's), stops the robot when buffers stall, reconnects a lost port
// with back-off and completes frames a slow port cut. It knows no GStreamer: what happens is reported to a
// WriterListener (the element turns that into bus messages).
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "colortrack/controller.hpp"
#include "colortrack/protocol.hpp"
#include "colortrack/heartbeat_watch.hpp"
#include "colortrack/robot_port.hpp"

namespace robotctl {

// The same value as GST_CLOCK_TIME_NONE.
constexpr std::uint64_t kNoTimestamp = ~std::uint64_t{0};

struct Command {
  colortrack::DriveOutput output;          // default: stop
  std::uint64_t timestamp = kNoTimestamp;  // of the buffer it was decided on, in nanoseconds
  const char *reason = "start";
};

struct WriterConfig {
  colortrack::ProtocolSettings protocol;
  double rate = 10.0;         // commands per second
  double stallTimeout = 0.5;  // seconds without a buffer while playing
  // MAVLink only: seconds without a HEARTBEAT from the target system before the link counts as lost (only
  // stop goes out until one comes again, and then stop first). 0: off. The watch starts with the first
  // heartbeat heard, so a vehicle that never answers changes nothing.
  double linkTimeout = 0;
};

// What the writer thread reports, called on that thread with no lock held. Each method does nothing unless
// overridden.
class WriterListener {
 public:
  virtual ~WriterListener() = default;
  // The last byte of `command` went out.
  virtual void sent(const Command & /*command*/) {}
  // No buffer came for `timeout` seconds while playing: the robot is sent stop.
  virtual void stalled(double /*timeout*/) {}
  // `port` did not take a whole write in time. `tail`: that write was the rest of a cut frame, of which
  // `left` bytes remain; otherwise `left` bytes of the command wait for the next tick (0: it was dropped).
  virtual void busy(const std::string & /*port*/, bool /*tail*/, std::size_t /*left*/) {}
  // A write failed: the port is closed and reopened with back-off.
  virtual void connectionLost(const std::string & /*port*/, const std::string & /*why*/) {}
  // The vehicle's heartbeats stopped, the port still open: only stop is sent until they are back.
  virtual void linkLost(const std::string & /*port*/, const std::string & /*why*/) {}
  // A reopen failed; `newReason` is false while the reason stays that of the previous failure.
  virtual void reopenFailed(const std::string & /*port*/, const std::string & /*why*/, bool /*newReason*/,
                            std::chrono::milliseconds /*retryIn*/) {}
  // The port is open again, or the vehicle's heartbeats are back; a stop went out first.
  virtual void reconnected(const std::string & /*port*/) {}
};

class CommandWriter {
 public:
  CommandWriter(std::unique_ptr<Port> port, const WriterConfig &config, WriterListener &listener);
  ~CommandWriter() { shutdown(); }

  void start();

  // The streaming thread's decision; replaces any command not sent yet (a queue of one: newest wins).
  // Ignored unless playing, not flushing and not held: a render() still running when a pause or a flush sent
  // stop must not bring a moving command back (the stall watchdog, off while not playing, would not stop it).
  void submit(const Command &command);
  // Stop now, not at the next tick.
  void stopNow(const char *reason);
  // Only a playing pipeline is expected to deliver buffers, and only its decisions are sent.
  void setPlaying(bool playing);
  // Between flush-start and flush-stop decisions are dropped (see submit()).
  void setFlushing(bool flushing);
  // Held: stop now, and only stop until released (a person's STOP; the decisions go on being made and
  // dropped, so the first one after the release is current).
  void setHeld(bool held);
  // How long a playing pipeline may go without a buffer (lost-timeout, which may change while playing).
  void setStallTimeout(double seconds);
  // Sends a last stop, ends the thread and closes the port. Idempotent.
  void shutdown();

 private:
  using Clock = std::chrono::steady_clock;

  void run();
  // The next send is stop, at once (the caller holds mutex_ and wakes the thread).
  void stopAtOnce(const char *reason);
  void send(const Command &command, int timeoutMs);
  bool reopen(const Command &command, Clock::time_point deadline);
  bool finishUnsent(Clock::time_point deadline);
  bool followLink(const Command &command, Clock::time_point deadline);
  bool receiveAll();
  bool write(const Command &command, Clock::time_point deadline);
  void sendHeartbeat(int timeoutMs);
  // `command`: what `bytes` carry, reported sent once they are all out; none for a heartbeat.
  bool writeFrame(const std::vector<std::uint8_t> &bytes, const std::optional<Command> &command,
                  Clock::time_point deadline);
  void connectionLost(const std::string &why);
  void noteWritten();

  std::unique_ptr<Port> port_;
  WriterConfig config_;
  WriterListener &listener_;
  colortrack::ProtocolEncoder encoder_;   // writer thread only, like the next five
  std::vector<std::uint8_t> unsent_;      // the tail of a frame a timed-out write cut
  std::optional<Command> unsentCommand_;  // the command that frame carries (none: a heartbeat)
  Clock::duration retryDelay_;
  Clock::time_point retryAt_;
  std::string waitingFor_;    // why the last reopen failed ("" while connected)
  bool unconfirmed_ = false;  // reopened, and no write after the reopen's stop has gone through yet
  bool stopWritten_ = false;  // that stop has gone through
  std::optional<HeartbeatWatch> heartbeats_;  // MAVLink with a link-timeout
  bool linkDown_ = false;  // the vehicle's heartbeats stopped (or the port went while they came)
  std::thread thread_;

  std::mutex mutex_;  // guards what follows; never held during I/O
  std::condition_variable wake_;
  Command pending_;
  bool urgent_ = false, quit_ = false, playing_ = false, flushing_ = false;
  std::atomic<bool> held_{false};  // written under mutex_, also read by send() without it
  double stallTimeout_;
  colortrack::Watchdog bufferWatchdog_;
};

}  // namespace robotctl
