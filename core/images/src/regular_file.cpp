// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/regular_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace colortrack {

namespace {

// Closes the descriptor on every way out.
class Descriptor {
 public:
  explicit Descriptor(int fd) : fd_(fd) {}
  ~Descriptor() {
    if (fd_ >= 0) ::close(fd_);
  }
  Descriptor(const Descriptor &) = delete;
  Descriptor &operator=(const Descriptor &) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

Result<std::vector<unsigned char>> readRegularFile(const std::string &path, std::size_t maxBytes) {
  const Descriptor fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC));
  if (fd.get() < 0) {
    return Status::failure(std::strerror(errno));
  }
  struct stat st;
  if (fstat(fd.get(), &st) != 0) {
    return Status::failure(std::strerror(errno));
  }
  if (!S_ISREG(st.st_mode)) {
    return Status::failure(S_ISFIFO(st.st_mode)  ? "it is a FIFO, not a regular file"
                           : S_ISDIR(st.st_mode) ? "it is a directory, not a regular file"
                                                 : "it is a device or socket, not a regular file");
  }
  if (static_cast<std::size_t>(st.st_size) > maxBytes) {
    return Status::failure("it is " + std::to_string(st.st_size) + " bytes, more than the " +
                           std::to_string(maxBytes) + " accepted");
  }
  std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size));
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::read(fd.get(), bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      return Status::failure(std::strerror(errno));
    }
    if (n == 0) break;  // shortened while being read
    done += static_cast<std::size_t>(n);
  }
  bytes.resize(done);
  return bytes;
}

}  // namespace colortrack
