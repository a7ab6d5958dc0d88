// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack in every caps format and at odd sizes: the frame is read through the real strides (tracking
// works), the overlay has the right colour in that format, and nothing else in the frame changes.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "gst_test_util.hpp"
#include "scene.hpp"

#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace {

using colortrack::scene::iou;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;
using colortrack::scene::SceneFrame;

using namespace colortrack::gst_test_util;

struct FormatCase {
  const char *format;
  int width, height;
};

// Every format of the caps, then odd sizes (chroma planes of ceil(size / 2), rows padded to 4 bytes).
const FormatCase kCases[] = {
    {"BGR", 320, 240},  {"RGB", 320, 240},  {"BGRx", 320, 240}, {"RGBx", 320, 240}, {"xBGR", 320, 240},
    {"xRGB", 320, 240}, {"BGRA", 320, 240}, {"RGBA", 320, 240}, {"ARGB", 320, 240}, {"ABGR", 320, 240},
    {"I420", 320, 240}, {"NV12", 320, 240}, {"YUY2", 320, 240}, {"I420", 321, 241}, {"NV12", 321, 241},
    {"YUY2", 321, 241}, {"BGRx", 321, 241}, {"RGB", 321, 241},
};

cv::Mat bgrFromBuffer(GstBuffer *buffer, cv::Size size) {
  GstVideoInfo info;
  gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, size.width, size.height);
  GstVideoFrame frame;
  fail_unless(gst_video_frame_map(&frame, &info, buffer, GST_MAP_READ));
  cv::Mat out =
      cv::Mat(size, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0), GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0))
          .clone();
  gst_video_frame_unmap(&frame);
  return out;
}

struct TrackMeta {
  bool present = false;
  cv::Rect box;
  std::string state;
  gboolean verified = FALSE;
};

TrackMeta readMeta(GstBuffer *buffer) {
  TrackMeta m;
  auto *roi = gst_buffer_get_video_region_of_interest_meta(buffer);
  if (!roi || roi->roi_type != g_quark_from_static_string("colortrack")) return m;
  m.present = true;
  m.box = cv::Rect(roi->x, roi->y, roi->w, roi->h);
  const GstStructure *p = gst_video_region_of_interest_meta_get_param(roi, "colortrack");
  fail_unless(p != nullptr);
  m.state = gst_structure_get_string(p, "state");
  gst_structure_get_boolean(p, "verified", &m.verified);
  return m;
}

// A harness over a launch line, fed with `caps`; one buffer in, one out.
class Harness {
 public:
  Harness(const std::string &launch, const std::string &caps) {
    h_ = gst_harness_new_parse(launch.c_str());
    gst_harness_set_src_caps_str(h_, caps.c_str());
  }
  ~Harness() { gst_harness_teardown(h_); }
  // The element named `name` in the launch line (a new reference).
  GstElement *element(const char *name) { return gst_bin_get_by_name(GST_BIN(h_->element), name); }
  Harness(const Harness &) = delete;
  Harness &operator=(const Harness &) = delete;

  GstBuffer *process(GstBuffer *in) {
    fail_unless_equals_int(gst_harness_push(h_, in), GST_FLOW_OK);
    GstBuffer *out = gst_harness_pull(h_);
    fail_unless(out != nullptr);
    return out;
  }

 private:
  GstHarness *h_;
};

// The pixel near the box's left edge (middle row) closest to `expected`, and its distance. The outline is
// 2 px (4 px on chroma-subsampled formats, grown to even coordinates) wide from the box's edge.
double closestOnLeftEdge(const cv::Mat &bgr, const cv::Rect &box, const cv::Vec3b &expected) {
  const int y = box.y + box.height / 2;
  double best = 1e9;
  for (int x = std::max(0, box.x - 1); x <= std::min(bgr.cols - 1, box.x + 3); ++x) {
    const cv::Vec3b p = bgr.at<cv::Vec3b>(y, x);
    best = std::min(best,
                    cv::norm(cv::Vec3d(p[0], p[1], p[2]) - cv::Vec3d(expected[0], expected[1], expected[2])));
  }
  return best;
}

}  // namespace

