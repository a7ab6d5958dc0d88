// SPDX-License-Identifier: LGPL-2.1-or-later
// The MQTT publisher's documents, from the streaming thread's hand-over to the broker's acknowledgement:
// waiting ones and ones in flight, both in sequence order. One rule holds everything together: whatever goes
// back to waiting (a failed send, every send of a lost connection) is merged by sequence, so the next sends
// start again from the oldest unacknowledged document whatever order Paho's answers come in. Not
// thread-safe: the publisher holds its lock around every call. No Paho, no GStreamer.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>

namespace trackpublish {

class SendQueue {
 public:
  using TimePoint = std::chrono::steady_clock::time_point;
  struct Document {
    std::uint64_t sequence = 0;
    std::string topic, payload;
    TimePoint sentAt{};  // in flight since
    // Which send this is (every send has its own number): Paho may answer an earlier send of a document
    // after it has gone back to waiting and been sent again, and that answer must not move the new send.
    std::uint64_t attempt = 0;
  };

  // Beyond `maxQueued` documents waiting or in flight, the oldest waiting one is dropped.
  explicit SendQueue(std::size_t maxQueued) : maxQueued_(maxQueued) {}

  // Adds a document; true when the oldest waiting one was dropped to make room.
  bool add(std::string topic, std::string payload);
  // The oldest waiting document, now in flight with a new attempt number; none when nothing waits or
  // `window` documents are in flight already.
  std::optional<Document> send(TimePoint now, std::size_t window);
  // The broker acknowledged this send: true when it was the current send of a document in flight.
  bool acknowledged(std::uint64_t sequence, std::uint64_t attempt);
  // This send failed: the document waits again, before every later one. A stale answer is ignored.
  void failed(std::uint64_t sequence, std::uint64_t attempt);
  // The connection went: everything in flight waits again, in order, to be sent on the next one.
  void requeueInFlight();

  bool empty() const { return waiting_.empty() && inFlight_.empty(); }
  std::size_t size() const { return waiting_.size() + inFlight_.size(); }
  std::size_t waiting() const { return waiting_.size(); }
  std::uint64_t dropped() const { return dropped_; }
  // Since when the oldest document in flight waits for its answer; none when nothing is in flight.
  std::optional<TimePoint> oldestSentAt() const;

 private:
  void wait(Document document);

  const std::size_t maxQueued_;
  std::deque<Document> waiting_;   // not yet sent, in sequence order
  std::deque<Document> inFlight_;  // sent, not yet acknowledged, in the order sent
  std::uint64_t nextSequence_ = 0, sendsMade_ = 0, dropped_ = 0;
};

}  // namespace trackpublish
