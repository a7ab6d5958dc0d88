// SPDX-License-Identifier: LGPL-2.1-or-later
#include "document-file.h"

#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace trackpublish {

namespace {

using Clock = std::chrono::steady_clock;

// How long one wait for a file that takes no more lasts before the stop's deadline is looked at again.
constexpr int kPollMs = 50;

}  // namespace

DocumentFile::DocumentFile(int fd, bool owned, std::size_t maxQueued)
    : fd_(fd), owned_(owned), maxQueued_(maxQueued == 0 ? 1 : maxQueued), worker_([this] { run(); }) {}

DocumentFile::~DocumentFile() {
  stop(std::chrono::milliseconds(0));
}

void DocumentFile::write(std::string document) {
  document.push_back('\n');
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!failure_.empty() || stopping_) return;
    queue_.push_back(std::move(document));
    while (queue_.size() > maxQueued_) {
      queue_.pop_front();
      ++dropped_;
    }
  }
  wake_.notify_one();
}

bool DocumentFile::waitWritten(std::chrono::milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  idle_.wait_for(lock, timeout, [this] { return (queue_.empty() && !writing_) || !failure_.empty(); });
  return queue_.empty() && !writing_ && failure_.empty();
}

void DocumentFile::stop(std::chrono::milliseconds drain) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!stopping_) {
      stopping_ = true;
      deadline_ = Clock::now() + drain;
    }
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
  if (owned_ && fd_ >= 0) close(fd_);
  fd_ = -1;
}

std::string DocumentFile::failure() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return failure_;
}

std::uint64_t DocumentFile::droppedCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return dropped_;
}

std::size_t DocumentFile::queued() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return queue_.size() + (writing_ ? 1 : 0);
}

std::uint64_t DocumentFile::written() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return written_;
}

bool DocumentFile::pastDeadline() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return stopping_ && Clock::now() >= deadline_;
}

bool DocumentFile::writeLine(const std::string &line, std::string &why) {
  std::size_t done = 0;
  while (done < line.size()) {
    const ssize_t n = ::write(fd_, line.data() + done, line.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) {
      // The reader is behind: wait for room, but not past the stop's deadline.
      if (pastDeadline()) return false;
      pollfd p{fd_, POLLOUT, 0};
      poll(&p, 1, kPollMs);
      continue;
    }
    why = n < 0 ? std::strerror(errno) : "nothing written";
    return false;
  }
  return true;
}

void DocumentFile::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
    if (queue_.empty()) break;  // stopping, and everything written
    if (stopping_ && Clock::now() >= deadline_) break;
    std::string line = std::move(queue_.front());
    queue_.pop_front();
    writing_ = true;
    lock.unlock();
    std::string why;
    const bool ok = writeLine(line, why);
    lock.lock();
    writing_ = false;
    if (ok) ++written_;
    if (!ok && why.empty()) {
      // The stop's drain time ran out: what is left stays counted in queued().
      queue_.push_front(std::move(line));
      break;
    }
    if (!ok) {
      if (failure_.empty()) failure_ = why;
      queue_.clear();  // a file that failed takes no more
    }
    idle_.notify_all();
  }
  idle_.notify_all();
}

}  // namespace trackpublish
