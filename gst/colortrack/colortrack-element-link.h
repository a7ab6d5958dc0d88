// SPDX-License-Identifier: LGPL-2.1-or-later
// ElementLink: the ElementSink of the colortrack element itself, writing into its private data.
#pragma once

#include <string>

#include "colortrack-element-sink.h"
#include "colortrack-state.h"

namespace colortrack_gst {

class ElementLink final : public ElementSink {
 public:
  // `priv`: the element's private data (the link needs no more of the element than that and the GstElement).
  ElementLink(GstElement *element, GstColorTrackPrivate *priv) : element_(element), priv_(priv) {}

  void error(GQuark domain, gint code, const std::string &text, const char *debug, const char *file,
             const char *function, int line) const override;
  void warning(GQuark domain, gint code, const std::string &text, const char *debug, const char *file,
               const char *function, int line) const override;
  void info(const std::string &text) const override;
  void targetChanged() const override;
  void resumed() const override;
  void stopped() const override;
  void tracksReset() const override;
  bool takeResetRequest() const override;
  colortrack::BlobSettings writeLearntRange(const colortrack::HsvRange &range) const override;
  void restoreTemplateLocation(const std::string &refused, const std::string &inUse) const override;

 private:
  GstElement *element_;
  GstColorTrackPrivate *priv_;
};

}  // namespace colortrack_gst
