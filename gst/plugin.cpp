// The colortrack plugin: one module, one registration function per element.
#include <gst/gst.h>

#include "gstcolortrack.h"
#include "gstrobotctl.h"

// Add later elements here (GST_ELEMENT_REGISTER(robotctl, plugin), ...).
static gboolean plugin_init(GstPlugin *plugin) {
  gboolean ok = FALSE;
  ok |= GST_ELEMENT_REGISTER(colortrack, plugin);
  ok |= GST_ELEMENT_REGISTER(robotctl, plugin);
  return ok;
}

GST_PLUGIN_DEFINE(GST_VERSION_MAJOR, GST_VERSION_MINOR, colortrack,
                  "Colour-indexing object tracker (modified colour indexing with Kalman filtering)", plugin_init,
                  VERSION, "LGPL", "colortrack", "Unknown package origin")
