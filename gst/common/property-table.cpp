// SPDX-License-Identifier: LGPL-2.1-or-later
#include "property-table.h"

#include <cmath>
#include <cstdio>

namespace gstglue {

colortrack::Status refuseNotFinite(const GValue *value) {
  if (std::isfinite(g_value_get_double(value))) return {};
  return colortrack::Status::failure("the value must be a number");
}

std::string textOf(const GValue *value) {
  const gchar *text = g_value_get_string(value);
  return text ? text : "";
}

namespace {

// A string as the messages quote it: null reads as empty.
std::string quoted(const GValue *value) {
  const gchar *text = g_value_get_string(value);
  return std::string("'") + (text ? text : "") + "'";
}

std::string contents(const GValue *value) {
  gchar *text = g_strdup_value_contents(value);
  std::string result(text);
  g_free(text);
  return result;
}

// A value as messages show it: numbers short, text quoted, an enum by its nick (its description is a
// sentence).
std::string shownValue(const GValue *value) {
  if (G_VALUE_HOLDS_DOUBLE(value)) {
    char text[G_ASCII_DTOSTR_BUF_SIZE];
    std::snprintf(text, sizeof text, "%g", g_value_get_double(value));
    return text;
  }
  if (G_VALUE_HOLDS_STRING(value)) return quoted(value);
  if (G_VALUE_HOLDS_ENUM(value)) {
    GEnumClass *enums = G_ENUM_CLASS(g_type_class_ref(G_VALUE_TYPE(value)));
    const GEnumValue *known = g_enum_get_value(enums, g_value_get_enum(value));
    const std::string nick = known ? std::string("'") + known->value_nick + "'" : contents(value);
    g_type_class_unref(enums);
    return nick;
  }
  return contents(value);
}

}  // namespace

GParamFlags flagsFor(Apply apply) {
  const auto rw = static_cast<GParamFlags>(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS);
  return apply == Apply::Live ? static_cast<GParamFlags>(rw | GST_PARAM_MUTABLE_PLAYING) : rw;
}

bool sameValue(const GValue *a, const GValue *b) {
  // Exact for doubles: g_param_values_cmp would call values within the spec's epsilon the same.
  if (G_VALUE_HOLDS_DOUBLE(a)) return g_value_get_double(a) == g_value_get_double(b);
  if (G_VALUE_HOLDS_STRING(a)) return g_strcmp0(g_value_get_string(a), g_value_get_string(b)) == 0;
  return gst_value_compare(a, b) == GST_VALUE_EQUAL;
}

std::string validUtf8(const std::string &text) {
  gchar *valid = g_utf8_make_valid(text.data(), static_cast<gssize>(text.size()));
  std::string result(valid);
  g_free(valid);
  return result;
}

std::string refusalText(GParamSpec *pspec, const GValue *value, const char *why, ShowValue shown) {
  const std::string text = shown ? shown(value) : shownValue(value);
  return validUtf8("Invalid value " + text + " for property '" + pspec->name + "': " + why);
}

std::string keepingText(const std::string &refusal, const GValue *kept, ShowValue shown) {
  return validUtf8(refusal + ". Keeping " + (shown ? shown(kept) : shownValue(kept)) + ".");
}

std::string readAtStartText(GParamSpec *pspec) {
  return std::string("Property '") + pspec->name +
         "' is read at start: the new value applies from the next start (READY to NULL and back).";
}

#define GST_CAT_DEFAULT category
void postSettingsWarning(GstElement *element, GstDebugCategory *category, const std::string &text) {
  GST_ELEMENT_WARNING(element, RESOURCE, SETTINGS, ("%s", validUtf8(text).c_str()), (nullptr));
}
void postStartRefusal(GstElement *element, GstDebugCategory *category, const std::string &refusal) {
  GST_ELEMENT_ERROR(element, RESOURCE, SETTINGS, ("%s.", validUtf8(refusal).c_str()), (nullptr));
}
void logRefusedBeforeStart(GstElement *element, GstDebugCategory *category, const std::string &refusal) {
  GST_WARNING_OBJECT(element, "%s: the element will fail to start", refusal.c_str());
}
void postStartProblem(GstElement *element, GstDebugCategory *category, GstResourceError code, bool error,
                      const std::string &text) {
  const std::string valid = validUtf8(text);
  GST_WARNING_OBJECT(element, "start: %s", valid.c_str());
  gst_element_message_full(element, error ? GST_MESSAGE_ERROR : GST_MESSAGE_WARNING, GST_RESOURCE_ERROR, code,
                           g_strdup(valid.c_str()), nullptr, __FILE__, GST_FUNCTION, __LINE__);
}
#undef GST_CAT_DEFAULT

}  // namespace gstglue
