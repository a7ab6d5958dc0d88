// GstRobotCtl: the `robotctl` element, a GstBaseSink that turns track metadata into robot drive commands.
#pragma once

#include <gst/base/gstbasesink.h>
#include <gst/gst.h>

G_BEGIN_DECLS

#define GST_TYPE_ROBOT_CTL (gst_robot_ctl_get_type())
#define GST_ROBOT_CTL(obj) (G_TYPE_CHECK_INSTANCE_CAST((obj), GST_TYPE_ROBOT_CTL, GstRobotCtl))
#define GST_IS_ROBOT_CTL(obj) (G_TYPE_CHECK_INSTANCE_TYPE((obj), GST_TYPE_ROBOT_CTL))

/**
 * GstRobotCtlProtocol:
 * @GST_ROBOT_CTL_PROTOCOL_ZONE_CHAR: one character per command (#GstRobotCtl:zone-chars)
 * @GST_ROBOT_CTL_PROTOCOL_TEXT: one line "L=<int> R=<int>\n" per command
 * @GST_ROBOT_CTL_PROTOCOL_BINARY: a 10-byte packet: 0xA5, sequence, length 6, command, flags, left and
 *   right (int16 little-endian), CRC-8
 * @GST_ROBOT_CTL_PROTOCOL_MAVLINK: MAVLink 2 frames for a gimbal or a drone (#GstRobotCtl:mavlink-mode), and
 *   a HEARTBEAT at 1 Hz
 */
typedef enum {
  GST_ROBOT_CTL_PROTOCOL_ZONE_CHAR = 0,
  GST_ROBOT_CTL_PROTOCOL_TEXT = 1,
  GST_ROBOT_CTL_PROTOCOL_BINARY = 2,
  GST_ROBOT_CTL_PROTOCOL_MAVLINK = 3,
} GstRobotCtlProtocol;

/**
 * GstRobotCtlMavlinkMode:
 * @GST_ROBOT_CTL_MAVLINK_MODE_GIMBAL: GIMBAL_MANAGER_SET_PITCHYAW: pitch and yaw rates that centre the target
 * @GST_ROBOT_CTL_MAVLINK_MODE_FOLLOW: SET_POSITION_TARGET_LOCAL_NED in the body frame: forward velocity and
 *   yaw rate
 */
typedef enum {
  GST_ROBOT_CTL_MAVLINK_MODE_GIMBAL = 0,
  GST_ROBOT_CTL_MAVLINK_MODE_FOLLOW = 1,
} GstRobotCtlMavlinkMode;

/**
 * GstRobotCtlController:
 * @GST_ROBOT_CTL_CONTROLLER_ZONE: five commands from the zone of the frame the target is in (not for a
 *   gimbal)
 * @GST_ROBOT_CTL_CONTROLLER_PROPORTIONAL: wheel speeds proportional to the offset and the distance error
 * @GST_ROBOT_CTL_CONTROLLER_AUTO: zone for a robot or a drone, proportional for a gimbal
 */
typedef enum {
  GST_ROBOT_CTL_CONTROLLER_ZONE = 0,
  GST_ROBOT_CTL_CONTROLLER_PROPORTIONAL = 1,
  GST_ROBOT_CTL_CONTROLLER_AUTO = 2,
} GstRobotCtlController;

/**
 * GstRobotCtlDistanceCue:
 * @GST_ROBOT_CTL_DISTANCE_CUE_SIZE: the box height (a closer target looks bigger)
 * @GST_ROBOT_CTL_DISTANCE_CUE_POSITION: the box bottom (on a flat floor a closer target sits lower)
 */
typedef enum {
  GST_ROBOT_CTL_DISTANCE_CUE_SIZE = 0,
  GST_ROBOT_CTL_DISTANCE_CUE_POSITION = 1,
} GstRobotCtlDistanceCue;

/**
 * GstRobotCtlParity:
 * @GST_ROBOT_CTL_PARITY_NONE: no parity bit
 * @GST_ROBOT_CTL_PARITY_ODD: odd parity
 * @GST_ROBOT_CTL_PARITY_EVEN: even parity
 * @GST_ROBOT_CTL_PARITY_MARK: parity bit always 1
 * @GST_ROBOT_CTL_PARITY_SPACE: parity bit always 0
 */
typedef enum {
  GST_ROBOT_CTL_PARITY_NONE = 0,
  GST_ROBOT_CTL_PARITY_ODD = 1,
  GST_ROBOT_CTL_PARITY_EVEN = 2,
  GST_ROBOT_CTL_PARITY_MARK = 3,
  GST_ROBOT_CTL_PARITY_SPACE = 4,
} GstRobotCtlParity;

/**
 * GstRobotCtlFlowControl:
 * @GST_ROBOT_CTL_FLOW_CONTROL_NONE: no flow control
 * @GST_ROBOT_CTL_FLOW_CONTROL_XONXOFF: software (XON/XOFF)
 * @GST_ROBOT_CTL_FLOW_CONTROL_RTSCTS: hardware (RTS/CTS)
 * @GST_ROBOT_CTL_FLOW_CONTROL_DTRDSR: hardware (DTR/DSR)
 */
typedef enum {
  GST_ROBOT_CTL_FLOW_CONTROL_NONE = 0,
  GST_ROBOT_CTL_FLOW_CONTROL_XONXOFF = 1,
  GST_ROBOT_CTL_FLOW_CONTROL_RTSCTS = 2,
  GST_ROBOT_CTL_FLOW_CONTROL_DTRDSR = 3,
} GstRobotCtlFlowControl;

/**
 * GstRobotCtlLockOn:
 * @GST_ROBOT_CTL_LOCK_ON_FIRST_CONFIRMED: the oldest track (lowest id)
 * @GST_ROBOT_CTL_LOCK_ON_LARGEST: the largest box
 * @GST_ROBOT_CTL_LOCK_ON_NEAREST_CENTRE: the box nearest the frame's centre
 */
typedef enum {
  GST_ROBOT_CTL_LOCK_ON_FIRST_CONFIRMED = 0,
  GST_ROBOT_CTL_LOCK_ON_LARGEST = 1,
  GST_ROBOT_CTL_LOCK_ON_NEAREST_CENTRE = 2,
} GstRobotCtlLockOn;

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
