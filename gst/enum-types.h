// Registration of the elements' enum and flags GTypes: one macro per kind, so each type is its list of values
// and nothing else.
#pragma once

#include <glib-object.h>

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
