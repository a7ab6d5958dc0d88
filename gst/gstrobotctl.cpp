/**
 * SECTION:element-robotctl
 * @title: robotctl
 *
 * Drives a robot towards a tracked target. Each video buffer's #GstVideoRegionOfInterestMeta (by default
 * the "colortrack" ROI with the lowest id, see #GstRobotCtl:roi-type and #GstRobotCtl:target-id) gives where
 * the target is; a controller turns that into a drive command and the command goes out on a serial port
 * (#GstRobotCtl:device) or to a file, FIFO, pseudo-terminal or stdout (#GstRobotCtl:location).
 *
 * Two controllers (#GstRobotCtl:controller): "zone" splits the frame into left / centre / right by the
 * target's horizontal offset and into too-far / right / too-close by its size (or the height of its bottom
 * edge, #GstRobotCtl:distance-cue) and sends forward, backward, left, right or stop, with a deadband and
 * hysteresis against chatter; "proportional" turns at a rate proportional to the offset and drives at a
 * speed proportional to the distance error, with gains, deadbands, limits and an acceleration limit, as
 * left/right wheel speeds.
 *
 * Three protocols (#GstRobotCtl:protocol): "zone-char" (one character per command, #GstRobotCtl:zone-chars,
 * default "FBLRS"), "text" ("L=<int> R=<int>\n", wheel speeds times #GstRobotCtl:output-scale) and "binary"
 * (0xA5, sequence, length, command, flags, left, right, CRC-8; see docs/robotctl.md).
 *
 * Commands go out at a fixed #GstRobotCtl:rate from a writer thread, repeated when unchanged so a watchdog
 * on the robot stays fed; the streaming thread only leaves the newest command for it and never waits for the
 * port. The robot is sent stop on EOS, on a flush, when going from PLAYING to PAUSED and from PAUSED to
 * READY, a last one when the port is closed (READY to NULL), when no confirmed target was seen for
 * #GstRobotCtl:lost-timeout ms, when upstream delivers no buffer for that long, and when the element is
 * disposed. A port that fails while running (a USB adapter unplugged) posts a warning and is reopened with
 * back-off; the first command after reconnecting is stop. A reopen never creates a file: it waits, with a
 * warning, for the same kind of file (device, FIFO or regular file) to be back at #GstRobotCtl:location.
 *
 * With #GstRobotCtl:post-messages, every command sent is also posted as an element message "robotctl" with
 * command (string), left and right (int, as sent), linear and angular (double), target-visible (boolean),
 * timestamp (the buffer the decision came from, or GST_CLOCK_TIME_NONE) and reason ("target", "no-target",
 * "stalled", "eos", "flush", "paused", "ready", "start", "reconnected", "shutdown").
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
 */

#include "gstrobotctl.h"
#include "command-writer.h"
#include "robot-port.h"
#include "track-params.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>

#include <gst/video/video.h>

#include "colortrack/controller.hpp"
#include "colortrack/protocol.hpp"

GST_DEBUG_CATEGORY_STATIC(gst_robot_ctl_debug);
#define GST_CAT_DEFAULT gst_robot_ctl_debug

namespace {

using robotctl::Command;
using robotctl::CommandWriter;
// The writer knows no GStreamer; its "no timestamp" must read as GST_CLOCK_TIME_NONE in the messages.
static_assert(robotctl::kNoTimestamp == GST_CLOCK_TIME_NONE);

constexpr const char *kDefaultRoiType = "colortrack";
constexpr const char *kDefaultZoneChars = "FBLRS";
constexpr guint kDefaultBaudRate = 9600;
constexpr gint kDefaultDataBits = 8;
constexpr gint kDefaultStopBits = 1;
constexpr gint kDefaultOutputScale = 255;
constexpr gdouble kDefaultRate = 10.0;
constexpr guint kDefaultLostTimeoutMs = 500;
constexpr gint kDefaultTargetId = -1;

// The rates a serial port can be set to portably (termios' Bxxx constants).
constexpr guint kStandardBaudRates[] = {50,      75,      110,     134,     150,     200,    300,     600,
                                        1200,    1800,    2400,    4800,    9600,    19200,  38400,   57600,
                                        115200,  230400,  460800,  500000,  576000,  921600, 1000000, 1152000,
                                        1500000, 2000000, 2500000, 3000000, 3500000, 4000000};

bool isStandardBaudRate(guint rate) {
  return std::find(std::begin(kStandardBaudRates), std::end(kStandardBaudRates), rate) !=
         std::end(kStandardBaudRates);
}

robotctl::Parity toParity(GstRobotCtlParity parity) {
  switch (parity) {
    case GST_ROBOT_CTL_PARITY_ODD:
      return robotctl::Parity::Odd;
    case GST_ROBOT_CTL_PARITY_EVEN:
      return robotctl::Parity::Even;
    case GST_ROBOT_CTL_PARITY_MARK:
      return robotctl::Parity::Mark;
    case GST_ROBOT_CTL_PARITY_SPACE:
      return robotctl::Parity::Space;
    case GST_ROBOT_CTL_PARITY_NONE:
      break;
  }
  return robotctl::Parity::None;
}

robotctl::FlowControl toFlowControl(GstRobotCtlFlowControl flow) {
  switch (flow) {
    case GST_ROBOT_CTL_FLOW_CONTROL_XONXOFF:
      return robotctl::FlowControl::XonXoff;
    case GST_ROBOT_CTL_FLOW_CONTROL_RTSCTS:
      return robotctl::FlowControl::RtsCts;
    case GST_ROBOT_CTL_FLOW_CONTROL_DTRDSR:
      return robotctl::FlowControl::DtrDsr;
    case GST_ROBOT_CTL_FLOW_CONTROL_NONE:
      break;
  }
  return robotctl::FlowControl::None;
}

double monotonicSeconds() {
  return static_cast<double>(g_get_monotonic_time()) / G_USEC_PER_SEC;
}

// A text property checked at start: what the user wrote and, if it does not parse, why.
struct TextSetting {
  std::string text;
  std::string error;
};

// What the properties say. Written by set_property, copied under GST_OBJECT_LOCK by start() and by the
// streaming thread; never touched by the writer thread (it gets its own copy at start).
struct Settings {
  std::string device, location;
  guint baudRate = kDefaultBaudRate;
  gint dataBits = kDefaultDataBits;
  GstRobotCtlParity parity = GST_ROBOT_CTL_PARITY_NONE;
  gint stopBits = kDefaultStopBits;
  GstRobotCtlFlowControl flowControl = GST_ROBOT_CTL_FLOW_CONTROL_NONE;
  GstRobotCtlProtocol protocol = GST_ROBOT_CTL_PROTOCOL_ZONE_CHAR;
  TextSetting zoneChars{kDefaultZoneChars, {}};
  gint outputScale = kDefaultOutputScale;
  gdouble rate = kDefaultRate;
  colortrack::ControllerSettings controller;
  colortrack::FailsafeSettings failsafe;
  guint64 controllerGeneration = 0;  // bumped on every change of `controller` or `failsafe`
  std::string roiType = kDefaultRoiType;
  gint targetId = kDefaultTargetId;
  bool postMessages = false;
  std::string turnGainError, driveGainError;  // a negative gain that was refused (reported at start)
  std::string roiTypeError;                   // an empty roi-type that was refused (reported at start)
  bool running = false;                       // between start() and stop()
};

// Reports the writer's events as the element's bus messages, warnings and debug log.
class ElementListener : public robotctl::WriterListener {
 public:
  ElementListener(GstElement *element, bool postMessages, int outputScale)
      : element_(element), postMessages_(postMessages), outputScale_(outputScale) {}

