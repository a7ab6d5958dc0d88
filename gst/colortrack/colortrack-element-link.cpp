// SPDX-License-Identifier: LGPL-2.1-or-later
// ElementLink: the modes' one way into the element's private data.
#include "colortrack-element-link.h"

#define GST_CAT_DEFAULT gst_color_track_debug

namespace colortrack_gst {

namespace {

void post(GstElement *element, GstMessageType type, GQuark domain, gint code, const std::string &text,
          const char *debug, const CallSite &where) {
  gst_element_message_full(element, type, domain, code, g_strdup(text.c_str()),
                           debug ? g_strdup(debug) : nullptr, where.file, where.function, where.line);
}

}  // namespace

void ElementLink::error(GQuark domain, gint code, const std::string &text, const char *debug,
                        const char *file, const char *function, int line) const {
  post(element_, GST_MESSAGE_ERROR, domain, code, text, debug, CallSite{file, function, line});
}

void ElementLink::warning(GQuark domain, gint code, const std::string &text, const char *debug,
                          const char *file, const char *function, int line) const {
  post(element_, GST_MESSAGE_WARNING, domain, code, text, debug, CallSite{file, function, line});
}

void ElementLink::info(const std::string &text) const {
  GST_INFO_OBJECT(element_, "%s", text.c_str());
}

void ElementLink::targetChanged() const {
  State &state = priv_->state;
  state.trails.clear();
  state.idle = false;
}

void ElementLink::resumed() const {
  priv_->state.idle = false;
}

void ElementLink::stopped() const {
  State &state = priv_->state;
  state.trails.clear();
  state.idle = true;
}

void ElementLink::tracksReset() const {
  priv_->state.trails.clear();
}

bool ElementLink::takeResetRequest() const {
  State &state = priv_->state;
  const bool reset = priv_->resetRequested.exchange(false) || state.capsChanged;
  state.capsChanged = false;
  return reset;
}

colortrack::BlobSettings ElementLink::writeLearntRange(const colortrack::HsvRange &range) const {
  GST_OBJECT_LOCK(element_);
  PropertyStore &store = priv_->core.store();
  store.settings.blobs.range = range;
  store.settings.hsvLower = colortrack::formatHsv(range.lower);
  store.settings.hsvUpper = colortrack::formatHsv(range.upper);
  const colortrack::BlobSettings blobs = store.settings.blobs;
  store.changed.remove(Settings::Change::Blobs);  // what the mode applies now
  GST_OBJECT_UNLOCK(element_);
  g_object_notify(G_OBJECT(element_), "hsv-lower");
  g_object_notify(G_OBJECT(element_), "hsv-upper");
  return blobs;
}

void ElementLink::restoreTemplateLocation(const std::string &refused, const std::string &inUse) const {
  GST_OBJECT_LOCK(element_);
  std::string &location = priv_->core.store().settings.templateLocation;
  const bool unchanged = location == refused;
  if (unchanged) location = inUse;
  GST_OBJECT_UNLOCK(element_);
  if (unchanged) g_object_notify(G_OBJECT(element_), "template-location");
}

}  // namespace colortrack_gst
