// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's DocumentFile alone (GoogleTest, no GStreamer): whole lines in order, a reader that stops
// reading fills the bounded queue (the oldest dropped and counted) and never holds write() or stop() past its
// drain time, and a write that fails is reported.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <string>

#include "document-file.h"

using std::chrono::milliseconds;
using trackpublish::DocumentFile;

namespace {

struct Pipe {
  int read = -1, write = -1;
  Pipe() {
    int fds[2];
    EXPECT_EQ(pipe2(fds, O_NONBLOCK | O_CLOEXEC), 0);
    read = fds[0], write = fds[1];
  }
  ~Pipe() { close(read); }
  std::string drain() const {
    std::string text;
    char buffer[4096];
    for (ssize_t n; (n = ::read(read, buffer, sizeof buffer)) > 0;)
      text.append(buffer, static_cast<std::size_t>(n));
    return text;
  }
};

}  // namespace

TEST(DocumentFile, WritesWholeLinesInOrder) {
  Pipe pipe;
  DocumentFile file(pipe.write, true, 100);
  for (int i = 0; i < 50; ++i) file.write("{\"frame\":" + std::to_string(i) + "}");
  EXPECT_TRUE(file.waitWritten(milliseconds(5000)));
  EXPECT_EQ(file.written(), 50u);
  EXPECT_EQ(file.droppedCount(), 0u);
  std::string expected;
  for (int i = 0; i < 50; ++i) expected += "{\"frame\":" + std::to_string(i) + "}\n";
  EXPECT_EQ(pipe.drain(), expected);
  file.stop(milliseconds(0));
  EXPECT_TRUE(file.failure().empty());
}

TEST(DocumentFile, AReaderThatStopsNeverHoldsTheWriterOrTheStop) {
  Pipe pipe;  // never read
  DocumentFile file(pipe.write, true, 10);
  const std::string document(1000, 'x');
  // One at a time until the pipe is full (64 KiB, so about 65 documents): the writer thread is then stuck.
  int accepted = 0;
  while (accepted < 1000) {
    file.write(document);
    ++accepted;
    if (!file.waitWritten(milliseconds(2000))) break;  // 2 s: only a full pipe takes that long
  }
  ASSERT_LT(accepted, 1000) << "the pipe never filled";
  // More documents: write() returns at once; past 10 waiting the oldest are dropped.
  for (int i = 0; i < 50; ++i) file.write(document);
  const std::uint64_t total = accepted + 50;
  EXPECT_EQ(file.queued(), 11u);  // 10 waiting, 1 being written
  EXPECT_EQ(file.droppedCount(), 40u);
  const auto start = std::chrono::steady_clock::now();
  file.stop(milliseconds(100));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("stop with a stalled reader after %d documents: %.3f s (drain 0.1 s); %zu left, %llu dropped\n",
              accepted, seconds, file.queued(), static_cast<unsigned long long>(file.droppedCount()));
  // What the drain time did not write is counted, not lost silently.
  EXPECT_EQ(file.queued(), 11u);
  EXPECT_EQ(file.written() + file.queued() + file.droppedCount(), total);
}

TEST(DocumentFile, AFailedWriteIsReported) {
  const int fd = open("/dev/full", O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) GTEST_SKIP() << "no /dev/full";
  DocumentFile file(fd, true, 10);
  file.write("{}");
  EXPECT_FALSE(file.waitWritten(milliseconds(5000)));
  EXPECT_NE(file.failure(), "");
  file.write("{}");  // nothing more is queued
  EXPECT_EQ(file.queued(), 0u);
  file.stop(milliseconds(0));
}
