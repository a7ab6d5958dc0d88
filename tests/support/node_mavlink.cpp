// SPDX-License-Identifier: LGPL-2.1-or-later
#include "node_mavlink.hpp"

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

namespace colortrack::node_mavlink {

namespace {

std::string env(const char *name) {
  const char *value = std::getenv(name);
  return value ? value : "";
}

// The script's output lines for `arguments`, its input from `input` (a file) when given.
std::vector<std::string> run(const std::string &arguments, const std::string &input = "") {
  std::string command = "'" + env("MAVLINK_NODE") + "' '" + env("MAVLINK_CHECK") + "' " + arguments;
  if (!input.empty()) command += " < '" + input + "'";
  std::vector<std::string> lines;
  FILE *pipe = popen(command.c_str(), "r");
  if (!pipe) return lines;
  std::string line;
  char chunk[4096];
  while (std::fgets(chunk, sizeof chunk, pipe)) {
    line += chunk;
    if (!line.empty() && line.back() == '\n') {
      line.pop_back();
      lines.push_back(line);
      line.clear();
    }
  }
  if (pclose(pipe) != 0) lines.clear();
  return lines;
}

std::string temporaryFile() {
  char path[] = "/tmp/colortrack-mavlink-XXXXXX";
  const int fd = mkstemp(path);
  if (fd >= 0) close(fd);
  return path;
}

}  // namespace

bool available(std::string &why) {
  const std::string node = env("MAVLINK_NODE"), script = env("MAVLINK_CHECK");
  if (node.empty() || access(node.c_str(), X_OK) != 0) {
    why = "node is not installed (tests/bootstrap.sh installs it)";
    return false;
  }
  const std::string modules = script.substr(0, script.rfind('/')) + "/node_modules/node-mavlink";
  if (script.empty() || access(modules.c_str(), R_OK) != 0) {
    why = "node-mavlink is not installed in tests/mavlink (tests/bootstrap.sh runs npm ci there)";
    return false;
  }
  return true;
}

std::vector<std::vector<std::uint8_t>> encode(const std::vector<std::string> &cases) {
  const std::string input = temporaryFile();
  {
    std::ofstream out(input);
    for (const std::string &c : cases) out << c << "\n";
  }
  std::vector<std::vector<std::uint8_t>> frames;
  for (const std::string &hex : run("encode", input)) {
    std::vector<std::uint8_t> bytes;
    for (std::size_t i = 0; i + 1 < hex.size(); i += 2)
      bytes.push_back(static_cast<std::uint8_t>(std::strtoul(hex.substr(i, 2).c_str(), nullptr, 16)));
    frames.push_back(bytes);
  }
  std::remove(input.c_str());
  return frames;
}

std::vector<std::string> decode(const std::vector<Datagram> &datagrams) {
  const std::string path = temporaryFile();
  {
    // The records mavlink-check.cjs reads: float64 time, uint32 length, bytes (little-endian, as here).
    std::ofstream out(path, std::ios::binary);
    for (const Datagram &d : datagrams) {
      const std::uint32_t length = static_cast<std::uint32_t>(d.bytes.size());
      out.write(reinterpret_cast<const char *>(&d.time), sizeof d.time);
      out.write(reinterpret_cast<const char *>(&length), sizeof length);
      out.write(reinterpret_cast<const char *>(d.bytes.data()), length);
    }
  }
  std::vector<std::string> lines = run("decode '" + path + "'");
  std::remove(path.c_str());
  return lines;
}

}  // namespace colortrack::node_mavlink
