// SPDX-License-Identifier: LGPL-2.1-or-later
// Where robotctl (and trackpublish) may send: udp://HOST:PORT parsed exactly, URL-like and drive-letter
// strings never taken for file names, output paths judged without opening anything, and a FIFO without a
// reader refused at once. GoogleTest, no GStreamer.
#include <gtest/gtest.h>
#include <glib/gstdio.h>
#include <sys/stat.h>
#include <unistd.h>

#include <string>

#include "colortrack/output_file.hpp"
#include "colortrack/udp_port.hpp"
#include "support/status_helpers.hpp"

namespace robotctl {
namespace {

TEST(UdpLocation, ParsesHostsAndPorts) {
  const auto v4 = parseUdpLocation("udp://127.0.0.1:14550");
  ASSERT_TRUE(v4) << v4.error();
  EXPECT_EQ(v4->host, "127.0.0.1");
  EXPECT_EQ(v4->port, 14550);
  const auto v6 = parseUdpLocation("udp://[::1]:1");
  ASSERT_TRUE(v6) << v6.error();
  EXPECT_EQ(v6->host, "::1");
  EXPECT_EQ(v6->port, 1);
  const auto name = parseUdpLocation("udp://flight-controller.local:65535");
  ASSERT_TRUE(name) << name.error();
  EXPECT_EQ(name->port, 65535);
}

TEST(UdpLocation, RefusesWhatIsNotHostAndPort) {
  for (const char *bad : {"udp://127.0.0.1", "udp://127.0.0.1:", "udp://127.0.0.1:0", "udp://127.0.0.1:65536",
                          "udp://127.0.0.1:14550x", "udp://:14550", "udp://::1:14550", "udp://[::1]14550",
                          "udp://[::1", "udp://127.0.0.1:-1", "udp://127.0.0.1:999999"}) {
    std::string why;
    EXPECT_FALSE(okOr(parseUdpLocation(bad), why)) << bad;
    EXPECT_FALSE(why.empty()) << bad;
    EXPECT_FALSE(checkLocation(bad)) << bad;
  }
}

// Issue 48: a multicast group would hand the commands to every listener; the unicast address just below
// the groups is still taken.
TEST(UdpLocation, RefusesMulticastGroups) {
  for (const char *group : {"udp://224.0.0.1:14550", "udp://239.255.255.250:1900", "udp://[ff02::1]:14550"}) {
    std::string why;
    EXPECT_FALSE(okOr(parseUdpLocation(group), why)) << group;
    EXPECT_NE(why.find("multicast"), std::string::npos) << why;
    EXPECT_NE(checkLocation(group).message().find("multicast"), std::string::npos) << group;
  }
  std::string why;
  EXPECT_TRUE(okOr(parseUdpLocation("udp://223.255.255.255:14550"), why)) << why;
}

TEST(Location, UrlLikeAndDriveLettersAreNeverFiles) {
  for (const char *typo : {"udp:127.0.0.1:14550", "udp:/127.0.0.1:1", "tcp://127.0.0.1:5760",
                           "serial:/dev/tty", "C:robot.txt", "c:\\robot.txt", "mqtt+ssl://x:1"}) {
    EXPECT_TRUE(colortrack::looksLikeUrl(typo)) << typo;
    EXPECT_FALSE(checkLocation(typo)) << typo;
  }
  for (const char *file : {"./udp:x", "/tmp/a:b", "commands.txt", "-", "1:2", ":x", "dir/udp:x"}) {
    EXPECT_FALSE(colortrack::looksLikeUrl(file)) << file;
    EXPECT_TRUE(checkLocation(file)) << file << ": " << checkLocation(file).message();
  }
}

TEST(OutputPath, JudgedWithoutOpening) {
  gchar *dir = g_dir_make_tmp("locations-XXXXXX", nullptr);
  ASSERT_NE(dir, nullptr);
  const std::string fifo = std::string(dir) + "/fifo", file = std::string(dir) + "/file";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  ASSERT_TRUE(g_file_set_contents(file.c_str(), "x", 1, nullptr));
  EXPECT_TRUE(colortrack::checkOutputPath(file));
  EXPECT_TRUE(colortrack::checkOutputPath(fifo));  // a reader may come before the start
  EXPECT_TRUE(colortrack::checkOutputPath(std::string(dir) + "/new"));
  EXPECT_TRUE(colortrack::checkOutputPath("/dev/null"));
  EXPECT_FALSE(colortrack::checkOutputPath(dir));  // a directory
  EXPECT_FALSE(colortrack::checkOutputPath("/nonexistent-folder/x"));
  EXPECT_FALSE(colortrack::checkOutputPath(""));
  // Opening the FIFO without a reader fails at once instead of waiting in open().
  mode_t kind = 0;
  std::string why;
  EXPECT_EQ(colortrack::openOutputFile(fifo, 0, kind, why), -1);
  EXPECT_NE(why.find("reading"), std::string::npos) << why;
  g_unlink(fifo.c_str());
  g_unlink(file.c_str());
  g_rmdir(dir);
  g_free(dir);
}

}  // namespace
}  // namespace robotctl
