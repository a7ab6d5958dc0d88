// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's settings, what its properties say, and the table that declares those properties.
#pragma once

#include <string>

#include "colortrack-requests.h"
#include "colortrack/blobs.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/settings.hpp"
#include "colortrack/tracker.hpp"
#include "colortrack-enums.h"
#include "element-core.h"

namespace colortrack_gst {

// Read by the streaming thread as a snapshot, under the object lock. Text properties keep what the user
// wrote, also a value refused before start (the error comes at start).
struct Settings {
  // What a change of a property marks (PropertyDef::changes), so the mode applies just that.
  enum class Change : unsigned {
    Tracker,   // `tracker`
    Template,  // template-location
    Blobs,     // `blobs`
    Range,     // hsv-lower/hsv-upper (a new target: ends idle)
  };

  colortrack::TrackingMode mode = colortrack::TrackingMode::Template;
  colortrack::TrackerSettings tracker;
  std::string bins = colortrack::formatBins(tracker.bins);
  std::string weights = colortrack::formatWeights(tracker.weights);
  std::string initBox;  // cleared once used
  std::string templateLocation;
  bool clickToTrack = true;
  int clickBoxSize = 64;
  guint draw = GST_COLOR_TRACK_DRAW_BOX | GST_COLOR_TRACK_DRAW_TRAIL | GST_COLOR_TRACK_DRAW_LABEL;
  guint trailLength = 30;
  bool postMessages = false;
  // mode=threshold: range, clean-up and blob limits; the range ends as the user wrote them.
  colortrack::BlobSettings blobs;
  std::string hsvLower = colortrack::formatHsv(blobs.range.lower);
  std::string hsvUpper = colortrack::formatHsv(blobs.range.upper);
};

using PropertyStore = gstglue::PropertyStore<Settings, Shared>;
using ElementCore = gstglue::ElementCore<Settings, Shared>;

// In the order gst-inspect-1.0 lists them.
const gstglue::PropertyTable<Settings, Shared> &properties();

}  // namespace colortrack_gst
