// SPDX-License-Identifier: LGPL-2.1-or-later
// Input files read without ever blocking: a path named as an image to read must be a regular file.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace colortrack {

// Reads the whole of `path` into `bytes`. The open never waits (O_NONBLOCK: a FIFO without a writer would
// otherwise hold the caller in open() for ever), and anything but a regular file of at most `maxBytes` is
// refused. Returns false with the reason in `why`.
bool readRegularFile(const std::string &path, std::size_t maxBytes, std::vector<unsigned char> &bytes,
                     std::string &why);

}  // namespace colortrack
