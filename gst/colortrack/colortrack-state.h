// colortrack's private data, shared by the files of the element: the property store (settings and requests,
// under the object lock) and what the streaming thread owns.
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include <gst/gst.h>

#include "colortrack/scratch_image.hpp"
#include "colortrack/threshold_tracker.hpp"
#include "colortrack/tracker.hpp"
#include "analytics-meta.h"
#include "colortrack-settings.h"
#include "gstcolortrack.h"
#include "track-overlay.h"

GST_DEBUG_CATEGORY_EXTERN(gst_color_track_debug);

namespace colortrack_gst {

// The settings as one frame sees them, with the store's counters at that moment.
struct Snapshot : Settings {
  guint64 trackerGeneration = 0, templateGeneration = 0, blobsGeneration = 0, rangeGeneration = 0;
};

// What the streaming thread owns (and start()/stop(), which never run concurrently with it).
struct State {
  std::unique_ptr<colortrack::Tracker> templateTracker;
  colortrack::ScratchImage frameCache;  // the frame view's converted pixels, kept from frame to frame
  std::unique_ptr<colortrack::ThresholdTracker> thresholdTracker;
  guint64 appliedTrackerGeneration = 0;
  guint64 appliedTemplateGeneration = 0;
  guint64 appliedBlobsGeneration = 0;
  guint64 appliedRangeGeneration = 0;
  std::string templateOrigin;    // "template-location 'x.png'" or "init-box '1,2,3,4'", for error messages
  std::string templateLocation;  // the template-location last loaded (what a refused one reads back as)
  Trails trails;
  AnalyticsTracks analytics;  // GStreamer >= 1.24: the tracks in the analytics meta (first seen, gone)
  guint64 frameCount = 0;
  bool warnedNoTemplate = false;
  bool capsChanged = false;
  // After a right click: nothing is tracked (no meta, no overlay) until a left click, init-box,
  // template-location (template mode) or hsv-lower/hsv-upper (threshold mode) gives a new target.
  bool idle = false;
  GstClockTime lastPts = GST_CLOCK_TIME_NONE;
};

}  // namespace colortrack_gst

struct _GstColorTrackPrivate {
  colortrack_gst::PropertyStore store;
  colortrack_gst::State state;
  std::atomic<bool> resetRequested{false};
};
