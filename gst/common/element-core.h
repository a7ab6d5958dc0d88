// SPDX-License-Identifier: LGPL-2.1-or-later
// What every element of the plugin does alike with its properties: the store of its settings under the
// object lock, the table that declares them, and the start sequence. Start takes the settings' snapshot,
// refuses what was refused before it (the first property's refusal), then judges the table's start rules;
// from the snapshot on the element counts as running, so a start-only property set meanwhile is refused
// instead of reading back a value that does not run. Each frame takes the settings with the set of what
// changed since the last one (ChangeSet), so the element's engine applies just that.
#pragma once

#include <gst/gst.h>

#include <optional>
#include <string>
#include <utility>

#include "property-table.h"

namespace gstglue {

template <typename S, typename X = NoShared>
class ElementCore {
 public:
  using Store = PropertyStore<S, X>;
  using Table = PropertyTable<S, X>;
  using Changes = ChangeSet<typename S::Change>;

  ElementCore(GstElement *element, GstDebugCategory *category, const Table &table)
      : element_(element), category_(category), table_(table) {}

  // Under the object lock.
  Store &store() { return store_; }
  const Store &store() const { return store_; }

  void set(guint id, const GValue *value, GParamSpec *pspec) {
    table_.set(element_, category_, store_, id, value, pspec);
  }
  void get(guint id, GValue *value, GParamSpec *pspec) const {
    table_.get(element_, store_, id, value, pspec);
  }

  // The settings the element starts with, or none after posting why it cannot start. Every change made
  // before is in the snapshot, so the set of changes starts empty.
  std::optional<S> start() {
    GST_OBJECT_LOCK(element_);
    table_.recheckRefused(store_);
    const S settings = store_.settings;
    const std::string refusal = store_.firstRefusal();
    store_.changed = {};
    store_.running = true;
    GST_OBJECT_UNLOCK(element_);
    if (!refusal.empty()) {
      postStartRefusal(element_, category_, refusal);
      stop();
      return std::nullopt;
    }
    for (const StartRule<S> &rule : table_.startRules()) {
      const colortrack::Status verdict = rule.problem(settings);
      if (verdict) continue;
      const bool error = rule.severity == StartRule<S>::Severity::Error;
      postStartProblem(element_, category_, rule.code, error, verdict.message());
      if (!error) continue;
      stop();
      return std::nullopt;
    }
    return settings;
  }

  // After stop(), or a start that fails after start() gave its settings.
  void stop() {
    GST_OBJECT_LOCK(element_);
    store_.running = false;
    GST_OBJECT_UNLOCK(element_);
  }

  // Under the object lock: what changed since the last call (or the start), now forgotten.
  Changes takeChanges() { return std::exchange(store_.changed, Changes{}); }

 private:
  GstElement *element_;
  GstDebugCategory *category_;
  const Table &table_;
  Store store_;
};

}  // namespace gstglue
