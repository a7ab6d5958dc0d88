// SPDX-License-Identifier: LGPL-2.1-or-later
#include "demo_run.hpp"

#include <gst/video/video.h>

#include <fstream>

namespace colortrack::demo {

namespace {

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

}  // namespace

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

void setProperty(GstElement *element, const char *name, const std::string &value) {
  if (!g_object_class_find_property(G_OBJECT_GET_CLASS(element), name))
    throw DemoError(std::string("element '") + GST_ELEMENT_NAME(element) + "' has no property '" + name +
                    "'");
  gst_util_set_object_arg(G_OBJECT(element), name, value.c_str());
}

void sendEos(RunState &run) {
  if (run.eosSent.exchange(true)) return;
  gst_element_send_event(run.pipeline, gst_event_new_eos());
}

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

}  // namespace colortrack::demo
