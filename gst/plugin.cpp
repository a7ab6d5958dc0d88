// SPDX-License-Identifier: LGPL-2.1-or-later
// The colortrack plugin: one module, one registration function per element.
#include <gst/gst.h>

#include "gstcolortrack.h"
#include "gstrobotctl.h"
#include "gsttrackpublish.h"
#include "track-params.h"

static gboolean plugin_init(GstPlugin *plugin) {
  colortrack_params_meta_register();
  gboolean ok = FALSE;
  ok |= GST_ELEMENT_REGISTER(colortrack, plugin);
  ok |= GST_ELEMENT_REGISTER(robotctl, plugin);
  ok |= GST_ELEMENT_REGISTER(trackpublish, plugin);
  return ok;
}

GST_PLUGIN_DEFINE(GST_VERSION_MAJOR, GST_VERSION_MINOR, colortrack,
                  "Colour object tracking (modified colour indexing, Kalman filtering) and robot control",
                  plugin_init, VERSION, "LGPL", GST_PACKAGE_NAME, GST_PACKAGE_ORIGIN)
