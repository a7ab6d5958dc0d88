// SPDX-License-Identifier: LGPL-2.1-or-later
// An element's properties declared once, in a table that installs them, sets and gets them and applies the
// rule for a refused value: an error at start when it was set before, a warning that keeps the old value when
// it is set while streaming.
#pragma once

#include <gst/gst.h>

#include <cstddef>
#include <iterator>
#include <map>
#include <string>
#include <type_traits>

namespace gstglue {

enum class Apply {
  Live,     // applied from the next buffer (GST_PARAM_MUTABLE_PLAYING)
  AtStart,  // read at start: a change while started warns that it applies from the next start
  // Fixed while started: a change then is refused with a warning that keeps the value (colortrack's mode,
  // which decides what the element's state holds).
  BeforeStart,
};

// An element with nothing to share besides its property values.
struct NoShared {};

// What an element keeps per instance, under its object lock. `S` is the element's settings: the property
// values and nothing else. `X` is what else the threads share: requests waiting for the streaming thread and
// runtime facts a property's check needs.
template <typename S, typename X = NoShared>
struct PropertyStore {
  S settings;
  X shared;
  // Counters bumped by each accepted value of a property that names them (PropertyDef::versions), so the
  // streaming thread re-reads only what changed.
  guint64 versions[4] = {};
  bool running = false;                  // between start and stop
  std::map<guint, std::string> refused;  // by property id: a value refused before start, an error at start

  // The refusal the start reports (the first property's), or empty.
  std::string firstRefusal() const { return refused.empty() ? std::string() : refused.begin()->second; }
};

// One property.
template <typename S, typename X = NoShared>
struct PropertyDef {
  Apply apply;
  unsigned versions;  // bit i set: an accepted value bumps PropertyStore::versions[i] (true: counter 0)
  GParamSpec *(*spec)(GParamFlags flags);
  void (*get)(const S &settings, GValue *value);
  void (*set)(S &settings, const GValue *value);
  // Why a value of the spec's range is still refused, or null to accept it.
  const char *(*refuse)(const GValue *value) = nullptr;
  // The same for a value judged by parsing it or against the store (the other settings, running, the
  // runtime facts): why it is refused, or empty to accept. May set `warning` to a whole text that replaces
  // the usual "Invalid value ... Keeping ..." while running.
  std::string (*check)(const PropertyStore<S, X> &store, const GValue *value, std::string *warning) = nullptr;
  // A value refused before start is still stored, so that it reads back as written (text properties).
  bool keepRefused = false;
  // Called under the lock after an accepted value is set, e.g. to post a request for the streaming thread.
  void (*accepted)(PropertyStore<S, X> &store) = nullptr;
  // How a value of this property is shown in messages, when not as itself: a secret ('***'), an address
  // whose password must not show. Null: as itself.
  std::string (*shown)(const GValue *value) = nullptr;
};

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

template <typename S, typename X = NoShared>
class PropertyTable {
 public:
  // Property ids are 1 + the index in `defs`; gst-inspect-1.0 lists them in this order.
  template <std::size_t N>
  explicit PropertyTable(const PropertyDef<S, X> (&defs)[N]) : defs_(defs), count_(N) {}

  void install(GObjectClass *klass) const {
    for (std::size_t i = 0; i < count_; ++i)
      g_object_class_install_property(klass, static_cast<guint>(i + 1),
                                      defs_[i].spec(flagsFor(defs_[i].apply)));
  }

  void get(GstElement *element, const PropertyStore<S, X> &store, guint id, GValue *value,
           GParamSpec *pspec) const {
    if (id == 0 || id > count_) {
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
    if (id == 0 || id > count_) {
      G_OBJECT_WARN_INVALID_PROPERTY_ID(element, id, pspec);
      return;
    }
    const PropertyDef<S, X> &def = defs_[id - 1];
    GValue before = G_VALUE_INIT, after = G_VALUE_INIT;
    g_value_init(&before, G_PARAM_SPEC_VALUE_TYPE(pspec));
    g_value_init(&after, G_PARAM_SPEC_VALUE_TYPE(pspec));
    std::string warning, refusedBeforeStart;
    GST_OBJECT_LOCK(element);
    def.get(store.settings, &before);
    const char *refused = def.refuse ? def.refuse(value) : nullptr;
    std::string why = refused ? refused : "";
    if (why.empty() && def.check) why = def.check(store, value, &warning);
    if (why.empty() && def.apply == Apply::BeforeStart && store.running && !sameValue(&before, value))
      why = "it cannot change while the element is started; set it before";
    if (!why.empty()) {
      const std::string refusal = refusalText(pspec, value, why.c_str(), def.shown);
      if (store.running) {
        if (warning.empty()) warning = keepingText(refusal, &before, def.shown);
      } else {
        store.refused[id] = refusedBeforeStart = refusal;
        if (def.keepRefused) def.set(store.settings, value);
      }
    } else {
      warning.clear();
      store.refused.erase(id);
      def.set(store.settings, value);
      for (unsigned i = 0; i < G_N_ELEMENTS(store.versions); ++i)
        if (def.versions & (1u << i)) ++store.versions[i];
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
      const PropertyDef<S, X> &def = defs_[it->first - 1];
      bool good = false;
      if (def.apply == Apply::AtStart && def.keepRefused && def.check) {
        GValue value = G_VALUE_INIT;
        g_value_init(&value, G_TYPE_STRING);
        def.get(store.settings, &value);
        std::string warning;
        good = (!def.refuse || !def.refuse(&value)) && def.check(store, &value, &warning).empty();
        g_value_unset(&value);
      }
      it = good ? store.refused.erase(it) : std::next(it);
    }
  }

 private:
  const PropertyDef<S, X> *defs_;
  std::size_t count_;
};

}  // namespace gstglue
