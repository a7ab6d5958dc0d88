// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl's CommandWriter against a fake port: the exact bytes the robot would receive when the port cuts
// frames, fails and comes back, and how stop, pause and flush gate what is sent. No GStreamer.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "colortrack/mavlink.hpp"
#include "colortrack/command_writer.hpp"

namespace robotctl {
namespace {

using Clock = std::chrono::steady_clock;
using Bytes = std::vector<std::uint8_t>;

// Long enough for any loaded machine; a passing test never waits for it.
constexpr auto kDeadline = std::chrono::seconds(3);

colortrack::DriveOutput drive(colortrack::DriveCommand command, double left, double right) {
  colortrack::DriveOutput out;
  out.command = command;
  out.left = left;
  out.right = right;
  out.targetVisible = true;
  return out;
}

Command commandOf(colortrack::DriveOutput output, const char *reason = "target") {
  Command command;
  command.output = output;
  command.reason = reason;
  return command;
}

const Command kForward = commandOf(drive(colortrack::DriveCommand::Forward, 0.5, 0.5));
const Command kLeft = commandOf(drive(colortrack::DriveCommand::Left, -0.3, 0.3));

// The text protocol: one line per frame, of a length that depends on the command.
WriterConfig textConfig(double rate) {
  WriterConfig config;
  config.protocol.protocol = colortrack::Protocol::Text;
  config.rate = rate;
  config.stallTimeout = 60;  // no stall unless a test asks for one
  return config;
}

std::string lineOf(const Command &command) {
  colortrack::ProtocolEncoder encoder(textConfig(1).protocol);
  const Bytes bytes = encoder.encode(command.output);
  return std::string(bytes.begin(), bytes.end());
}

const std::string kStopLine = lineOf(Command{});

// What the port received and the writer reported, shared by the fake port, the listener and the test.
struct Wire {
  std::mutex mutex;
  std::condition_variable changed;
  std::string received;  // every byte the port took, in order
  std::vector<std::string> sentReasons;
  std::vector<std::string> sentLines;
  std::vector<std::pair<Clock::time_point, colortrack::DriveOutput>> sentOutputs;  // when each went out
  int lost = 0, reconnected = 0, stalled = 0;
  std::vector<bool> reopenFailures;  // newReason of each failed reopen

  // Waits until `done` (called with the lock held) or the deadline; returns `done`'s last answer.
  bool waitFor(const std::function<bool()> &done) {
    std::unique_lock<std::mutex> lock(mutex);
    return changed.wait_until(lock, Clock::now() + kDeadline, done);
  }
  template <typename F>
  auto read(F f) {
    std::lock_guard<std::mutex> lock(mutex);
    return f();
  }
};

// A port that takes every byte unless told to cut writes short, fail one or refuse to open.
class FakePort : public Port {
 public:
  explicit FakePort(Wire &wire) : wire_(wire) {}

  // From the first write of `frame` on, the writes take only cuts[0], cuts[1], ... bytes (then all again).
  // `onCut` runs in the first cut write, so the test acts before the writer's next tick.
  void cutFrom(const std::string &frame, std::deque<std::size_t> cuts, std::function<void()> onCut) {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    cutTrigger_ = frame;
    cuts_ = std::move(cuts);
    onCut_ = std::move(onCut);
  }
  // The next write fails; then `refusals` opens are refused.
  void failNextWrite(int refusals) {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    failNext_ = true;
    refusals_ = refusals;
  }
  // What the other end sends back; receive() hands it out one datagram at a time.
  void deliver(const Bytes &datagram) {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    incoming_.push_back(datagram);
  }
  std::size_t cutsLeft() {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    return cuts_.size();
  }
  // When the failed write happened and how much had been received then; when each open was tried.
  Clock::time_point failedAt;
  std::size_t receivedAtFailure = 0;
  std::vector<Clock::time_point> openAttempts;

  colortrack::Status open() override {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    openAttempts.push_back(Clock::now());
    if (refusals_ > 0) {
      --refusals_;
      return colortrack::Status::failure("fake: not there");
    }
    open_ = true;
    return {};
  }
  void close() override { open_ = false; }
  bool isOpen() const override { return open_; }