GST_START_TEST(test_format) {
  const FormatCase &c = kCases[__i__];
  SceneConfig config;
  config.frameSize = cv::Size(c.width, c.height);
  config.objectSize = cv::Size(48, 48);
  config.frames = 60;
  config.seed = 3;
  const Scene scene(config);
  const cv::Size size = config.frameSize;
  GST_INFO("format %s %dx%d", c.format, c.width, c.height);

  // BGR -> format under test, colortrack in that format, and back to BGR to look at the result.
  Harness toNative("videoconvert ! capsfilter caps=" + videoCaps(c.format, size), videoCaps("BGR", size));
  Harness tracker("colortrack name=ct draw=box init-box=" + boxString(scene.initBox()),
                  videoCaps(c.format, size));
  Harness toBgrOut("videoconvert ! capsfilter caps=" + videoCaps("BGR", size), videoCaps(c.format, size));
  Harness toBgrRef("videoconvert ! capsfilter caps=" + videoCaps("BGR", size), videoCaps(c.format, size));

  const cv::Vec3b red(0, 0, 255), green(0, 255, 0);  // BGR
  std::vector<double> ious;
  int greenChecks = 0, redChecks = 0;
  for (int i = 0; i < 40; ++i) {
    if (i == 20) {
      // From here on no match passes the edge check (a tolerance of 0 asks for identical edges): the same
      // object, now reported colour-only, must be outlined in red. Also a property change while playing.
      GstElement *ct = tracker.element("ct");
      g_object_set(ct, "verify-tolerance", 0.0, nullptr);
      gst_object_unref(ct);
    }
    const SceneFrame f = scene.render(i);
    GstBuffer *native = toNative.process(bgrBuffer(f.bgr, i));
    GstBuffer *reference = gst_buffer_copy_deep(native);
    GstBuffer *out = tracker.process(native);
    const TrackMeta m = readMeta(out);
    ious.push_back(m.present ? iou(m.box, f.box) : 0.0);

    if (i % 8 == 7 && m.present) {
      const cv::Mat outBgr = bgrFromBuffer(out = toBgrOut.process(out), size);
      const cv::Mat refBgr = bgrFromBuffer(reference = toBgrRef.process(reference), size);

      // In place and nothing else: outside a band around the outline the frame is bit-identical to the
      // same input converted without colortrack.
      cv::Mat changed;
      cv::absdiff(outBgr, refBgr, changed);
      cv::cvtColor(changed, changed, cv::COLOR_BGR2GRAY);
      cv::Mat allowed = cv::Mat::zeros(size, CV_8UC1);
      const int margin = 6;  // outline width, rounding to even, chroma interpolation
      cv::rectangle(
          allowed,
          cv::Rect(m.box.x - margin, m.box.y - margin, m.box.width + 2 * margin, m.box.height + 2 * margin),
          cv::Scalar(255), cv::FILLED);
      cv::rectangle(
          allowed,
          cv::Rect(m.box.x + margin, m.box.y + margin, m.box.width - 2 * margin, m.box.height - 2 * margin),
          cv::Scalar(0), cv::FILLED);
      changed.setTo(0, allowed);
      const int stray = cv::countNonZero(changed);
      fail_unless(stray == 0, "%s %dx%d frame %d: %d pixels changed away from the overlay", c.format, c.width,
                  c.height, i, stray);

      // The outline colour: green for a verified match, red for a colour-only one (the two are 360 apart, so
      // a pixel within 40 of one is not the other, nor the object's own reds and oranges).
      if (m.state == "tracking") {
        const cv::Vec3b &expected = m.verified ? green : red;
        const double distance = closestOnLeftEdge(outBgr, m.box, expected);
        GST_INFO("frame %d: outline %s at distance %.1f", i, m.verified ? "green" : "red", distance);
        fail_unless(distance < 40, "%s %dx%d frame %d: no %s outline pixel (closest at distance %.1f)",
                    c.format, c.width, c.height, i, m.verified ? "green" : "red", distance);
        ++(m.verified ? greenChecks : redChecks);
      }
    }
    gst_buffer_unref(out);
    gst_buffer_unref(reference);
  }
  double meanIou = 0;
  for (double v : ious) meanIou += v / ious.size();
  GST_INFO("%s %dx%d: mean IoU %.3f, %d green and %d red outline checks", c.format, c.width, c.height,
           meanIou, greenChecks, redChecks);
  fail_unless(meanIou >= 0.5, "%s %dx%d: mean IoU %.3f", c.format, c.width, c.height, meanIou);
  fail_unless(greenChecks >= 1 && redChecks >= 1, "%s: %d green and %d red outline checks", c.format,
              greenChecks, redChecks);
}
GST_END_TEST;

