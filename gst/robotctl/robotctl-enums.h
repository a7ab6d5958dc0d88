// SPDX-License-Identifier: LGPL-2.1-or-later
// The types of robotctl's enum properties: what the settings need of the element, without the element.
#pragma once

#include <glib-object.h>

G_BEGIN_DECLS

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

G_END_DECLS
