// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's GstPreset: GStreamer's default implementation (a .prs keyfile per element type), with the list
// of saved properties narrowed and a fix-up after a load. See colortrack-preset.cpp.
#pragma once

#include <gst/gst.h>

G_BEGIN_DECLS

// The interface init for G_IMPLEMENT_INTERFACE(GST_TYPE_PRESET, ...).
void gst_color_track_preset_init(GstPresetInterface *iface);

G_END_DECLS