  void sent(const Command &command) override {
    if (postMessages_) post(command);
  }
  void stalled(double timeout) override {
    GST_INFO_OBJECT(element_, "no buffer for %.0f ms: stopping", timeout * 1000);
  }
  void busy(const std::string &port, bool tail, std::size_t left) override {
    if (tail)
      GST_LOG_OBJECT(element_, "%s is not taking data: %zu bytes of a command still to send", port.c_str(),
                     left);
    else
      GST_LOG_OBJECT(element_, "%s is not taking data: %s", port.c_str(),
                     left > 0 ? "the rest of the command goes first on the next tick" : "command dropped");
  }
  void connectionLost(const std::string &port, const std::string &why) override {
    GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                        ("Lost the connection to %s: %s. Retrying.", port.c_str(), why.c_str()), (nullptr));
  }
  void reopenFailed(const std::string &port, const std::string &why, bool newReason,
                    std::chrono::milliseconds retryIn) override {
    if (newReason)
      GST_ELEMENT_WARNING(element_, RESOURCE, OPEN_WRITE,
                          ("Cannot reopen %s: %s. Retrying.", port.c_str(), why.c_str()), (nullptr));
    GST_DEBUG_OBJECT(element_, "could not reopen %s: %s (next try in %lld ms)", port.c_str(), why.c_str(),
                     static_cast<long long>(retryIn.count()));
  }
  void reconnected(const std::string &port) override {
    GST_ELEMENT_INFO(element_, RESOURCE, WRITE, ("Reconnected to %s.", port.c_str()), (nullptr));
  }

 private:
  void post(const Command &command) {
    const colortrack::DriveOutput &out = command.output;
    const bool stop = out.command == colortrack::DriveCommand::Stop;
    GstStructure *s = gst_structure_new(
        "robotctl", "command", G_TYPE_STRING, colortrack::toString(out.command), "left", G_TYPE_INT,
        stop ? 0 : colortrack::scaledSpeed(out.left, outputScale_), "right", G_TYPE_INT,
        stop ? 0 : colortrack::scaledSpeed(out.right, outputScale_), "linear", G_TYPE_DOUBLE, out.linear,
        "angular", G_TYPE_DOUBLE, out.angular, "target-visible", G_TYPE_BOOLEAN,
        static_cast<gboolean>(out.targetVisible), "timestamp", G_TYPE_UINT64,
        static_cast<guint64>(command.timestamp), "reason", G_TYPE_STRING, command.reason, nullptr);
    gst_element_post_message(element_, gst_message_new_element(GST_OBJECT(element_), s));
  }

  GstElement *element_;
  const bool postMessages_;
  const int outputScale_;
};

// What the streaming thread owns (and start()/stop(), which never run concurrently with it).
struct State {
  std::unique_ptr<colortrack::RobotController> controller;
  colortrack::ControllerKind controllerKind = colortrack::ControllerKind::Zone;  // of `controller`
  guint64 appliedControllerGeneration = 0;
  cv::Size frameSize;
  std::string roiType;
};

}  // namespace

struct _GstRobotCtlPrivate {
  Settings settings;
  State state;
  std::unique_ptr<ElementListener> listener;  // outlives the writer
  std::unique_ptr<CommandWriter> writer;      // between start() and stop()
  std::atomic<bool> resetRequested{false};
};

