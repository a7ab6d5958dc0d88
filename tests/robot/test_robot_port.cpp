// SPDX-License-Identifier: LGPL-2.1-or-later
// The ports robotctl writes through (robot/src/robot_port.cpp), without the element: a regular file, a FIFO
// with and without a reader, a file that changes kind between opens, a directory, a serial port that is not
// there, and which port the settings name.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <stdlib.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "colortrack/port_choice.hpp"
#include "colortrack/robot_port.hpp"
#include "support/status_helpers.hpp"

namespace {

using robotctl::FilePort;
using robotctl::SerialConfig;
using robotctl::SerialPort;
using robotctl::WriteResult;

// A folder of its own, removed with what the test left in it.
struct TempDir {
  std::string path;
  TempDir() {
    char name[] = "/tmp/robot-port-XXXXXX";
    path = mkdtemp(name);
  }
  ~TempDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

std::string contents(const std::string &path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::vector<std::uint8_t> bytesOf(const std::string &text) {
  return {text.begin(), text.end()};
}

WriteResult write(FilePort &port, const std::string &text, std::size_t &written, std::string &why) {
  return port.write(bytesOf(text), 100, written, why);
}

TEST(FilePort, FirstOpenEmptiesAFileAndAReopenAppends) {
  TempDir dir;
  const std::string path = dir.path + "/robot.txt";
  std::ofstream(path) << "old commands\n";
  FilePort port(path);
  std::string why;
  std::size_t written = 0;
  ASSERT_TRUE(okOr(port.open(), why)) << why;
  ASSERT_EQ(write(port, "F\n", written, why), WriteResult::Written) << why;
  EXPECT_EQ(written, 2u);
  port.close();
  ASSERT_TRUE(okOr(port.open(), why)) << why;
  ASSERT_EQ(write(port, "S\n", written, why), WriteResult::Written) << why;
  port.close();
  EXPECT_EQ(contents(path), "F\nS\n");
}

TEST(FilePort, AFifoWithoutAReaderIsRefusedAtOnce) {
  TempDir dir;
  const std::string path = dir.path + "/fifo";
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  FilePort port(path);
  std::string why;
  EXPECT_FALSE(okOr(port.open(), why));
  EXPECT_NE(why.find("no process has it open for reading"), std::string::npos) << why;
}

// A reader that never reads: the pipe fills, and the write says Busy with how much went out instead of
// waiting past its timeout.
TEST(FilePort, AFullFifoIsBusyNotBlocking) {
  TempDir dir;
  const std::string path = dir.path + "/fifo";
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  const int reader = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
  ASSERT_GE(reader, 0);
  FilePort port(path);
  std::string why;
  ASSERT_TRUE(okOr(port.open(), why)) << why;
  const std::vector<std::uint8_t> block(1 << 20, 'x');  // more than any pipe buffer holds
  std::size_t written = 0;
  EXPECT_EQ(port.write(block, 50, written, why), WriteResult::Busy);
  EXPECT_GT(written, 0u);
  EXPECT_LT(written, block.size());
  port.close();
  ::close(reader);
}

// A FIFO whose reader removed it must never become a regular file that swallows the robot's commands.
TEST(FilePort, AReopenWaitsForTheKindOfFileItLost) {
  TempDir dir;
  const std::string path = dir.path + "/fifo";
  ASSERT_EQ(mkfifo(path.c_str(), 0600), 0);
  const int reader = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
  FilePort port(path);
  std::string why;
  ASSERT_TRUE(okOr(port.open(), why)) << why;
  port.close();
  ::close(reader);
  unlink(path.c_str());
  EXPECT_FALSE(okOr(port.open(), why));
  EXPECT_NE(why.find("it is gone"), std::string::npos) << why;
  std::ofstream(path) << "";
  EXPECT_FALSE(okOr(port.open(), why));
  EXPECT_NE(why.find("regular file"), std::string::npos) << why;
  EXPECT_EQ(contents(path), "");
}

TEST(FilePort, ADirectoryIsRefused) {
  TempDir dir;
  FilePort port(dir.path);
  std::string why;
  EXPECT_FALSE(okOr(port.open(), why));
  EXPECT_FALSE(why.empty());
}

// SerialPort cannot be opened on a pseudo-terminal (libserialport looks a port up in sysfs and answers "no
// such serial port" for /dev/pts/N), so only its refusal is tested here; a pty is written through FilePort
// (location=), which tests/gst/test_robotctl.cpp covers end to end.
TEST(SerialPort, AMissingDeviceIsNamedInTheError) {
  SerialConfig config;
  config.device = "/dev/ttyNO-SUCH-ADAPTER";
  SerialPort port(config);
  std::string why;
  EXPECT_FALSE(okOr(port.open(), why));
  EXPECT_EQ(why, "no such serial port");
  EXPECT_FALSE(port.isOpen());
  EXPECT_NE(port.describe().find("/dev/ttyNO-SUCH-ADAPTER"), std::string::npos);
}

// Issue 48: a pseudo-terminal (or a plain file) given as device= exists but is no serial port: the error
// says to use location=.
TEST(SerialPort, APseudoTerminalOrAFileIsSentToLocation) {
  const int master = posix_openpt(O_RDWR | O_NOCTTY);
  const bool pty = master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0;
  const std::string file =
      std::filesystem::temp_directory_path() / ("colortrack-not-a-serial-port-" + std::to_string(getpid()));
  std::ofstream(file).put('x');
  std::vector<std::string> devices = {file};
  if (pty) devices.push_back(ptsname(master));
  for (const std::string &device : devices) {
    SerialConfig config;
    config.device = device;
    SerialPort port(config);
    std::string why;
    EXPECT_FALSE(okOr(port.open(), why)) << device;
    EXPECT_NE(why.find("'location'"), std::string::npos) << device << ": " << why;
  }
  std::filesystem::remove(file);
  if (master >= 0) close(master);
}

// The device property wins over location; a udp:// location is a UDP destination; anything else a file.
TEST(PortChoice, DeviceThenUdpThenFile) {
  using robotctl::PortKind;
  EXPECT_EQ(robotctl::portKind("/dev/ttyUSB0", "udp://127.0.0.1:14550"), PortKind::Serial);
  EXPECT_EQ(robotctl::portKind("", "udp://127.0.0.1:14550"), PortKind::Udp);
  EXPECT_EQ(robotctl::portKind("", "/tmp/robot.txt"), PortKind::File);
  EXPECT_EQ(robotctl::portKind("", "-"), PortKind::File);
  const auto file = robotctl::makePort("", SerialConfig{}, "-");
  EXPECT_NE(file->describe().find("stdout"), std::string::npos);
  SerialConfig serial;
  serial.device = "/dev/ttyUSB0";
  const auto port = robotctl::makePort("/dev/ttyUSB0", serial, "");
  EXPECT_NE(port->describe().find("serial port '/dev/ttyUSB0'"), std::string::npos);
  EXPECT_FALSE(port->isOpen());
}

}  // namespace
