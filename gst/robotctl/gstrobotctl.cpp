// SPDX-License-Identifier: LGPL-2.1-or-later
/**
 * SECTION:element-robotctl
 * @title: robotctl
 *
 * Drives a robot towards a tracked target. Each video buffer's #GstVideoRegionOfInterestMeta (by default
 * the "colortrack" ROIs, see #GstRobotCtl:roi-type) gives where the target is. With several tracks,
 * robotctl locks onto one (#GstRobotCtl:lock-on: the oldest, the largest or the one nearest the centre, or a
 * fixed #GstRobotCtl:target-id) and keeps following it while its track lives, even when another object
 * passes in front; it chooses again only when that track is lost or gone, and then never a track it saw
 * beside the followed one (another object, such as a decoy that hid the target); a controller turns that into
 * a drive command and the command goes out on a serial port
 * (#GstRobotCtl:device) or to a file, FIFO, pseudo-terminal or stdout (#GstRobotCtl:location).
 *
 * Two controllers (#GstRobotCtl:controller): "zone" splits the frame into left / centre / right by the
 * target's horizontal offset and into too-far / right / too-close by its size (or the height of its bottom
 * edge, #GstRobotCtl:distance-cue) and sends forward, backward, left, right or stop, with a deadband and
 * hysteresis against chatter, and near the centre turns in single steps that wait #GstRobotCtl:latency for
 * their effect; "proportional" sets the turn from the offset and the speed from the distance error, each
 * with a proportional, an integral (without wind-up) and a rate term, limits and an acceleration limit, as
 * left/right wheel speeds, and stops once the target is well within the deadbands.
 *
 * Four protocols (#GstRobotCtl:protocol): "zone-char" (one character per command, #GstRobotCtl:zone-chars,
 * default "FBLRS"), "text" ("L=<int> R=<int>\n", wheel speeds times #GstRobotCtl:output-scale), "binary"
 * (0xA5, sequence, length, command, flags, left, right, CRC-8; see docs/robotctl.md) and "mavlink"
 * (MAVLink 2 for a flight controller or a gimbal, with a HEARTBEAT at 1 Hz from #GstRobotCtl:system-id and
 * #GstRobotCtl:component-id). With MAVLink, #GstRobotCtl:mavlink-mode "gimbal" sends
 * GIMBAL_MANAGER_SET_PITCHYAW with pitch and yaw rates that centre the target (the proportional law on both
 * axes, whatever #GstRobotCtl:controller says), "follow" sends SET_POSITION_TARGET_LOCAL_NED in the body
 * frame with a forward velocity and a yaw rate; a turn of 1.0 is tan(#GstRobotCtl:hfov / 2) rad/s, a speed
 * of 1.0 is 1 m/s; every stop is zero rates (and zero velocity).
 *
 * #GstRobotCtl:location may also be "udp://HOST:PORT": each frame a datagram to that address (a flight
 * controller, mavlink-router, a ground station), for any protocol.
 *
 * Commands go out at a fixed #GstRobotCtl:rate from a writer thread, repeated when unchanged so a watchdog
 * on the robot stays fed; the streaming thread only leaves the newest command for it and never waits for the
 * port. The robot is sent stop on EOS, on a flush, when going from PLAYING to PAUSED and from PAUSED to
 * READY, a last one when the port is closed (READY to NULL), when no confirmed target was seen for half of
 * #GstRobotCtl:lost-timeout (the drive is held that long, never the turn), when upstream delivers no buffer
 * for all of it (after half of it without a buffer the last decision goes out without its turn or tilt), and
 * when the element is disposed. A port that fails while running (a USB adapter unplugged,
 * a UDP peer that stopped listening) posts a warning and is reopened with back-off; the first command after
 * reconnecting is stop. A reopen never creates a file: it waits, with a warning, for the same kind of file
 * (device, FIFO or regular file) to be back at #GstRobotCtl:location. With MAVLink over UDP, a vehicle whose
 * HEARTBEAT has not come back for #GstRobotCtl:link-timeout ms is sent only stop, with a warning, until it
 * answers again.
 *
 * #GstRobotCtl:hold is a person's STOP (a button in an application, colortrack-studio's page): set to true,
 * the robot is sent stop at once (the set wakes the writer: no tick or buffer is waited for) and only stop
 * until it is set back to false; the pipeline keeps playing and the target stays locked, so the first
 * decision after the release is current.
 *
 * With #GstRobotCtl:post-messages, every command sent is also posted as an element message "robotctl" with
 * command (string), left and right (int, as sent; with MAVLink instead pitch-rate or vx and yaw-rate, as
 * sent: rad/s and m/s, yaw > 0 to the right), linear and angular (double; angular > 0 turns left, the
 * opposite sign to yaw-rate), target-visible (boolean),
 * timestamp (the buffer the decision came from, or GST_CLOCK_TIME_NONE) and reason ("target", "no-target",
 * "stalling", "stalled", "eos", "flush", "paused", "ready", "start", "hold", "reconnected", "link-lost",
 * "shutdown").
 *
 * ## Example launch lines
 * |[
 * gst-launch-1.0 v4l2src ! videoconvert ! colortrack template-location=ball.png ! \
 *     robotctl device=/dev/ttyUSB0 baud-rate=9600
 * ]| Follows the ball of ball.png with the zone controller, one character per command at 10 Hz.
 * |[
 * gst-launch-1.0 v4l2src ! videoconvert ! colortrack template-location=ball.png ! \
 *     robotctl device=/dev/ttyACM0 baud-rate=115200 controller=proportional protocol=text set-point=0.25
 * ]| Wheel speeds as text lines, keeping the ball at a quarter of the frame height.
 * |[
 * gst-launch-1.0 filesrc location=clip.mp4 ! decodebin ! videoconvert ! colortrack init-box=120,80,64,64 ! \
 *     robotctl location=- rate=5
 * ]| A dry run: the commands are printed on stdout.
 * |[
 * gst-launch-1.0 v4l2src ! videoconvert ! cvtracker object-initial-x=100 object-initial-y=80 \
 *     object-initial-width=60 object-initial-height=60 ! robotctl roi-type=object location=/tmp/commands.txt
 * ]| Follows the box of gst-plugins-bad's cvtracker.
 * |[
 * gst-launch-1.0 v4l2src ! videoconvert ! colortrack template-location=ball.png ! \
 *     robotctl protocol=mavlink mavlink-mode=gimbal hfov=62 location=udp://127.0.0.1:14550 \
 *     turn-gain=3 max-angular=1
 * ]| Turns a MAVLink gimbal (through the autopilot's gimbal manager, or mavlink-router) to keep the ball
 * centred.
 */