enum {
  PROP_0,
  PROP_DEVICE,
  PROP_BAUD_RATE,
  PROP_DATA_BITS,
  PROP_PARITY,
  PROP_STOP_BITS,
  PROP_FLOW_CONTROL,
  PROP_LOCATION,
  PROP_PROTOCOL,
  PROP_ZONE_CHARS,
  PROP_OUTPUT_SCALE,
  PROP_RATE,
  PROP_CONTROLLER,
  PROP_DISTANCE_CUE,
  PROP_SET_POINT,
  PROP_TURN_DEADBAND,
  PROP_DISTANCE_DEADBAND,
  PROP_HYSTERESIS,
  PROP_TURN_GAIN,
  PROP_DRIVE_GAIN,
  PROP_MAX_LINEAR,
  PROP_MAX_ANGULAR,
  PROP_MAX_LINEAR_ACCEL,
  PROP_MAX_ANGULAR_ACCEL,
  PROP_LOST_TIMEOUT,
  PROP_MIN_SCORE,
  PROP_SEARCH_TURN,
  PROP_SEARCH_SPEED,
  PROP_ROI_TYPE,
  PROP_TARGET_ID,
  PROP_POST_MESSAGES,
};

// Any video: only the frame size is used, never the pixels.
static GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS("video/x-raw(ANY)"));

#define gst_robot_ctl_parent_class parent_class
G_DEFINE_TYPE(GstRobotCtl, gst_robot_ctl, GST_TYPE_BASE_SINK);
GST_ELEMENT_REGISTER_DEFINE(robotctl, "robotctl", GST_RANK_NONE, GST_TYPE_ROBOT_CTL);

// ---------------------------------------------------------------------------------------------------------
// Enum types

#define DEFINE_ENUM_TYPE(function, name, ...)                                                     \
  GType function(void) {                                                                          \
    static gsize type = 0;                                                                        \
    static const GEnumValue values[] = {__VA_ARGS__, {0, nullptr, nullptr}};                      \
    if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static(name, values)); \
    return type;                                                                                  \
  }

DEFINE_ENUM_TYPE(gst_robot_ctl_protocol_get_type, "GstRobotCtlProtocol",
                 {GST_ROBOT_CTL_PROTOCOL_ZONE_CHAR, "One character per command (zone-chars)", "zone-char"},
                 {GST_ROBOT_CTL_PROTOCOL_TEXT, "One line \"L=<int> R=<int>\" per command", "text"},
                 {GST_ROBOT_CTL_PROTOCOL_BINARY, "Framed packet with sequence number and CRC-8", "binary"})
DEFINE_ENUM_TYPE(gst_robot_ctl_controller_get_type, "GstRobotCtlController",
                 {GST_ROBOT_CTL_CONTROLLER_ZONE, "Forward/backward/left/right/stop by frame zone", "zone"},
                 {GST_ROBOT_CTL_CONTROLLER_PROPORTIONAL, "Wheel speeds proportional to the errors",
                  "proportional"})
DEFINE_ENUM_TYPE(gst_robot_ctl_distance_cue_get_type, "GstRobotCtlDistanceCue",
                 {GST_ROBOT_CTL_DISTANCE_CUE_SIZE, "Box height / frame height", "size"},
                 {GST_ROBOT_CTL_DISTANCE_CUE_POSITION, "Box bottom / frame height", "position"})
DEFINE_ENUM_TYPE(gst_robot_ctl_parity_get_type, "GstRobotCtlParity",
                 {GST_ROBOT_CTL_PARITY_NONE, "None", "none"}, {GST_ROBOT_CTL_PARITY_ODD, "Odd", "odd"},
                 {GST_ROBOT_CTL_PARITY_EVEN, "Even", "even"}, {GST_ROBOT_CTL_PARITY_MARK, "Mark", "mark"},
                 {GST_ROBOT_CTL_PARITY_SPACE, "Space", "space"})
DEFINE_ENUM_TYPE(gst_robot_ctl_flow_control_get_type, "GstRobotCtlFlowControl",
                 {GST_ROBOT_CTL_FLOW_CONTROL_NONE, "None", "none"},
                 {GST_ROBOT_CTL_FLOW_CONTROL_XONXOFF, "Software (XON/XOFF)", "xonxoff"},
                 {GST_ROBOT_CTL_FLOW_CONTROL_RTSCTS, "Hardware (RTS/CTS)", "rtscts"},
                 {GST_ROBOT_CTL_FLOW_CONTROL_DTRDSR, "Hardware (DTR/DSR)", "dtrdsr"})

// ---------------------------------------------------------------------------------------------------------
// GObject

namespace {

Settings &settingsOf(GstRobotCtl *self) {
  return self->priv->settings;
}
State &stateOf(GstRobotCtl *self) {
  return self->priv->state;
}

// Where a double property lives in the settings, and whether it is a controller setting.
double *doubleSetting(Settings &s, guint prop_id) {
  colortrack::ControllerSettings &c = s.controller;
  switch (prop_id) {
    case PROP_SET_POINT:
      return &c.setPoint;
    case PROP_TURN_DEADBAND:
      return &c.turnDeadband;
    case PROP_DISTANCE_DEADBAND:
      return &c.distanceDeadband;
    case PROP_HYSTERESIS:
      return &c.hysteresis;
    case PROP_TURN_GAIN:
      return &c.turnGain;
    case PROP_DRIVE_GAIN:
      return &c.driveGain;
    case PROP_MAX_LINEAR:
      return &c.maxLinear;
    case PROP_MAX_ANGULAR:
      return &c.maxAngular;
    case PROP_MAX_LINEAR_ACCEL:
      return &c.maxLinearAccel;
    case PROP_MAX_ANGULAR_ACCEL:
      return &c.maxAngularAccel;
    case PROP_MIN_SCORE:
      return &s.failsafe.minScore;
    case PROP_SEARCH_SPEED:
      return &s.failsafe.searchSpeed;
    default:
      return nullptr;
  }
}

}  // namespace

