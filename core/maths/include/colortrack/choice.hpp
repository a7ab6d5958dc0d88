// SPDX-License-Identifier: LGPL-2.1-or-later
// One value of an enumerated choice (a controller, a protocol, a lock-on rule...), declared once as a row of
// its enum's table: the value, the short name a user types and what it means. The elements' enum types
// (gst-inspect-1.0, gst-launch-1.0 names) are generated from these tables, so a new value is one row.
#pragma once

#include <cstddef>

namespace colortrack {

template <typename E>
struct Choice {
  E value;
  const char *nick;
  const char *description;
};

// The nick of `value` in `choices`, or "?" for a value not in the table.
template <typename E, std::size_t N>
constexpr const char *nickOf(const Choice<E> (&choices)[N], E value) {
  for (const Choice<E> &c : choices)
    if (c.value == value) return c.nick;
  return "?";
}

}  // namespace colortrack
