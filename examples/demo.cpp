// colortrack-demo: runs the colortrack element on the built-in synthetic scene (and scores it against the
// scene's ground truth) or on a camera, a file or a stream, and writes the annotated video to an AVI file.
//
//   colortrack-demo [--output FILE] [--frames N]                        synthetic scene
//   colortrack-demo /dev/video0 --init-box 200,150,80,80 [--frames N]   camera
//   colortrack-demo clip.mp4 --template object.png                      file, URI or rtsp:// stream
//
// The video, the robot commands and their timestamped log are written to temporary files next to their
// targets and renamed over them only when the run succeeds, so a failed run leaves the previous ones intact.

#include <glib-unix.h>
#include <glib/gstdio.h>
#include <sys/stat.h>
#include <unistd.h>
#include <gst/app/gstappsrc.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "scene.hpp"

namespace colortrack::demo {
namespace {

constexpr const char *kElementName = "colortrack";
constexpr int kSceneFrames = 300;
constexpr int kFpsNum = 30, kFpsDen = 1;

class DemoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string input;  // empty: the synthetic scene
  std::string output = "colortrack-demo.avi";
  int frames = -1;  // -1: kSceneFrames for the scene, until EOS for real inputs
  std::string initBox;
  std::string templatePath;
  std::string robotDevice;                                // serial port of a real robot (robotctl device=)
  std::string robotOutput = "colortrack-demo-robot.txt";  // else the commands go here (robotctl location=)
  std::string robotLog;  // when each command was sent, and why (default: next to robotOutput)
};

// The log's default: the robot file's name with ".log" for its extension; colortrack-demo-robot.log when the
// commands go to a device or to stdout.
std::string defaultRobotLog(const Options &options) {
  if (!options.robotDevice.empty() || options.robotOutput == "-") return "colortrack-demo-robot.log";
  const std::string &out = options.robotOutput;
  const std::size_t slash = out.rfind('/'), dot = out.rfind('.');
  const bool hasExtension =
      dot != std::string::npos && dot > 0 && (slash == std::string::npos || dot > slash + 1);
  return (hasExtension ? out.substr(0, dot) : out) + ".log";
}

// An output file written under a temporary name next to its target and renamed over it on success only, so
// a failed run keeps the previous file. Targets that are not regular files (a FIFO, a pty, stdout) are
// written directly.
class StagedFile {
 public:
  explicit StagedFile(const std::string &target) : target_(target), path_(target) {
    GStatBuf st;
    const bool exists = g_stat(target.c_str(), &st) == 0;
    if (target != "-" && (!exists || S_ISREG(st.st_mode)))
      path_ = target + ".partial-" + std::to_string(static_cast<long>(getpid()));
  }
  StagedFile(const StagedFile &) = delete;
  StagedFile &operator=(const StagedFile &) = delete;
  ~StagedFile() {
    if (staged() && !committed_) g_unlink(path_.c_str());
  }
  const std::string &path() const { return path_; }      // where to write now
  const std::string &target() const { return target_; }  // where it ends up
  bool staged() const { return path_ != target_; }
  void commit() {
    if (staged() && g_rename(path_.c_str(), target_.c_str()) != 0)
      throw DemoError("cannot rename " + path_ + " to " + target_ + ": " + g_strerror(errno));
    committed_ = true;
  }