namespace {

std::string textOf(const GValue *value) {
  return std::string(g_value_get_string(value) ? g_value_get_string(value) : "");
}

// A setting read only at start; false for another property. `changed`: the value is not the one it had.
bool setStartSetting(Settings &s, guint prop_id, const GValue *value, bool &changed) {
  auto assign = [&changed](auto &setting, auto value) {
    changed = !(setting == value);
    setting = value;
  };
  auto text = [value] { return textOf(value); };
  switch (prop_id) {
    case PROP_DEVICE:
      assign(s.device, text());
      break;
    case PROP_BAUD_RATE:
      assign(s.baudRate, g_value_get_uint(value));
      break;
    case PROP_DATA_BITS:
      assign(s.dataBits, g_value_get_int(value));
      break;
    case PROP_PARITY:
      assign(s.parity, static_cast<GstRobotCtlParity>(g_value_get_enum(value)));
      break;
    case PROP_STOP_BITS:
      assign(s.stopBits, g_value_get_int(value));
      break;
    case PROP_FLOW_CONTROL:
      assign(s.flowControl, static_cast<GstRobotCtlFlowControl>(g_value_get_enum(value)));
      break;
    case PROP_LOCATION:
      assign(s.location, text());
      break;
    case PROP_PROTOCOL:
      assign(s.protocol, static_cast<GstRobotCtlProtocol>(g_value_get_enum(value)));
      break;
    case PROP_ZONE_CHARS:
      assign(s.zoneChars.text, text());
      s.zoneChars.error.clear();
      colortrack::parseZoneChars(s.zoneChars.text, &s.zoneChars.error);
      break;
    case PROP_OUTPUT_SCALE:
      assign(s.outputScale, g_value_get_int(value));
      break;
    case PROP_RATE:
      assign(s.rate, g_value_get_double(value));
      break;
    case PROP_POST_MESSAGES:
      assign(s.postMessages, static_cast<bool>(g_value_get_boolean(value)));
      break;
    default:
      return false;
  }
  return true;
}

// A setting applied from the next buffer, other than a double or roi-type; false for another property.
bool setLiveSetting(Settings &s, guint prop_id, const GValue *value) {
  switch (prop_id) {
    case PROP_CONTROLLER:
      s.controller.kind = g_value_get_enum(value) == GST_ROBOT_CTL_CONTROLLER_PROPORTIONAL
                              ? colortrack::ControllerKind::Proportional
                              : colortrack::ControllerKind::Zone;
      ++s.controllerGeneration;
      break;
    case PROP_DISTANCE_CUE:
      s.controller.distanceCue = g_value_get_enum(value) == GST_ROBOT_CTL_DISTANCE_CUE_POSITION
                                     ? colortrack::DistanceCue::Position
                                     : colortrack::DistanceCue::Size;
      ++s.controllerGeneration;
      break;
    case PROP_LOST_TIMEOUT:
      s.failsafe.lostTimeout = g_value_get_uint(value) / 1000.0;
      ++s.controllerGeneration;
      break;
    case PROP_SEARCH_TURN:
      s.failsafe.searchTurn = g_value_get_boolean(value);
      ++s.controllerGeneration;
      break;
    case PROP_TARGET_ID:
      s.targetId = g_value_get_int(value);
      break;
    default:
      return false;
  }
  return true;
}

}  // namespace

static void gst_robot_ctl_set_property(GObject *object, guint prop_id, const GValue *value,
                                       GParamSpec *pspec) {
  GstRobotCtl *self = GST_ROBOT_CTL(object);
  GST_OBJECT_LOCK(self);
  Settings &s = settingsOf(self);
  if (prop_id == PROP_TURN_GAIN || prop_id == PROP_DRIVE_GAIN) {
    // A negative gain drives away from the target: refused, with a reason (an error at start; while
    // running a warning, and the previous gain stays).
    const double gain = g_value_get_double(value);
    std::string &error = prop_id == PROP_TURN_GAIN ? s.turnGainError : s.driveGainError;
    if (gain < 0) {
      const char *name = prop_id == PROP_TURN_GAIN ? "turn-gain" : "drive-gain";
      const std::string why = std::string("Invalid value ") + std::to_string(gain) + " for property '" +
                              name + "': a gain must not be negative (it would steer away from the target)";
      const bool running = s.running;
      const double kept = *doubleSetting(s, prop_id);
      if (!running) error = why;
      GST_OBJECT_UNLOCK(self);
      if (running)
        GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS, ("%s. Keeping %g.", why.c_str(), kept), (nullptr));
      return;
    }
    error.clear();
  }
  if (double *setting = doubleSetting(s, prop_id)) {
    *setting = g_value_get_double(value);
    ++s.controllerGeneration;
    GST_OBJECT_UNLOCK(self);
    return;
  }
  // A setting read only at start that changes while started: said at once, or the user would think it
  // applied.
  bool startSettingChanged = false;
  if (prop_id == PROP_ROI_TYPE) {
    // An empty type matches no region: the robot would never see a target. Refused like a bad gain.
    const std::string type = textOf(value);
    if (type.empty()) {
      const std::string why =
          "Invalid value '' for property 'roi-type': it names the type of the regions "
          "to follow (e.g. colortrack, object)";
      if (s.running) {
        const std::string kept = s.roiType;
        GST_OBJECT_UNLOCK(self);
        GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS, ("%s. Keeping '%s'.", why.c_str(), kept.c_str()),
                            (nullptr));
        return;
      }
      s.roiTypeError = why;
    } else {
      s.roiTypeError.clear();
      s.roiType = type;
    }
  } else if (!setLiveSetting(s, prop_id, value) && !setStartSetting(s, prop_id, value, startSettingChanged)) {
    G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
  }
  const bool warn = startSettingChanged && s.running;
  GST_OBJECT_UNLOCK(self);
  if (warn)
    GST_ELEMENT_WARNING(
        self, RESOURCE, SETTINGS,
        ("Property '%s' is read at start: the new value applies from the next start (READY to "
         "NULL and back).",
         pspec->name),
        (nullptr));
}