#include "gstrobotctl.h"
#include "property-table.h"
#include "robotctl-controller-stage.h"
#include "robotctl-listener.h"
#include "robotctl-output.h"
#include "robotctl-properties.h"
#include "robotctl-settings.h"
#include "track-params.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <gst/video/video.h>

#include "colortrack/command_writer.hpp"
#include "colortrack/controller.hpp"
#include "colortrack/port_choice.hpp"
#include "colortrack/protocol.hpp"

GST_DEBUG_CATEGORY_STATIC(gst_robot_ctl_debug);
#define GST_CAT_DEFAULT gst_robot_ctl_debug

namespace {

using robotctl::Command;
using robotctl::CommandWriter;
// The writer knows no GStreamer; its "no timestamp" must read as GST_CLOCK_TIME_NONE in the messages.
static_assert(robotctl::kNoTimestamp == GST_CLOCK_TIME_NONE);

double monotonicSeconds() {
  return static_cast<double>(g_get_monotonic_time()) / G_USEC_PER_SEC;
}

// What the streaming thread owns (and start()/stop(), which never run concurrently with it).
struct State {
  std::unique_ptr<robotctl::ControllerStage> stage;  // the controller and the target lock
  cv::Size frameSize;
  std::string roiType;  // and its quark, made again only when it changes
  GQuark roiQuark = 0;
};

// What render() reads of the settings for a buffer, under the lock: a few values, and all the settings only
// when the controller's or the failsafe's changed (rarely: the strings are not copied per buffer).
struct BufferSettings {
  colortrack::LockOn lockOn;
  gint targetId;
  std::optional<robotctl::Settings> changed;
};

BufferSettings takeBufferSettings(robotctl::ElementCore &core, State &state) {
  const robotctl::Settings &s = core.store().settings;
  BufferSettings taken{s.lockOn, s.targetId, std::nullopt};
  if (core.takeChanges().has(robotctl::Settings::Change::Controller)) taken.changed = s;
  if (state.roiQuark == 0 || s.roiType != state.roiType) {
    state.roiType = s.roiType;
    state.roiQuark = g_quark_from_string(state.roiType.c_str());
  }
  return taken;
}

}  // namespace

