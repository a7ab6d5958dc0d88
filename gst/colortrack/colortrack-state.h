// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's private data, shared by the files of the element: the element core (settings and requests,
// under the object lock) and what the streaming thread owns.
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include <gst/gst.h>

#include "colortrack/scratch_image.hpp"
#include "analytics-meta.h"
#include "colortrack-mode.h"
#include "colortrack-settings.h"
#include "track-overlay.h"

GST_DEBUG_CATEGORY_EXTERN(gst_color_track_debug);

namespace colortrack_gst {

// What the streaming thread owns (and start()/stop(), which never run concurrently with it).
struct State {
  // The mode property's mode, made at start (the property cannot change while the element is started).
  std::unique_ptr<Mode> mode;
  colortrack::ScratchImage frameCache;  // the frame view's converted pixels, kept from frame to frame
  Trails trails;
  AnalyticsTracks analytics;  // GStreamer >= 1.24: the tracks in the analytics meta (first seen, gone)
  guint64 frameCount = 0;
  bool capsChanged = false;
  // After a right click: nothing is tracked (no meta, no overlay) until a left click, init-box,
  // template-location (template mode) or hsv-lower/hsv-upper (threshold mode) gives a new target.
  bool idle = false;
  GstClockTime lastPts = GST_CLOCK_TIME_NONE;
};

}  // namespace colortrack_gst

typedef struct _GstColorTrackPrivate GstColorTrackPrivate;  // (also declared by gstcolortrack.h)
struct _GstColorTrackPrivate {
  explicit _GstColorTrackPrivate(GstElement *element)
      : core(element, gst_color_track_debug, colortrack_gst::properties()) {}
  colortrack_gst::ElementCore core;
  colortrack_gst::State state;
  std::atomic<bool> resetRequested{false};
};
