// SPDX-License-Identifier: LGPL-2.1-or-later
// FrameView against videoconvert: a decoded frame in I420, NV12 or YUY2, read by colortrack, is byte for byte
// the image videoconvert makes of it in BGRx (what a user with an RGB pipeline hands colortrack), for the
// colorimetries decoders give: jpegdec's full range with centred chroma, and limited-range BT.601 and BT.709
// video.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "frame-view.h"
#include "gst_test_util.hpp"
#include "scene.hpp"

#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace {

using namespace colortrack::gst_test_util;

// `in` (not taken) through a videoconvert to `caps`.
GstBuffer *convert(GstBuffer *in, const std::string &inCaps, const std::string &caps) {
  GstHarness *h = gst_harness_new_parse(("videoconvert ! capsfilter caps=" + caps).c_str());
  gst_harness_set_src_caps_str(h, inCaps.c_str());
  fail_unless_equals_int(gst_harness_push(h, gst_buffer_ref(in)), GST_FLOW_OK);
  GstBuffer *out = gst_harness_pull(h);
  gst_harness_teardown(h);
  return out;
}

// What colortrack reads of `buffer` in `rect` at `step`, as BGR.
cv::Mat readByFrameView(GstBuffer *buffer, const std::string &caps, const cv::Rect &rect, int step) {
  GstCaps *parsed = gst_caps_from_string(caps.c_str());
  GstVideoInfo info;
  fail_unless(gst_video_info_from_caps(&info, parsed));
  gst_caps_unref(parsed);
  GstVideoFrame frame;
  fail_unless(gst_video_frame_map(&frame, &info, buffer, GST_MAP_READ));
  cv::Mat out;
  {
    const colortrack_gst::FrameView view(&frame);
    if (step == 1)
      view.bgr(rect, out);
    else
      view.sampledBgr(rect, step, out);
  }
  gst_video_frame_unmap(&frame);
  return out;
}

double meanAbsDifference(const cv::Mat &a, const cv::Mat &b) {
  const cv::Scalar d = cv::mean(cv::abs(a - b) + cv::abs(b - a));
  return (d[0] + d[1] + d[2]) / 3;
}

const char *kColorimetries[] = {",colorimetry=1:4:0:0,chroma-site=jpeg",
                                ",colorimetry=bt601,chroma-site=jpeg",
                                ",colorimetry=bt709,chroma-site=mpeg2"};

}  // namespace

GST_START_TEST(test_yuv_read_as_videoconvert_converts) {
  const char *colorimetry = kColorimetries[__i__];
  colortrack::scene::SceneConfig config;
  config.frameSize = cv::Size(322, 242);
  const cv::Size size = config.frameSize;
  const cv::Mat source = colortrack::scene::Scene(config).render(5).bgr;
  GstBuffer *bgr = bgrBuffer(source, 0);
  const std::string decodedCaps = videoCaps("I420", size) + colorimetry;
  GstBuffer *decoded = convert(bgr, videoCaps("BGR", size), decodedCaps);
  const std::string bgrxCaps = videoCaps("BGRx", size);
  GstBuffer *bgrx = convert(decoded, decodedCaps, bgrxCaps);
  const cv::Rect all(cv::Point(), size);
  const cv::Mat reference = readByFrameView(bgrx, bgrxCaps, all, 1);
  for (const char *format : {"I420", "NV12", "YUY2"}) {
    const std::string caps = videoCaps(format, size) + colorimetry;
    GstBuffer *native =
        std::string(format) == "I420" ? gst_buffer_ref(decoded) : convert(decoded, decodedCaps, caps);
    const cv::Mat read = readByFrameView(native, caps, all, 1);
    const double error = meanAbsDifference(read, reference);
    const double worst = cv::norm(read, reference, cv::NORM_INF);
    GST_INFO("%s%s: mean |difference| %.2f, largest %.0f", format, colorimetry, error, worst);
    // colortrack applies the matrix with videoconvert's own integer maths (core/images/src/yuv_image.cpp): the
    // same bytes, so a tracker fed YUV sees what it would see behind `videoconvert ! BGRx`. (With the
    // standard matrix it read 1-2 levels apart, 2-4 at limited range, and the answer moved with them.)
    fail_unless(worst == 0, "%s%s: read with mean |difference| %.2f (largest %.0f) from videoconvert's BGRx",
                format, colorimetry, error, worst);
    // A region and a sample of it read the same pixels.
    const cv::Rect region(41, 17, 151, 99);
    fail_unless(cv::norm(readByFrameView(native, caps, region, 1), read(region), cv::NORM_INF) == 0);
    const cv::Mat sampled = readByFrameView(native, caps, region, 2);
    cv::Mat everyOther;
    cv::resize(read(colortrack::sampledCover(region, 2)), everyOther, colortrack::sampledSize(region, 2), 0,
               0, cv::INTER_NEAREST);
    fail_unless(cv::norm(sampled, everyOther, cv::NORM_INF) <= 1, "%s: a sample is not the pixels it samples",
                format);
    gst_buffer_unref(native);
  }
  gst_buffer_unref(bgrx);
  gst_buffer_unref(decoded);
  gst_buffer_unref(bgr);
}
GST_END_TEST;

static Suite *frame_view_suite(void) {
  Suite *s = suite_create("frame_view");
  TCase *tc = tcase_create("frame_view");
  suite_add_tcase(s, tc);
  tcase_add_loop_test(tc, test_yuv_read_as_videoconvert_converts, 0, G_N_ELEMENTS(kColorimetries));
  return s;
}

GST_CHECK_MAIN(frame_view);