struct _GstRobotCtlPrivate {
  explicit _GstRobotCtlPrivate(GstElement *element)
      : core(element, gst_robot_ctl_debug, robotctl::properties()) {}
  robotctl::ElementCore core;
  State state;
  std::unique_ptr<robotctl::ElementListener> listener;  // outlives the writer
  std::unique_ptr<CommandWriter> writer;                // between start() and stop()
  std::atomic<bool> resetRequested{false};
};

// Any video: only the frame size is used, never the pixels.
static GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS("video/x-raw(ANY)"));

#define gst_robot_ctl_parent_class parent_class
G_DEFINE_TYPE(GstRobotCtl, gst_robot_ctl, GST_TYPE_BASE_SINK);
GST_ELEMENT_REGISTER_DEFINE(robotctl, "robotctl", GST_RANK_NONE, GST_TYPE_ROBOT_CTL);

// ---------------------------------------------------------------------------------------------------------
// GObject

namespace {

robotctl::PropertyStore &storeOf(GstRobotCtl *self) {
  return self->priv->core.store();
}
State &stateOf(GstRobotCtl *self) {
  return self->priv->state;
}

// The writer `hold` reaches at once (null: none), told the hold of now: one set while starting is not lost.
void shareWriter(GstRobotCtl *self, CommandWriter *writer) {
  GST_OBJECT_LOCK(self);
  robotctl::PropertyStore &store = storeOf(self);
  store.shared.writer = writer;
  if (writer) writer->setHeld(store.settings.hold);
  GST_OBJECT_UNLOCK(self);
}

}  // namespace

static void gst_robot_ctl_set_property(GObject *object, guint prop_id, const GValue *value,
                                       GParamSpec *pspec) {
  GstRobotCtl *self = GST_ROBOT_CTL(object);
  self->priv->core.set(prop_id, value, pspec);
}

static void gst_robot_ctl_get_property(GObject *object, guint prop_id, GValue *value, GParamSpec *pspec) {
  GstRobotCtl *self = GST_ROBOT_CTL(object);
  self->priv->core.get(prop_id, value, pspec);
}

// Whatever happens, a robot that was moving is told to stop before the element goes away.
static void gst_robot_ctl_dispose(GObject *object) {
  GstRobotCtl *self = GST_ROBOT_CTL(object);
  if (self->priv && self->priv->writer) {
    shareWriter(self, nullptr);
    self->priv->writer->shutdown();
    self->priv->writer.reset();
  }
  G_OBJECT_CLASS(parent_class)->dispose(object);
}

static void gst_robot_ctl_finalize(GObject *object) {
  GstRobotCtl *self = GST_ROBOT_CTL(object);
  delete self->priv;
  self->priv = nullptr;
  G_OBJECT_CLASS(parent_class)->finalize(object);
}

// ---------------------------------------------------------------------------------------------------------
// Streaming

