// SPDX-License-Identifier: LGPL-2.1-or-later
// Helpers shared by the gst-check element tests: buffers from cv::Mat frames, caps strings, a harness with
// its own bus, ROI meta and bus-message reading, and preloading plugins before check forks the tests.
// Include it before the GStreamer headers of a test: gstcheck.h defines macros (fail, ...) that clash with
// names in the standard library, so the C++ headers must come first.
#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace colortrack::gst_test_util {

// Every test stream runs at this frame rate (timestamps and caps agree on it).
constexpr int kFps = 30;
// How long a pipeline may take to reach EOS or an error before the test calls it a hang.
constexpr GstClockTime kBusTimeout = 20 * GST_SECOND;

inline bool contains(const std::string &text, const std::string &part) {
  return text.find(part) != std::string::npos;
}

// "x,y,width,height", the form of colortrack's init-box property.
inline std::string boxString(const cv::Rect &r) {
  return std::to_string(r.x) + "," + std::to_string(r.y) + "," + std::to_string(r.width) + "," +
         std::to_string(r.height);
}

// Raw video caps of `format` at `size` and kFps.
inline std::string videoCaps(const char *format, cv::Size size) {
  return std::string("video/x-raw,format=") + format + ",width=" + std::to_string(size.width) +
         ",height=" + std::to_string(size.height) + ",framerate=" + std::to_string(kFps) + "/1";
}

// A BGR frame as a buffer with GStreamer's strides (rows padded to 4 bytes) and frame `index`'s timestamps.
inline GstBuffer *bgrBuffer(const cv::Mat &bgr, int index) {
  GstVideoInfo info;
  gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, bgr.cols, bgr.rows);
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, info.size, nullptr);
  GstVideoFrame frame;
  fail_unless(gst_video_frame_map(&frame, &info, buffer, GST_MAP_WRITE));
  bgr.copyTo(cv::Mat(bgr.size(), CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                     GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0)));
  gst_video_frame_unmap(&frame);
  GST_BUFFER_PTS(buffer) = gst_util_uint64_scale_int(index, GST_SECOND, kFps);
  GST_BUFFER_DURATION(buffer) = gst_util_uint64_scale_int(1, GST_SECOND, kFps);
  return buffer;
}

