// SPDX-License-Identifier: LGPL-2.1-or-later
// gstglue::PropertyTable on an element of its own (three properties, one of each kind of apply): a value
// refused before start is remembered (and, for text, kept so it reads back) for the start to fail on; a
// value refused while started warns, names the property and keeps the old one; a read-at-start property
// changed while started says so; a fixed-while-started one refuses a change but not the same value; every
// message is valid UTF-8. GoogleTest, no pipeline.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "property-table.h"

namespace {

struct Settings {
  gint gain = 1;            // Live: negatives refused
  std::string path = "ok";  // AtStart: "bad" refused, kept so it reads back
  gboolean fixed = FALSE;   // BeforeStart
};
using Store = gstglue::PropertyStore<Settings>;
using Def = gstglue::PropertyDef<Settings>;

const char *refuseNegative(const GValue *v) {
  return g_value_get_int(v) < 0 ? "it must not be negative" : nullptr;
}
std::string checkPath(const Store &, const GValue *v, std::string *) {
  return gstglue::textOf(v).rfind("bad", 0) == 0 ? "it is bad" : "";
}

const Def kDefs[] = {
    {gstglue::Apply::Live, true,
     [](GParamFlags f) { return g_param_spec_int("gain", "Gain", "A gain", -10, 10, 1, f); },
     gstglue::getValue<&Settings::gain>, gstglue::setValue<&Settings::gain>, refuseNegative},
    {gstglue::Apply::AtStart, false,
     [](GParamFlags f) { return g_param_spec_string("path", "Path", "A path", "ok", f); },
     gstglue::getText<&Settings::path>, gstglue::setText<&Settings::path>, nullptr, checkPath, true},
    {gstglue::Apply::BeforeStart, false,
     [](GParamFlags f) { return g_param_spec_boolean("fixed", "Fixed", "Fixed while started", FALSE, f); },
     [](const Settings &s, GValue *v) { g_value_set_boolean(v, s.fixed); },
     [](Settings &s, const GValue *v) { s.fixed = g_value_get_boolean(v); }},
};
const gstglue::PropertyTable<Settings> kTable(kDefs);

// A plain GstElement whose properties are the table's.
struct TableElement {
  GstElement parent;
  Store *store;
};
struct TableElementClass {
  GstElementClass parent;
};
G_DEFINE_TYPE(TableElement, table_element, GST_TYPE_ELEMENT)
GST_DEBUG_CATEGORY_STATIC(table_debug);

void tableSet(GObject *object, guint id, const GValue *value, GParamSpec *pspec) {
  auto *self = reinterpret_cast<TableElement *>(object);
  kTable.set(GST_ELEMENT(object), table_debug, *self->store, id, value, pspec);
}
void tableGet(GObject *object, guint id, GValue *value, GParamSpec *pspec) {
  auto *self = reinterpret_cast<TableElement *>(object);
  kTable.get(GST_ELEMENT(object), *self->store, id, value, pspec);
}
void tableFinalize(GObject *object) {
  delete reinterpret_cast<TableElement *>(object)->store;
  G_OBJECT_CLASS(table_element_parent_class)->finalize(object);
}
void table_element_class_init(TableElementClass *klass) {
  GObjectClass *gobject = G_OBJECT_CLASS(klass);
  gobject->set_property = tableSet;
  gobject->get_property = tableGet;
  gobject->finalize = tableFinalize;
  kTable.install(gobject);
}
void table_element_init(TableElement *self) {
  self->store = new Store();
}

// The element on a bus of its own; `warnings` takes what it posted.
struct Rig {
  Rig() {
    GST_DEBUG_CATEGORY_INIT(table_debug, "tabletest", 0, "property table test");
    element = GST_ELEMENT(g_object_new(table_element_get_type(), nullptr));
    gst_object_ref_sink(element);
    bus = gst_bus_new();
    gst_element_set_bus(element, bus);
  }
  ~Rig() {
    gst_element_set_bus(element, nullptr);
    gst_object_unref(bus);
    gst_object_unref(element);
  }
  Store &store() { return *reinterpret_cast<TableElement *>(element)->store; }
  std::vector<std::string> warnings() {
    std::vector<std::string> texts;
    while (GstMessage *m = gst_bus_pop_filtered(bus, GST_MESSAGE_WARNING)) {
      GError *error = nullptr;
      gst_message_parse_warning(m, &error, nullptr);
      texts.push_back(error->message);
      g_error_free(error);
      gst_message_unref(m);
    }
    return texts;
  }
  std::string path() {
    gchar *text = nullptr;
    g_object_get(element, "path", &text, nullptr);
    std::string result = text ? text : "";
    g_free(text);
    return result;
  }
  gint gain() {
    gint value = 0;
    g_object_get(element, "gain", &value, nullptr);
    return value;
  }
  GstElement *element;
  GstBus *bus;
};

TEST(PropertyTable, BeforeStartARefusalIsRememberedForTheStart) {
  Rig rig;
  g_object_set(rig.element, "gain", -1, nullptr);
  EXPECT_EQ(rig.gain(), 1);
  ASSERT_EQ(rig.store().refused.size(), 1u);
  EXPECT_NE(rig.store().refused.begin()->second.find("'gain'"), std::string::npos);
  g_object_set(rig.element, "gain", 3, nullptr);  // a good value clears the refusal
  EXPECT_EQ(rig.gain(), 3);
  EXPECT_TRUE(rig.store().refused.empty());
  EXPECT_EQ(rig.store().versions[0], 1u);
  g_object_set(rig.element, "path", "bad1", nullptr);  // text reads back as written, still refused
  EXPECT_EQ(rig.path(), "bad1");
  EXPECT_EQ(rig.store().refused.size(), 1u);
  EXPECT_TRUE(rig.warnings().empty());  // not started: no warning, the start will fail
}

TEST(PropertyTable, WhileStartedARefusalWarnsAndKeepsTheOldValue) {
  Rig rig;
  rig.store().running = true;
  g_object_set(rig.element, "gain", -2, nullptr);
  EXPECT_EQ(rig.gain(), 1);
  std::vector<std::string> warnings = rig.warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("Invalid value -2 for property 'gain'"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("Keeping 1"), std::string::npos) << warnings[0];
  EXPECT_TRUE(rig.store().refused.empty());
  g_object_set(rig.element, "path", "bad\xff\xfe", nullptr);  // invalid UTF-8 in the value
  EXPECT_EQ(rig.path(), "ok");
  warnings = rig.warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_TRUE(g_utf8_validate(warnings[0].c_str(), -1, nullptr)) << warnings[0];
}

TEST(PropertyTable, WhileStartedReadAtStartAndFixedPropertiesSaySo) {
  Rig rig;
  rig.store().running = true;
  g_object_set(rig.element, "path", "new", nullptr);
  EXPECT_EQ(rig.path(), "new");
  std::vector<std::string> warnings = rig.warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("'path' is read at start"), std::string::npos) << warnings[0];
  g_object_set(rig.element, "fixed", FALSE, nullptr);  // the same value: nothing to refuse
  EXPECT_TRUE(rig.warnings().empty());
  g_object_set(rig.element, "fixed", TRUE, nullptr);
  gboolean fixed = TRUE;
  g_object_get(rig.element, "fixed", &fixed, nullptr);
  EXPECT_FALSE(fixed);
  warnings = rig.warnings();
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("cannot change while the element is started"), std::string::npos) << warnings[0];
  g_object_set(rig.element, "gain", 5, nullptr);  // live: applied, nothing said
  EXPECT_EQ(rig.gain(), 5);
  EXPECT_TRUE(rig.warnings().empty());
}

}  // namespace

int main(int argc, char **argv) {
  gst_init(&argc, &argv);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
