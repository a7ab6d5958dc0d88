// SPDX-License-Identifier: LGPL-2.1-or-later
// GstRobotCtl: the `robotctl` element, a GstBaseSink that turns track metadata into robot drive commands.
#pragma once

#include <gst/base/gstbasesink.h>
#include <gst/gst.h>

G_BEGIN_DECLS

#define GST_TYPE_ROBOT_CTL (gst_robot_ctl_get_type())
#define GST_ROBOT_CTL(obj) (G_TYPE_CHECK_INSTANCE_CAST((obj), GST_TYPE_ROBOT_CTL, GstRobotCtl))
#define GST_IS_ROBOT_CTL(obj) (G_TYPE_CHECK_INSTANCE_TYPE((obj), GST_TYPE_ROBOT_CTL))

/* The enum types of the properties (protocol, mavlink-mode, controller, distance-cue, parity, flow-control,
 * lock-on) are generated from the core tables that declare their values (the protocol registry's
 * protocolDescriptors(); colortrack::Choice tables kMavlinkModes, kControllerKinds, kDistanceCues, kLockOns;
 * robot-port.h: kParities, kFlowControls); the values are those tables' enums, in their order. */
GType gst_robot_ctl_protocol_get_type(void);
GType gst_robot_ctl_mavlink_mode_get_type(void);
GType gst_robot_ctl_controller_get_type(void);
GType gst_robot_ctl_distance_cue_get_type(void);
GType gst_robot_ctl_parity_get_type(void);
GType gst_robot_ctl_flow_control_get_type(void);
GType gst_robot_ctl_lock_on_get_type(void);
#define GST_TYPE_ROBOT_CTL_PROTOCOL (gst_robot_ctl_protocol_get_type())
#define GST_TYPE_ROBOT_CTL_MAVLINK_MODE (gst_robot_ctl_mavlink_mode_get_type())
#define GST_TYPE_ROBOT_CTL_CONTROLLER (gst_robot_ctl_controller_get_type())
#define GST_TYPE_ROBOT_CTL_DISTANCE_CUE (gst_robot_ctl_distance_cue_get_type())
#define GST_TYPE_ROBOT_CTL_PARITY (gst_robot_ctl_parity_get_type())
#define GST_TYPE_ROBOT_CTL_FLOW_CONTROL (gst_robot_ctl_flow_control_get_type())
#define GST_TYPE_ROBOT_CTL_LOCK_ON (gst_robot_ctl_lock_on_get_type())

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
