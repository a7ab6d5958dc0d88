// SPDX-License-Identifier: LGPL-2.1-or-later
// For tests that check both what a call answers and why: whether a Status or Result is ok, with its message
// (empty when ok) in `why`.
#pragma once

#include <string>

#include "colortrack/status.hpp"

inline bool okOr(const colortrack::Status &status, std::string &why) {
  why = status.message();
  return status.ok();
}

template <typename T>
bool okOr(const colortrack::Result<T> &result, std::string &why) {
  why = result.error();
  return result.ok();
}
