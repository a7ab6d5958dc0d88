// SPDX-License-Identifier: LGPL-2.1-or-later
// The tests' way to node-mavlink, an independent MAVLink implementation (tests/mavlink/mavlink-check.cjs,
// installed by tests/bootstrap.sh): frames it encodes, and its decoding of captured datagrams. meson gives
// the paths in the environment (MAVLINK_NODE, MAVLINK_CHECK).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace colortrack::node_mavlink {

// The exit status of a test that cannot run here (meson's "skipped").
constexpr int kSkip = 77;

// Whether node and node-mavlink are there; `why` says what is missing.
bool available(std::string &why);

// One frame per case (a JSON object, see mavlink-check.cjs), as bytes; empty when node failed.
std::vector<std::vector<std::uint8_t>> encode(const std::vector<std::string> &cases);

// A captured datagram and when it arrived (s, monotonic).
struct Datagram {
  double time = 0;
  std::vector<std::uint8_t> bytes;
};
// node-mavlink's decoding of the datagrams: one JSON line per frame (see mavlink-check.cjs).
std::vector<std::string> decode(const std::vector<Datagram> &datagrams);

}  // namespace colortrack::node_mavlink
