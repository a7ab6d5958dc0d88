// SPDX-License-Identifier: LGPL-2.1-or-later
// What the demo's pipeline shares between its threads (RunState), and the callbacks that fill it: the scene
// source, the probe on the tracker's output, the decoded pads, the bus (the robot's log), Ctrl-C.
#pragma once

#include <gst/app/gstappsrc.h>
#include <gst/gst.h>

#include <atomic>
#include <cstdio>
#include <map>
#include <mutex>
#include <string>

#include <opencv2/core.hpp>

#include "demo_options.hpp"
#include "scene.hpp"

namespace colortrack::demo {

inline constexpr const char *kElementName = "colortrack";
inline constexpr int kSceneFrames = 300;
inline constexpr int kFpsNum = 30, kFpsDen = 1;

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

// The element, or DemoError saying which package or plugin path is missing.
GstElement *makeElement(const char *factory);
// Sets a property from its string form (flags like "box+trail", boxes like "1,2,3,4"), checking that the
// element has it, so a mismatching plugin build is reported instead of silently ignored.
void setProperty(GstElement *element, const char *name, const std::string &value);
void sendEos(RunState &run);

// appsrc need-data: renders and pushes the next scene frame, or ends the stream.
void pushSceneFrame(GstAppSrc *appsrc, guint length, gpointer userData);
// Probe on the tracker's output: counts frames, keeps the reported box per frame, enforces --frames.
GstPadProbeReturn onTrackedBuffer(GstPad *pad, GstPadProbeInfo *info, gpointer userData);
void onDecodedPad(GstElement *decodebin, GstPad *pad, gpointer userData);
void onNoMorePads(GstElement *decodebin, gpointer userData);
gboolean onBusMessage(GstBus *bus, GstMessage *message, gpointer userData);
GstBusSyncReply onBusSync(GstBus *bus, GstMessage *message, gpointer userData);
gboolean onInterrupt(gpointer userData);
// Lines of a text file (the text protocol's commands) and how many are stops; -1 when it cannot be read.
int countLines(const std::string &path, int *stops);

}  // namespace colortrack::demo