namespace {

// The port the settings name, opened; null (with an error posted) when it cannot be opened.
std::unique_ptr<robotctl::Port> openPort(GstRobotCtl *self, const robotctl::Settings &s) {
  const robotctl::PortKind kind = robotctl::portKind(s.device, s.location);
  std::unique_ptr<robotctl::Port> port =
      robotctl::makePort(s.device, robotctl::toSerialConfig(s), s.location);
  const colortrack::Status opened = port->open();
  if (!opened) {
    const std::string &why = opened.message();
    if (kind == robotctl::PortKind::Udp)
      GST_ELEMENT_ERROR(self, RESOURCE, OPEN_WRITE,
                        ("Cannot send to '%s' (property 'location'): %s",
                         gstglue::validUtf8(s.location).c_str(), gstglue::validUtf8(why).c_str()),
                        (nullptr));
    else if (kind == robotctl::PortKind::Serial)
      GST_ELEMENT_ERROR(self, RESOURCE, OPEN_WRITE,
                        ("Could not open serial port '%s' (property 'device'): %s",
                         gstglue::validUtf8(s.device).c_str(), gstglue::validUtf8(why).c_str()),
                        (nullptr));
    else
      GST_ELEMENT_ERROR(self, RESOURCE, OPEN_WRITE,
                        ("Could not open '%s' (property 'location') for writing: %s",
                         gstglue::validUtf8(s.location).c_str(), gstglue::validUtf8(why).c_str()),
                        (nullptr));
    return nullptr;
  }
  return port;
}

}  // namespace

static gboolean gst_robot_ctl_start(GstBaseSink *sink) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  const std::optional<robotctl::Settings> settings = self->priv->core.start();
  if (!settings) return FALSE;
  const robotctl::Settings &s = *settings;
  std::unique_ptr<robotctl::Port> port = openPort(self, s);
  if (!port) {
    self->priv->core.stop();
    return FALSE;
  }
  GST_INFO_OBJECT(self, "writing to %s", port->describe().c_str());

  robotctl::WriterConfig config;
  config.protocol.protocol = s.protocol;
  config.protocol.zoneChars = *colortrack::parseZoneChars(s.zoneChars);  // a start rule checked it
  config.protocol.outputScale = s.outputScale;
  config.protocol.mavlink = robotctl::toMavlinkSettings(s);
  config.rate = s.rate;
  config.stallTimeout = s.failsafe.lostTimeout;
  config.linkTimeout = s.linkTimeoutMs / 1000.0;

  State &state = stateOf(self);
  state = State{};
  state.stage = std::make_unique<robotctl::ControllerStage>(s);
  self->priv->resetRequested = false;

  // The robot hears stop from the start, at the rate, until there is something to follow.
  self->priv->listener = std::make_unique<robotctl::ElementListener>(GST_ELEMENT(self), GST_CAT_DEFAULT,
                                                                     s.postMessages, config.protocol);
  self->priv->writer = std::make_unique<CommandWriter>(std::move(port), config, *self->priv->listener);
  self->priv->writer->start();
  shareWriter(self, self->priv->writer.get());
  return TRUE;
}

static gboolean gst_robot_ctl_stop(GstBaseSink *sink) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  self->priv->core.stop();
  shareWriter(self, nullptr);
  if (self->priv->writer) {
    self->priv->writer->shutdown();  // sends the final stop
    self->priv->writer.reset();
    self->priv->listener.reset();
  }
  stateOf(self) = State{};
  return TRUE;
}

static gboolean gst_robot_ctl_set_caps(GstBaseSink *sink, GstCaps *caps) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  GstVideoInfo info;
  if (!gst_video_info_from_caps(&info, caps)) {
    GST_WARNING_OBJECT(self, "caps without a frame size: %" GST_PTR_FORMAT, caps);
    return FALSE;
  }
  stateOf(self).frameSize = cv::Size(GST_VIDEO_INFO_WIDTH(&info), GST_VIDEO_INFO_HEIGHT(&info));
  GST_DEBUG_OBJECT(self, "frame size %dx%d", stateOf(self).frameSize.width, stateOf(self).frameSize.height);
  return TRUE;
}

static gboolean gst_robot_ctl_event(GstBaseSink *sink, GstEvent *event) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  CommandWriter *writer = self->priv->writer.get();
  switch (GST_EVENT_TYPE(event)) {
    case GST_EVENT_EOS:
      GST_DEBUG_OBJECT(self, "EOS: stop");
      if (writer) writer->stopNow("eos");
      break;
    case GST_EVENT_FLUSH_START:
      GST_DEBUG_OBJECT(self, "flush: stop");
      if (writer) {
        writer->setFlushing(true);
        writer->stopNow("flush");
      }
      break;
    case GST_EVENT_FLUSH_STOP:
      self->priv->resetRequested = true;  // what comes after a seek has nothing to do with before
      if (writer) writer->setFlushing(false);
      break;
    default:
      break;
  }
  return GST_BASE_SINK_CLASS(parent_class)->event(sink, event);
}

