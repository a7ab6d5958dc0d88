// SPDX-License-Identifier: LGPL-2.1-or-later
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
#include <gst/app/gstappsrc.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "demo_options.hpp"
#include "demo_run.hpp"
#include "scene.hpp"

namespace colortrack::demo {
namespace {

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

// The built-in scene: one pass of the motion script is always kSceneFrames long, so --frames changes the
// length of the run and not the object's speed (the script repeats after a pass).
scene::SceneConfig demoScene() {
  scene::SceneConfig config;
  config.frameSize = cv::Size(640, 480);
  config.frames = kSceneFrames;
  config.scaleMin = 0.7;
  config.scaleMax = 1.4;
  config.rotationDegrees = 90;
  config.brightness = 0.4;
  config.decoy = true;
  return config;
}

// The input's elements up to `convertIn` (added to `run.pipeline` by the caller, except uridecodebin's,
// which links its video pad itself once it knows it).
std::vector<GstElement *> sourceChain(RunState &run, const Options &options, const scene::SceneConfig &scene,
                                      GstElement *convertIn) {
  switch (run.kind) {
    case InputKind::Scene: {
      GstElement *source = makeElement("appsrc");
      GstVideoInfo info;
      gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, scene.frameSize.width, scene.frameSize.height);
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
      return {source, convertIn};
    }
    case InputKind::Device: {
      GstElement *source = makeElement("v4l2src");
      g_object_set(source, "device", options.input.c_str(), nullptr);
      return {source, convertIn};
    }
    case InputKind::Uri:
      break;
  }
  // uridecodebin picks the source for the scheme: filesrc, souphttpsrc, rtspsrc for rtsp:// ...
  GstElement *source = makeElement("uridecodebin");
  g_object_set(source, "uri", toUri(options.input).c_str(), nullptr);
  gst_bin_add(GST_BIN(run.pipeline), source);
  run.videoEntry = convertIn;
  g_signal_connect(source, "pad-added", G_CALLBACK(onDecodedPad), &run);
  g_signal_connect(source, "no-more-pads", G_CALLBACK(onNoMorePads), &run);
  return {convertIn};
}

// colortrack with the demo's overlay and its object.
void setUpTracker(RunState &run, const Options &options, const scene::Scene &scene) {
  run.tracker = makeElement(kElementName);
  setProperty(run.tracker, "post-messages", "true");
  setProperty(run.tracker, "draw", "box+trail+label+search-window");
  // One definition of the object (colortrack refuses two): the scene's box unless a template is given.
  if (run.kind == InputKind::Scene && options.templatePath.empty() && options.initBox.empty())
    setProperty(run.tracker, "init-box", boxText(scene.initBox()));
  if (!options.initBox.empty()) setProperty(run.tracker, "init-box", options.initBox);
  if (!options.templatePath.empty()) {
    if (!g_file_test(options.templatePath.c_str(), G_FILE_TEST_IS_REGULAR))
      throw DemoError("template file not found: " + options.templatePath);
    setProperty(run.tracker, "template-location", options.templatePath);
  }
}

// robotctl: what a robot would be told, next to the annotated video (a real one with --robot).
void setUpRobot(RunState &run, const Options &options, const std::string &robotFile) {
  run.robot = makeElement("robotctl");
  setProperty(run.robot, "post-messages", "true");
  // In step with the frames' timestamps, as with a camera: the robot is told at its `rate` what it would
  // be told live (the 300-frame scene takes 10 s).
  setProperty(run.robot, "sync", "true");
  if (!options.robotDevice.empty()) {
    setProperty(run.robot, "device", options.robotDevice);
  } else {
    setProperty(run.robot, "protocol", "text");
    setProperty(run.robot, "location", robotFile);
  }
}

// source ! videoconvert ! colortrack ! tee ! queue ! videoconvert ! jpegenc ! avimux ! filesink, and the
// tee's second branch to robotctl. Throws DemoError; the pipeline owns what was added to it.
void buildPipeline(RunState &run, const Options &options, const scene::Scene &scene,
                   const std::string &videoFile, const std::string &robotFile) {
  GstElement *convertIn = makeElement("videoconvert");
  setUpTracker(run, options, scene);
  GstElement *convertOut = makeElement("videoconvert");
  GstElement *encoder = makeElement("jpegenc");
  GstElement *muxer = makeElement("avimux");
  GstElement *sink = makeElement("filesink");
  g_object_set(sink, "location", videoFile.c_str(), nullptr);
  GstElement *tee = makeElement("tee");
  GstElement *videoQueue = makeElement("queue");
  GstElement *robotQueue = makeElement("queue");
  setUpRobot(run, options, robotFile);

  std::vector<GstElement *> chain = sourceChain(run, options, scene.config(), convertIn);
  chain.insert(chain.end(), {run.tracker, tee, videoQueue, convertOut, encoder, muxer, sink});
  addAndLink(run.pipeline, chain);
  addAndLink(run.pipeline, {robotQueue, run.robot});
  if (!gst_element_link(tee, robotQueue)) throw DemoError("cannot link the robot branch");
}

void openRobotLog(RunState &run, const Options &options, const std::string &path) {
  run.robotLog = g_fopen(path.c_str(), "w");
  if (!run.robotLog) throw DemoError("cannot write " + path + ": " + g_strerror(errno));
  std::fprintf(
      run.robotLog,
      "# colortrack-demo: one line per command robotctl sent to %s, in the order sent (line N here is "
      "command N there)\n"
      "# sent_s: seconds since the pipeline started, when the command's bytes had been written\n"
      "# frame_s: timestamp of the video frame the command was decided on (- for a stop not decided "
      "on a frame)\n"
      "# reason: target, no-target, start, stalling, stalled, eos, paused, ready, shutdown, reconnected\n"
      "# n sent_s frame_s command left right reason\n",
      options.robotDevice.empty() ? options.robotOutput.c_str() : options.robotDevice.c_str());
}

// Plays until EOS, an error or a second Ctrl-C, then takes the pipeline down.
void play(RunState &run, const Options &options) {
  GstElement *pipeline = run.pipeline;
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
}

// Frames processed and tracked, and the mean IoU against the scene's ground truth.
void printTracking(RunState &run) {
  std::lock_guard<std::mutex> lock(run.mutex);
  g_print("frames processed : %d\n", run.framesProcessed);
  if (run.messagesOnBus == 0) g_printerr("warning: the element posted no \"colortrack\" messages\n");
  g_print("frames tracked   : %d (state tracking, from the element's bus messages)\n",
          run.framesTrackedOnBus);
  if (run.kind != InputKind::Scene) {
    g_print("mean IoU         : n/a (no ground truth for a real input)\n");
    return;
  }
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
    g_print("mean IoU         : %.3f (over %d frames with the object in view)\n", iouSum / visible, visible);
  else
    g_print("mean IoU         : n/a (no frame with the object in view was processed)\n");
}

// What the robot was told: the file's lines (text protocol, one command per line), or what robotctl said
// it sent to a device.
void printRobot(RunState &run, const Options &options, int fileLines, int fileStops) {
  std::string commands;
  for (const auto &[command, count] : run.robotCommands)
    commands += (commands.empty() ? "" : ", ") + command + " " + std::to_string(count);
  const std::string byCommand = commands.empty() ? "none" : commands;
  if (fileLines >= 0) {
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
    g_print("robot commands   : %d sent to %s (%s), %d of them stops at end of stream and shutdown\n",
            run.robotLines,
            options.robotDevice.empty() ? options.robotOutput.c_str() : options.robotDevice.c_str(),
            byCommand.c_str(), run.robotFinalStops);
  }
  g_print("robot log        : %s (when each command was sent, the frame it was decided on, why)\n",
          options.robotLog.c_str());
}

int run(const Options &options) {
  RunState run;
  run.kind = inputKind(options.input);
  run.frameLimit = options.frames;
  scene::Scene scene(demoScene());
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
  try {
    buildPipeline(run, options, scene, video.path(), robotFile ? robotFile->path() : "");
    openRobotLog(run, options, robotLog.path());
  } catch (...) {
    gst_object_unref(run.pipeline);
    throw;
  }
  GstPad *trackerSrc = gst_element_get_static_pad(run.tracker, "src");
  gst_pad_add_probe(trackerSrc, GST_PAD_PROBE_TYPE_BUFFER, onTrackedBuffer, &run, nullptr);
  gst_object_unref(trackerSrc);

  play(run, options);
  gst_object_unref(run.pipeline);
  const bool logWritten = std::fclose(run.robotLog) == 0;
  run.robotLog = nullptr;
  if (run.failed) throw DemoError(run.errorText);
  if (!logWritten) throw DemoError("cannot write " + robotLog.path());

  printTracking(run);
  if (run.framesProcessed == 0) throw DemoError("no frame reached the tracker");
  int fileStops = 0;
  const int fileLines = robotFile && robotFile->staged() ? countLines(robotFile->path(), &fileStops) : -1;
  video.commit();
  if (robotFile) robotFile->commit();
  robotLog.commit();
  g_print("output           : %s\n", options.output.c_str());
  printRobot(run, options, fileLines, fileStops);
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