 private:
  std::string target_, path_;
  bool committed_ = false;
};

enum class InputKind { Scene, Device, Uri };

InputKind inputKind(const std::string &input) {
  if (input.empty()) return InputKind::Scene;
  if (input.rfind("/dev/video", 0) == 0) return InputKind::Device;
  return InputKind::Uri;
}

// A plain path becomes a file:// URI; anything GStreamer already accepts as a URI is kept.
std::string toUri(const std::string &input) {
  if (gst_uri_is_valid(input.c_str())) return input;
  if (!g_file_test(input.c_str(), G_FILE_TEST_EXISTS)) throw DemoError("input file not found: " + input);
  GError *error = nullptr;
  gchar *uri = gst_filename_to_uri(input.c_str(), &error);
  if (!uri) {
    std::string text = error ? error->message : "unknown error";
    g_clear_error(&error);
    throw DemoError("cannot make a URI of '" + input + "': " + text);
  }
  std::string result(uri);
  g_free(uri);
  return result;
}

Options parseOptions(int &argc, char **&argv) {
  gchar *output = nullptr, *initBox = nullptr, *templatePath = nullptr, *robotDevice = nullptr,
        *robotOutput = nullptr, *robotLog = nullptr;
  gchar **positional = nullptr;
  gint frames = -1;
  const GOptionEntry entries[] = {
      {"output", 'o', 0, G_OPTION_ARG_FILENAME, &output, "Output AVI file (default colortrack-demo.avi)",
       "FILE"},
      {"frames", 'n', 0, G_OPTION_ARG_INT, &frames,
       "Frames to process (default 300 for the scene, until end of stream otherwise)", "N"},
      {"init-box", 'b', 0, G_OPTION_ARG_STRING, &initBox, "Object box in the first frame", "X,Y,W,H"},
      {"template", 't', 0, G_OPTION_ARG_FILENAME, &templatePath, "Template image of the object (PNG/JPEG)",
       "FILE"},
      {"robot", 'r', 0, G_OPTION_ARG_FILENAME, &robotDevice,
       "Serial port of a robot to drive (robotctl device=), e.g. /dev/ttyUSB0", "DEVICE"},
      {"robot-output", 0, 0, G_OPTION_ARG_FILENAME, &robotOutput,
       "Without --robot, write the robot commands here, '-' for stdout (default colortrack-demo-robot.txt)",
       "FILE"},
      {"robot-log", 0, 0, G_OPTION_ARG_FILENAME, &robotLog,
       "Write one timestamped line per robot command here (default: the robot file's name with .log, "
       "colortrack-demo-robot.log)",
       "FILE"},
      {G_OPTION_REMAINING, 0, 0, G_OPTION_ARG_FILENAME_ARRAY, &positional, nullptr, nullptr},
      {nullptr, 0, 0, G_OPTION_ARG_NONE, nullptr, nullptr, nullptr}};

  GOptionContext *context = g_option_context_new("[/dev/videoN | FILE | URI]");
  g_option_context_set_summary(
      context,
      "Tracks a coloured object with the colortrack element and writes the annotated "
      "video.\nWithout an input, runs the built-in synthetic scene and reports the "
      "accuracy against its ground truth.");
  g_option_context_add_main_entries(context, entries, nullptr);
  g_option_context_add_group(context, gst_init_get_option_group());  // also initialises GStreamer
  GError *error = nullptr;
  const bool parsed = g_option_context_parse(context, &argc, &argv, &error);
  g_option_context_free(context);

  Options options;
  std::string problem;
  if (!parsed) problem = error ? error->message : "invalid arguments";
  g_clear_error(&error);
  if (output) options.output = output;
  if (initBox) options.initBox = initBox;
  if (templatePath) options.templatePath = templatePath;
  if (robotDevice) options.robotDevice = robotDevice;
  if (robotOutput) options.robotOutput = robotOutput;
  options.robotLog = robotLog ? robotLog : defaultRobotLog(options);
  options.frames = frames;
  if (positional && positional[0]) {
    options.input = positional[0];
    if (positional[1]) problem = std::string("more than one input given: ") + positional[1];
  }
  g_free(output);
  g_free(initBox);
  g_free(templatePath);
  g_free(robotDevice);
  g_free(robotOutput);
  g_free(robotLog);
  g_strfreev(positional);

  if (!problem.empty()) throw DemoError(problem + " (see --help)");
  if (options.frames == 0 || options.frames < -1) throw DemoError("--frames must be a positive number");
  if (options.output.empty()) throw DemoError("--output must name a file");
  if (options.robotLog.empty()) throw DemoError("--robot-log must name a file");
  if (options.robotLog == options.output ||
      (options.robotDevice.empty() && options.robotLog == options.robotOutput))
    throw DemoError("--robot-log must differ from --output and --robot-output");
  if (inputKind(options.input) == InputKind::Uri && !gst_uri_is_valid(options.input.c_str())) {
    // filesink truncates its file at start: writing over the input would destroy it.
    gchar *in = g_canonicalize_filename(options.input.c_str(), nullptr);
    gchar *out = g_canonicalize_filename(options.output.c_str(), nullptr);
    const bool same = g_strcmp0(in, out) == 0;
    g_free(in);
    g_free(out);
    if (same) throw DemoError("the output file is the input file: choose another --output");
  }
  if (inputKind(options.input) != InputKind::Scene && options.initBox.empty() && options.templatePath.empty())
    throw DemoError(
        "a camera, file or stream input needs --init-box X,Y,W,H or --template FILE to know what "
        "to track");
  return options;
}

GstElement *makeElement(const char *factory) {
  GstElement *element = gst_element_factory_make(factory, nullptr);
  if (element) return element;
  if (std::string(factory) == kElementName)
    throw DemoError(
        "the colortrack plugin was not found. Set GST_PLUGIN_PATH to the build's gst/ directory "
        "(e.g. GST_PLUGIN_PATH=$PWD/build/gst) or run the demo through `meson devenv -C build -w .`.");
  throw DemoError(std::string("GStreamer element '") + factory +
                  "' not found: install the plugin package that provides it (gst-inspect-1.0 " + factory +
                  ")");
}

// Sets a property from its string form (flags like "box+trail", boxes like "1,2,3,4"), checking that the
// element has it, so a mismatching plugin build is reported instead of silently ignored.
void setProperty(GstElement *element, const char *name, const std::string &value) {
  if (!g_object_class_find_property(G_OBJECT_GET_CLASS(element), name))
    throw DemoError(std::string("element '") + GST_ELEMENT_NAME(element) + "' has no property '" + name +
                    "'");
  gst_util_set_object_arg(G_OBJECT(element), name, value.c_str());
}

// "state" of the colortrack structures, whether the element stores it as a string or as an enum.
std::string stateOf(const GstStructure *structure) {
  const GValue *value = gst_structure_get_value(structure, "state");
  if (!value) return {};
  if (G_VALUE_HOLDS_STRING(value)) return g_value_get_string(value) ? g_value_get_string(value) : "";
  if (G_VALUE_HOLDS_ENUM(value)) {
    GEnumClass *enumClass = G_ENUM_CLASS(g_type_class_ref(G_VALUE_TYPE(value)));
    GEnumValue *enumValue = g_enum_get_value(enumClass, g_value_get_enum(value));
    std::string nick = enumValue ? enumValue->value_nick : "";
    g_type_class_unref(enumClass);
    return nick;
  }
  return {};
}

// What the element reported for one frame (from the region-of-interest meta on its output buffers).
struct FrameResult {
  bool hasBox = false;
  cv::Rect2d box;
  std::string state;
};

// Everything the streaming threads report to the main thread.
struct RunState {
  InputKind kind = InputKind::Scene;
  int frameLimit = -1;
  GMainLoop *loop = nullptr;
  GstElement *pipeline = nullptr;
  GstElement *videoEntry = nullptr;  // where a decoded video pad is linked (uridecodebin inputs)
  GstElement *tracker = nullptr;

