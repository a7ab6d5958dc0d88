// SPDX-License-Identifier: LGPL-2.1-or-later
#pragma once

#include <gst/base/gstbasetransform.h>
#include <gst/gst.h>

G_BEGIN_DECLS

#define GST_TYPE_TRACK_PUBLISH (gst_track_publish_get_type())
#define GST_TRACK_PUBLISH(obj) (G_TYPE_CHECK_INSTANCE_CAST((obj), GST_TYPE_TRACK_PUBLISH, GstTrackPublish))

typedef struct _GstTrackPublish GstTrackPublish;
typedef struct _GstTrackPublishClass GstTrackPublishClass;
typedef struct _GstTrackPublishPrivate GstTrackPublishPrivate;

struct _GstTrackPublish {
  GstBaseTransform parent;
  GstTrackPublishPrivate *priv;
};

struct _GstTrackPublishClass {
  GstBaseTransformClass parent_class;
};

GType gst_track_publish_get_type(void);

GST_ELEMENT_REGISTER_DECLARE(trackpublish);

G_END_DECLS
