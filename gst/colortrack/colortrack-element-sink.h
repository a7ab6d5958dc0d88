// SPDX-License-Identifier: LGPL-2.1-or-later
// What a mode may do to the element (colortrack-mode.h): post messages, tell it the target changed or
// stopped (its trails and idle state), take a pending reset, and write back the two properties the streaming
// thread ever writes (a learnt colour range, a refused template-location).
#pragma once

#include <string>

#include <gst/gst.h>

#include "colortrack/blobs.hpp"

namespace colortrack_gst {

// Where in the source a message was decided: the caller's place. error() and warning() take it through
// default arguments that are GCC's and Clang's __builtin_FILE / __builtin_FUNCTION / __builtin_LINE, which
// are evaluated at each call (as C++20's std::source_location::current() is; this project builds as C++17),
// so GST_DEBUG and the message's debug text name the mode's line, not the sink's.
struct CallSite {
  const char *file;
  const char *function;
  int line;
};

// An interface, so that a mode can be tested against a fake (the element's is ElementLink,
// colortrack-element-link.h).
class ElementSink {
 public:
  virtual ~ElementSink() = default;

  // An element error or warning (GST_ELEMENT_ERROR / GST_ELEMENT_WARNING with this text and debug detail).
  virtual void error(GQuark domain, gint code, const std::string &text, const char *debug = nullptr,
                     const char *file = __builtin_FILE(), const char *function = __builtin_FUNCTION(),
                     int line = __builtin_LINE()) const = 0;
  virtual void warning(GQuark domain, gint code, const std::string &text, const char *debug = nullptr,
                       const char *file = __builtin_FILE(), const char *function = __builtin_FUNCTION(),
                       int line = __builtin_LINE()) const = 0;
  virtual void info(const std::string &text) const = 0;

  // A new target: its trails start over and the element leaves the idle state.
  virtual void targetChanged() const = 0;
  // A new target the tracks there are may carry on with: the element leaves the idle state, trails kept.
  virtual void resumed() const = 0;
  // A right click: trails cleared, and nothing reported until a new target.
  virtual void stopped() const = 0;
  // The tracks were reset (no new target): their trails go.
  virtual void tracksReset() const = 0;
  // New caps or the "reset" signal since the last call.
  virtual bool takeResetRequest() const = 0;

  // Writes a colour range learnt from the video to hsv-lower/hsv-upper (and notifies); returns the blob
  // settings as they now are, which the mode thereby applies (no longer a change for the next frame).
  virtual colortrack::BlobSettings writeLearntRange(const colortrack::HsvRange &range) const = 0;
  // template-location reads back as `inUse` when the value `refused` could not be used (unless it was set
  // again meanwhile).
  virtual void restoreTemplateLocation(const std::string &refused, const std::string &inUse) const = 0;
};

}  // namespace colortrack_gst
