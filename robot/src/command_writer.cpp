// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/command_writer.hpp"

#include <signal.h>

#include <algorithm>
#include <cstdio>

namespace robotctl {

namespace {

using Clock = std::chrono::steady_clock;

// Reconnection back-off: from the first to the longest wait between attempts to reopen a lost port.
constexpr auto kFirstRetry = std::chrono::milliseconds(100);
constexpr auto kLongestRetry = std::chrono::milliseconds(2000);
// MAVLink's heartbeat: once a second, whatever the command rate.
constexpr auto kHeartbeatPeriod = std::chrono::seconds(1);
// The final stop may wait this long for a slow port before the element gives up on it.
constexpr int kFinalStopTimeoutMs = 250;

double monotonicSeconds() {
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

int writeTimeoutMs(Clock::duration period) {
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(period).count();
  return static_cast<int>(std::clamp<long long>(ms, 5, 100));
}

// Time left until `deadline`, at least 1 ms (a port is always given a chance to take something).
int msUntil(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return static_cast<int>(std::max<long long>(left, 1));
}

// Whether `output` turns (or tilts) the robot or its camera.
bool turns(const colortrack::DriveOutput &output) {
  return output.angular != 0 || output.tilt != 0 || output.command == colortrack::DriveCommand::Left ||
         output.command == colortrack::DriveCommand::Right;
}

}  // namespace

CommandWriter::CommandWriter(std::unique_ptr<Port> port, const WriterConfig &config, WriterListener &listener)
    : port_(std::move(port)),
      config_(config),
      listener_(listener),
      encoder_(config.protocol),
      retryDelay_(kFirstRetry),
      stallTimeout_(config.stallTimeout),
      bufferWatchdog_(config.stallTimeout) {
  // target-system 0 (broadcast) names no vehicle to watch.
  const colortrack::MavlinkSettings &m = config.protocol.mavlink;
  if (encoder_.hasHeartbeat() && config.linkTimeout > 0 && m.targetSystem != 0)
    heartbeats_.emplace(
        m.targetSystem, m.targetComponent, m.systemId, m.componentId,
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(config.linkTimeout)));
}

void CommandWriter::start() {
  thread_ = std::thread([this] { run(); });
}

void CommandWriter::submit(const Command &command) {
  std::lock_guard<std::mutex> lock(mutex_);
  bufferWatchdog_.feed(monotonicSeconds());
  if (!playing_ || flushing_ || held_) return;
  pending_ = command;
}

void CommandWriter::stopNow(const char *reason) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopAtOnce(reason);
  }
  wake_.notify_one();
}

void CommandWriter::stopAtOnce(const char *reason) {
  pending_ = Command{};
  pending_.reason = reason;
  urgent_ = true;
}

void CommandWriter::setPlaying(bool playing) {
  std::lock_guard<std::mutex> lock(mutex_);
  playing_ = playing;
  if (playing) bufferWatchdog_.feed(monotonicSeconds());
}

void CommandWriter::setFlushing(bool flushing) {
  std::lock_guard<std::mutex> lock(mutex_);
  flushing_ = flushing;
}

void CommandWriter::setHeld(bool held) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (held == held_) return;
    held_ = held;
    if (!held) return;
    stopAtOnce("hold");
  }
  wake_.notify_one();
}

void CommandWriter::setStallTimeout(double seconds) {
  std::lock_guard<std::mutex> lock(mutex_);
  stallTimeout_ = seconds;
  bufferWatchdog_.setTimeout(seconds);
}

void CommandWriter::shutdown() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_one();
  if (thread_.joinable()) thread_.join();
  port_->close();
}