// Everything drawn at once (trail, search window and label too, near the frame edges at odd sizes): no
// crash, no stray writes outside the frame (the harness's buffers are checked by the allocator), meta intact.
GST_START_TEST(test_format_full_overlay) {
  const FormatCase &c = kCases[__i__];
  SceneConfig config;
  config.frameSize = cv::Size(c.width, c.height);
  config.objectSize = cv::Size(48, 48);
  config.frames = 40;
  config.speed = 3;  // sweeps the whole frame: the overlay reaches the edges
  const Scene scene(config);
  const cv::Size size = config.frameSize;
  Harness toNative("videoconvert ! capsfilter caps=" + videoCaps(c.format, size), videoCaps("BGR", size));
  Harness tracker("colortrack draw=box+trail+search-window+label init-box=" + boxString(scene.initBox()),
                  videoCaps(c.format, size));
  int withMeta = 0;
  for (int i = 0; i < 40; ++i) {
    GstBuffer *out = tracker.process(toNative.process(bgrBuffer(scene.render(i).bgr, i)));
    withMeta += readMeta(out).present ? 1 : 0;
    gst_buffer_unref(out);
  }
  fail_unless(withMeta >= 36, "%s: meta on %d of 40 frames", c.format, withMeta);
}
GST_END_TEST;

// The same decoded frames handed to colortrack in each format give the same track. The frames are I420 as
// jpegdec gives them (full range, chroma centred: colorimetry 1:4:0:0, chroma-site jpeg) or as most video
// is (limited range); videoconvert turns them into each other format, as a user's pipeline would.
GST_START_TEST(test_formats_agree) {
  const bool jpegLike = __i__ == 0;
  SceneConfig config;
  config.frameSize = cv::Size(320, 240);
  config.objectSize = cv::Size(48, 48);
  config.frames = 80;
  config.brightness = 0.3;
  config.rotationDegrees = 30;
  config.seed = 5;
  const Scene scene(config);
  const cv::Size size = config.frameSize;
  const std::string decoded =
      videoCaps("I420", size) + (jpegLike ? ",colorimetry=1:4:0:0,chroma-site=jpeg" : ",colorimetry=bt601");
  Harness toDecoded("videoconvert ! capsfilter caps=" + decoded, videoCaps("BGR", size));
  const char *formats[] = {"I420", "BGRx", "RGB", "NV12", "YUY2"};
  std::vector<std::vector<cv::Rect2d>> boxes(G_N_ELEMENTS(formats));
  for (size_t k = 0; k < G_N_ELEMENTS(formats); ++k) {
    const std::string convert =
        k == 0 ? std::string("identity") : "videoconvert ! capsfilter caps=" + videoCaps(formats[k], size);
    Harness pipeline(convert + " ! colortrack init-box=" + boxString(scene.initBox()), decoded);
    for (int i = 0; i < config.frames; ++i) {
      GstBuffer *out = pipeline.process(toDecoded.process(bgrBuffer(scene.render(i).bgr, i)));
      const TrackMeta m = readMeta(out);
      boxes[k].push_back(m.present ? cv::Rect2d(m.box) : cv::Rect2d());
      gst_buffer_unref(out);
    }
  }
  for (size_t k = 1; k < G_N_ELEMENTS(formats); ++k) {
    double agreement = 0;
    for (int i = 0; i < config.frames; ++i) agreement += iou(boxes[0][i], boxes[k][i]) / config.frames;
    GST_INFO("%s frames: I420 and %s agree at mean IoU %.3f", jpegLike ? "jpeg" : "bt601", formats[k],
             agreement);
    fail_unless(agreement >= 0.95, "%s frames: I420 and %s agree at mean IoU %.3f only",
                jpegLike ? "jpeg" : "bt601", formats[k], agreement);
  }
}
GST_END_TEST;

static Suite *colortrack_formats_suite(void) {
  preloadPlugins({"colortrack", "videoconvertscale"});
  Suite *s = suite_create("colortrack_formats");
  TCase *tc = tcase_create("formats");
  suite_add_tcase(s, tc);
  const int cases = static_cast<int>(G_N_ELEMENTS(kCases));
  tcase_add_loop_test(tc, test_format, 0, cases);
  tcase_add_loop_test(tc, test_format_full_overlay, 0, cases);
  tcase_add_loop_test(tc, test_formats_agree, 0, 2);
  return s;
}

GST_CHECK_MAIN(colortrack_formats);
