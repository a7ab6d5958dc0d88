// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's file side: documents handed over by the streaming thread, appended one line each by a
// worker thread, so a slow disk, a full pty or a FIFO whose reader stops reading never holds the video (as
// MQTT's queue does for the network). The queue is bounded like MQTT's: past `maxQueued` documents waiting
// the oldest are dropped and counted. No GStreamer here.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <mutex>
#include <string>
#include <thread>

namespace trackpublish {

class DocumentFile {
 public:
  // Writes to `fd`, best opened non-blocking (then a write that cannot go on waits in poll(), and stop()
  // keeps its deadline); closes it at stop when `owned` (stdout is not).
  DocumentFile(int fd, bool owned, std::size_t maxQueued);
  ~DocumentFile();  // stop(0)
  DocumentFile(const DocumentFile &) = delete;
  DocumentFile &operator=(const DocumentFile &) = delete;

  // Queues a document (a line is written for it); never waits for the file. Nothing is queued after a
  // write failed.
  void write(std::string document);
  // Waits up to `timeout` until everything queued is written; true when it is (false after a failure).
  bool waitWritten(std::chrono::milliseconds timeout);
  // Writes what is queued for up to `drain` more, then drops the rest and closes an owned descriptor.
  void stop(std::chrono::milliseconds drain);

  std::string failure() const;  // why a write failed (the first failure), empty while none has
  std::uint64_t droppedCount() const;
  std::size_t queued() const;  // waiting or being written
  std::uint64_t written() const;

 private:
  void run();
  // Writes all of `line`; false with `why` on an error, or with an empty `why` when the stop's drain time
  // ran out first.
  bool writeLine(const std::string &line, std::string &why);
  bool pastDeadline() const;

  int fd_;
  const bool owned_;
  const std::size_t maxQueued_;
  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<std::string> queue_;
  bool writing_ = false, stopping_ = false;
  std::chrono::steady_clock::time_point deadline_;
  std::string failure_;
  std::uint64_t dropped_ = 0, written_ = 0;
  std::thread worker_;
};

}  // namespace trackpublish