void CommandWriter::run() {
  // A reader that goes away must come back as EPIPE, not as a signal that kills the process.
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);

  const auto period =
      std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / config_.rate));
  auto nextTick = Clock::now();
  auto nextHeartbeat = nextTick;  // the first one goes out with the first command
  const bool heartbeats = encoder_.hasHeartbeat();
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait_until(lock, heartbeats ? std::min(nextTick, nextHeartbeat) : nextTick,
                     [this] { return quit_ || urgent_; });
    if (quit_) break;
    if (heartbeats && Clock::now() >= nextHeartbeat) {
      // On its own clock, so its period holds whatever the rate and however often a stop restarts the
      // commands' rhythm.
      lock.unlock();
      sendHeartbeat(writeTimeoutMs(period));
      lock.lock();
      nextHeartbeat += kHeartbeatPeriod;
      if (nextHeartbeat <= Clock::now()) nextHeartbeat = Clock::now() + kHeartbeatPeriod;
      if (quit_) break;
      if (!urgent_ && Clock::now() < nextTick) continue;  // only the heartbeat was due
    }
    const bool urgent = urgent_;
    urgent_ = false;
    const double seconds = monotonicSeconds();
    const bool stalled =
        playing_ && bufferWatchdog_.expired(seconds) && !colortrack::isStill(pending_.output);
    if (stalled) {
      pending_ = Command{};
      pending_.reason = "stalled";
    }
    Command command = pending_;
    // The same rule as for a target that is not confirmed (RobotController): a decision without a fresh
    // buffer is not turned on for more than the hold share of the stall timeout. pending_ keeps its turn, so
    // the stall is still seen and reported at the timeout.
    if (playing_ && !bufferWatchdog_.within(seconds, colortrack::kDriveHoldShare) && turns(command.output)) {
      command.output = colortrack::withoutTurn(command.output);
      command.reason = "stalling";
    }
    const double stallTimeout = stallTimeout_;
    lock.unlock();
    if (stalled) listener_.stalled(stallTimeout);
    send(command, writeTimeoutMs(period));
    lock.lock();
    const auto now = Clock::now();
    // An urgent stop restarts the rhythm; a tick that fell far behind (a slow port) does not burst to catch
    // up.
    nextTick = urgent || nextTick + period < now ? now + period : nextTick + period;
  }
  lock.unlock();
  Command last;
  last.reason = "shutdown";
  send(last, kFinalStopTimeoutMs);
}

void CommandWriter::send(const Command &decided, int timeoutMs) {
  // A hold that came after the command was taken still stops it (held_ is read without the lock for this).
  Command stop;
  stop.reason = "hold";
  const Command &command = held_ && !colortrack::isStill(decided.output) ? stop : decided;
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
  if (!port_->isOpen() && !reopen(command, deadline)) return;
  // The rest of a cut frame goes first: the robot would misread a newer frame glued to a fragment.
  if (!finishUnsent(deadline)) return;
  if (heartbeats_ && !followLink(command, deadline)) return;
  write(command, deadline);
}

// The link as the vehicle's heartbeats tell it: while they are missing only stop goes out, and when they
// are back stop goes first, as after a reopened port. True when `command` may follow.
bool CommandWriter::followLink(const Command &command, Clock::time_point deadline) {
  if (!receiveAll()) return false;
  const HeartbeatWatch::Link link = heartbeats_->state(Clock::now());
  if (link == HeartbeatWatch::Link::Lost && !linkDown_) {
    linkDown_ = true;
    char why[96];
    std::snprintf(why, sizeof why, "no HEARTBEAT from system %u for %.1f s (link-timeout)",
                  unsigned{heartbeats_->system()},
                  std::chrono::duration<double>(heartbeats_->timeout()).count());
    listener_.linkLost(port_->describe(), why);
  }
  if (!linkDown_) return true;
  const bool back = link == HeartbeatWatch::Link::Alive;
  Command stop;
  stop.reason = back ? "reconnected" : "link-lost";
  if (!write(stop, deadline) || !back) return false;
  linkDown_ = false;
  listener_.reconnected(port_->describe());
  return !colortrack::isStill(command.output);
}

// Takes what the port received (at most a bounded number of datagrams a tick: a flood of telemetry must
// not hold the commands up). False when the port failed.
bool CommandWriter::receiveAll() {
  constexpr int kMostReadsPerTick = 256;
  std::uint8_t buffer[2048];  // a MAVLink frame is at most 280 bytes
  for (int i = 0; i < kMostReadsPerTick; ++i) {
    std::size_t received = 0;
    std::string why;
    if (!port_->receive(buffer, sizeof buffer, received, why)) {
      connectionLost(why);
      return false;
    }
    if (received == 0) break;
    heartbeats_->feed(buffer, received, Clock::now());
  }
  return true;
}