  std::atomic<bool> stopRequested{false};  // Ctrl-C or --frames reached: finish with EOS
  std::atomic<bool> eosSent{false};
  bool failed = false;
  std::string errorText;
  int framesTrackedOnBus = 0;  // "colortrack" messages with state "tracking"
  int messagesOnBus = 0;
  GstElement *robot = nullptr;

  // The robot log, written from the bus's sync handler in the thread that posts (robotctl's writer, just
  // after the command's bytes went out), so each line is stamped when the command was sent.
  std::mutex robotMutex;  // guards the members below
  FILE *robotLog = nullptr;
  gint64 startTime = 0;                      // g_get_monotonic_time() when the pipeline was started
  int robotLines = 0;                        // "robotctl" messages (one per command sent)
  std::map<std::string, int> robotCommands;  // by command
  int robotFinalStops = 0;                   // stops sent at end of stream, pause or shutdown

  // Scene input.
  const scene::Scene *scene = nullptr;
  int sceneFrames = 0;
  int nextSceneFrame = 0;

  std::mutex mutex;  // guards the members below (written by streaming threads)
  int framesProcessed = 0;
  std::map<int, scene::SceneFrame> groundTruth;  // by frame index; pixels dropped once pushed
  std::map<int, FrameResult> results;
  bool videoLinked = false;
};

void sendEos(RunState &run) {
  if (run.eosSent.exchange(true)) return;
  gst_element_send_event(run.pipeline, gst_event_new_eos());
}

// appsrc need-data: renders and pushes the next scene frame, or ends the stream.
void pushSceneFrame(GstAppSrc *appsrc, guint /*length*/, gpointer userData) {
  auto &run = *static_cast<RunState *>(userData);
  const int index = run.nextSceneFrame;
  if (index >= run.sceneFrames || run.stopRequested) {
    gst_app_src_end_of_stream(appsrc);
    return;
  }
  run.nextSceneFrame = index + 1;

  scene::SceneFrame frame = run.scene->render(index);
  GstVideoInfo info;
  gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, frame.bgr.cols, frame.bgr.rows);
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, GST_VIDEO_INFO_SIZE(&info), nullptr);
  GstVideoFrame mapped;
  if (!gst_video_frame_map(&mapped, &info, buffer, GST_MAP_WRITE)) {
    gst_buffer_unref(buffer);
    gst_app_src_end_of_stream(appsrc);
    return;
  }
  // GStreamer rows may be padded to 4 bytes: copy through a Mat with the buffer's stride.
  cv::Mat destination(frame.bgr.rows, frame.bgr.cols, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&mapped, 0),
                      GST_VIDEO_FRAME_PLANE_STRIDE(&mapped, 0));
  frame.bgr.copyTo(destination);
  gst_video_frame_unmap(&mapped);

  const GstClockTime pts = gst_util_uint64_scale(index, GST_SECOND * kFpsDen, kFpsNum);
  GST_BUFFER_PTS(buffer) = pts;
  GST_BUFFER_DTS(buffer) = pts;
  GST_BUFFER_DURATION(buffer) = gst_util_uint64_scale(index + 1, GST_SECOND * kFpsDen, kFpsNum) - pts;
  GST_BUFFER_OFFSET(buffer) = index;

  frame.bgr.release();
  {
    std::lock_guard<std::mutex> lock(run.mutex);
    run.groundTruth[index] = std::move(frame);
  }
  gst_app_src_push_buffer(appsrc, buffer);  // takes the buffer
}

