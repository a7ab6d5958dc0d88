// SPDX-License-Identifier: LGPL-2.1-or-later
// The GTypes of robotctl's enum properties, generated from the tables that declare the values.

#include "robotctl-enums.h"

#include "colortrack/controller.hpp"
#include "colortrack/protocol.hpp"
#include "colortrack/target_lock.hpp"
#include "colortrack/robot_port.hpp"
#include "enum-types.h"

COLORTRACK_DEFINE_CHOICE_TYPE(gst_robot_ctl_protocol_get_type, "GstRobotCtlProtocol",
                              colortrack::protocolDescriptors())
COLORTRACK_DEFINE_CHOICE_TYPE(gst_robot_ctl_mavlink_mode_get_type, "GstRobotCtlMavlinkMode",
                              colortrack::kMavlinkModes)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_robot_ctl_controller_get_type, "GstRobotCtlController",
                              colortrack::kControllerKinds)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_robot_ctl_distance_cue_get_type, "GstRobotCtlDistanceCue",
                              colortrack::kDistanceCues)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_robot_ctl_parity_get_type, "GstRobotCtlParity", robotctl::kParities)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_robot_ctl_flow_control_get_type, "GstRobotCtlFlowControl",
                              robotctl::kFlowControls)
COLORTRACK_DEFINE_CHOICE_TYPE(gst_robot_ctl_lock_on_get_type, "GstRobotCtlLockOn", colortrack::kLockOns)
