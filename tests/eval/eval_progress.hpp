// SPDX-License-Identifier: LGPL-2.1-or-later
// The lines a colortrack-eval user sees: a live progress line on a terminal, one line per finished run
// otherwise.
#pragma once

#include <unistd.h>

#include <cstdio>
#include <string>

namespace colortrack::eval {

class Progress {
 public:
  Progress() : live_(isatty(STDERR_FILENO)) {}
  void update(const std::string &line) {
    if (!live_) return;
    std::fprintf(stderr, "\r%-100.100s", line.c_str());
    std::fflush(stderr);
  }
  void finish(const std::string &line) {
    if (live_)
      std::fprintf(stderr, "\r%-100.100s\n", line.c_str());
    else
      std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
  }

 private:
  bool live_;
};

}  // namespace colortrack::eval