static void gst_robot_ctl_get_property(GObject *object, guint prop_id, GValue *value, GParamSpec *pspec) {
  GstRobotCtl *self = GST_ROBOT_CTL(object);
  GST_OBJECT_LOCK(self);
  Settings &s = settingsOf(self);
  if (double *setting = doubleSetting(s, prop_id)) {
    g_value_set_double(value, *setting);
    GST_OBJECT_UNLOCK(self);
    return;
  }
  auto stringOrNull = [](const std::string &text) { return text.empty() ? nullptr : text.c_str(); };
  switch (prop_id) {
    case PROP_DEVICE:
      g_value_set_string(value, stringOrNull(s.device));
      break;
    case PROP_BAUD_RATE:
      g_value_set_uint(value, s.baudRate);
      break;
    case PROP_DATA_BITS:
      g_value_set_int(value, s.dataBits);
      break;
    case PROP_PARITY:
      g_value_set_enum(value, s.parity);
      break;
    case PROP_STOP_BITS:
      g_value_set_int(value, s.stopBits);
      break;
    case PROP_FLOW_CONTROL:
      g_value_set_enum(value, s.flowControl);
      break;
    case PROP_LOCATION:
      g_value_set_string(value, stringOrNull(s.location));
      break;
    case PROP_PROTOCOL:
      g_value_set_enum(value, s.protocol);
      break;
    case PROP_ZONE_CHARS:
      g_value_set_string(value, s.zoneChars.text.c_str());
      break;
    case PROP_OUTPUT_SCALE:
      g_value_set_int(value, s.outputScale);
      break;
    case PROP_RATE:
      g_value_set_double(value, s.rate);
      break;
    case PROP_CONTROLLER:
      g_value_set_enum(value, s.controller.kind == colortrack::ControllerKind::Proportional
                                  ? GST_ROBOT_CTL_CONTROLLER_PROPORTIONAL
                                  : GST_ROBOT_CTL_CONTROLLER_ZONE);
      break;
    case PROP_DISTANCE_CUE:
      g_value_set_enum(value, s.controller.distanceCue == colortrack::DistanceCue::Position
                                  ? GST_ROBOT_CTL_DISTANCE_CUE_POSITION
                                  : GST_ROBOT_CTL_DISTANCE_CUE_SIZE);
      break;
    case PROP_LOST_TIMEOUT:
      g_value_set_uint(value, static_cast<guint>(std::lround(s.failsafe.lostTimeout * 1000)));
      break;
    case PROP_SEARCH_TURN:
      g_value_set_boolean(value, s.failsafe.searchTurn);
      break;
    case PROP_ROI_TYPE:
      g_value_set_string(value, s.roiType.c_str());
      break;
    case PROP_TARGET_ID:
      g_value_set_int(value, s.targetId);
      break;
    case PROP_POST_MESSAGES:
      g_value_set_boolean(value, s.postMessages);
      break;
    default:
      G_OBJECT_WARN_INVALID_PROPERTY_ID(object, prop_id, pspec);
      break;
  }
  GST_OBJECT_UNLOCK(self);
}

