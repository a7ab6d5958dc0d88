// SPDX-License-Identifier: LGPL-2.1-or-later
// What a mode may do to the element (colortrack-mode.h): post messages, tell it the target changed or
// stopped (its trails and idle state), take a pending reset, and write back the two properties the streaming
// thread ever writes (a learnt colour range, a refused template-location).
#pragma once

#include <string>

#include <gst/gst.h>

#include "colortrack/blobs.hpp"
#include "gstcolortrack.h"

namespace colortrack_gst {

class ElementSink {
 public:
  explicit ElementSink(GstColorTrack *element) : element_(element) {}

  // An element error or warning (GST_ELEMENT_ERROR / GST_ELEMENT_WARNING with this text and debug detail).
  void error(GQuark domain, gint code, const std::string &text, const char *debug = nullptr) const;
  void warning(GQuark domain, gint code, const std::string &text, const char *debug = nullptr) const;
  void info(const std::string &text) const;

  // A new target: its trails start over and the element leaves the idle state.
  void targetChanged() const;
  // A new target the tracks there are may carry on with: the element leaves the idle state, trails kept.
  void resumed() const;
  // A right click: trails cleared, and nothing reported until a new target.
  void stopped() const;
  // The tracks were reset (no new target): their trails go.
  void tracksReset() const;
  // New caps or the "reset" signal since the last call.
  bool takeResetRequest() const;

  // Writes a colour range learnt from the video to hsv-lower/hsv-upper (and notifies); returns the blob
  // settings as they now are and their counter, which the mode has thereby applied.
  colortrack::BlobSettings writeLearntRange(const colortrack::HsvRange &range, guint64 &generation) const;
  // template-location reads back as `inUse` when the value `refused` could not be used (unless it was set
  // again meanwhile).
  void restoreTemplateLocation(const std::string &refused, const std::string &inUse) const;

 private:
  GstColorTrack *element_;
};

}  // namespace colortrack_gst
