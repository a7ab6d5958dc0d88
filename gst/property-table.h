// An element's properties declared once, in a table that installs them, sets and gets them and applies the
// rule for a refused value: an error at start when it was set before, a warning that keeps the old value when
// it is set while streaming.
#pragma once

#include <gst/gst.h>

#include <cstddef>
#include <map>
#include <string>

namespace gstglue {

enum class Apply {
  Live,     // applied from the next buffer (GST_PARAM_MUTABLE_PLAYING)
  AtStart,  // read at start: a change while started warns that it applies from the next start
};

// One property. `S` is the element's settings: the property values and nothing else.
template <typename S>
struct PropertyDef {
  Apply apply;
  bool versioned;  // an accepted value bumps PropertyStore::version
  GParamSpec *(*spec)(GParamFlags flags);
  void (*get)(const S &settings, GValue *value);
  void (*set)(S &settings, const GValue *value);
  // Why a value of the spec's range is still refused, or null to accept it.
  const char *(*refuse)(const GValue *value) = nullptr;
};

// What an element keeps per instance, under its object lock.
template <typename S>
struct PropertyStore {
  S settings;
  // Bumped by each accepted value of a versioned property, so the streaming thread re-reads only on change.
  guint64 version = 0;
  bool running = false;                  // between start and stop
  std::map<guint, std::string> refused;  // by property id: a value refused before start, an error at start
};

// The helpers the table's templates share; in property-table.cpp.
GParamFlags flagsFor(Apply apply);
bool sameValue(const GValue *a, const GValue *b);
std::string refusalText(GParamSpec *pspec, const GValue *value, const char *why);
std::string keepingText(const std::string &refusal, const GValue *kept);
std::string readAtStartText(GParamSpec *pspec);
void postSettingsWarning(GstElement *element, GstDebugCategory *category, const std::string &text);

template <typename S>
class PropertyTable {
 public:
  // Property ids are 1 + the index in `defs`; gst-inspect-1.0 lists them in this order.
  template <std::size_t N>
  explicit PropertyTable(const PropertyDef<S> (&defs)[N]) : defs_(defs), count_(N) {}

  void install(GObjectClass *klass) const {
    for (std::size_t i = 0; i < count_; ++i)
      g_object_class_install_property(klass, static_cast<guint>(i + 1),
                                      defs_[i].spec(flagsFor(defs_[i].apply)));
  }

  void get(GstElement *element, const PropertyStore<S> &store, guint id, GValue *value,
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
  void set(GstElement *element, GstDebugCategory *category, PropertyStore<S> &store, guint id,
           const GValue *value, GParamSpec *pspec) const {
    if (id == 0 || id > count_) {
      G_OBJECT_WARN_INVALID_PROPERTY_ID(element, id, pspec);
      return;
    }
    const PropertyDef<S> &def = defs_[id - 1];
    GValue before = G_VALUE_INIT, after = G_VALUE_INIT;
    g_value_init(&before, G_PARAM_SPEC_VALUE_TYPE(pspec));
    g_value_init(&after, G_PARAM_SPEC_VALUE_TYPE(pspec));
    std::string warning;
    GST_OBJECT_LOCK(element);
    def.get(store.settings, &before);
    if (const char *why = def.refuse ? def.refuse(value) : nullptr) {
      const std::string refusal = refusalText(pspec, value, why);
      if (store.running)
        warning = keepingText(refusal, &before);
      else
        store.refused[id] = refusal;
    } else {
      store.refused.erase(id);
      def.set(store.settings, value);
      if (def.versioned) ++store.version;
      def.get(store.settings, &after);
      // Said at once, or the user would think the new value applied.
      if (def.apply == Apply::AtStart && store.running && !sameValue(&before, &after))
        warning = readAtStartText(pspec);
    }
    GST_OBJECT_UNLOCK(element);
    g_value_unset(&before);
    g_value_unset(&after);
    if (!warning.empty()) postSettingsWarning(element, category, warning);
  }

 private:
  const PropertyDef<S> *defs_;
  std::size_t count_;
};

}  // namespace gstglue
