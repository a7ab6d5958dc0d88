// SPDX-License-Identifier: LGPL-2.1-or-later
/* Names of what the colortrack and robotctl elements attach to buffers and post on the bus, so an
 * application can read them without spelling field names by hand. Plain C, no dependency beyond the
 * preprocessor: include it next to <gst/video/video.h>. docs/api.md lists every field with its type.
 *
 * Installed as <colortrack/colortrack-meta.h>.
 */
#ifndef COLORTRACK_META_H
#define COLORTRACK_META_H

/* GstVideoRegionOfInterestMeta attached by colortrack: one per tracked object on every buffer with a
 * track. Its roi_type is this quark string; meta->id is the track id (>= 1, new at every acquisition);
 * x, y, w, h is the Kalman-filtered box, rounded and clipped to the frame. */
#define COLORTRACK_ROI_TYPE "colortrack"

/* The parameter structure on that meta (gst_video_region_of_interest_meta_get_param). */
#define COLORTRACK_PARAMS_NAME "colortrack"
#define COLORTRACK_PARAM_STATE "state" /* string: one of COLORTRACK_STATE_* */
/* double: method=fused: confidence 0-1 (under 0.5: coasting); else the match value, 0 while coasting */
#define COLORTRACK_PARAM_SCORE "score"
#define COLORTRACK_PARAM_VERIFIED "verified" /* gboolean: the edge check accepted the match */
#define COLORTRACK_PARAM_SCALE "scale"       /* double: box size relative to the template */
#define COLORTRACK_PARAM_VX "vx"             /* double: horizontal velocity, pixels per frame */
#define COLORTRACK_PARAM_VY "vy"             /* double: vertical velocity, pixels per frame */
#define COLORTRACK_PARAM_AREA "area"         /* double: blob area in pixels (mode=threshold only) */

/* GStreamer 1.22 drops the parameter structure when videoconvert, videoscale or a buffer copy transforms the
 * ROI meta. colortrack therefore also attaches one GstCustomMeta of this name per buffer (registered when the
 * plugin loads): its structure holds each track's parameter structure (GST_TYPE_STRUCTURE) in a field named
 * "id-<track id>.<element name>", and in "id-<track id>" for the first element that reports that id on the
 * buffer; each entry adds "element" and the attached box ("roi-x", "roi-y", "roi-w", "roi-h"). It survives
 * those elements. Read it with
 *   gst_buffer_get_custom_meta (buffer, COLORTRACK_PARAMS_META_NAME)
 * when gst_video_region_of_interest_meta_get_param () returns NULL. */
#define COLORTRACK_PARAMS_META_NAME "GstColorTrackParamsMeta"

/* Built against GStreamer 1.24 or newer, colortrack also attaches a GstAnalyticsRelationMeta: per track with
 * a ROI meta an object-detection mtd (type COLORTRACK_ROI_TYPE, the same box, confidence = score clamped to
 * 0..1) related (GST_ANALYTICS_REL_TYPE_RELATE_TO) to a tracking mtd (tracking id = meta->id, first and last
 * seen, lost); a track gone since the previous buffer gets a lost tracking mtd alone. docs/api.md has more.
 */

/* Track states, as in the meta params and the bus message. */
#define COLORTRACK_STATE_SEARCHING "searching"
#define COLORTRACK_STATE_TRACKING "tracking"
#define COLORTRACK_STATE_COASTING "coasting"
#define COLORTRACK_STATE_LOST "lost"
/* Messages only: tracking stopped by a right click until the next click, init-box or template. */
#define COLORTRACK_STATE_IDLE "idle"

/* Element message posted by colortrack for every frame when post-messages=true. */
#define COLORTRACK_MESSAGE_NAME "colortrack"
#define COLORTRACK_MESSAGE_TIMESTAMP "timestamp"     /* guint64: buffer PTS, GST_CLOCK_TIME_NONE if unknown */
#define COLORTRACK_MESSAGE_STREAM_TIME "stream-time" /* guint64 */
#define COLORTRACK_MESSAGE_RUNNING_TIME "running-time" /* guint64 */
#define COLORTRACK_MESSAGE_DURATION "duration"         /* guint64 */
#define COLORTRACK_MESSAGE_FRAME "frame"               /* guint64: frames since start, from 0 */
#define COLORTRACK_MESSAGE_ID "id"                     /* gint: track id, 0 when there is none */
#define COLORTRACK_MESSAGE_STATE "state"               /* string: one of COLORTRACK_STATE_* */
#define COLORTRACK_MESSAGE_X "x"                       /* double: box, pixels (0 without a track) */
#define COLORTRACK_MESSAGE_Y "y"                       /* double */
#define COLORTRACK_MESSAGE_WIDTH "width"               /* double */
#define COLORTRACK_MESSAGE_HEIGHT "height"             /* double */
#define COLORTRACK_MESSAGE_SCORE "score"               /* double */
#define COLORTRACK_MESSAGE_VERIFIED "verified"         /* gboolean */
#define COLORTRACK_MESSAGE_SCALE "scale"               /* double */
/* mode=threshold only: a GST_TYPE_LIST of structures named COLORTRACK_OBJECT_NAME. */
#define COLORTRACK_MESSAGE_OBJECTS "objects"
#define COLORTRACK_OBJECT_NAME "colortrack-object"
#define COLORTRACK_OBJECT_ID "id"         /* gint */
#define COLORTRACK_OBJECT_X "x"           /* double */
#define COLORTRACK_OBJECT_Y "y"           /* double */
#define COLORTRACK_OBJECT_WIDTH "width"   /* double */
#define COLORTRACK_OBJECT_HEIGHT "height" /* double */
#define COLORTRACK_OBJECT_CX "cx"         /* double: blob centroid */
#define COLORTRACK_OBJECT_CY "cy"         /* double */
#define COLORTRACK_OBJECT_AREA "area"     /* double: pixels */
#define COLORTRACK_OBJECT_STATE "state"   /* string */
#define COLORTRACK_OBJECT_SCORE "score"   /* double */

/* Element message posted by robotctl for every command sent when post-messages=true. */
#define ROBOTCTL_MESSAGE_NAME "robotctl"
#define ROBOTCTL_MESSAGE_COMMAND "command" /* string: forward, backward, left, right, stop */
#define ROBOTCTL_MESSAGE_LEFT "left"       /* gint: left wheel speed as sent (not MAVLink) */
#define ROBOTCTL_MESSAGE_RIGHT "right"     /* gint: right wheel speed as sent (not MAVLink) */
/* MAVLink only, as sent, in MAVLink's units and signs: */
#define ROBOTCTL_MESSAGE_PITCH_RATE "pitch-rate" /* gdouble: rad/s, > 0 up (mavlink-mode=gimbal) */
#define ROBOTCTL_MESSAGE_YAW_RATE "yaw-rate"     /* gdouble: rad/s, > 0 clockwise seen from above (right) */
#define ROBOTCTL_MESSAGE_VX "vx"                 /* gdouble: m/s forward (mavlink-mode=follow) */
#define ROBOTCTL_MESSAGE_LINEAR "linear"         /* double */
#define ROBOTCTL_MESSAGE_ANGULAR "angular"       /* double */
#define ROBOTCTL_MESSAGE_TARGET_VISIBLE "target-visible" /* gboolean */
#define ROBOTCTL_MESSAGE_TIMESTAMP "timestamp"           /* guint64: PTS of the deciding buffer, or NONE */
#define ROBOTCTL_MESSAGE_REASON "reason"                 /* string: why this command was sent */

#endif /* COLORTRACK_META_H */