namespace {

// One ROI of the followed type, as robotctl sees it.
struct Region {
  colortrack::TargetCandidate candidate;
  double score = 1.0;
};

// The buffer's ROIs of type `roiType`. Other elements' boxes carry no state or score: they count as tracking
// with score 1.
std::vector<Region> readRegions(GstBuffer *buffer, GQuark roiType) {
  std::vector<Region> regions;
  gpointer iter = nullptr;
  while (GstMeta *meta =
             gst_buffer_iterate_meta_filtered(buffer, &iter, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (roi->roi_type != roiType) continue;
    Region region;
    region.candidate.id = roi->id;
    region.candidate.box = cv::Rect2d(roi->x, roi->y, roi->w, roi->h);
    // Also found after videoconvert / videoscale, which drop the ROI meta's own parameters in GStreamer 1.22.
    if (const GstStructure *params = colortrack_find_roi_params(buffer, roi)) {
      // A missing or unknown state reads as tracking, like a box without params.
      region.candidate.state =
          colortrack::parseTrackState(gst_structure_get_string(params, COLORTRACK_PARAM_STATE))
              .value_or(colortrack::TrackState::Tracking);
      gst_structure_get_double(params, COLORTRACK_PARAM_SCORE, &region.score);
    }
    regions.push_back(region);
  }
  return regions;
}

// The target of this frame: the locked track (or `targetId`), chosen again by the lock's policy when it is
// lost or gone.
void readTarget(GstBuffer *buffer, GQuark roiType, gint targetId, colortrack::TargetLock &lock,
                colortrack::Observation &o) {
  const std::vector<Region> regions = readRegions(buffer, roiType);
  std::vector<colortrack::TargetCandidate> candidates;
  for (const Region &region : regions) candidates.push_back(region.candidate);
  const int chosen = lock.choose(candidates, o.frameSize, targetId);
  if (chosen < 0) return;
  o.box = regions[chosen].candidate.box;
  o.state = regions[chosen].candidate.state;
  o.score = regions[chosen].score;
}

}  // namespace

static GstFlowReturn gst_robot_ctl_render(GstBaseSink *sink, GstBuffer *buffer) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  State &state = stateOf(self);
  CommandWriter *writer = self->priv->writer.get();
  if (!writer || !state.stage) {
    GST_ELEMENT_ERROR(self, CORE, FAILED, ("robotctl was not started."), (nullptr));
    return GST_FLOW_ERROR;
  }

  GST_OBJECT_LOCK(self);
  const BufferSettings now = takeBufferSettings(self->priv->core, state);
  GST_OBJECT_UNLOCK(self);
  state.stage->lock().setPolicy(now.lockOn);
  if (now.changed) {
    state.stage->apply(*now.changed);
    writer->setStallTimeout(now.changed->failsafe.lostTimeout);
  }
  if (self->priv->resetRequested.exchange(false)) state.stage->reset();

  colortrack::Observation o;
  o.frameSize = state.frameSize;
  // Stream time drives the controller, so a file plays back the same decisions whatever the load.
  const GstClockTime pts = GST_BUFFER_PTS(buffer);
  const GstClockTime running = GST_CLOCK_TIME_IS_VALID(pts)
                                   ? gst_segment_to_running_time(&sink->segment, GST_FORMAT_TIME, pts)
                                   : GST_CLOCK_TIME_NONE;
  o.time = GST_CLOCK_TIME_IS_VALID(running) ? static_cast<double>(running) / GST_SECOND : monotonicSeconds();
  readTarget(buffer, state.roiQuark, now.targetId, state.stage->lock(), o);

  Command command;
  command.output = state.stage->decide(o);
  command.timestamp = pts;
  command.reason = command.output.targetVisible ? "target" : "no-target";
  GST_LOG_OBJECT(self, "%s: %s left %.3f right %.3f", o.box ? "target" : "no target",
                 colortrack::toString(command.output.command), command.output.left, command.output.right);
  writer->submit(command);
  return GST_FLOW_OK;
}

