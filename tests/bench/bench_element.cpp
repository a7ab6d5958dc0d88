// SPDX-License-Identifier: LGPL-2.1-or-later
// Throughput of the colortrack element inside a pipeline, against `identity` as the cost of the pipeline
// itself: appsrc (pre-rendered BGR frames) ! colortrack|identity ! fakesink sync=false.
//
//   bench-element [--frames N] [--warmup N]
//
// Frames are rendered and copied before the clock starts, and handed over with a single reference so the
// element gets writable buffers (no copy-on-write inside the measured span). The time runs from the first
// measured frame at the sink to the last, on OpenCV's single thread like bench-tracker.

#include <gst/app/gstappsrc.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include "scene.hpp"

namespace colortrack::bench {
namespace {

constexpr int kFpsNum = 30, kFpsDen = 1;

struct BenchOptions {
  int frames = 100;
  int warmup = 10;
};

struct Variant {
  const char *name;
  const char *factory;
  const char *draw;    // colortrack "draw" flags ("" = draw nothing); nullptr for identity
  const char *method;  // colortrack "method"; nullptr = the element's default
};

const Variant kVariants[] = {
    {"identity", "identity", nullptr, nullptr},
    {"colortrack", "colortrack", "", nullptr},
    {"colortrack+draw", "colortrack", "box+trail+label+search-window", nullptr},
    {"colortrack-indexing", "colortrack", "", "indexing"},
};

struct RunResult {
  double fps = 0;
  double msPerFrame = 0;
};

// The scene of bench-tracker (object scaled with the frame height).
scene::SceneConfig sceneConfig(cv::Size frameSize, int frames) {
  scene::SceneConfig config;
  config.frameSize = frameSize;
  config.frames = frames;
  const int side = cvRound(72.0 * frameSize.height / 480.0);
  config.objectSize = cv::Size(side, side);
  config.scaleMin = 0.7;
  config.scaleMax = 1.4;
  config.rotationDegrees = 90;
  config.brightness = 0.4;
  config.decoy = true;
  return config;
}

std::vector<GstBuffer *> renderFrames(const scene::Scene &scene, int count, const GstVideoInfo &info) {
  std::vector<GstBuffer *> buffers;
  for (int index = 0; index < count; ++index) {
    const scene::SceneFrame frame = scene.render(index);
    GstBuffer *buffer = gst_buffer_new_allocate(nullptr, GST_VIDEO_INFO_SIZE(&info), nullptr);
    GstVideoFrame mapped;
    if (!gst_video_frame_map(&mapped, &info, buffer, GST_MAP_WRITE))
      throw std::runtime_error("cannot map buffer");
    cv::Mat destination(frame.bgr.rows, frame.bgr.cols, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&mapped, 0),
                        GST_VIDEO_FRAME_PLANE_STRIDE(&mapped, 0));
    frame.bgr.copyTo(destination);
    gst_video_frame_unmap(&mapped);
    const GstClockTime pts = gst_util_uint64_scale(index, GST_SECOND * kFpsDen, kFpsNum);
    GST_BUFFER_PTS(buffer) = pts;
    GST_BUFFER_DURATION(buffer) = gst_util_uint64_scale(index + 1, GST_SECOND * kFpsDen, kFpsNum) - pts;
    buffers.push_back(buffer);
  }
  return buffers;
}

struct SinkClock {
  int warmup = 0;
  int seen = 0;
  std::chrono::steady_clock::time_point first, last;
};

GstPadProbeReturn onSinkBuffer(GstPad * /*pad*/, GstPadProbeInfo * /*info*/, gpointer userData) {
  auto &clock = *static_cast<SinkClock *>(userData);
  const auto now = std::chrono::steady_clock::now();
  // The span starts when the last warm-up frame has left the element, so it covers exactly the measured ones.
  if (clock.seen == clock.warmup - 1) clock.first = now;
  clock.last = now;
  ++clock.seen;
  return GST_PAD_PROBE_OK;
}

GstElement *makeElement(const char *factory) {
  GstElement *element = gst_element_factory_make(factory, nullptr);
  if (!element)
    throw std::runtime_error(
        std::string("element '") + factory +
        "' not found (for colortrack: set GST_PLUGIN_PATH to the build's gst/ directory)");
  return element;
}

RunResult runVariant(const Variant &variant, const scene::Scene &scene,
                     const std::vector<GstBuffer *> &frames, const GstVideoInfo &info,
                     const BenchOptions &options) {
  GstElement *pipeline = gst_pipeline_new(nullptr);
  GstElement *source = makeElement("appsrc");
  GstElement *under = makeElement(variant.factory);
  GstElement *sink = makeElement("fakesink");
  gst_bin_add_many(GST_BIN(pipeline), source, under, sink, nullptr);
  if (!gst_element_link_many(source, under, sink, nullptr))
    throw std::runtime_error(std::string("cannot link appsrc ! ") + variant.factory + " ! fakesink");

  GstCaps *caps = gst_video_info_to_caps(&info);
  g_object_set(source, "caps", caps, "format", GST_FORMAT_TIME, "block", TRUE, "max-bytes",
               static_cast<guint64>(4 * GST_VIDEO_INFO_SIZE(&info)), nullptr);
  gst_caps_unref(caps);
  g_object_set(sink, "sync", FALSE, nullptr);
  if (variant.draw) {
    const cv::Rect box = scene.initBox();
    const std::string boxText = std::to_string(box.x) + "," + std::to_string(box.y) + "," +
                                std::to_string(box.width) + "," + std::to_string(box.height);
    gst_util_set_object_arg(G_OBJECT(under), "init-box", boxText.c_str());
    if (*variant.draw)
      gst_util_set_object_arg(G_OBJECT(under), "draw", variant.draw);
    else
      g_object_set(under, "draw", 0u, nullptr);
    if (variant.method) gst_util_set_object_arg(G_OBJECT(under), "method", variant.method);
  }

  SinkClock clock;
  clock.warmup = options.warmup;
  GstPad *sinkPad = gst_element_get_static_pad(sink, "sink");
  gst_pad_add_probe(sinkPad, GST_PAD_PROBE_TYPE_BUFFER, onSinkBuffer, &clock, nullptr);
  gst_object_unref(sinkPad);

  // Private copies, made before the clock starts: each reaches the element with a single reference.
  std::vector<GstBuffer *> copies;
  copies.reserve(frames.size());
  for (GstBuffer *frame : frames) copies.push_back(gst_buffer_copy_deep(frame));

  if (gst_element_set_state(pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE)
    throw std::runtime_error(std::string("pipeline with ") + variant.name + " failed to start");
  for (GstBuffer *copy : copies) gst_app_src_push_buffer(GST_APP_SRC(source), copy);  // takes ownership
  gst_app_src_end_of_stream(GST_APP_SRC(source));

  GstBus *bus = gst_element_get_bus(pipeline);
  GstMessage *message = gst_bus_timed_pop_filtered(bus, GST_CLOCK_TIME_NONE,
                                                   GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
  std::string error;
  if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR) {
    GError *gerror = nullptr;
    gst_message_parse_error(message, &gerror, nullptr);
    error = std::string(variant.name) + ": " + (gerror ? gerror->message : "error");
    g_clear_error(&gerror);
  }
  gst_message_unref(message);
  gst_object_unref(bus);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(pipeline);
  if (!error.empty()) throw std::runtime_error(error);

  const int measured = clock.seen - options.warmup;
  if (measured <= 0)
    throw std::runtime_error(std::string(variant.name) + ": too few frames reached the sink");
  const double seconds = std::chrono::duration<double>(clock.last - clock.first).count();
  RunResult result;
  result.msPerFrame = 1000.0 * seconds / measured;
  result.fps = measured / seconds;
  return result;
}

}  // namespace
}  // namespace colortrack::bench