// Probe on the tracker's output: counts frames, keeps the reported box per frame, enforces --frames.
GstPadProbeReturn onTrackedBuffer(GstPad * /*pad*/, GstPadProbeInfo *info, gpointer userData) {
  auto &run = *static_cast<RunState *>(userData);
  GstBuffer *buffer = GST_PAD_PROBE_INFO_BUFFER(info);
  if (!buffer) return GST_PAD_PROBE_OK;

  std::lock_guard<std::mutex> lock(run.mutex);
  if (run.frameLimit > 0 && run.framesProcessed >= run.frameLimit) return GST_PAD_PROBE_DROP;
  const int index = run.framesProcessed++;
  if (run.frameLimit > 0 && run.framesProcessed == run.frameLimit && run.kind != InputKind::Scene) {
    // Not from a streaming thread: the main loop sends EOS on this message.
    gst_element_post_message(run.pipeline,
                             gst_message_new_application(GST_OBJECT(run.pipeline),
                                                         gst_structure_new_empty("colortrack-demo-stop")));
  }

  FrameResult result;
  gpointer iter = nullptr;
  const GQuark roiType = g_quark_from_static_string(kElementName);
  while (GstMeta *meta =
             gst_buffer_iterate_meta_filtered(buffer, &iter, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (roi->roi_type != roiType) continue;
    result.hasBox = true;
    result.box = cv::Rect2d(roi->x, roi->y, roi->w, roi->h);
    if (GstStructure *params = gst_video_region_of_interest_meta_get_param(roi, kElementName))
      result.state = stateOf(params);
    break;
  }
  // The scene's frames carry their index in the timestamp; real inputs are numbered in arrival order.
  int frameIndex = index;
  if (run.kind == InputKind::Scene && GST_BUFFER_PTS_IS_VALID(buffer))
    frameIndex =
        static_cast<int>(gst_util_uint64_scale_round(GST_BUFFER_PTS(buffer), kFpsNum, GST_SECOND * kFpsDen));
  run.results[frameIndex] = result;
  return GST_PAD_PROBE_OK;
}

// uridecodebin exposes one pad per stream: video goes to the tracker, anything else to a fakesink so an
// unlinked audio pad cannot stop the pipeline.
void onDecodedPad(GstElement * /*decodebin*/, GstPad *pad, gpointer userData) {
  auto &run = *static_cast<RunState *>(userData);
  GstCaps *caps = gst_pad_get_current_caps(pad);
  if (!caps) caps = gst_pad_query_caps(pad, nullptr);
  const std::string media = gst_structure_get_name(gst_caps_get_structure(caps, 0));
  gst_caps_unref(caps);

  GstElement *target = nullptr;
  {
    std::lock_guard<std::mutex> lock(run.mutex);
    if (media.rfind("video/", 0) == 0 && !run.videoLinked) {
      run.videoLinked = true;
      target = GST_ELEMENT(gst_object_ref(run.videoEntry));
    }
  }
  if (!target) {
    target = gst_element_factory_make("fakesink", nullptr);
    if (!target) return;
    g_object_set(target, "sync", FALSE, "async", FALSE, nullptr);
    gst_bin_add(GST_BIN(run.pipeline), target);
    gst_element_sync_state_with_parent(target);
    gst_object_ref(target);
  }
  GstPad *sinkPad = gst_element_get_static_pad(target, "sink");
  if (gst_pad_link(pad, sinkPad) != GST_PAD_LINK_OK)
    g_printerr("warning: could not link the decoded %s stream\n", media.c_str());
  gst_object_unref(sinkPad);
  gst_object_unref(target);
}

void onNoMorePads(GstElement * /*decodebin*/, gpointer userData) {
  auto &run = *static_cast<RunState *>(userData);
  bool linked;
  {
    std::lock_guard<std::mutex> lock(run.mutex);
    linked = run.videoLinked;
  }
  if (!linked)
    gst_element_post_message(
        run.pipeline, gst_message_new_application(GST_OBJECT(run.pipeline),
                                                  gst_structure_new_empty("colortrack-demo-no-video")));
}

gboolean onBusMessage(GstBus * /*bus*/, GstMessage *message, gpointer userData) {
  auto &run = *static_cast<RunState *>(userData);
  switch (GST_MESSAGE_TYPE(message)) {
    case GST_MESSAGE_ERROR: {
      GError *error = nullptr;
      gchar *debug = nullptr;
      gst_message_parse_error(message, &error, &debug);
      run.failed = true;
      run.errorText = std::string(GST_OBJECT_NAME(GST_MESSAGE_SRC(message))) + ": " +
                      (error ? error->message : "unknown error") + (debug ? std::string("\n  ") + debug : "");
      g_clear_error(&error);
      g_free(debug);
      g_main_loop_quit(run.loop);
      break;
    }
    case GST_MESSAGE_WARNING: {
      GError *error = nullptr;
      gst_message_parse_warning(message, &error, nullptr);
      g_printerr("warning from %s: %s\n", GST_OBJECT_NAME(GST_MESSAGE_SRC(message)),
                 error ? error->message : "?");
      g_clear_error(&error);
      break;
    }
    case GST_MESSAGE_EOS:
      g_main_loop_quit(run.loop);
      break;
    case GST_MESSAGE_APPLICATION: {
      const GstStructure *s = gst_message_get_structure(message);
      if (gst_structure_has_name(s, "colortrack-demo-stop")) {
        sendEos(run);
      } else if (gst_structure_has_name(s, "colortrack-demo-no-video")) {
        run.failed = true;
        run.errorText = "the input has no video stream";
        g_main_loop_quit(run.loop);
      }
      break;
    }
    case GST_MESSAGE_ELEMENT: {
      const GstStructure *s = gst_message_get_structure(message);
      if (GST_MESSAGE_SRC(message) == GST_OBJECT(run.tracker) && gst_structure_has_name(s, kElementName)) {
        // Frames past --frames still go through the element while EOS travels: they are not counted.
        guint64 frame = 0;
        if (run.frameLimit > 0 && gst_structure_get_uint64(s, "frame", &frame) &&
            frame >= static_cast<guint64>(run.frameLimit))
          break;
        ++run.messagesOnBus;
        if (stateOf(s) == "tracking") ++run.framesTrackedOnBus;
      }
      break;
    }
    default:
      break;
  }
  return TRUE;
}

// Bus sync handler: one line in the robot log per command robotctl sent (see RunState::robotLog).
GstBusSyncReply onBusSync(GstBus * /*bus*/, GstMessage *message, gpointer userData) {
  auto &run = *static_cast<RunState *>(userData);
  if (GST_MESSAGE_TYPE(message) != GST_MESSAGE_ELEMENT || GST_MESSAGE_SRC(message) != GST_OBJECT(run.robot))
    return GST_BUS_PASS;
  const GstStructure *s = gst_message_get_structure(message);
  if (!gst_structure_has_name(s, "robotctl")) return GST_BUS_PASS;
  const gint64 now = g_get_monotonic_time();
  const char *command = gst_structure_get_string(s, "command");
  const char *reason = gst_structure_get_string(s, "reason");
  int left = 0, right = 0;
  guint64 timestamp = GST_CLOCK_TIME_NONE;
  gst_structure_get_int(s, "left", &left);
  gst_structure_get_int(s, "right", &right);
  gst_structure_get_uint64(s, "timestamp", &timestamp);
  command = command ? command : "?";
  reason = reason ? reason : "?";

  std::lock_guard<std::mutex> lock(run.robotMutex);
  ++run.robotLines;
  ++run.robotCommands[command];
  const std::string why(reason);
  if (why == "eos" || why == "paused" || why == "ready" || why == "shutdown") ++run.robotFinalStops;
  if (run.robotLog) {
    char frameTime[32] = "-";
    if (GST_CLOCK_TIME_IS_VALID(timestamp))
      std::snprintf(frameTime, sizeof frameTime, "%.3f", static_cast<double>(timestamp) / GST_SECOND);
    std::fprintf(run.robotLog, "%d %.3f %s %s %d %d %s\n", run.robotLines,
                 static_cast<double>(now - run.startTime) / G_USEC_PER_SEC, frameTime, command, left, right,
                 reason);
  }
  return GST_BUS_PASS;
}

// Lines of a text file (the text protocol's commands); -1 when it cannot be read.
int countLines(const std::string &path, int *stops) {
  std::ifstream in(path);
  if (!in) return -1;
  int lines = 0;
  *stops = 0;
  for (std::string line; std::getline(in, line);) {
    ++lines;
    if (line == "L=0 R=0") ++*stops;
  }
  return lines;
}

// First Ctrl-C: EOS, so avimux writes its index and the file stays playable. Second: stop at once.
gboolean onInterrupt(gpointer userData) {
  auto &run = *static_cast<RunState *>(userData);
  if (run.stopRequested.exchange(true)) {
    g_printerr("\ninterrupted again: stopping without finalising the output\n");
    run.failed = true;
    run.errorText = "interrupted";
    g_main_loop_quit(run.loop);
  } else {
    g_printerr("\ninterrupted: finishing the output file (Ctrl-C again to abort)\n");
    sendEos(run);
  }
  return G_SOURCE_CONTINUE;
}

// Adds elements to the bin and links them in order.
void addAndLink(GstElement *bin, const std::vector<GstElement *> &chain) {
  for (GstElement *element : chain) gst_bin_add(GST_BIN(bin), element);
  for (size_t i = 1; i < chain.size(); ++i) {
    if (!gst_element_link(chain[i - 1], chain[i]))
      throw DemoError(std::string("cannot link ") + GST_ELEMENT_NAME(chain[i - 1]) + " to " +
                      GST_ELEMENT_NAME(chain[i]));
  }
}

std::string boxText(const cv::Rect &box) {
  return std::to_string(box.x) + "," + std::to_string(box.y) + "," + std::to_string(box.width) + "," +
         std::to_string(box.height);
}

// What the annotated video shows (the README's "What the overlay shows" has a picture).
void printLegend(InputKind kind) {
  g_print(
      "overlay: box = the track: green = colour and edge check agree (verified), red = colour only (a "
      "same-colour\n"
      "         look-alike or a changed object), orange = coasting on the prediction; label \"1 0.91 "
      "tracking\" =\n"
      "         track id, score, state (tracking / coasting); yellow line = the trail of the box centre; "
      "thin "
      "blue box =\n"
      "         the search window (the demo turns it on with draw=...+search-window; it is off by "
      "default)\n");
  if (kind == InputKind::Scene)
    g_print(
        "scene  : a textured object turns, scales and moves under changing light; the plain disc of its "
        "colours\n"
        "         in the bottom-right corner is a decoy that colour alone would match, the tracker must "
        "ignore it\n");
}

int run(const Options &options) {
  RunState run;
  run.kind = inputKind(options.input);
  run.frameLimit = options.frames;

  scene::SceneConfig sceneConfig;
  sceneConfig.frameSize = cv::Size(640, 480);
  // One pass of the motion script is always kSceneFrames long, so --frames changes the length of the run and
  // not the object's speed (the script repeats after a pass).
  sceneConfig.frames = kSceneFrames;
  sceneConfig.scaleMin = 0.7;
  sceneConfig.scaleMax = 1.4;
  sceneConfig.rotationDegrees = 90;
  sceneConfig.brightness = 0.4;
  sceneConfig.decoy = true;
  scene::Scene scene(sceneConfig);
  if (run.kind == InputKind::Scene) {
    run.scene = &scene;
    run.sceneFrames = options.frames > 0 ? options.frames : kSceneFrames;
  }

  // Written under temporary names, renamed over the targets only if the run succeeds.
  StagedFile video(options.output);
  std::unique_ptr<StagedFile> robotFile;
  if (options.robotDevice.empty()) robotFile = std::make_unique<StagedFile>(options.robotOutput);
  StagedFile robotLog(options.robotLog);

  run.pipeline = gst_pipeline_new("colortrack-demo");
  GstElement *pipeline = run.pipeline;
  // Everything below throws on a problem; the pipeline owns what was added to it.
  try {
    GstElement *convertIn = makeElement("videoconvert");
    run.tracker = makeElement(kElementName);
    GstElement *convertOut = makeElement("videoconvert");
    GstElement *encoder = makeElement("jpegenc");
    GstElement *muxer = makeElement("avimux");
    GstElement *sink = makeElement("filesink");

    setProperty(run.tracker, "post-messages", "true");
    setProperty(run.tracker, "draw", "box+trail+label+search-window");
    if (run.kind == InputKind::Scene) setProperty(run.tracker, "init-box", boxText(scene.initBox()));
    if (!options.initBox.empty()) setProperty(run.tracker, "init-box", options.initBox);
    if (!options.templatePath.empty()) {
      if (!g_file_test(options.templatePath.c_str(), G_FILE_TEST_IS_REGULAR))
        throw DemoError("template file not found: " + options.templatePath);
      setProperty(run.tracker, "template-location", options.templatePath);
    }
    g_object_set(sink, "location", video.path().c_str(), nullptr);
    // The robot branch: what a robot would be told, next to the annotated video.
    GstElement *tee = makeElement("tee");
    GstElement *videoQueue = makeElement("queue");
    GstElement *robotQueue = makeElement("queue");
    run.robot = makeElement("robotctl");
    setProperty(run.robot, "post-messages", "true");
    // In step with the frames' timestamps, as with a camera: the robot is told at its `rate` what it would
    // be told live (the 300-frame scene takes 10 s).
    setProperty(run.robot, "sync", "true");
    if (!options.robotDevice.empty()) {
      setProperty(run.robot, "device", options.robotDevice);
    } else {
      setProperty(run.robot, "protocol", "text");
      setProperty(run.robot, "location", robotFile->path());
    }

    std::vector<GstElement *> chain;
    switch (run.kind) {
      case InputKind::Scene: {
        GstElement *source = makeElement("appsrc");
        GstVideoInfo info;
        gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, sceneConfig.frameSize.width,
                                  sceneConfig.frameSize.height);
        GST_VIDEO_INFO_FPS_N(&info) = kFpsNum;
        GST_VIDEO_INFO_FPS_D(&info) = kFpsDen;
        GstCaps *caps = gst_video_info_to_caps(&info);
        // A few frames of queue: rendering stays just ahead of the tracker instead of filling memory.
        g_object_set(source, "caps", caps, "format", GST_FORMAT_TIME, "is-live", FALSE, "max-bytes",
                     static_cast<guint64>(4 * GST_VIDEO_INFO_SIZE(&info)), nullptr);
        gst_caps_unref(caps);
        GstAppSrcCallbacks callbacks = {};
        callbacks.need_data = pushSceneFrame;
        gst_app_src_set_callbacks(GST_APP_SRC(source), &callbacks, &run, nullptr);
        chain = {source, convertIn};
        break;
      }
      case InputKind::Device: {
        GstElement *source = makeElement("v4l2src");
        g_object_set(source, "device", options.input.c_str(), nullptr);
        chain = {source, convertIn};
        break;
      }
      case InputKind::Uri: {
        // uridecodebin picks the source for the scheme: filesrc, souphttpsrc, rtspsrc for rtsp:// ...
        GstElement *source = makeElement("uridecodebin");
        g_object_set(source, "uri", toUri(options.input).c_str(), nullptr);
        gst_bin_add(GST_BIN(pipeline), source);
        run.videoEntry = convertIn;
        g_signal_connect(source, "pad-added", G_CALLBACK(onDecodedPad), &run);
        g_signal_connect(source, "no-more-pads", G_CALLBACK(onNoMorePads), &run);
        chain = {convertIn};
        break;
      }
    }
    chain.insert(chain.end(), {run.tracker, tee, videoQueue, convertOut, encoder, muxer, sink});
    addAndLink(pipeline, chain);
    addAndLink(pipeline, {robotQueue, run.robot});
    if (!gst_element_link(tee, robotQueue)) throw DemoError("cannot link the robot branch");
  } catch (...) {
    gst_object_unref(pipeline);
    throw;
  }

  GstPad *trackerSrc = gst_element_get_static_pad(run.tracker, "src");
  gst_pad_add_probe(trackerSrc, GST_PAD_PROBE_TYPE_BUFFER, onTrackedBuffer, &run, nullptr);
  gst_object_unref(trackerSrc);

  run.robotLog = g_fopen(robotLog.path().c_str(), "w");
  if (!run.robotLog) {
    const std::string why = g_strerror(errno);
    gst_object_unref(pipeline);
    throw DemoError("cannot write " + robotLog.path() + ": " + why);
  }
  std::fprintf(
      run.robotLog,
      "# colortrack-demo: one line per command robotctl sent to %s, in the order sent (line N here is "
      "command N there)\n"
      "# sent_s: seconds since the pipeline started, when the command's bytes had been written\n"
      "# frame_s: timestamp of the video frame the command was decided on (- for a stop not decided "
      "on a frame)\n"
      "# reason: target, no-target, start, stalled, eos, paused, ready, shutdown, reconnected\n"
      "# n sent_s frame_s command left right reason\n",
      options.robotDevice.empty() ? options.robotOutput.c_str() : options.robotDevice.c_str());

  run.loop = g_main_loop_new(nullptr, FALSE);
  GstBus *bus = gst_element_get_bus(pipeline);
  const guint busWatch = gst_bus_add_watch(bus, onBusMessage, &run);
  gst_bus_set_sync_handler(bus, onBusSync, &run, nullptr);
  const guint sigintWatch = g_unix_signal_add(SIGINT, onInterrupt, &run);

  g_print("input : %s\n", run.kind == InputKind::Scene
                              ? "synthetic scene (640x480, turning, scaling, lighting "
                                "+-40%, decoy)"
                              : options.input.c_str());
  printLegend(run.kind);
  run.startTime = g_get_monotonic_time();
  if (gst_element_set_state(pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE) {
    // The reason is on the bus as an error message; let the watch collect it.
    run.failed = true;
    run.errorText = "the pipeline could not start";
    GstMessage *message = gst_bus_timed_pop_filtered(GST_ELEMENT_BUS(pipeline), 0, GST_MESSAGE_ERROR);
    if (message) {
      onBusMessage(nullptr, message, &run);
      gst_message_unref(message);
    }
  } else {
    g_main_loop_run(run.loop);
  }

  // READY first: robotctl sends its last stops on the way (end of stream, shutdown), while the bus still
  // carries their messages to the log; going to NULL flushes the bus.
  gst_element_set_state(pipeline, GST_STATE_READY);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_bus_set_sync_handler(bus, nullptr, nullptr, nullptr);
  gst_object_unref(bus);
  g_source_remove(sigintWatch);
  g_source_remove(busWatch);
  g_main_loop_unref(run.loop);
  gst_object_unref(pipeline);
  const bool logWritten = std::fclose(run.robotLog) == 0;
  run.robotLog = nullptr;

  if (run.failed) throw DemoError(run.errorText);
  if (!logWritten) throw DemoError("cannot write " + robotLog.path());

  std::lock_guard<std::mutex> lock(run.mutex);
  g_print("frames processed : %d\n", run.framesProcessed);
  if (run.messagesOnBus == 0) g_printerr("warning: the element posted no \"colortrack\" messages\n");
  g_print("frames tracked   : %d (state tracking, from the element's bus messages)\n",
          run.framesTrackedOnBus);
  if (run.kind == InputKind::Scene) {
    // IoU over the frames where the object is in view; a frame without a box counts as 0.
    double iouSum = 0;
    int visible = 0;
    for (const auto &[index, truth] : run.groundTruth) {
      if (!truth.objectVisible) continue;
      auto found = run.results.find(index);
      if (found == run.results.end()) continue;  // never came out of the tracker (stopped early)
      ++visible;
      if (found->second.hasBox) iouSum += scene::iou(found->second.box, truth.box);
    }
    if (visible > 0)
      g_print("mean IoU         : %.3f (over %d frames with the object in view)\n", iouSum / visible,
              visible);
    else
      g_print("mean IoU         : n/a (no frame with the object in view was processed)\n");
  } else {
    g_print("mean IoU         : n/a (no ground truth for a real input)\n");
  }
  if (run.framesProcessed == 0) throw DemoError("no frame reached the tracker");

  std::string commands;
  for (const auto &[command, count] : run.robotCommands)
    commands += (commands.empty() ? "" : ", ") + command + " " + std::to_string(count);
  const std::string byCommand = commands.empty() ? "none" : commands;
  const std::string finalStops = std::to_string(run.robotFinalStops);
  int fileStops = 0;
  const int fileLines = robotFile && robotFile->staged() ? countLines(robotFile->path(), &fileStops) : -1;
  video.commit();
  if (robotFile) robotFile->commit();
  robotLog.commit();

  g_print("output           : %s\n", options.output.c_str());
  if (fileLines >= 0) {
    // What the robot would have received: the file's lines (text protocol, one command per line).
    g_print(
        "robot commands   : %d lines in %s, %d of them stop (L=0 R=0); %d stop%s sent at end of stream "
        "and shutdown\n",
        fileLines, options.robotOutput.c_str(), fileStops, run.robotFinalStops,
        run.robotFinalStops == 1 ? " was" : "s were");
    g_print("                   by command: %s\n", byCommand.c_str());
    if (fileLines != run.robotLines)
      g_printerr("warning: %s has %d lines but robotctl reported %d commands sent\n",
                 options.robotOutput.c_str(), fileLines, run.robotLines);
  } else {
    g_print("robot commands   : %d sent to %s (%s), %s of them stops at end of stream and shutdown\n",
            run.robotLines,
            options.robotDevice.empty() ? options.robotOutput.c_str() : options.robotDevice.c_str(),
            byCommand.c_str(), finalStops.c_str());
  }
  g_print("robot log        : %s (when each command was sent, the frame it was decided on, why)\n",
          options.robotLog.c_str());
  return 0;
}

}  // namespace
}  // namespace colortrack::demo

int main(int argc, char **argv) {
  using namespace colortrack::demo;
  try {
    const Options options = parseOptions(argc, argv);
    return run(options);
  } catch (const std::exception &error) {
    g_printerr("colortrack-demo: error: %s\n", error.what());
    return 1;
  }
}
