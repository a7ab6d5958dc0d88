// Registration of the elements' enum and flags GTypes: one macro per kind, so each type is its list of values
// and nothing else.
#pragma once

#include <glib-object.h>

#include <cstddef>

#include "colortrack/choice.hpp"

namespace gstglue {

// A GEnum registered from a core table (colortrack/choice.hpp): each row's value, description and nick.
// The values array lives as long as the type does: for the process.
template <typename E, std::size_t N>
GType registerChoices(const char *name, const colortrack::Choice<E> (&choices)[N]) {
  auto *values = new GEnumValue[N + 1];
  for (std::size_t i = 0; i < N; ++i)
    values[i] = {static_cast<gint>(choices[i].value), choices[i].description, choices[i].nick};
  values[N] = {0, nullptr, nullptr};
  return g_enum_register_static(name, values);
}

}  // namespace gstglue

// Defines `GType function(void)` registering the enum `name` from the core table `choices`.
#define COLORTRACK_DEFINE_CHOICE_TYPE(function, name, choices)                                       \
  GType function(void) {                                                                             \
    static gsize type = 0;                                                                           \
    if (g_once_init_enter(&type)) g_once_init_leave(&type, gstglue::registerChoices(name, choices)); \
    return type;                                                                                     \
  }

// Defines `GType function(void)` registering the enum `name` with the given GEnumValue entries (no
// terminator).
#define COLORTRACK_DEFINE_ENUM_TYPE(function, name, ...)                                          \
  GType function(void) {                                                                          \
    static gsize type = 0;                                                                        \
    static const GEnumValue values[] = {__VA_ARGS__, {0, nullptr, nullptr}};                      \
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static(name, values)); \
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