// The ROI metas colortrack put on a buffer (other elements' ROI metas are skipped), in buffer order.
inline std::vector<GstVideoRegionOfInterestMeta *> colortrackRois(GstBuffer *buffer) {
  std::vector<GstVideoRegionOfInterestMeta *> rois;
  gpointer iter = nullptr;
  while (GstMeta *meta =
             gst_buffer_iterate_meta_filtered(buffer, &iter, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (roi->roi_type == g_quark_from_static_string("colortrack")) rois.push_back(roi);
  }
  return rois;
}

// The next element message named `name` on `bus` (owned by the caller), or nullptr; others are dropped.
inline GstMessage *popElementMessage(GstBus *bus, const char *name) {
  while (GstMessage *msg = gst_bus_pop_filtered(bus, GST_MESSAGE_ELEMENT)) {
    if (gst_message_has_name(msg, name)) return msg;
    gst_message_unref(msg);
  }
  return nullptr;
}

// A harness around a launch line whose element of interest is named "ct", fed with `caps`. The bin gets its
// own bus so that element messages, warnings and errors can be read.
class BusHarness {
 public:
  BusHarness(const std::string &launch, const std::string &caps) {
    h_ = gst_harness_new_parse(launch.c_str());
    bus_ = gst_bus_new();
    gst_element_set_bus(h_->element, bus_);
    gst_harness_set_src_caps_str(h_, caps.c_str());
    element_ = gst_bin_get_by_name(GST_BIN(h_->element), "ct");
    fail_unless(element_ != nullptr);
  }
  ~BusHarness() {
    gst_object_unref(element_);
    gst_element_set_bus(h_->element, nullptr);
    gst_object_unref(bus_);
    gst_harness_teardown(h_);
  }
  BusHarness(const BusHarness &) = delete;
  BusHarness &operator=(const BusHarness &) = delete;

  // Pushes `in` (taking it) and returns the output buffer (owned by the caller).
  GstBuffer *process(GstBuffer *in) {
    fail_unless_equals_int(gst_harness_push(h_, in), GST_FLOW_OK);
    GstBuffer *out = gst_harness_pull(h_);
    fail_unless(out != nullptr);
    return out;
  }
  // The next "colortrack" element message (owned by the caller), or nullptr.
  GstMessage *popTrackMessage() { return popElementMessage(bus_, "colortrack"); }

  GstHarness *harness() const { return h_; }
  GstElement *element() const { return element_; }
  GstBus *bus() const { return bus_; }

 private:
  GstHarness *h_ = nullptr;
  GstBus *bus_ = nullptr;
  GstElement *element_ = nullptr;
};

// How a pipeline run ended, and the warnings on the way ("message | debug" texts).
struct BusOutcome {
  bool eos = false;
  bool error = false;
  GQuark errorDomain = 0;
  int errorCode = 0;
  std::string errorText;
  std::vector<std::string> warnings;
  bool warned(const std::string &part) const {
    for (const std::string &w : warnings)
      if (contains(w, part)) return true;
    return false;
  }
};

// Reads `bus` until EOS or an error, collecting warnings; fails when neither comes within kBusTimeout.
inline BusOutcome waitForEnd(GstBus *bus) {
  BusOutcome outcome;
  const auto types = static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR | GST_MESSAGE_WARNING);
  while (GstMessage *msg = gst_bus_timed_pop_filtered(bus, kBusTimeout, types)) {
    GError *err = nullptr;
    gchar *debug = nullptr;
    const GstMessageType type = GST_MESSAGE_TYPE(msg);
    if (type == GST_MESSAGE_WARNING) {
      gst_message_parse_warning(msg, &err, &debug);
      outcome.warnings.push_back(std::string(err->message) + " | " + (debug ? debug : ""));
    } else if (type == GST_MESSAGE_ERROR) {
      gst_message_parse_error(msg, &err, &debug);
      outcome.error = true;
      outcome.errorDomain = err->domain;
      outcome.errorCode = err->code;
      outcome.errorText = std::string(err->message) + " | " + (debug ? debug : "");
      GST_INFO("error: %s", outcome.errorText.c_str());
    } else {
      outcome.eos = true;
    }
    if (err) g_error_free(err);
    g_free(debug);
    gst_message_unref(msg);
    if (type != GST_MESSAGE_WARNING) return outcome;
  }
  fail("neither EOS nor an error within %d s: the pipeline hangs",
       static_cast<int>(kBusTimeout / GST_SECOND));
  return outcome;
}

// Waits until robotctl has sent a command decided on the buffer with timestamp `pts` (its message names the
// frame's timestamp); fails on an error or after 5 s without one.
inline void waitForCommandOf(GstBus *bus, GstClockTime pts) {
  while (true) {
    GstMessage *m = gst_bus_timed_pop_filtered(
        bus, 5 * GST_SECOND, static_cast<GstMessageType>(GST_MESSAGE_ELEMENT | GST_MESSAGE_ERROR));
    fail_unless(m != nullptr, "no command for frame %" GST_TIME_FORMAT, GST_TIME_ARGS(pts));
    if (GST_MESSAGE_TYPE(m) == GST_MESSAGE_ERROR) {
      GError *error = nullptr;
      gst_message_parse_error(m, &error, nullptr);
      fail("error on the bus: %s", error->message);
    }
    const GstStructure *s = gst_message_get_structure(m);
    guint64 timestamp = GST_CLOCK_TIME_NONE;
    const bool ours = gst_structure_has_name(s, "robotctl") &&
                      gst_structure_get_uint64(s, "timestamp", &timestamp) &&
                      GST_CLOCK_TIME_IS_VALID(timestamp) && timestamp >= pts;
    gst_message_unref(m);
    if (ours) return;
  }
}

// Loads `plugins` once in the parent process: every test runs in a forked child, which would otherwise load
// them (and the many libraries behind them) again.
inline void preloadPlugins(std::initializer_list<const char *> plugins) {
  for (const char *plugin : plugins) {
    GstPlugin *loaded = gst_plugin_load_by_name(plugin);
    if (loaded) gst_object_unref(loaded);
  }
}

}  // namespace colortrack::gst_test_util
