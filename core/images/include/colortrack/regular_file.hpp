// SPDX-License-Identifier: LGPL-2.1-or-later
// Input files read without ever blocking: a path named as an image to read must be a regular file.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "colortrack/status.hpp"

namespace colortrack {

// The whole of `path`, or why not. The open never waits (O_NONBLOCK: a FIFO without a writer would otherwise
// hold the caller in open() for ever), and anything but a regular file of at most `maxBytes` is refused.
Result<std::vector<unsigned char>> readRegularFile(const std::string &path, std::size_t maxBytes);

}  // namespace colortrack