  WriteResult write(const Bytes &bytes, int /*timeoutMs*/, std::size_t &written, std::string &why) override {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    written = 0;
    if (failNext_) {
      failNext_ = false;
      failedAt = Clock::now();
      receivedAtFailure = wire_.received.size();
      why = "fake: unplugged";
      return WriteResult::Failed;
    }
    std::function<void()> onCut;
    if (!cutTrigger_.empty() && std::string(bytes.begin(), bytes.end()) == cutTrigger_) {
      cutTrigger_.clear();
      onCut = std::move(onCut_);
    }
    written = bytes.size();
    if (cutTrigger_.empty() && !cuts_.empty()) {
      written = std::min(written, cuts_.front());
      cuts_.pop_front();
    }
    if (onCut) onCut();
    wire_.received.append(bytes.begin(), bytes.begin() + static_cast<std::ptrdiff_t>(written));
    wire_.changed.notify_all();
    return written == bytes.size() ? WriteResult::Written : WriteResult::Busy;
  }
  bool receive(std::uint8_t *buffer, std::size_t capacity, std::size_t &received, std::string &) override {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    received = 0;
    if (incoming_.empty()) return true;
    received = std::min(capacity, incoming_.front().size());
    std::copy_n(incoming_.front().begin(), received, buffer);
    incoming_.pop_front();
    return true;
  }
  std::string describe() const override { return "fake port"; }

 private:
  Wire &wire_;
  std::deque<Bytes> incoming_;
  bool open_ = false;  // writer thread only
  std::string cutTrigger_;
  std::deque<std::size_t> cuts_;
  std::function<void()> onCut_;
  bool failNext_ = false;
  int refusals_ = 0;
};

class Recorder : public WriterListener {
 public:
  explicit Recorder(Wire &wire) : wire_(wire) {}
  void sent(const Command &command) override {
    record([&] {
      wire_.sentReasons.push_back(command.reason);
      wire_.sentLines.push_back(lineOf(command));
      wire_.sentOutputs.emplace_back(Clock::now(), command.output);
    });
  }
  void stalled(double) override {
    record([&] { ++wire_.stalled; });
  }
  void connectionLost(const std::string &, const std::string &) override {
    record([&] { ++wire_.lost; });
  }
  void linkLost(const std::string &, const std::string &) override {
    record([&] { ++wire_.lost; });
  }
  void reopenFailed(const std::string &, const std::string &, bool newReason,
                    std::chrono::milliseconds) override {
    record([&] { wire_.reopenFailures.push_back(newReason); });
  }
  void reconnected(const std::string &) override {
    record([&] { ++wire_.reconnected; });
  }

 private:
  template <typename F>
  void record(F f) {
    std::lock_guard<std::mutex> lock(wire_.mutex);
    f();
    wire_.changed.notify_all();
  }
  Wire &wire_;
};

// A writer on a fake port, started.
struct Rig {
  Wire wire;
  Recorder recorder{wire};
  FakePort *port = nullptr;  // owned by the writer
  std::unique_ptr<CommandWriter> writer;

