// SPDX-License-Identifier: LGPL-2.1-or-later
// gst-inspect tells the truth: every numeric property of colortrack, robotctl and trackpublish accepts its
// declared minimum and maximum (set in the NULL state, read back unchanged) and GLib refuses a value just
// outside them, and no property hides one of a base class (trackpublish's MQTT QoS once hid
// GstBaseTransform's qos). C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in
// the standard library.
#include <cmath>
#include <cstdio>
#include <string>

#include "gst_test_util.hpp"

#include <gst/check/gstcheck.h>

namespace {

using namespace colortrack::gst_test_util;

// Sets `value` on a fresh element and reads it back; `glibRefused`: GLib warned (its range check).
GValue setAndRead(const char *factory, GParamSpec *spec, const GValue *value, bool &glibRefused) {
  GstElement *element = gst_element_factory_make(factory, nullptr);
  fail_unless(element != nullptr);
  _gst_check_expecting_log = TRUE;
  _gst_check_raised_warning = _gst_check_raised_critical = FALSE;
  g_object_set_property(G_OBJECT(element), spec->name, value);
  glibRefused = _gst_check_raised_warning || _gst_check_raised_critical;
  _gst_check_expecting_log = FALSE;
  _gst_check_raised_warning = _gst_check_raised_critical = FALSE;
  GValue back = G_VALUE_INIT;
  g_value_init(&back, spec->value_type);
  g_object_get_property(G_OBJECT(element), spec->name, &back);
  gst_object_unref(element);
  return back;
}

// The value of `spec`'s type holding `number`.
GValue valueOf(GParamSpec *spec, double number) {
  GValue v = G_VALUE_INIT;
  g_value_init(&v, spec->value_type);
  if (G_IS_PARAM_SPEC_INT(spec))
    g_value_set_int(&v, static_cast<gint>(number));
  else if (G_IS_PARAM_SPEC_UINT(spec))
    g_value_set_uint(&v, static_cast<guint>(number));
  else if (G_IS_PARAM_SPEC_INT64(spec))
    g_value_set_int64(&v, static_cast<gint64>(number));
  else if (G_IS_PARAM_SPEC_UINT64(spec))
    g_value_set_uint64(&v, static_cast<guint64>(number));
  else
    g_value_set_double(&v, number);
  return v;
}

struct Range {
  double min, max, typeMin, typeMax;
};

bool rangeOf(GParamSpec *spec, Range &r) {
  if (G_IS_PARAM_SPEC_INT(spec)) {
    r = {double(G_PARAM_SPEC_INT(spec)->minimum), double(G_PARAM_SPEC_INT(spec)->maximum), G_MININT,
         G_MAXINT};
  } else if (G_IS_PARAM_SPEC_UINT(spec)) {
    r = {double(G_PARAM_SPEC_UINT(spec)->minimum), double(G_PARAM_SPEC_UINT(spec)->maximum), 0, G_MAXUINT};
  } else if (G_IS_PARAM_SPEC_DOUBLE(spec)) {
    r = {G_PARAM_SPEC_DOUBLE(spec)->minimum, G_PARAM_SPEC_DOUBLE(spec)->maximum, -G_MAXDOUBLE, G_MAXDOUBLE};
  } else {
    return false;  // int64 / uint64 / float: none of the three elements declares one today
  }
  return true;
}

// Checks every writable numeric property `factory` declares itself; returns how many were checked.
int checkRanges(const char *factory) {
  GstElement *element = gst_element_factory_make(factory, nullptr);
  fail_unless(element != nullptr);
  const GType type = G_OBJECT_TYPE(element);
  GObjectClass *parent = G_OBJECT_CLASS(g_type_class_peek(g_type_parent(type)));
  guint count = 0;
  GParamSpec **specs = g_object_class_list_properties(G_OBJECT_GET_CLASS(element), &count);
  int checked = 0;
  for (guint i = 0; i < count; ++i) {
    GParamSpec *spec = specs[i];
    if (spec->owner_type != type) continue;
    fail_unless(g_object_class_find_property(parent, spec->name) == nullptr,
                "%s's '%s' hides the base class's property of that name", factory, spec->name);
    Range r;
    if (!(spec->flags & G_PARAM_WRITABLE) || !rangeOf(spec, r)) continue;
    ++checked;
    for (const double end : {r.min, r.max}) {
      GValue v = valueOf(spec, end);
      bool glibRefused = false;
      GValue back = setAndRead(factory, spec, &v, glibRefused);
      fail_unless(!glibRefused && gst_value_compare(&v, &back) == GST_VALUE_EQUAL,
                  "%s: '%s' declares %g but does not take it", factory, spec->name, end);
      g_value_unset(&back);
      g_value_unset(&v);
    }
    // Just outside: GLib's to refuse (the value stays the default).
    for (const double outside : {r.min - 1, r.max + 1}) {
      if (outside < r.typeMin || outside > r.typeMax) continue;
      GValue v = valueOf(spec, outside);
      bool glibRefused = false;
      GValue back = setAndRead(factory, spec, &v, glibRefused);
      fail_unless(glibRefused && gst_value_compare(&v, &back) != GST_VALUE_EQUAL,
                  "%s: '%s' took %g, outside its declared range", factory, spec->name, outside);
      g_value_unset(&back);
      g_value_unset(&v);
    }
  }
  g_free(specs);
  gst_object_unref(element);
  std::printf("%s: %d numeric properties, each end taken, just outside refused\n", factory, checked);
  return checked;
}

}  // namespace

GST_START_TEST(test_declared_ranges_are_accepted_ranges) {
  for (const char *factory : {"colortrack", "robotctl", "trackpublish"})
    fail_unless(checkRanges(factory) > 0);
}
GST_END_TEST;

static Suite *property_ranges_suite(void) {
  preloadPlugins({"colortrack"});
  Suite *s = suite_create("property_ranges");
  TCase *tc = tcase_create("ranges");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_declared_ranges_are_accepted_ranges);
  return s;
}

GST_CHECK_MAIN(property_ranges);
