// SPDX-License-Identifier: LGPL-2.1-or-later
// An element's properties declared once, in a table that installs them, sets and gets them and applies the
// rule for a refused value: an error at start when it was set before, a warning that keeps the old value when
// it is set while streaming. The rules that join several properties (a pair that contradicts itself) are
// declared with the rows, as start rules, and judged by the element's start (element-core.h).
#pragma once

#include <gst/gst.h>

#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "property-def.h"

namespace gstglue {

// A refusal for a double property: NaN. GLib's own check refuses it too (its clamp leaves NaN, which never
// equals itself); this is for a GLib that would not, so that NaN never reaches the engine.
colortrack::Status refuseNotFinite(const GValue *value);

// The helpers the table's templates share; in property-table.cpp.
GParamFlags flagsFor(Apply apply);
bool sameValue(const GValue *a, const GValue *b);
// `text` with each invalid UTF-8 sequence replaced (U+FFFD): a GStreamer message must be valid UTF-8, and a
// value typed or read from a file may not be (an application in Python would fail to read the message).
std::string validUtf8(const std::string &text);
// `shown`: the property's own way to show a value (PropertyDef::shown), or null.
using ShowValue = std::string (*)(const GValue *value);
std::string refusalText(GParamSpec *pspec, const GValue *value, const char *why, ShowValue shown = nullptr);
std::string keepingText(const std::string &refusal, const GValue *kept, ShowValue shown = nullptr);
std::string readAtStartText(GParamSpec *pspec);
void postSettingsWarning(GstElement *element, GstDebugCategory *category, const std::string &text);
void logRefusedBeforeStart(GstElement *element, GstDebugCategory *category, const std::string &refusal);
// The start's error for a value refused before it (PropertyStore::firstRefusal()).
void postStartRefusal(GstElement *element, GstDebugCategory *category, const std::string &refusal);
// The start's error or warning for a broken start rule: `text` is whole.
void postStartProblem(GstElement *element, GstDebugCategory *category, GstResourceError code, bool error,
                      const std::string &text);

// A rule between properties, judged at start after every property's own check: a failure whose message is
// the whole error (naming the properties and what to set) when the settings break it.
template <typename S>
struct StartRule {
  colortrack::Status (*problem)(const S &settings);
  enum class Severity { Error, Warning } severity = Severity::Error;
  GstResourceError code = GST_RESOURCE_ERROR_SETTINGS;
};

// The table's rows, from groups of rows (a function each, by concept), in order.
template <typename Def, typename... Groups>
std::vector<Def> rowsOf(Groups... groups) {
  std::vector<Def> rows;
  rows.reserve((groups.size() + ...));
  for (const std::vector<Def> &group : {groups...})
    for (const Def &row : group) rows.push_back(row);
  return rows;
}

template <typename S, typename X = NoShared>
class PropertyTable {
 public:
  using Def = PropertyDef<S, X>;
  // Property ids are 1 + the index in `defs`; gst-inspect-1.0 lists them in this order.
  explicit PropertyTable(std::vector<Def> defs, std::vector<StartRule<S>> rules = {})
      : defs_(std::move(defs)), rules_(std::move(rules)) {}

  const std::vector<StartRule<S>> &startRules() const { return rules_; }

  void install(GObjectClass *klass) const {
    for (std::size_t i = 0; i < defs_.size(); ++i)
      g_object_class_install_property(klass, static_cast<guint>(i + 1),
                                      defs_[i].spec(flagsFor(defs_[i].apply)));
  }

  void get(GstElement *element, const PropertyStore<S, X> &store, guint id, GValue *value,
           GParamSpec *pspec) const {
    if (id == 0 || id > defs_.size()) {
      G_OBJECT_WARN_INVALID_PROPERTY_ID(element, id, pspec);
      return;
    }
    GST_OBJECT_LOCK(element);
    defs_[id - 1].get(store.settings, value);
    GST_OBJECT_UNLOCK(element);
  }

  // Warnings are logged in `category`, the element's.
  void set(GstElement *element, GstDebugCategory *category, PropertyStore<S, X> &store, guint id,
           const GValue *value, GParamSpec *pspec) const {
    if (id == 0 || id > defs_.size()) {
      G_OBJECT_WARN_INVALID_PROPERTY_ID(element, id, pspec);
      return;
    }
    const Def &def = defs_[id - 1];
    GValue before = G_VALUE_INIT, after = G_VALUE_INIT;
    g_value_init(&before, G_PARAM_SPEC_VALUE_TYPE(pspec));
    g_value_init(&after, G_PARAM_SPEC_VALUE_TYPE(pspec));
    std::string warning, refusedBeforeStart;
    GST_OBJECT_LOCK(element);
    def.get(store.settings, &before);
    colortrack::Status verdict = def.refuse ? def.refuse(value) : colortrack::Status();
    if (verdict && def.check) verdict = def.check(store, value);
    std::string why = verdict ? std::string() : verdict.message();  // a failure's message is never empty
    if (why.empty() && def.apply == Apply::BeforeStart && store.running && !sameValue(&before, value))
      why = "it cannot change while the element is started; set it before";
    if (!why.empty()) {
      const std::string refusal = refusalText(pspec, value, why.c_str(), def.shown);
      if (store.running) {
        warning = keepingText(refusal, &before, def.shown);
      } else {
        store.refused[id] = refusedBeforeStart = refusal;
        if (def.keepRefused) def.set(store.settings, value);
      }
    } else {
      store.refused.erase(id);
      def.set(store.settings, value);
      store.changed |= def.changes;
      if (def.accepted) def.accepted(store);
      def.get(store.settings, &after);
      // Said at once, or the user would think the new value applied.
      if (def.apply == Apply::AtStart && store.running && !sameValue(&before, &after))
        warning = readAtStartText(pspec);
    }
    GST_OBJECT_UNLOCK(element);
    if (!refusedBeforeStart.empty()) logRefusedBeforeStart(element, category, refusedBeforeStart);
    g_value_unset(&before);
    g_value_unset(&after);
    if (!warning.empty()) postSettingsWarning(element, category, warning);
  }

  // At start, under the object lock: a read-at-start text refused when it was set is judged again (a folder
  // or a certificate the application created since may make it good now), and forgotten if it passes.
  void recheckRefused(PropertyStore<S, X> &store) const {
    for (auto it = store.refused.begin(); it != store.refused.end();) {
      const Def &def = defs_[it->first - 1];
      bool good = false;
      if (def.apply == Apply::AtStart && def.keepRefused && def.check) {
        GValue value = G_VALUE_INIT;
        g_value_init(&value, G_TYPE_STRING);
        def.get(store.settings, &value);
        good = (!def.refuse || def.refuse(&value)) && def.check(store, &value);
        g_value_unset(&value);
      }
      it = good ? store.refused.erase(it) : std::next(it);
    }
  }

 private:
  std::vector<Def> defs_;
  std::vector<StartRule<S>> rules_;
};

}  // namespace gstglue
