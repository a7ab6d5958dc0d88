// SPDX-License-Identifier: LGPL-2.1-or-later
// GstRobotCtl: the `robotctl` element, a GstBaseSink that turns track metadata into robot drive commands.
#pragma once

#include <gst/base/gstbasesink.h>
#include <gst/gst.h>

#include "robotctl-enums.h"

G_BEGIN_DECLS

#define GST_TYPE_ROBOT_CTL (gst_robot_ctl_get_type())
#define GST_ROBOT_CTL(obj) (G_TYPE_CHECK_INSTANCE_CAST((obj), GST_TYPE_ROBOT_CTL, GstRobotCtl))
#define GST_IS_ROBOT_CTL(obj) (G_TYPE_CHECK_INSTANCE_TYPE((obj), GST_TYPE_ROBOT_CTL))

typedef struct _GstRobotCtl GstRobotCtl;
typedef struct _GstRobotCtlClass GstRobotCtlClass;
typedef struct _GstRobotCtlPrivate GstRobotCtlPrivate;

struct _GstRobotCtl {
  GstBaseSink parent;
  GstRobotCtlPrivate *priv;
};

struct _GstRobotCtlClass {
  GstBaseSinkClass parent_class;
};

GType gst_robot_ctl_get_type(void);

GST_ELEMENT_REGISTER_DECLARE(robotctl);

G_END_DECLS
