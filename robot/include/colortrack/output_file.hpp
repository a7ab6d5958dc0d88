// SPDX-License-Identifier: LGPL-2.1-or-later
// Output files (robotctl's and trackpublish's location): opened for writing without ever blocking the thread
// that opens them.
#pragma once

#include <sys/types.h>

#include <string>

#include "colortrack/status.hpp"

namespace colortrack {

// "regular file", "FIFO", "character device", ... for the S_IFMT bits of a mode.
std::string fileKindName(mode_t kind);

// Opens `path` for writing with O_NONBLOCK (so a FIFO without a reader fails at once instead of waiting in
// open() for one), close-on-exec and no controlling terminal, plus `extraFlags` (O_CREAT, O_APPEND, ...).
// Only a regular file, a character device (a serial port, a pty) or a FIFO is accepted. Returns the
// descriptor, still non-blocking, and its kind in `kind`; or -1 with the reason in `why`.
int openOutputFile(const std::string &path, int extraFlags, mode_t &kind, std::string &why);

// Whether `location` starts like a URL or a drive letter, "scheme:" (letters, digits, + - . after a first
// letter): such a string is an address the element cannot reach, never a file name it should create in the
// working directory ("udp:127.0.0.1:14550", "tcp://...", "C:\\robot.txt"). A file whose name really has a
// colon is written "./udp:x".
bool looksLikeUrl(const std::string &location);

// Why `path` cannot be an output location, judged without opening or creating anything (so it may be
// checked when the property is set): it exists and is not a regular file, character device or FIFO, or it
// does not exist and neither does its folder. Ok when it may be: whether a FIFO has a reader, or a file
// can be written, is known only when it is opened.
Status checkOutputPath(const std::string &path);

}  // namespace colortrack