// Reopens a lost port once its back-off has passed and sends stop; true when `command` should follow.
bool CommandWriter::reopen(const Command &command, Clock::time_point deadline) {
  if (Clock::now() < retryAt_) return false;
  const colortrack::Status opened = port_->open();
  if (!opened) {
    const std::string &why = opened.message();
    retryDelay_ = std::min(retryDelay_ * 2, std::chrono::duration_cast<Clock::duration>(kLongestRetry));
    retryAt_ = Clock::now() + retryDelay_;
    // Said once per outage (and again if the reason changes), not at every attempt.
    listener_.reopenFailed(port_->describe(), why, why != waitingFor_,
                           std::chrono::duration_cast<std::chrono::milliseconds>(retryDelay_));
    waitingFor_ = why;
    return false;
  }
  waitingFor_.clear();
  // Reconnected only once a write after the stop goes through too: a UDP socket always "reopens", and only
  // the send after one the peer refused (ICMP port unreachable) tells that nobody listens yet.
  unconfirmed_ = true;
  // Whatever the robot did while it was cut off, it hears stop first.
  Command stop;
  stop.reason = "reconnected";
  if (!write(stop, deadline)) return false;
  stopWritten_ = true;
  return !colortrack::isStill(command.output);
}

// Sends the tail of the frame cut by an earlier timeout; true when there is none left.
bool CommandWriter::finishUnsent(Clock::time_point deadline) {
  if (unsent_.empty()) return true;
  std::size_t written = 0;
  std::string why;
  const WriteResult result = port_->write(unsent_, msUntil(deadline), written, why);
  unsent_.erase(unsent_.begin(), unsent_.begin() + static_cast<std::ptrdiff_t>(written));
  switch (result) {
    case WriteResult::Written:
      noteWritten();
      if (unsentCommand_) listener_.sent(*unsentCommand_);
      return true;
    case WriteResult::Busy:
      listener_.busy(port_->describe(), true, unsent_.size());
      return false;
    case WriteResult::Failed:
      break;
  }
  connectionLost(why);
  return false;
}

bool CommandWriter::write(const Command &command, Clock::time_point deadline) {
  return writeFrame(encoder_.encode(command.output), command, deadline);
}

// Waits for no reopen (the commands' ticks do that), but comes after the rest of a cut frame.
void CommandWriter::sendHeartbeat(int timeoutMs) {
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
  if (!port_->isOpen() || !finishUnsent(deadline)) return;
  writeFrame(encoder_.heartbeat(), std::nullopt, deadline);
}

bool CommandWriter::writeFrame(const std::vector<std::uint8_t> &bytes, const std::optional<Command> &command,
                               Clock::time_point deadline) {
  std::size_t written = 0;
  std::string why;
  switch (port_->write(bytes, msUntil(deadline), written, why)) {
    case WriteResult::Written:
      noteWritten();
      if (command) listener_.sent(*command);
      return true;
    case WriteResult::Busy:
      if (written > 0) {
        unsent_.assign(bytes.begin() + static_cast<std::ptrdiff_t>(written), bytes.end());
        unsentCommand_ = command;  // reported sent once its last byte is out
      }
      listener_.busy(port_->describe(), false, written > 0 ? unsent_.size() : 0);
      return false;
    case WriteResult::Failed:
      break;
  }
  connectionLost(why);
  return false;
}

// A write went through: after a reopen, the first one after its stop confirms the link.
void CommandWriter::noteWritten() {
  if (!unconfirmed_) {
    retryDelay_ = kFirstRetry;
    return;
  }
  if (!stopWritten_) return;  // the reopen's own stop
  unconfirmed_ = stopWritten_ = false;
  retryDelay_ = kFirstRetry;
  // While the vehicle's heartbeats are missing the port being back is not the link being back: that is
  // said when they return (followLink).
  if (!linkDown_) listener_.reconnected(port_->describe());
}

void CommandWriter::connectionLost(const std::string &why) {
  port_->close();
  unsent_.clear();  // a new connection starts with a whole frame (stop)
  if (unconfirmed_) {
    // The same outage: a reopen that never got a second write through. Said once; the retries back off.
    stopWritten_ = false;
    retryDelay_ = std::min(retryDelay_ * 2, std::chrono::duration_cast<Clock::duration>(kLongestRetry));
  } else {
    if (!linkDown_) listener_.connectionLost(port_->describe(), why);
    retryDelay_ = kFirstRetry;
  }
  // A vehicle that was answering must answer again, after the port is back, before anything but stop is
  // sent: a heartbeat heard before the loss is no news of now, however recent.
  if (heartbeats_ && heartbeats_->state(Clock::now()) != HeartbeatWatch::Link::Unknown) {
    linkDown_ = true;
    heartbeats_->forget();
  }
  retryAt_ = Clock::now() + retryDelay_;
}

}  // namespace robotctl
