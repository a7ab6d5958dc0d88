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
#include "property-table.h"

namespace colortrack_gst {

// Read by the streaming thread as a snapshot, under the object lock. Text properties keep what the user
// wrote, also a value refused before start (the error comes at start).
struct Settings {
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

// The store's counters (PropertyStore::versions).
enum Version : unsigned {
  kTrackerVersion,   // `tracker` changed
  kTemplateVersion,  // template-location set
  kBlobsVersion,     // `blobs` changed
  kRangeVersion,     // hsv-lower/hsv-upper set (a new target: ends idle)
};

using PropertyStore = gstglue::PropertyStore<Settings, Shared>;

// In the order gst-inspect-1.0 lists them.
const gstglue::PropertyTable<Settings, Shared> &properties();

// Why properties that each define the object contradict each other, for start() to refuse; empty when they
// do not: a template file with an init-box (the box would replace the file's template on the first frame),
// or in threshold mode (which never reads it).
std::string objectDefinitionConflict(const Settings &s);

// The properties whose refused value start() reports, in the order it checks them.
inline constexpr const char *kCheckedAtStart[] = {"bins", "channel-weights", "init-box", "hsv-lower",
                                                  "hsv-upper"};

}  // namespace colortrack_gst
