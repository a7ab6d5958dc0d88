// SPDX-License-Identifier: LGPL-2.1-or-later
// gstglue::PropertyTable and ElementCore on an element of its own (three properties, one of each kind of
// apply, and two start rules): a value
// refused before start is remembered (and, for text, kept so it reads back) for the start to fail on; a
// value refused while started warns, names the property and keeps the old one; a read-at-start property
// changed while started says so; a fixed-while-started one refuses a change but not the same value; every
// message is valid UTF-8; the change set holds what an accepted value marks until it is taken; the start
// reports a refusal first, then the rules, and counts as running from its snapshot. GoogleTest, no pipeline.
#include <gtest/gtest.h>

#include <optional>
#include <string>
#include <vector>

#include "element-core.h"

namespace {

struct Settings {
  enum class Change : unsigned { Gain, Fixed };
  gint gain = 1;            // Live: negatives refused
  std::string path = "ok";  // AtStart: "bad" refused, kept so it reads back
  gboolean fixed = FALSE;   // BeforeStart
};
using Store = gstglue::PropertyStore<Settings>;
using Def = gstglue::PropertyDef<Settings>;
using Core = gstglue::ElementCore<Settings>;
using Rule = gstglue::StartRule<Settings>;

using colortrack::Status;

Status refuseNegative(const GValue *v) {
  return g_value_get_int(v) < 0 ? Status::failure("it must not be negative") : Status();
}
Status checkPath(const Store &, const GValue *v) {
  return gstglue::textOf(v).rfind("bad", 0) == 0 ? Status::failure("it is bad") : Status();
}

Status fixedWithBadPath(const Settings &s) {
  return s.fixed && s.path == "clash" ? Status::failure("'fixed' and 'path' clash") : Status();
}
Status gainOfNine(const Settings &s) {
  return s.gain == 9 ? Status::failure("a gain of 9 is loud") : Status();
}

const gstglue::PropertyTable<Settings> kTable(
    {Def::live([](GParamFlags f) { return g_param_spec_int("gain", "Gain", "A gain", -10, 10, 1, f); })
         .marks({Settings::Change::Gain})
         .field<&Settings::gain>()
         .refusing(refuseNegative),
     Def::atStart([](GParamFlags f) { return g_param_spec_string("path", "Path", "A path", "ok", f); })
         .text<&Settings::path>()
         .checking(checkPath)
         .keepingRefused(),
     Def::beforeStart([](GParamFlags f) {
       return g_param_spec_boolean("fixed", "Fixed", "Fixed while started", FALSE, f);
     })
         .marks({Settings::Change::Fixed})
         .accessors([](const Settings &s, GValue *v) { g_value_set_boolean(v, s.fixed); },
                    [](Settings &s, const GValue *v) { s.fixed = g_value_get_boolean(v); })},
    {{fixedWithBadPath}, {gainOfNine, Rule::Severity::Warning}});

// A plain GstElement whose properties are the table's.
struct TableElement {
  GstElement parent;
  Core *core;
};
struct TableElementClass {
  GstElementClass parent;
};
G_DEFINE_TYPE(TableElement, table_element, GST_TYPE_ELEMENT)
GST_DEBUG_CATEGORY_STATIC(table_debug);

void tableSet(GObject *object, guint id, const GValue *value, GParamSpec *pspec) {
  auto *self = reinterpret_cast<TableElement *>(object);
  self->core->set(id, value, pspec);
}
void tableGet(GObject *object, guint id, GValue *value, GParamSpec *pspec) {
  auto *self = reinterpret_cast<TableElement *>(object);
  self->core->get(id, value, pspec);
}
void tableFinalize(GObject *object) {
  delete reinterpret_cast<TableElement *>(object)->core;
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
  self->core = new Core(GST_ELEMENT(self), table_debug, kTable);
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
  Core &core() { return *reinterpret_cast<TableElement *>(element)->core; }
  Store &store() { return core().store(); }
  std::vector<std::string> warnings() { return messages(GST_MESSAGE_WARNING); }
  std::vector<std::string> errors() { return messages(GST_MESSAGE_ERROR); }
  std::vector<std::string> messages(GstMessageType type) {
    std::vector<std::string> texts;
    while (GstMessage *m = gst_bus_pop_filtered(bus, type)) {
      GError *error = nullptr;
      if (type == GST_MESSAGE_WARNING)
        gst_message_parse_warning(m, &error, nullptr);
      else
        gst_message_parse_error(m, &error, nullptr);
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
  EXPECT_TRUE(rig.core().takeChanges().has(Settings::Change::Gain));
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

TEST(ElementCore, ChangesAreMarkedByTheRowAndTakenOnce) {
  Rig rig;
  EXPECT_TRUE(rig.core().takeChanges().empty());
  g_object_set(rig.element, "path", "other", nullptr);  // marks nothing
  EXPECT_TRUE(rig.core().takeChanges().empty());
  g_object_set(rig.element, "gain", -3, nullptr);  // refused: marks nothing
  EXPECT_TRUE(rig.core().takeChanges().empty());
  g_object_set(rig.element, "gain", 4, "fixed", TRUE, nullptr);
  const Core::Changes changes = rig.core().takeChanges();
  EXPECT_TRUE(changes.has(Settings::Change::Gain));
  EXPECT_TRUE(changes.has(Settings::Change::Fixed));
  EXPECT_TRUE(rig.core().takeChanges().empty());
}

TEST(ElementCore, StartReportsARefusalThenTheRulesAndRunsFromItsSnapshot) {
  Rig rig;
  g_object_set(rig.element, "gain", -1, "fixed", TRUE, "path", "clash", nullptr);
  EXPECT_FALSE(rig.core().start());
  std::vector<std::string> errors = rig.errors();
  ASSERT_EQ(errors.size(), 1u);  // the refusal only, not the rule too
  EXPECT_NE(errors[0].find("'gain'"), std::string::npos) << errors[0];
  EXPECT_FALSE(rig.store().running);

  g_object_set(rig.element, "gain", 9, nullptr);
  EXPECT_FALSE(rig.core().start());
  errors = rig.errors();
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_EQ(errors[0], "'fixed' and 'path' clash");
  EXPECT_FALSE(rig.store().running);

  g_object_set(rig.element, "path", "fine", nullptr);
  const std::optional<Settings> started = rig.core().start();
  ASSERT_TRUE(started);
  EXPECT_EQ(started->gain, 9);
  // (Popping one type from the bus discards the others: the warnings first.)
  const std::vector<std::string> warnings = rig.warnings();
  ASSERT_EQ(warnings.size(), 1u);  // a warning rule does not stop the start
  EXPECT_EQ(warnings[0], "a gain of 9 is loud");
  EXPECT_TRUE(rig.store().running);
  EXPECT_TRUE(rig.core().takeChanges().empty());       // what was set before is in the snapshot
  g_object_set(rig.element, "fixed", FALSE, nullptr);  // fixed while started
  EXPECT_EQ(rig.warnings().size(), 1u);
  rig.core().stop();
  EXPECT_FALSE(rig.store().running);
}

}  // namespace

int main(int argc, char **argv) {
  gst_init(&argc, &argv);
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