int main(int argc, char **argv) {
  using namespace colortrack::bench;
  gst_init(&argc, &argv);
  BenchOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if ((arg == "--frames" || arg == "--warmup") && i + 1 < argc) {
      (arg == "--frames" ? options.frames : options.warmup) = std::atoi(argv[++i]);
    } else {
      std::fprintf(stderr, "usage: %s [--frames N] [--warmup N]\n", argv[0]);
      return 2;
    }
  }
  if (options.frames <= 0 || options.warmup <= 0) {
    std::fprintf(stderr, "--frames and --warmup must be positive\n");
    return 2;
  }
  // Same footing as bench-tracker: OpenCV is a shared library, so this also holds inside the plugin.
  cv::setNumThreads(1);

  const cv::Size sizes[] = {{640, 480}, {1920, 1080}};
  std::printf(
      "colortrack element benchmark: appsrc (BGR, pre-rendered) ! X ! fakesink sync=false, "
      "%d frames after %d warm-up, OpenCV on 1 thread\n\n",
      options.frames, options.warmup);
  std::printf("%-10s %-20s %10s %12s %14s\n", "size", "element", "fps", "ms/frame", "over identity");
  std::vector<std::string> machineLines;
  try {
    for (const cv::Size size : sizes) {
      const int total = options.warmup + options.frames;
      const colortrack::scene::Scene scene(sceneConfig(size, total));
      GstVideoInfo info;
      gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, size.width, size.height);
      GST_VIDEO_INFO_FPS_N(&info) = kFpsNum;
      GST_VIDEO_INFO_FPS_D(&info) = kFpsDen;
      const std::vector<GstBuffer *> frames = renderFrames(scene, total, info);

      double identityMs = 0;
      for (const Variant &variant : kVariants) {
        const RunResult r = runVariant(variant, scene, frames, info, options);
        if (variant.draw == nullptr) identityMs = r.msPerFrame;
        const std::string sizeText = std::to_string(size.width) + "x" + std::to_string(size.height);
        std::printf("%-10s %-20s %10.1f %12.3f %14.3f\n", sizeText.c_str(), variant.name, r.fps, r.msPerFrame,
                    r.msPerFrame - identityMs);
        std::fflush(stdout);
        char line[256];
        std::snprintf(line, sizeof line,
                      "BENCH element case=%s size=%s frames=%d fps=%.2f ms_per_frame=%.4f "
                      "over_identity_ms=%.4f",
                      variant.name, sizeText.c_str(), options.frames, r.fps, r.msPerFrame,
                      r.msPerFrame - identityMs);
        machineLines.emplace_back(line);
      }
      for (GstBuffer *frame : frames) gst_buffer_unref(frame);
    }
  } catch (const std::exception &error) {
    std::fprintf(stderr, "benchmark failed: %s\n", error.what());
    return 1;
  }
  std::printf("\n");
  for (const std::string &line : machineLines) std::printf("%s\n", line.c_str());
  return 0;
}
