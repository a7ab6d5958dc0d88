// SPDX-License-Identifier: LGPL-2.1-or-later
// A pseudo-terminal standing in for a serial port: robotctl writes to its slave, the test reads the master.
// Shared by the robotctl tests and the closed-loop robot simulation; include it after gstcheck.h (it uses
// fail_unless).
#pragma once

#include <fcntl.h>
#include <stdlib.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include <gst/check/gstcheck.h>

namespace colortrack::gst_test_util {

// Without pseudo-terminals (a container that does not mount /dev/pts) no test here can run: the binary says
// SKIPPED, naming what is missing, and exits 77 (meson's "skipped") before its first test.
inline const bool kPseudoTerminalsAvailable = [] {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  const char *name = master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0 ? ptsname(master) : nullptr;
  const bool usable = name && access(name, R_OK | W_OK) == 0;
  if (master >= 0) close(master);
  if (!usable) {
    std::fprintf(stderr,
                 "SKIPPED: no pseudo-terminals to stand in for a serial port (is /dev/pts mounted? "
                 "mount -t devpts devpts /dev/pts)\n");
    std::exit(77);
  }
  return true;
}();

struct Pty {
  int master = -1;
  std::string slave;
  Pty() {
    master = posix_openpt(O_RDWR | O_NOCTTY | O_NONBLOCK);
    fail_unless(master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0);
    slave = ptsname(master);
    // Held open so that the element closing its end does not hang up the pty (the master would read EIO
    // and lose what was written last).
    keepSlave = open(slave.c_str(), O_RDWR | O_NOCTTY);
    fail_unless(keepSlave >= 0);
  }
  ~Pty() {
    close(keepSlave);
    close(master);
  }
  int keepSlave = -1;
  std::vector<std::uint8_t> drain() const {
    std::vector<std::uint8_t> bytes;
    std::uint8_t chunk[4096];
    ssize_t n;
    while ((n = read(master, chunk, sizeof chunk)) > 0) bytes.insert(bytes.end(), chunk, chunk + n);
    return bytes;
  }
  // Reads for `ms` milliseconds.
  std::vector<std::uint8_t> readFor(int ms) const {
    std::vector<std::uint8_t> bytes;
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(ms);
    while (std::chrono::steady_clock::now() < end) {
      const std::vector<std::uint8_t> more = drain();
      bytes.insert(bytes.end(), more.begin(), more.end());
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
    }
    return bytes;
  }
  // Milliseconds until `byte` arrives (-1 after timeoutMs); the bytes before it are appended to `seen`.
  int waitForByte(std::uint8_t byte, int timeoutMs, std::vector<std::uint8_t> *seen = nullptr) const {
    const auto start = std::chrono::steady_clock::now();
    while (std::chrono::steady_clock::now() - start < std::chrono::milliseconds(timeoutMs)) {
      for (std::uint8_t b : drain()) {
        if (b == byte)
          return static_cast<int>(
              std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::steady_clock::now() - start)
                  .count());
        if (seen) seen->push_back(b);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    return -1;
  }
};

}  // namespace colortrack::gst_test_util
