// SPDX-License-Identifier: LGPL-2.1-or-later
// One row of an element's property table, and what the rows act on: the store of the element's settings.
// A row is written by name, e.g.
//   Def::live(spec).marks({Change::Tracker}).field<&Settings::tracker, &TrackerSettings::method>()
// so that a reader never counts positional fields.
#pragma once

#include <gst/gst.h>

#include <map>
#include <string>

#include "colortrack/status.hpp"
#include "change-set.h"
#include "property-accessors.h"

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
// values and nothing else, with `S::Change`, the groups a change is marked with. `X` is what else the threads
// share: requests waiting for the streaming thread and runtime facts a property's check needs.
template <typename S, typename X = NoShared>
struct PropertyStore {
  S settings;
  X shared;
  ChangeSet<typename S::Change> changed;  // since the streaming thread last took it
  bool running = false;                   // from start's snapshot to stop
  std::map<guint, std::string> refused;   // by property id: a value refused before start, an error at start

  // The refusal the start reports (the first property's), or empty.
  std::string firstRefusal() const { return refused.empty() ? std::string() : refused.begin()->second; }
};

template <typename S, typename X = NoShared>
struct PropertyDef {
  using Store = PropertyStore<S, X>;
  using Changes = ChangeSet<typename S::Change>;
  using Spec = GParamSpec *(*)(GParamFlags flags);
  using Get = void (*)(const S &settings, GValue *value);
  using Set = void (*)(S &settings, const GValue *value);
  using Refuse = colortrack::Status (*)(const GValue *value);
  using Check = colortrack::Status (*)(const Store &store, const GValue *value);
  using Accepted = void (*)(Store &store);
  using Show = std::string (*)(const GValue *value);

  Apply apply = Apply::Live;
  Changes changes;  // added to the store's `changed` by each accepted value
  Spec spec = nullptr;
  Get get = nullptr;
  Set set = nullptr;
  // Why a value of the spec's range is still refused (a failed Status), judged by the value alone.
  Refuse refuse = nullptr;
  // The same for a value judged by parsing it or against the store (the other settings, running, the
  // runtime facts).
  Check check = nullptr;
  // A value refused before start is still stored, so that it reads back as written (text properties).
  bool keepRefused = false;
  // Called under the lock after an accepted value is set, e.g. to post a request for the streaming thread.
  Accepted accepted = nullptr;
  // How a value of this property is shown in messages, when not as itself: a secret ('***'), an address
  // whose password must not show. Null: as itself.
  Show shown = nullptr;

  // --- The row's parts, by name ---
  static PropertyDef live(Spec spec) { return made(Apply::Live, spec); }
  static PropertyDef atStart(Spec spec) { return made(Apply::AtStart, spec); }
  static PropertyDef beforeStart(Spec spec) { return made(Apply::BeforeStart, spec); }

  PropertyDef marks(Changes groups) const { return with(&PropertyDef::changes, groups); }
  // A bool, gint, guint, double or enum field, or one reached through a path of members.
  template <auto... path>
  PropertyDef field() const {
    return accessors(getValue<path...>, setValue<path...>);
  }
  template <auto member>
  PropertyDef flags() const {
    return accessors(getFlags<member>, setFlags<member>);
  }
  template <auto member>
  PropertyDef text() const {
    return accessors(getText<member>, setText<member>);
  }
  // An empty text reads back as NULL (a property whose default is "none").
  template <auto member>
  PropertyDef textOrNull() const {
    return accessors(getTextOrNull<member>, setText<member>);
  }
  // A value that needs more than a field's copy (a text parsed into a second field).
  PropertyDef accessors(Get getter, Set setter) const {
    PropertyDef row = *this;
    row.get = getter;
    row.set = setter;
    return row;
  }
  PropertyDef refusing(Refuse why) const { return with(&PropertyDef::refuse, why); }
  PropertyDef checking(Check why) const { return with(&PropertyDef::check, why); }
  PropertyDef keepingRefused() const { return with(&PropertyDef::keepRefused, true); }
  PropertyDef onAccepted(Accepted then) const { return with(&PropertyDef::accepted, then); }
  PropertyDef showing(Show how) const { return with(&PropertyDef::shown, how); }

 private:
  static PropertyDef made(Apply apply, Spec spec) {
    PropertyDef row;
    row.apply = apply;
    row.spec = spec;
    return row;
  }
  template <typename T>
  PropertyDef with(T PropertyDef::*part, T value) const {
    PropertyDef row = *this;
    row.*part = value;
    return row;
  }
};

}  // namespace gstglue