  explicit Rig(const WriterConfig &config) {
    auto fake = std::make_unique<FakePort>(wire);
    port = fake.get();
    port->open();  // as the element does before it creates the writer
    writer = std::make_unique<CommandWriter>(std::move(fake), config, recorder);
    writer->start();
  }
  bool waitForText(const std::string &text, std::size_t from = 0) {
    return wire.waitFor([&] { return wire.received.find(text, from) != std::string::npos; });
  }
  bool waitForSends(std::size_t count) {
    return wire.waitFor([&] { return wire.sentReasons.size() >= count; });
  }
  std::string received() {
    return wire.read([&] { return wire.received; });
  }
  std::size_t sends() {
    return wire.read([&] { return wire.sentReasons.size(); });
  }
};

// The lines of `text`, each checked to be one of `frames` whole; a fragment glued to a frame is not.
::testing::AssertionResult wholeFrames(const std::string &text, const std::vector<std::string> &frames) {
  std::size_t begin = 0;
  for (std::size_t end; (end = text.find('\n', begin)) != std::string::npos; begin = end + 1) {
    const std::string line = text.substr(begin, end + 1 - begin);
    if (std::find(frames.begin(), frames.end(), line) == frames.end())
      return ::testing::AssertionFailure() << "spliced or unknown frame \"" << line.substr(0, line.size() - 1)
                                           << "\" in \"" << text << "\"";
  }
  return ::testing::AssertionSuccess();
}

TEST(CommandWriter, CutFrameIsCompletedBeforeAnyOtherCommand) {
  Rig rig(textConfig(100));
  ASSERT_TRUE(rig.waitForText(kStopLine));
  rig.writer->setPlaying(true);
  // The forward line is cut after 3 bytes, and its rest after 2 more: the robot has a fragment. A newer
  // command is waiting by then.
  rig.port->cutFrom(lineOf(kForward), {3, 2}, [&] { rig.writer->submit(kLeft); });
  rig.writer->submit(kForward);
  ASSERT_TRUE(rig.waitForText(lineOf(kLeft) + lineOf(kLeft)));
  rig.writer->shutdown();

  const std::string text = rig.received();
  EXPECT_TRUE(wholeFrames(text, {kStopLine, lineOf(kForward), lineOf(kLeft)}));
  const std::size_t forward = text.find(lineOf(kForward));
  ASSERT_NE(forward, std::string::npos) << text;
  EXPECT_EQ(text.substr(forward + lineOf(kForward).size(), lineOf(kLeft).size()), lineOf(kLeft));
  EXPECT_EQ(rig.port->cutsLeft(), 0u);
  // Forward is reported sent once, when its last byte went out, before the newer command.
  const auto lines = rig.wire.read([&] { return rig.wire.sentLines; });
  const auto firstForward = std::find(lines.begin(), lines.end(), lineOf(kForward));
  ASSERT_NE(firstForward, lines.end());
  EXPECT_EQ(std::count(lines.begin(), lines.end(), lineOf(kForward)), 1);
  EXPECT_EQ(*(firstForward + 1), lineOf(kLeft));
}

TEST(CommandWriter, FailedWriteReconnectsWithBackOffAndStopsFirst) {
  Rig rig(textConfig(100));
  rig.writer->setPlaying(true);
  rig.writer->submit(kForward);
  ASSERT_TRUE(rig.waitForText(lineOf(kForward)));
  rig.port->failNextWrite(2);  // unplugged; the first two reopens find nothing
  ASSERT_TRUE(rig.wire.waitFor([&] { return rig.wire.reconnected == 1; }));
  const std::size_t from = rig.wire.read([&] { return rig.port->receivedAtFailure; });
  ASSERT_TRUE(rig.waitForText(lineOf(kForward), from));
  rig.writer->shutdown();

  // After the failure: stop first, then the command again.
  const std::string after = rig.received().substr(from);
  EXPECT_EQ(after.substr(0, kStopLine.size() + lineOf(kForward).size()), kStopLine + lineOf(kForward))
      << after;
  EXPECT_TRUE(wholeFrames(after, {kStopLine, lineOf(kForward)}));
  rig.wire.read([&] {
    EXPECT_EQ(rig.wire.lost, 1);
    // Warned once for the outage, not at each attempt.
    EXPECT_EQ(rig.wire.reopenFailures, (std::vector<bool>{true, false}));
    const auto reconnected =
        std::find(rig.wire.sentReasons.begin(), rig.wire.sentReasons.end(), std::string("reconnected"));
    ASSERT_NE(reconnected, rig.wire.sentReasons.end());
    EXPECT_EQ(*(reconnected + 1), "target");
    // Back-off: 100 ms after the failure, then 200 and 400 ms between attempts (the first open is the rig's).
    const std::vector<Clock::time_point> &opens = rig.port->openAttempts;
    ASSERT_EQ(opens.size(), 4u);
    using ms = std::chrono::milliseconds;
    EXPECT_GE(std::chrono::duration_cast<ms>(opens[1] - rig.port->failedAt).count(), 100);
    EXPECT_GE(std::chrono::duration_cast<ms>(opens[2] - opens[1]).count(), 200);
    EXPECT_GE(std::chrono::duration_cast<ms>(opens[3] - opens[2]).count(), 400);
  });
}

TEST(CommandWriter, StopNowDoesNotWaitForTheTick) {
  Rig rig(textConfig(0.5));          // a tick every 2 s
  ASSERT_TRUE(rig.waitForSends(1));  // the first tick: stop
  rig.writer->setPlaying(true);
  rig.writer->submit(kForward);
  const auto asked = Clock::now();
  rig.writer->stopNow("eos");
  ASSERT_TRUE(rig.waitForSends(2));
  EXPECT_LT(Clock::now() - asked, std::chrono::seconds(1));
  EXPECT_EQ(rig.wire.read([&] { return rig.wire.sentReasons; }), (std::vector<std::string>{"start", "eos"}));
  rig.writer->shutdown();
  EXPECT_EQ(rig.received(), kStopLine + kStopLine + kStopLine);  // start, eos, shutdown: forward never
  EXPECT_EQ(rig.wire.read([&] { return rig.wire.sentReasons.back(); }), "shutdown");
}

TEST(CommandWriter, SendsOnlyStopUnlessPlayingAndNotFlushing) {
  Rig rig(textConfig(200));
  rig.writer->submit(kForward);  // not playing yet
  ASSERT_TRUE(rig.waitForSends(10));
  rig.writer->setPlaying(true);
  rig.writer->setFlushing(true);
  rig.writer->submit(kForward);
  ASSERT_TRUE(rig.waitForSends(rig.sends() + 10));
  EXPECT_TRUE(wholeFrames(rig.received(), {kStopLine}));
  // The same command is sent once the flush is over.
  rig.writer->setFlushing(false);
  rig.writer->submit(kForward);
  EXPECT_TRUE(rig.waitForText(lineOf(kForward)));
}

// A person's STOP: at once (not at the next tick), only stop while held, the newest decision after release.
TEST(CommandWriter, HeldSendsOnlyStopAtOnceUntilReleased) {
  Rig rig(textConfig(2));  // a tick every 500 ms: a stop within it came at once
  rig.writer->setPlaying(true);
  rig.writer->submit(kForward);
  ASSERT_TRUE(rig.waitForText(lineOf(kForward)));
  const auto asked = Clock::now();
  rig.writer->setHeld(true);
  ASSERT_TRUE(rig.wire.waitFor([&] { return rig.wire.sentReasons.back() == "hold"; }));
  EXPECT_LT(Clock::now() - asked, std::chrono::milliseconds(250));
  const std::size_t heldFrom = rig.received().size();
  for (int i = 0; i < 5; ++i) rig.writer->submit(kForward);  // decisions while held are dropped
  rig.writer->setHeld(true);                                 // holding again changes nothing
  ASSERT_TRUE(rig.waitForSends(rig.sends() + 3));
  const std::string held = rig.received().substr(heldFrom);
  EXPECT_TRUE(wholeFrames(held, {kStopLine})) << held;
  rig.writer->setHeld(false);
  const std::size_t releasedFrom = rig.received().size();
  rig.writer->submit(kLeft);
  EXPECT_TRUE(rig.waitForText(lineOf(kLeft), releasedFrom));
}

TEST(CommandWriter, StallStopsAMovingRobot) {
  WriterConfig config = textConfig(200);
  config.stallTimeout = 0.05;
  Rig rig(config);
  rig.writer->setPlaying(true);
  rig.writer->submit(kForward);
  ASSERT_TRUE(rig.waitForText(lineOf(kForward)));
  // No more buffers: stop, reported once.
  ASSERT_TRUE(rig.wire.waitFor([&] {
    return std::find(rig.wire.sentReasons.begin(), rig.wire.sentReasons.end(), std::string("stalled")) !=
           rig.wire.sentReasons.end();
  }));
  const std::string text = rig.received();
  EXPECT_EQ(text.substr(text.rfind(lineOf(kForward)) + lineOf(kForward).size(), kStopLine.size()), kStopLine);
  EXPECT_EQ(rig.wire.read([&] { return rig.wire.stalled; }), 1);
}

// A stalled stream is not turned on for long: the last decision goes out as it was for the hold share of the
// stall timeout, then without its turn (a zone turn becomes stop, a turning drive a straight one), then the
// stall stops the robot.
TEST(CommandWriter, StallDropsTheTurnAfterTheHoldShare) {
  constexpr double kTimeout = 0.4;
  const auto hold = std::chrono::duration<double>(colortrack::kDriveHoldShare * kTimeout);
  const colortrack::DriveOutput turningDrive = colortrack::makeOutput(0.4, 0.3, true);
  for (const colortrack::DriveOutput &decision : {kLeft.output, turningDrive}) {
    WriterConfig config = textConfig(200);
    config.stallTimeout = kTimeout;
    Rig rig(config);
    rig.writer->setPlaying(true);
    const Clock::time_point lastBuffer = Clock::now();
    rig.writer->submit(commandOf(decision));
    // The stall's stop is reported stalled before it is sent: wait for the stop itself.
    const auto sentStalled = [&] {
      const auto &r = rig.wire.sentReasons;
      return std::find(r.begin(), r.end(), std::string("stalled")) != r.end();
    };
    ASSERT_TRUE(rig.wire.waitFor(sentStalled));
    // Both read under one lock, so they describe the same commands.
    const auto [reasons, outputs] =
        rig.wire.read([&] { return std::make_pair(rig.wire.sentReasons, rig.wire.sentOutputs); });
    ASSERT_EQ(reasons.size(), outputs.size());
    const auto firstOf = [&](const char *reason) {
      return static_cast<std::size_t>(std::find(reasons.begin(), reasons.end(), std::string(reason)) -
                                      reasons.begin());
    };
    const std::size_t stalling = firstOf("stalling"), stalled = firstOf("stalled");
    ASSERT_LT(stalled, reasons.size());
    ASSERT_LT(stalling, stalled) << "no turnless command before the stall's stop";
    EXPECT_LT(firstOf("target"), stalling) << "the decision itself went out first";
    EXPECT_GE(outputs[stalling].first - lastBuffer, hold);
    EXPECT_GE(outputs[stalled].first - lastBuffer, std::chrono::duration<double>(kTimeout));
    for (std::size_t i = stalling; i < outputs.size(); ++i) {
      const colortrack::DriveOutput &o = outputs[i].second;
      EXPECT_EQ(o.angular, 0) << reasons[i];
      EXPECT_TRUE(o.command != colortrack::DriveCommand::Left &&
                  o.command != colortrack::DriveCommand::Right);
      EXPECT_EQ(o.linear, i < stalled ? decision.linear : 0) << reasons[i];
    }
  }
}

// MAVLink's heartbeat keeps its own 1 Hz clock: with a command every 2 s, and a stop that restarts the
// commands' rhythm in between; one sequence number counts every frame.
TEST(CommandWriter, MavlinkHeartbeatOnItsOwnClock) {
  WriterConfig config;
  config.protocol.protocol = colortrack::Protocol::Mavlink;
  config.rate = 0.5;
  config.stallTimeout = 60;
  const auto start = Clock::now();
  Rig rig(config);
  std::vector<double> heartbeats;  // s after the start
  std::vector<int> sequence;
  std::size_t parsed = 0;
  bool stopped = false;
  while (heartbeats.size() < 3 && Clock::now() - start < std::chrono::seconds(4)) {
    const std::string received = rig.received();
    std::size_t used = 0;
    while (const auto frame = colortrack::mavlink::parseFrame(
               reinterpret_cast<const std::uint8_t *>(received.data()) + parsed, received.size() - parsed,
               &used)) {
      parsed += used;
      sequence.push_back(frame->sequence);
      if (frame->messageId == colortrack::mavlink::kHeartbeat.id)
        heartbeats.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    }
    if (!stopped && Clock::now() - start > std::chrono::milliseconds(500)) {
      rig.writer->stopNow("test");
      stopped = true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  ASSERT_EQ(heartbeats.size(), 3u);
  EXPECT_NEAR(heartbeats[1] - heartbeats[0], 1.0, 0.05);
  EXPECT_NEAR(heartbeats[2] - heartbeats[1], 1.0, 0.05);
  // Heartbeat, stop (first tick), stop (stopNow), heartbeat, heartbeat: the commands did not add ticks.
  EXPECT_EQ(sequence, (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(rig.sends(), 2u);
}

// MAVLink with a link-timeout: a gimbal turning at every tick while the vehicle's heartbeats come.
struct LinkRig {
  static WriterConfig config() {
    WriterConfig c;
    c.protocol.protocol = colortrack::Protocol::Mavlink;
    c.rate = 50;
    c.stallTimeout = 60;
    c.linkTimeout = 0.3;
    return c;
  }
  static Command turn() {
    colortrack::DriveOutput out;
    out.command = colortrack::DriveCommand::Left;
    out.angular = 0.5;
    out.targetVisible = true;
    return commandOf(out);
  }
  // A heartbeat of `system` every 50 ms for `seconds`, the turn submitted at each.
  void beat(std::uint8_t system, double seconds) {
    const auto until = Clock::now() + std::chrono::duration<double>(seconds);
    while (Clock::now() < until) {
      colortrack::mavlink::Sender vehicle{system, 1, 0};
      if (system != 0)
        rig.port->deliver(colortrack::mavlink::encode(colortrack::mavlink::Heartbeat(), vehicle));
      rig.writer->submit(turn());
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
  }
  std::vector<std::string> reasons() {
    return rig.wire.read([&] { return rig.wire.sentReasons; });
  }
  Rig rig{config()};
};

// The vehicle's heartbeats stop: one warning, only stop while they are missing; when they are back, stop
// first, one "reconnected", then the turn again. The port itself never failed.
TEST(CommandWriter, MissingHeartbeatsStopTheVehicleUntilTheyAreBack) {
  LinkRig link;
  link.rig.writer->setPlaying(true);
  link.beat(1, 0.5);
  ASSERT_EQ(link.reasons().back(), "target");
  link.beat(0, 0.8);  // silence: lost after 0.3 s
  ASSERT_EQ(link.rig.wire.read([&] { return link.rig.wire.lost; }), 1);
  std::vector<std::string> reasons = link.reasons();
  const std::size_t lastTurn = static_cast<std::size_t>(
      std::find(reasons.rbegin(), reasons.rend(), "target").base() - reasons.begin());
  ASSERT_LT(lastTurn + 5, reasons.size());  // ~25 stops since
  for (std::size_t i = lastTurn; i < reasons.size(); ++i) EXPECT_EQ(reasons[i], "link-lost") << i;
  link.beat(1, 0.3);
  reasons = link.reasons();
  const auto back = std::find(reasons.begin() + static_cast<std::ptrdiff_t>(lastTurn), reasons.end(),
                              std::string("reconnected"));
  ASSERT_NE(back, reasons.end());
  EXPECT_EQ(*(back - 1), "link-lost");
  ASSERT_NE(back + 1, reasons.end());
  EXPECT_EQ(*(back + 1), "target");
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.reconnected; }), 1);
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.lost; }), 1);
  EXPECT_EQ(link.rig.port->openAttempts.size(), 1u);
}

// Heartbeats of another system (a ground station behind mavlink-router) are not the vehicle's, and a
// vehicle that never answered is no evidence of a lost link: the commands go on.
TEST(CommandWriter, NoHeartbeatOfTheTargetSystemChangesNothing) {
  LinkRig link;
  link.rig.writer->setPlaying(true);
  link.beat(255, 0.8);
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.lost; }), 0);
  EXPECT_EQ(link.reasons().back(), "target");
}

