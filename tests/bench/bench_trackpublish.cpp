// SPDX-License-Identifier: LGPL-2.1-or-later
// What trackpublish costs the streaming thread per frame, with 8 tracks on every buffer: appsrc (buffers made
// beforehand, each with 8 colortrack ROI metas and their parameters) ! X ! fakesink, X being identity (the
// pipeline itself), trackpublish writing JSON lines to /dev/null, and trackpublish publishing to an MQTT
// address nobody listens on (the documents go into its queue, which is what the streaming thread pays for).
//
//   bench-trackpublish [--frames N]
//
// Prints the median over 5 runs of the milliseconds per frame of each, and the difference to identity.

#include <gst/app/gstappsrc.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

constexpr int kWidth = 1280, kHeight = 720, kTracks = 8, kRuns = 5;

GstBuffer *frameWithTracks(int frame) {
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, 16, nullptr);
  for (int id = 1; id <= kTracks; ++id) {
    GstVideoRegionOfInterestMeta *roi = gst_buffer_add_video_region_of_interest_meta(
        buffer, "colortrack", (frame * 7 + id * 120) % 1200, 40 + id * 70, 60, 60);
    roi->id = id;
    gst_video_region_of_interest_meta_add_param(
        roi, gst_structure_new("colortrack", "state", G_TYPE_STRING, "tracking", "score", G_TYPE_DOUBLE, 0.87,
                               "verified", G_TYPE_BOOLEAN, TRUE, "scale", G_TYPE_DOUBLE, 1.0, "vx",
                               G_TYPE_DOUBLE, 7.0, "vy", G_TYPE_DOUBLE, -0.5, nullptr));
  }
  GST_BUFFER_PTS(buffer) = gst_util_uint64_scale_int(frame, GST_SECOND, 30);
  return buffer;
}

// Milliseconds per frame through `element`.
double run(const std::string &element, int frames) {
  const std::string launch =
      "appsrc name=src format=time caps=video/x-raw,format=GRAY8,width=" + std::to_string(kWidth) +
      ",height=" + std::to_string(kHeight) + ",framerate=30/1 ! " + element + " ! fakesink sync=false";
  GError *error = nullptr;
  GstElement *pipeline = gst_parse_launch(launch.c_str(), &error);
  if (!pipeline) {
    std::fprintf(stderr, "%s\n", error ? error->message : "?");
    std::exit(1);
  }
  GstElement *src = gst_bin_get_by_name(GST_BIN(pipeline), "src");
  std::vector<GstBuffer *> buffers;
  for (int i = 0; i < frames; ++i) buffers.push_back(frameWithTracks(i));
  gst_element_set_state(pipeline, GST_STATE_PLAYING);
  const auto start = std::chrono::steady_clock::now();
  for (GstBuffer *b : buffers) gst_app_src_push_buffer(GST_APP_SRC(src), b);
  gst_app_src_end_of_stream(GST_APP_SRC(src));
  GstBus *bus = gst_element_get_bus(pipeline);
  GstMessage *msg = gst_bus_timed_pop_filtered(
      bus, GST_CLOCK_TIME_NONE, static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (GST_MESSAGE_TYPE(msg) == GST_MESSAGE_ERROR) {
    std::fprintf(stderr, "error in %s\n", element.c_str());
    std::exit(1);
  }
  gst_message_unref(msg);
  gst_object_unref(bus);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(src);
  gst_object_unref(pipeline);
  return ms / frames;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char **argv) {
  gst_init(&argc, &argv);
  int frames = 2000;
  for (int i = 1; i < argc; ++i)
    if (std::string(argv[i]) == "--frames" && i + 1 < argc) frames = std::atoi(argv[++i]);
  // drain-timeout=0: EOS is not held up by the queue nobody drains; the measured time is the streaming
  // thread's alone.
  const std::vector<std::pair<const char *, std::string>> variants = {
      {"identity", "identity"},
      {"trackpublish, JSON lines to /dev/null", "trackpublish location=/dev/null"},
      {"trackpublish, MQTT (queued, broker absent)",
       "trackpublish address=tcp://127.0.0.1:9 max-queued=100000 drain-timeout=0"},
  };
  std::printf("%d frames of %dx%d with %d tracks each, median of %d runs\n", frames, kWidth, kHeight, kTracks,
              kRuns);
  double base = 0;
  for (const auto &[name, element] : variants) {
    std::vector<double> times;
    for (int r = 0; r < kRuns; ++r) times.push_back(run(element, frames));
    const double ms = median(times);
    if (base == 0) base = ms;
    std::printf("%-44s %.4f ms/frame  (+%.4f ms over identity)\n", name, ms, ms - base);
  }
  return 0;
}
