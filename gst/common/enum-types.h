// SPDX-License-Identifier: LGPL-2.1-or-later
// Registration of the elements' enum and flags GTypes: an enum type is generated from the core table that
// declares its values; a flags type (colortrack's draw) is its list of values.
#pragma once

#include <glib-object.h>

#include <cstddef>
#include <iterator>

namespace gstglue {

// A GEnum registered from a core table: rows with a value, a nick and a description (colortrack::Choice, or a
// registry's descriptor). The values array lives as long as the type does: for the process.
template <typename Rows>
GType registerChoices(const char *name, const Rows &rows) {
  const std::size_t n = static_cast<std::size_t>(std::end(rows) - std::begin(rows));
  auto *values = new GEnumValue[n + 1];
  std::size_t i = 0;
  for (const auto &row : rows) values[i++] = {static_cast<gint>(row.value), row.description, row.nick};
  values[n] = {0, nullptr, nullptr};
  return g_enum_register_static(name, values);
}

}  // namespace gstglue

// Defines `GType function(void)` registering the enum `name` from the core table `rows`.
#define COLORTRACK_DEFINE_CHOICE_TYPE(function, name, rows)                                       \
  GType function(void) {                                                                          \
    static gsize type = 0;                                                                        \
    if (g_once_init_enter(&type)) g_once_init_leave(&type, gstglue::registerChoices(name, rows)); \
    return type;                                                                                  \
  }

// The same for a flags type (GFlagsValue entries).
#define COLORTRACK_DEFINE_FLAGS_TYPE(function, name, ...)                                          \
  GType function(void) {                                                                           \
    static gsize type = 0;                                                                         \
    static const GFlagsValue values[] = {__VA_ARGS__, {0, nullptr, nullptr}};                      \
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_flags_register_static(name, values)); \
    return type;                                                                                   \
  }