// The port fails while the vehicle answers and stays away longer than link-timeout: one warning (not a
// second one for the heartbeats), and after the reopen only stop until the heartbeats are back, then one
// "reconnected".
TEST(CommandWriter, APortLostWhileTheVehicleAnsweredWaitsForItsHeartbeat) {
  LinkRig link;
  link.rig.writer->setPlaying(true);
  link.beat(1, 0.3);
  link.rig.port->failNextWrite(2);  // reopened about 0.7 s later
  link.beat(0, 1.2);
  EXPECT_EQ(link.rig.port->openAttempts.size(), 4u);
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.lost; }), 1);
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.reconnected; }), 0);
  EXPECT_EQ(link.reasons().back(), "link-lost");
  link.beat(1, 0.3);
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.reconnected; }), 1);
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.lost; }), 1);
  EXPECT_EQ(link.reasons().back(), "target");
}

// A port outage shorter than link-timeout: the heartbeat heard before it is no news of after it, so only
// stop goes out from the reopen until a fresh heartbeat comes (then "reconnected" once).
TEST(CommandWriter, AShortPortOutageStillWaitsForAFreshHeartbeat) {
  LinkRig link;
  link.rig.writer->setPlaying(true);
  link.beat(1, 0.3);
  const std::size_t before = link.reasons().size();
  link.rig.port->failNextWrite(0);  // reopened 0.1 s later, well within link-timeout (0.3 s)
  link.beat(0, 0.25);
  std::vector<std::string> reasons = link.reasons();
  ASSERT_LT(before + 3, reasons.size());
  for (std::size_t i = before; i < reasons.size(); ++i) EXPECT_NE(reasons[i], "target") << i;
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.reconnected; }), 0);
  link.beat(1, 0.3);
  EXPECT_EQ(link.rig.wire.read([&] { return link.rig.wire.reconnected; }), 1);
  EXPECT_EQ(link.reasons().back(), "target");
}

}  // namespace
}  // namespace robotctl
