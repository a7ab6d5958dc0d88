// SPDX-License-Identifier: LGPL-2.1-or-later
#include "colortrack/robot_port.hpp"

#include "colortrack/output_file.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <system_error>

#include <libserialport.h>

namespace robotctl {

namespace {

using colortrack::fileKindName;

using Clock = std::chrono::steady_clock;

bool fail(std::string &why) {
  why = std::generic_category().message(errno);  // strerror without its shared buffer
  return false;
}

// The writer thread blocks SIGPIPE (a FIFO or pipe whose reader went away); take the pending one.
void consumeSigpipe() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGPIPE);
  struct timespec zero = {0, 0};
  sigtimedwait(&set, nullptr, &zero);
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// FilePort

colortrack::Status FilePort::open() {
  std::string why;
  return openWithReason(why) ? colortrack::Status() : colortrack::Status::failure(why);
}

bool FilePort::openWithReason(std::string &why) {
  if (path_ == "-") {
    fd_ = dup(STDOUT_FILENO);  // our own descriptor, so closing it leaves stdout alone
    if (fd_ < 0) return fail(why);
    return true;
  }
  struct stat st;
  const bool exists = stat(path_.c_str(), &st) == 0;
  int flags = 0;
  if (!openedBefore_) {
    // Only the first open creates, and only a regular file (the user named a file to write to); it starts
    // empty.
    if (!exists || S_ISREG(st.st_mode)) flags |= O_CREAT | O_TRUNC;
  } else {
    // A reopen waits for the kind of file it lost. An unplugged adapter's path (a udev symlink) or a FIFO
    // its reader removed must never become a regular file that swallows the robot's commands.
    if (!exists) {
      why = "it is gone; waiting for the " + fileKindName(kind_) + " to come back";
      return false;
    }
    if ((st.st_mode & S_IFMT) != kind_) {
      why = "it is now " + fileKindName(st.st_mode & S_IFMT) + ", not the " + fileKindName(kind_) +
            " it was; waiting for that to come back";
      return false;
    }
    if (S_ISREG(st.st_mode)) flags |= O_APPEND;  // a regular file reopened is appended to
  }
  mode_t opened = 0;
  fd_ = colortrack::openOutputFile(path_, flags, opened, why);
  if (fd_ < 0) return false;
  // Checked again on the descriptor: the path may have changed between stat() and open().
  if (openedBefore_ && opened != kind_) {
    why = "it is now " + fileKindName(opened) + ", not the " + fileKindName(kind_) + " it was";
    close();
    return false;
  }
  kind_ = opened;
  openedBefore_ = true;
  // A terminal (a pty) would turn "\n" into "\r\n" and echo: send the bytes as they are.
  struct termios tio;
  if (isatty(fd_) && tcgetattr(fd_, &tio) == 0) {
    cfmakeraw(&tio);
    tcsetattr(fd_, TCSANOW, &tio);
  }
  return true;
}

void FilePort::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

WriteResult FilePort::write(const std::vector<std::uint8_t> &bytes, int timeoutMs, std::size_t &done,
                            std::string &why) {
  const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
  done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd_, bytes.data() + done, bytes.size() - done);
    if (n > 0) {
      done += static_cast<std::size_t>(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK) {
      if (errno == EPIPE) consumeSigpipe();
      fail(why);
      return WriteResult::Failed;
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return WriteResult::Busy;
    struct pollfd pfd = {fd_, POLLOUT, 0};
    const int ready = poll(&pfd, 1, static_cast<int>(left));
    if (ready == 0) return WriteResult::Busy;
    // POLLERR/POLLHUP: the next write reports the error.
  }
  return WriteResult::Written;
}

std::string FilePort::describe() const {
  return path_ == "-" ? "stdout (property 'location')" : "'" + path_ + "' (property 'location')";
}

// ---------------------------------------------------------------------------------------------------------
// SerialPort

namespace {

bool check(sp_return result, const char *what, std::string &why) {
  if (result >= 0) return true;
  char *message = result == SP_ERR_FAIL ? sp_last_error_message() : nullptr;
  why = std::string("could not ") + what + ": " +
        (message                 ? message
         : result == SP_ERR_SUPP ? "not supported by this port"
                                 : "invalid argument");
  if (message) sp_free_error_message(message);
  return false;
}

sp_parity toParity(Parity parity) {
  switch (parity) {
    case Parity::Odd:
      return SP_PARITY_ODD;
    case Parity::Even:
      return SP_PARITY_EVEN;
    case Parity::Mark:
      return SP_PARITY_MARK;
    case Parity::Space:
      return SP_PARITY_SPACE;
    case Parity::None:
      break;
  }
  return SP_PARITY_NONE;
}

sp_flowcontrol toFlowControl(FlowControl flow) {
  switch (flow) {
    case FlowControl::XonXoff:
      return SP_FLOWCONTROL_XONXOFF;
    case FlowControl::RtsCts:
      return SP_FLOWCONTROL_RTSCTS;
    case FlowControl::DtrDsr:
      return SP_FLOWCONTROL_DTRDSR;
    case FlowControl::None:
      break;
  }
  return SP_FLOWCONTROL_NONE;
}

// Why `path` (resolved) is no serial port libserialport knows. A pseudo-terminal, a FIFO or a file exists
// but belongs in 'location'; another character device is named as such.
std::string notASerialPort(const std::string &path) {
  struct stat info;
  if (stat(path.c_str(), &info) != 0) return "no such serial port";
  if (!S_ISCHR(info.st_mode) || path.rfind("/dev/pts/", 0) == 0)
    return "it exists but is not a serial port (a pseudo-terminal, a FIFO or a file goes in 'location' "
           "instead of 'device')";
  return "no such serial port (a character device libserialport does not know as one)";
}

}  // namespace

colortrack::Status SerialPort::open() {
  std::string why;
  return openWithReason(why) ? colortrack::Status() : colortrack::Status::failure(why);
}

bool SerialPort::openWithReason(std::string &why) {
  // libserialport looks a port up by its /dev name: a link (/dev/serial/by-id/...) is followed first.
  char *resolved = realpath(config_.device.c_str(), nullptr);
  const std::string name = resolved ? resolved : config_.device;
  free(resolved);
  if (sp_get_port_by_name(name.c_str(), &port_) != SP_OK) {
    port_ = nullptr;
    why = notASerialPort(name);
    return false;
  }
  if (!check(sp_open(port_, SP_MODE_WRITE), "open", why)) {
    sp_free_port(port_);
    port_ = nullptr;
    return false;
  }
  const bool configured =
      check(sp_set_baudrate(port_, static_cast<int>(config_.baudRate)), "set the baud rate", why) &&
      check(sp_set_bits(port_, config_.dataBits), "set the data bits", why) &&
      check(sp_set_parity(port_, toParity(config_.parity)), "set the parity", why) &&
      check(sp_set_stopbits(port_, config_.stopBits), "set the stop bits", why) &&
      check(sp_set_flowcontrol(port_, toFlowControl(config_.flowControl)), "set the flow control", why);
  if (!configured) close();
  return configured;
}

void SerialPort::close() {
  if (!port_) return;
  sp_close(port_);
  sp_free_port(port_);
  port_ = nullptr;
}

WriteResult SerialPort::write(const std::vector<std::uint8_t> &bytes, int timeoutMs, std::size_t &written,
                              std::string &why) {
  written = 0;
  // A timeout of 0 would block for ever in libserialport.
  const sp_return n =
      sp_blocking_write(port_, bytes.data(), bytes.size(), static_cast<unsigned>(std::max(timeoutMs, 1)));
  if (n < 0) {
    check(n, "write", why);
    return WriteResult::Failed;
  }
  written = static_cast<std::size_t>(n);
  return written == bytes.size() ? WriteResult::Written : WriteResult::Busy;
}

}  // namespace robotctl
