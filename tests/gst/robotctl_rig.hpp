// SPDX-License-Identifier: LGPL-2.1-or-later
// robotctl in a harness writing to a pseudo-terminal, and the frames with ROI metas the robotctl tests push:
// shared by test_robotctl.cpp, test_robotctl_port.cpp and test_robotctl_settings.cpp. Include it after
// gstcheck.h (it uses fail_unless).
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "gst_test_util.hpp"

#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

#include "pty.hpp"

namespace robotctl_rig {

using Bytes = std::vector<std::uint8_t>;
using Clock = std::chrono::steady_clock;
using colortrack::gst_test_util::waitForCommandOf;
inline constexpr int kWidth = 320, kHeight = 240, kFps = 30;

using colortrack::gst_test_util::Pty;

struct Roi {
  const char *type = "colortrack";
  int id = 1;
  cv::Rect box;
  const char *state = "tracking";  // nullptr: no params structure (like other elements' boxes)
  double score = 0.9;
};

inline GstClockTime ptsOf(int frame) {
  return gst_util_uint64_scale_int(frame, GST_SECOND, kFps);
}

inline GstBuffer *frameWith(const std::vector<Roi> &rois, int frame) {
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, kWidth * kHeight, nullptr);
  gst_buffer_memset(buffer, 0, 0, kWidth * kHeight);
  for (const Roi &r : rois) {
    GstVideoRegionOfInterestMeta *meta = gst_buffer_add_video_region_of_interest_meta(
        buffer, r.type, r.box.x, r.box.y, r.box.width, r.box.height);
    meta->id = r.id;
    if (r.state)
      gst_video_region_of_interest_meta_add_param(
          meta, gst_structure_new("colortrack", "state", G_TYPE_STRING, r.state, "score", G_TYPE_DOUBLE,
                                  r.score, "verified", G_TYPE_BOOLEAN, TRUE, nullptr));
  }
  GST_BUFFER_PTS(buffer) = ptsOf(frame);
  GST_BUFFER_DURATION(buffer) = ptsOf(1);
  return buffer;
}

// Boxes in a 320x240 frame (set-point 0.3 = 72 px high; deadband 0.1 of the half width = 16 px).
inline const cv::Rect kRight(216, 100, 48, 48);        // offset +0.5, far
inline const cv::Rect kLeft(40, 100, 48, 48);          // offset -0.5
inline const cv::Rect kCentreFar(148, 100, 24, 24);    // size 0.1
inline const cv::Rect kCentreNear(100, 60, 120, 120);  // size 0.5
inline const cv::Rect kCentreRight(124, 84, 72, 72);   // at the set-point

inline Roi roi(const cv::Rect &box, int id = 1) {
  Roi r;
  r.box = box;
  r.id = id;
  return r;
}

// robotctl in a harness, writing to a pty, posting its messages on `bus`.
struct Ctl {
  Pty pty;
  GstHarness *h = nullptr;
  GstBus *bus = nullptr;
  int frame = 0;

  explicit Ctl(const std::string &properties, const std::string &location = "") {
    const std::string launch = "robotctl name=ctl sync=false post-messages=true location=" +
                               (location.empty() ? pty.slave : location) + " " + properties;
    h = gst_harness_new_parse(launch.c_str());
    bus = gst_bus_new();
    gst_element_set_bus(h->element, bus);
    gst_harness_set_src_caps_str(h, "video/x-raw,format=GRAY8,width=320,height=240,framerate=30/1");
  }
  ~Ctl() {
    gst_element_set_bus(h->element, nullptr);
    gst_harness_teardown(h);
    gst_object_unref(bus);
  }
  void push(const std::vector<Roi> &rois) {
    fail_unless_equals_int(gst_harness_push(h, frameWith(rois, frame)), GST_FLOW_OK);
    ++frame;
  }
  // Pushes one frame and returns the bytes on the pty once the command decided on it has been sent.
  Bytes decide(const std::vector<Roi> &rois) {
    push(rois);
    waitForCommandOf(bus, ptsOf(frame - 1));
    return pty.drain();
  }
};

inline std::string asText(const Bytes &b) {
  return std::string(b.begin(), b.end());
}
inline std::string lastLine(const Bytes &b) {
  const std::string t = asText(b);
  const std::size_t end = t.rfind('\n');
  fail_unless(end != std::string::npos);
  const std::size_t start = t.rfind('\n', end - 1);
  return t.substr(start == std::string::npos ? 0 : start + 1,
                  end - (start == std::string::npos ? 0 : start + 1) + 1);
}

// The macro keeps a pointer past the statement that made it: the text must outlive it (a temporary's
// c_str() would dangle, as ASan reports).
inline void expectLastLine(const Bytes &b, const char *expected) {
  const std::string line = lastLine(b);
  fail_unless_equals_string(line.c_str(), expected);
}

}  // namespace robotctl_rig
