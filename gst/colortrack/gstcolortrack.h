// SPDX-License-Identifier: LGPL-2.1-or-later
// GstColorTrack: the `colortrack` element, a GstVideoFilter that tracks a coloured object in place.
#pragma once

#include <gst/gst.h>
#include <gst/video/gstvideofilter.h>
#include <gst/video/video.h>

#include "colortrack-enums.h"

G_BEGIN_DECLS

#define GST_TYPE_COLOR_TRACK (gst_color_track_get_type())
#define GST_COLOR_TRACK(obj) (G_TYPE_CHECK_INSTANCE_CAST((obj), GST_TYPE_COLOR_TRACK, GstColorTrack))
#define GST_COLOR_TRACK_CLASS(klass) \
  (G_TYPE_CHECK_CLASS_CAST((klass), GST_TYPE_COLOR_TRACK, GstColorTrackClass))
#define GST_IS_COLOR_TRACK(obj) (G_TYPE_CHECK_INSTANCE_TYPE((obj), GST_TYPE_COLOR_TRACK))

typedef struct _GstColorTrack GstColorTrack;
typedef struct _GstColorTrackClass GstColorTrackClass;

// C++ data (settings and streaming state); defined in gstcolortrack.cpp.
typedef struct _GstColorTrackPrivate GstColorTrackPrivate;

struct _GstColorTrack {
  GstVideoFilter parent;
  GstColorTrackPrivate *priv;
};

struct _GstColorTrackClass {
  GstVideoFilterClass parent_class;
  /* action signals */
  void (*reset)(GstColorTrack *self);
};

GType gst_color_track_get_type(void);
GST_ELEMENT_REGISTER_DECLARE(colortrack);

G_END_DECLS