// Whatever happens, a robot that was moving is told to stop before the element goes away.
static void gst_robot_ctl_dispose(GObject *object) {
  GstRobotCtl *self = GST_ROBOT_CTL(object);
  if (self->priv && self->priv->writer) {
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
std::unique_ptr<robotctl::Port> openPort(GstRobotCtl *self, const Settings &s) {
  std::unique_ptr<robotctl::Port> port;
  if (!s.device.empty())
    port = std::make_unique<robotctl::SerialPort>(robotctl::SerialConfig{
        s.device, s.baudRate, s.dataBits, s.stopBits, toParity(s.parity), toFlowControl(s.flowControl)});
  else
    port = std::make_unique<robotctl::FilePort>(s.location);
  std::string why;
  if (!port->open(why)) {
    if (!s.device.empty())
      GST_ELEMENT_ERROR(
          self, RESOURCE, OPEN_WRITE,
          ("Could not open serial port '%s' (property 'device'): %s", s.device.c_str(), why.c_str()),
          (nullptr));
    else
      GST_ELEMENT_ERROR(
          self, RESOURCE, OPEN_WRITE,
          ("Could not open '%s' (property 'location') for writing: %s", s.location.c_str(), why.c_str()),
          (nullptr));
    return nullptr;
  }
  return port;
}

}  // namespace

static gboolean gst_robot_ctl_start(GstBaseSink *sink) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  GST_OBJECT_LOCK(self);
  const Settings s = settingsOf(self);
  GST_OBJECT_UNLOCK(self);

  if (s.device.empty() && s.location.empty()) {
    GST_ELEMENT_ERROR(
        self, RESOURCE, NOT_FOUND,
        ("No output: set 'device' (a serial port) or 'location' (a file, FIFO, pseudo-terminal, "
         "or '-' for stdout)."),
        (nullptr));
    return FALSE;
  }
  if (!s.device.empty() && !s.location.empty()) {
    GST_ELEMENT_ERROR(
        self, RESOURCE, SETTINGS,
        ("Set either 'device' ('%s') or 'location' ('%s'), not both.", s.device.c_str(), s.location.c_str()),
        (nullptr));
    return FALSE;
  }
  if (!s.device.empty() && !isStandardBaudRate(s.baudRate)) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Unsupported baud rate %u (property 'baud-rate'): use a standard rate such as 9600, "
                       "19200, 38400, 57600 or 115200.",
                       s.baudRate),
                      (nullptr));
    return FALSE;
  }
  for (const std::string *error : {&s.turnGainError, &s.driveGainError, &s.roiTypeError}) {
    if (!error->empty()) {
      GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("%s.", error->c_str()), (nullptr));
      return FALSE;
    }
  }
  const std::optional<colortrack::ZoneChars> zoneChars = colortrack::parseZoneChars(s.zoneChars.text);
  if (!zoneChars) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Invalid value '%s' for property 'zone-chars': %s", s.zoneChars.text.c_str(),
                       s.zoneChars.error.c_str()),
                      (nullptr));
    return FALSE;
  }

  std::unique_ptr<robotctl::Port> port = openPort(self, s);
  if (!port) return FALSE;
  GST_INFO_OBJECT(self, "writing to %s", port->describe().c_str());

  robotctl::WriterConfig config;
  config.protocol.protocol = s.protocol == GST_ROBOT_CTL_PROTOCOL_TEXT     ? colortrack::Protocol::Text
                             : s.protocol == GST_ROBOT_CTL_PROTOCOL_BINARY ? colortrack::Protocol::Binary
                                                                           : colortrack::Protocol::ZoneChar;
  config.protocol.zoneChars = *zoneChars;
  config.protocol.outputScale = s.outputScale;
  config.rate = s.rate;
  config.stallTimeout = s.failsafe.lostTimeout;

  State &state = stateOf(self);
  state = State{};
  state.controller = std::make_unique<colortrack::RobotController>(s.controller, s.failsafe);
  state.controllerKind = s.controller.kind;
  state.appliedControllerGeneration = s.controllerGeneration;
  self->priv->resetRequested = false;

  // The robot hears stop from the start, at the rate, until there is something to follow.
  self->priv->listener = std::make_unique<ElementListener>(GST_ELEMENT(self), s.postMessages, s.outputScale);
  self->priv->writer = std::make_unique<CommandWriter>(std::move(port), config, *self->priv->listener);
  self->priv->writer->start();
  GST_OBJECT_LOCK(self);
  settingsOf(self).running = true;
  GST_OBJECT_UNLOCK(self);
  return TRUE;
}

static gboolean gst_robot_ctl_stop(GstBaseSink *sink) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  GST_OBJECT_LOCK(self);
  settingsOf(self).running = false;
  GST_OBJECT_UNLOCK(self);
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

// The selected ROI of a buffer: of type `roiType`, with id `targetId` (or the lowest id when it is < 0).
// Other elements' boxes carry no state or score: they count as tracking with score 1.
void readTarget(GstBuffer *buffer, GQuark roiType, gint targetId, colortrack::Observation &o) {
  const GstVideoRegionOfInterestMeta *chosen = nullptr;
  gpointer iter = nullptr;
  while (GstMeta *meta =
             gst_buffer_iterate_meta_filtered(buffer, &iter, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (roi->roi_type != roiType) continue;
    if (targetId >= 0 ? roi->id == targetId : (!chosen || roi->id < chosen->id)) chosen = roi;
  }
  if (!chosen) return;
  o.box = cv::Rect2d(chosen->x, chosen->y, chosen->w, chosen->h);
  o.state = colortrack::TrackState::Tracking;
  o.score = 1.0;
  // Also found after videoconvert / videoscale, which drop the ROI meta's own parameters in GStreamer 1.22.
  const GstStructure *params =
      colortrack_find_roi_params(buffer, const_cast<GstVideoRegionOfInterestMeta *>(chosen));
  if (params) {
    // A missing or unknown state reads as tracking, like a box without params.
    o.state = colortrack::parseTrackState(gst_structure_get_string(params, "state"))
                  .value_or(colortrack::TrackState::Tracking);
    gst_structure_get_double(params, "score", &o.score);
  }
}

}  // namespace

