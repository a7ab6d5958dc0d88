// SPDX-License-Identifier: LGPL-2.1-or-later
#include "send-queue.h"

#include <algorithm>
#include <utility>

namespace trackpublish {

namespace {

template <typename Documents>
auto findSend(Documents &documents, std::uint64_t sequence, std::uint64_t attempt) {
  return std::find_if(documents.begin(), documents.end(), [&](const SendQueue::Document &d) {
    return d.sequence == sequence && d.attempt == attempt;
  });
}

}  // namespace

bool SendQueue::add(std::string topic, std::string payload) {
  waiting_.push_back(Document{nextSequence_++, std::move(topic), std::move(payload)});
  // In-flight documents may still be acknowledged: only waiting ones are dropped.
  if (size() <= maxQueued_ || waiting_.size() <= 1) return false;
  waiting_.pop_front();
  ++dropped_;
  return true;
}

std::optional<SendQueue::Document> SendQueue::send(TimePoint now, std::size_t window) {
  if (waiting_.empty() || inFlight_.size() >= window) return std::nullopt;
  inFlight_.push_back(std::move(waiting_.front()));
  waiting_.pop_front();
  inFlight_.back().sentAt = now;
  inFlight_.back().attempt = ++sendsMade_;
  return inFlight_.back();
}

bool SendQueue::acknowledged(std::uint64_t sequence, std::uint64_t attempt) {
  const auto it = findSend(inFlight_, sequence, attempt);
  if (it == inFlight_.end()) return false;
  inFlight_.erase(it);
  return true;
}

void SendQueue::failed(std::uint64_t sequence, std::uint64_t attempt) {
  const auto it = findSend(inFlight_, sequence, attempt);
  if (it == inFlight_.end()) return;  // an answer to an earlier send: the new send stands
  Document document = std::move(*it);
  inFlight_.erase(it);
  wait(std::move(document));
}

void SendQueue::requeueInFlight() {
  while (!inFlight_.empty()) {
    wait(std::move(inFlight_.back()));
    inFlight_.pop_back();
  }
}

std::optional<SendQueue::TimePoint> SendQueue::oldestSentAt() const {
  if (inFlight_.empty()) return std::nullopt;
  return inFlight_.front().sentAt;
}

// Merged by sequence: a send that failed before its connection was declared lost waits already when the
// rest of that connection's sends come back, and must still go first.
void SendQueue::wait(Document document) {
  const auto at =
      std::upper_bound(waiting_.begin(), waiting_.end(), document.sequence,
                       [](std::uint64_t sequence, const Document &d) { return sequence < d.sequence; });
  waiting_.insert(at, std::move(document));
}

}  // namespace trackpublish
