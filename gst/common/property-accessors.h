// SPDX-License-Identifier: LGPL-2.1-or-later
// The getters and setters a property table row takes for a field of an element's settings, chosen by the
// field's type, so that no row writes its own.
#pragma once

#include <gst/gst.h>

#include <string>
#include <type_traits>

namespace gstglue {

// The class a pointer to member belongs to, so that the field accessors below need only the member.
template <typename T>
struct MemberClass;
template <typename C, typename M>
struct MemberClass<M C::*> {
  using type = C;
};
template <auto field>
using ClassOf = typename MemberClass<decltype(field)>::type;

// The text of a string GValue, "" for NULL.
std::string textOf(const GValue *value);

// Table accessors of a std::string field of an element's settings.
template <auto field>
void getText(const ClassOf<field> &s, GValue *v) {
  g_value_set_string(v, (s.*field).c_str());
}
// An empty text reads back as NULL (a property whose default is "none").
template <auto field>
void getTextOrNull(const ClassOf<field> &s, GValue *v) {
  g_value_set_string(v, (s.*field).empty() ? nullptr : (s.*field).c_str());
}
template <auto field>
void setText(ClassOf<field> &s, const GValue *v) {
  s.*field = textOf(v);
}

// The settings class a path of members starts from, and the field the path leads to: s.*a.*b... (a field of
// a part of the settings, such as &Settings::tracker, &TrackerSettings::method).
template <auto first, auto...>
struct Root {
  using type = ClassOf<first>;
};
template <auto... path>
using RootOf = typename Root<path...>::type;
template <auto first, auto... rest, typename S>
decltype(auto) fieldAt(S &s) {
  if constexpr (sizeof...(rest) == 0)
    return (s.*first);
  else
    return fieldAt<rest...>(s.*first);
}

// Table accessors of a bool, gint, guint, double or enum field of an element's settings (or of one of its
// parts, through a path of members), by the field's type.
template <auto... path>
void getValue(const RootOf<path...> &s, GValue *v) {
  const auto &field = fieldAt<path...>(s);
  using T = std::remove_cv_t<std::remove_reference_t<decltype(field)>>;
  if constexpr (std::is_same_v<T, bool>)
    g_value_set_boolean(v, field);
  else if constexpr (std::is_same_v<T, gint>)
    g_value_set_int(v, field);
  else if constexpr (std::is_same_v<T, guint>)
    g_value_set_uint(v, field);
  else if constexpr (std::is_same_v<T, double>)
    g_value_set_double(v, field);
  else
    g_value_set_enum(v, static_cast<gint>(field));
}
template <auto... path>
void setValue(RootOf<path...> &s, const GValue *v) {
  auto &field = fieldAt<path...>(s);
  using T = std::remove_cv_t<std::remove_reference_t<decltype(field)>>;
  if constexpr (std::is_same_v<T, bool>)
    field = g_value_get_boolean(v);
  else if constexpr (std::is_same_v<T, gint>)
    field = g_value_get_int(v);
  else if constexpr (std::is_same_v<T, guint>)
    field = g_value_get_uint(v);
  else if constexpr (std::is_same_v<T, double>)
    field = g_value_get_double(v);
  else
    field = static_cast<T>(g_value_get_enum(v));
}

// A flags field (a guint holding GFlags bits).
template <auto field>
void getFlags(const ClassOf<field> &s, GValue *v) {
  g_value_set_flags(v, s.*field);
}
template <auto field>
void setFlags(ClassOf<field> &s, const GValue *v) {
  s.*field = g_value_get_flags(v);
}

}  // namespace gstglue