static GstFlowReturn gst_robot_ctl_render(GstBaseSink *sink, GstBuffer *buffer) {
  GstRobotCtl *self = GST_ROBOT_CTL(sink);
  State &state = stateOf(self);
  CommandWriter *writer = self->priv->writer.get();
  if (!writer || !state.controller) {
    GST_ELEMENT_ERROR(self, CORE, FAILED, ("robotctl was not started."), (nullptr));
    return GST_FLOW_ERROR;
  }

  GST_OBJECT_LOCK(self);
  const Settings &shared = settingsOf(self);
  const guint64 generation = shared.controllerGeneration;
  const colortrack::ControllerSettings controllerSettings = shared.controller;
  const colortrack::FailsafeSettings failsafeSettings = shared.failsafe;
  const GQuark roiType = g_quark_from_string(shared.roiType.c_str());
  const gint targetId = shared.targetId;
  GST_OBJECT_UNLOCK(self);

  if (generation != state.appliedControllerGeneration) {
    // A new gain or limit keeps the ramp and the lost-target hold; only another controller starts afresh.
    if (controllerSettings.kind != state.controllerKind) {
      state.controller = std::make_unique<colortrack::RobotController>(controllerSettings, failsafeSettings);
      state.controllerKind = controllerSettings.kind;
    } else {
      state.controller->setSettings(controllerSettings, failsafeSettings);
    }
    writer->setStallTimeout(failsafeSettings.lostTimeout);
    state.appliedControllerGeneration = generation;
  }
  if (self->priv->resetRequested.exchange(false)) state.controller->reset();

  colortrack::Observation o;
  o.frameSize = state.frameSize;
  // Stream time drives the controller, so a file plays back the same decisions whatever the load.
  const GstClockTime pts = GST_BUFFER_PTS(buffer);
  const GstClockTime running = GST_CLOCK_TIME_IS_VALID(pts)
                                   ? gst_segment_to_running_time(&sink->segment, GST_FORMAT_TIME, pts)
                                   : GST_CLOCK_TIME_NONE;
  o.time = GST_CLOCK_TIME_IS_VALID(running) ? static_cast<double>(running) / GST_SECOND : monotonicSeconds();
  readTarget(buffer, roiType, targetId, o);

  Command command;
  command.output = state.controller->update(o);
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

namespace {

constexpr auto rw = static_cast<GParamFlags>(G_PARAM_READWRITE | G_PARAM_STATIC_STRINGS);
// Read by start() (NULL to READY): a change while started applies from the next start, with a warning.
constexpr auto readAtStart = rw;
// Applied from the next buffer.
constexpr auto live = static_cast<GParamFlags>(rw | GST_PARAM_MUTABLE_PLAYING);

// Where the commands go and how they are encoded.
void installOutputProperties(GObjectClass *gobject_class) {
  auto install = [gobject_class](guint id, GParamSpec *spec) {
    g_object_class_install_property(gobject_class, id, spec);
  };

  install(PROP_DEVICE, g_param_spec_string("device", "Device",
                                           "Serial port to send the commands to (e.g. /dev/ttyUSB0, COM3); "
                                           "exclusive with 'location'; read at start",
                                           nullptr, readAtStart));
  install(
      PROP_BAUD_RATE,
      g_param_spec_uint("baud-rate", "Baud rate",
                        "Serial port speed in bit/s; one of the standard rates 50 ... 4000000; read at start",
                        50, 4000000, kDefaultBaudRate, readAtStart));
  install(PROP_DATA_BITS, g_param_spec_int("data-bits", "Data bits", "Serial port data bits; read at start",
                                           5, 8, kDefaultDataBits, readAtStart));
  install(PROP_PARITY, g_param_spec_enum("parity", "Parity", "Serial port parity; read at start",
                                         GST_TYPE_ROBOT_CTL_PARITY, GST_ROBOT_CTL_PARITY_NONE, readAtStart));
  install(PROP_STOP_BITS, g_param_spec_int("stop-bits", "Stop bits", "Serial port stop bits; read at start",
                                           1, 2, kDefaultStopBits, readAtStart));
  install(PROP_FLOW_CONTROL,
          g_param_spec_enum("flow-control", "Flow control", "Serial port flow control; read at start",
                            GST_TYPE_ROBOT_CTL_FLOW_CONTROL, GST_ROBOT_CTL_FLOW_CONTROL_NONE, readAtStart));
  install(PROP_LOCATION,
          g_param_spec_string("location", "Location",
                              "File, FIFO or pseudo-terminal to write the commands to, '-' for "
                              "stdout (dry runs, tests); exclusive with 'device'; read at start",
                              nullptr, readAtStart));
  install(PROP_PROTOCOL,
          g_param_spec_enum("protocol", "Protocol", "How commands are encoded; read at start",
                            GST_TYPE_ROBOT_CTL_PROTOCOL, GST_ROBOT_CTL_PROTOCOL_ZONE_CHAR, readAtStart));
  install(
      PROP_ZONE_CHARS,
      g_param_spec_string("zone-chars", "Zone characters",
                          "The zone-char protocol's characters for forward, backward, left, "
                          "right and stop, in that order (five distinct printable characters); read at start",
                          kDefaultZoneChars, readAtStart));
  install(
      PROP_OUTPUT_SCALE,
      g_param_spec_int("output-scale", "Output scale",
                       "Integer sent for full wheel speed by the text and binary protocols; read at start", 1,
                       32767, kDefaultOutputScale, readAtStart));
  install(PROP_RATE, g_param_spec_double(
                         "rate", "Rate",
                         "Commands per second; the current command is repeated at this rate; read at start",
                         0.5, 1000.0, kDefaultRate, readAtStart));
}

// How commands are decided.
void installControllerProperties(GObjectClass *gobject_class) {
  const colortrack::ControllerSettings c;
  auto install = [gobject_class](guint id, GParamSpec *spec) {
    g_object_class_install_property(gobject_class, id, spec);
  };
  install(PROP_CONTROLLER,
          g_param_spec_enum("controller", "Controller", "How commands are decided",
                            GST_TYPE_ROBOT_CTL_CONTROLLER, GST_ROBOT_CTL_CONTROLLER_ZONE, live));
  install(PROP_DISTANCE_CUE,
          g_param_spec_enum("distance-cue", "Distance cue", "What tells how far the target is",
                            GST_TYPE_ROBOT_CTL_DISTANCE_CUE, GST_ROBOT_CTL_DISTANCE_CUE_SIZE, live));
  install(PROP_SET_POINT,
          g_param_spec_double("set-point", "Set-point",
                              "Wanted distance cue: box height (or box bottom) as a fraction of the "
                              "frame height",
                              0.01, 1.0, c.setPoint, live));
  install(PROP_TURN_DEADBAND,
          g_param_spec_double("turn-deadband", "Turn deadband",
                              "Horizontal offset (fraction of half the frame width) within "
                              "which the target counts as centred",
                              0.0, 1.0, c.turnDeadband, live));
  install(PROP_DISTANCE_DEADBAND,
          g_param_spec_double("distance-deadband", "Distance deadband",
                              "Relative distance error within which the distance counts "
                              "as right",
                              0.0, 1.0, c.distanceDeadband, live));
  install(PROP_HYSTERESIS,
          g_param_spec_double("hysteresis", "Hysteresis",
                              "Zone controller: how far inside a deadband the error must come "
                              "back before a turn or drive ends",
                              0.0, 1.0, c.hysteresis, live));
  install(PROP_TURN_GAIN,
          g_param_spec_double(
              "turn-gain", "Turn gain",
              "Proportional controller: angular speed per unit horizontal offset, 0-100. The range "
              "admits negatives only so that robotctl can refuse them with a clear error (at start; a "
              "warning while playing, the old gain stays)",
              -100.0, 100.0, c.turnGain, live));
  install(
      PROP_DRIVE_GAIN,
      g_param_spec_double("drive-gain", "Drive gain",
                          "Proportional controller: linear speed per unit relative distance "
                          "error, 0-100. The range admits negatives only so that robotctl can refuse "
                          "them with a clear error (at start; a warning while playing, the old gain stays)",
                          -100.0, 100.0, c.driveGain, live));
  install(PROP_MAX_LINEAR,
          g_param_spec_double("max-linear", "Maximum linear speed",
                              "Largest forward/backward speed (fraction of full speed); the zone "
                              "controller's driving speed",
                              0.0, 1.0, c.maxLinear, live));
  install(PROP_MAX_ANGULAR, g_param_spec_double("max-angular", "Maximum angular speed",
                                                "Largest turn speed (fraction of full wheel speed); the zone "
                                                "controller's turning speed",
                                                0.0, 1.0, c.maxAngular, live));
  install(PROP_MAX_LINEAR_ACCEL,
          g_param_spec_double("max-linear-accel", "Maximum linear acceleration",
                              "Proportional controller: largest change of the linear speed "
                              "per second (0 = unlimited)",
                              0.0, 1000.0, c.maxLinearAccel, live));
  install(PROP_MAX_ANGULAR_ACCEL,
          g_param_spec_double("max-angular-accel", "Maximum angular acceleration",
                              "Proportional controller: largest change of the angular "
                              "speed per second (0 = unlimited)",
                              0.0, 1000.0, c.maxAngularAccel, live));
}

// The failsafe, which target to follow and the messages.
void installTargetProperties(GObjectClass *gobject_class) {
  const colortrack::FailsafeSettings f;
  auto install = [gobject_class](guint id, GParamSpec *spec) {
    g_object_class_install_property(gobject_class, id, spec);
  };
  install(PROP_LOST_TIMEOUT,
          g_param_spec_uint("lost-timeout", "Lost timeout",
                            "Milliseconds without a confirmed target, or without any buffer, "
                            "before the robot is stopped",
                            1, 600000, kDefaultLostTimeoutMs, live));
  install(PROP_MIN_SCORE,
          g_param_spec_double("min-score", "Minimum score", "A target with a lower score counts as not seen",
                              0.0, 1.0, f.minScore, live));
  install(PROP_SEARCH_TURN,
          g_param_spec_boolean("search-turn", "Search turn",
                               "After lost-timeout turn slowly towards where the target was last "
                               "seen instead of standing still",
                               f.searchTurn, live));
  install(
      PROP_SEARCH_SPEED,
      g_param_spec_double(
          "search-speed", "Search speed",
          "Angular speed of the search turn (fraction of full wheel speed); only used with search-turn=true",
          0.0, 1.0, f.searchSpeed, live));
  install(PROP_ROI_TYPE, g_param_spec_string("roi-type", "ROI type",
                                             "Type of the region-of-interest meta to follow, not empty "
                                             "(\"object\" for cvtracker)",
                                             kDefaultRoiType, live));
  install(PROP_TARGET_ID, g_param_spec_int("target-id", "Target id",
                                           "Id of the region of interest to follow; -1 = the lowest id", -1,
                                           G_MAXINT, kDefaultTargetId, live));
  install(PROP_POST_MESSAGES,
          g_param_spec_boolean("post-messages", "Post messages",
                               "Post a \"robotctl\" element message for every command sent; read at start",
                               FALSE, readAtStart));
}

}  // namespace

static void gst_robot_ctl_class_init(GstRobotCtlClass *klass) {
  GObjectClass *gobject_class = G_OBJECT_CLASS(klass);
  GstElementClass *element_class = GST_ELEMENT_CLASS(klass);
  GstBaseSinkClass *sink_class = GST_BASE_SINK_CLASS(klass);

  GST_DEBUG_CATEGORY_INIT(gst_robot_ctl_debug, "robotctl", 0, "Robot control from track metadata");

  gobject_class->set_property = gst_robot_ctl_set_property;
  gobject_class->get_property = gst_robot_ctl_get_property;
  gobject_class->dispose = gst_robot_ctl_dispose;
  gobject_class->finalize = gst_robot_ctl_finalize;

  // In this order: it is the order gst-inspect-1.0 lists them in.
  installOutputProperties(gobject_class);
  installControllerProperties(gobject_class);
  installTargetProperties(gobject_class);

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
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_CONTROLLER, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_DISTANCE_CUE, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_PARITY, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_ROBOT_CTL_FLOW_CONTROL, static_cast<GstPluginAPIFlags>(0));
}

static void gst_robot_ctl_init(GstRobotCtl *self) {
  self->priv = new GstRobotCtlPrivate();
}
