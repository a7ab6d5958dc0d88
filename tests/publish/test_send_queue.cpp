// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's SendQueue alone (GoogleTest, no broker): the order in which documents go to the broker
// whatever order Paho answers in. A failed send followed by the loss of its connection once put the later
// documents in flight ahead of the failed one (frame 61 reached a subscriber before frame 60).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "send-queue.h"

using trackpublish::SendQueue;

namespace {

const SendQueue::TimePoint kNow{};

SendQueue withDocuments(int count, std::size_t maxQueued = 100) {
  SendQueue queue(maxQueued);
  for (int i = 0; i < count; ++i) queue.add("t", std::to_string(i));
  return queue;
}

// Sends everything the window allows; the documents' sequences and attempts, in the order sent.
std::vector<SendQueue::Document> sendAll(SendQueue &queue, std::size_t window = 32) {
  std::vector<SendQueue::Document> sent;
  while (auto document = queue.send(kNow, window)) sent.push_back(*document);
  return sent;
}

std::vector<std::uint64_t> sequencesOf(const std::vector<SendQueue::Document> &documents) {
  std::vector<std::uint64_t> sequences;
  for (const auto &d : documents) sequences.push_back(d.sequence);
  return sequences;
}

using Sequences = std::vector<std::uint64_t>;

}  // namespace

TEST(SendQueue, SendsInOrderWithinTheWindow) {
  SendQueue queue = withDocuments(5);
  const auto first = sendAll(queue, 3);
  EXPECT_EQ(sequencesOf(first), (Sequences{0, 1, 2}));
  EXPECT_EQ(first[1].payload, "1");
  EXPECT_TRUE(queue.acknowledged(0, first[0].attempt));
  EXPECT_EQ(sequencesOf(sendAll(queue, 3)), (Sequences{3}));
  EXPECT_EQ(queue.size(), 4u);
}

TEST(SendQueue, ALostConnectionResendsFromTheOldestUnacknowledged) {
  SendQueue queue = withDocuments(5);
  const auto sent = sendAll(queue);
  EXPECT_TRUE(queue.acknowledged(1, sent[1].attempt));
  queue.requeueInFlight();
  EXPECT_EQ(sequencesOf(sendAll(queue)), (Sequences{0, 2, 3, 4}));
}

// The race behind the flaky broker-restart test: Paho fails one send, and only then reports the connection
// lost, which sends the rest of that connection's documents back.
TEST(SendQueue, AFailedSendBeforeTheLossStillGoesFirst) {
  SendQueue queue = withDocuments(5);
  const auto sent = sendAll(queue);
  queue.failed(0, sent[0].attempt);
  queue.requeueInFlight();
  EXPECT_EQ(sequencesOf(sendAll(queue)), (Sequences{0, 1, 2, 3, 4}));
}

TEST(SendQueue, FailuresAnsweredInAnyOrderKeepTheOrder) {
  SendQueue queue = withDocuments(6);
  const auto sent = sendAll(queue);
  queue.failed(3, sent[3].attempt);
  queue.failed(1, sent[1].attempt);
  EXPECT_TRUE(queue.acknowledged(2, sent[2].attempt));
  queue.failed(5, sent[5].attempt);
  queue.requeueInFlight();
  EXPECT_EQ(sequencesOf(sendAll(queue)), (Sequences{0, 1, 3, 4, 5}));
}

TEST(SendQueue, AnAnswerToAnEarlierSendIsStale) {
  SendQueue queue = withDocuments(1);
  const auto first = sendAll(queue);
  queue.requeueInFlight();
  const auto second = sendAll(queue);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_NE(second[0].attempt, first[0].attempt);
  queue.failed(0, first[0].attempt);  // the old connection's late answer: ignored
  EXPECT_EQ(queue.waiting(), 0u);
  EXPECT_FALSE(queue.acknowledged(0, first[0].attempt));
  EXPECT_TRUE(queue.acknowledged(0, second[0].attempt));
  EXPECT_TRUE(queue.empty());
}

TEST(SendQueue, DropsTheOldestWaitingNeverOneInFlight) {
  SendQueue queue = withDocuments(2, 3);
  sendAll(queue);
  EXPECT_FALSE(queue.add("t", "2"));
  EXPECT_TRUE(queue.add("t", "3"));
  EXPECT_TRUE(queue.add("t", "4"));
  EXPECT_EQ(queue.dropped(), 2u);
  EXPECT_EQ(queue.size(), 3u);
  queue.requeueInFlight();
  EXPECT_EQ(sequencesOf(sendAll(queue)), (Sequences{0, 1, 4}));
}

TEST(SendQueue, TellsSinceWhenTheOldestSendWaits) {
  SendQueue queue = withDocuments(2);
  EXPECT_FALSE(queue.oldestSentAt());
  const SendQueue::TimePoint early = kNow + std::chrono::seconds(1), late = early + std::chrono::seconds(1);
  const auto first = queue.send(early, 32);
  queue.send(late, 32);
  EXPECT_EQ(queue.oldestSentAt(), early);
  queue.acknowledged(0, first->attempt);
  EXPECT_EQ(queue.oldestSentAt(), late);
}