static GstStateChangeReturn gst_robot_ctl_change_state(GstElement *element, GstStateChange transition) {
  GstRobotCtl *self = GST_ROBOT_CTL(element);
  // GstBaseSink opens the port (start(), which creates the writer) from NULL to READY and closes it (stop(),
  // a final stop) from READY to NULL. Everything here happens before the base class: on the way down, the
  // writer stops taking decisions (a render() still running cannot undo the stop) and the stop goes out
  // before anything else of the change happens; on the way up, it takes decisions before the base class
  // lets the first buffer of PLAYING (the preroll buffer) be rendered. In READY and PAUSED the robot keeps
  // hearing stop at the rate.
  CommandWriter *writer = self->priv->writer.get();
  switch (transition) {
    case GST_STATE_CHANGE_PAUSED_TO_PLAYING:
    case GST_STATE_CHANGE_PLAYING_TO_PLAYING:  // back to PLAYING before a pause completed
      if (writer) writer->setPlaying(true);
      break;
    case GST_STATE_CHANGE_PLAYING_TO_PAUSED:
      if (writer) {
        writer->setPlaying(false);
        writer->stopNow("paused");
      }
      break;
    case GST_STATE_CHANGE_PAUSED_TO_READY:
      if (writer) {
        writer->setPlaying(false);
        writer->stopNow("ready");
      }
      break;
    default:
      break;
  }
  const GstStateChangeReturn ret = GST_ELEMENT_CLASS(parent_class)->change_state(element, transition);
  // Still paused: its decisions must not be sent.
  if (ret == GST_STATE_CHANGE_FAILURE && transition == GST_STATE_CHANGE_PAUSED_TO_PLAYING && writer)
    writer->setPlaying(false);
  return ret;
}

// ---------------------------------------------------------------------------------------------------------
// Class

static void gst_robot_ctl_class_init(GstRobotCtlClass *klass) {
  GObjectClass *gobject_class = G_OBJECT_CLASS(klass);
  GstElementClass *element_class = GST_ELEMENT_CLASS(klass);
  GstBaseSinkClass *sink_class = GST_BASE_SINK_CLASS(klass);

  GST_DEBUG_CATEGORY_INIT(gst_robot_ctl_debug, "robotctl", 0, "Robot control from track metadata");

  gobject_class->set_property = gst_robot_ctl_set_property;
  gobject_class->get_property = gst_robot_ctl_get_property;
  gobject_class->dispose = gst_robot_ctl_dispose;
  gobject_class->finalize = gst_robot_ctl_finalize;

  robotctl::properties().install(gobject_class);

  gst_element_class_set_static_metadata(element_class, "Robot controller", "Sink/Video/Analyzer",
                                        "Drives a robot towards the tracked target: serial commands from "
                                        "region-of-interest meta, with failsafe stop",
                                        "colortrack developers");
  gst_element_class_add_static_pad_template(element_class, &sink_template);

  element_class->change_state = GST_DEBUG_FUNCPTR(gst_robot_ctl_change_state);
  sink_class->start = GST_DEBUG_FUNCPTR(gst_robot_ctl_start);
  sink_class->stop = GST_DEBUG_FUNCPTR(gst_robot_ctl_stop);
  sink_class->set_caps = GST_DEBUG_FUNCPTR(gst_robot_ctl_set_caps);
  sink_class->event = GST_DEBUG_FUNCPTR(gst_robot_ctl_event);
  sink_class->render = GST_DEBUG_FUNCPTR(gst_robot_ctl_render);

  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_PROTOCOL, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_MAVLINK_MODE, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_CONTROLLER, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_DISTANCE_CUE, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_PARITY, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_FLOW_CONTROL, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_LOCK_ON, static_cast<GstPluginAPIFlags>(0));
}

static void gst_robot_ctl_init(GstRobotCtl *self) {
  self->priv = new GstRobotCtlPrivate(GST_ELEMENT(self));
}
