// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack mode=threshold as an element: a red ball on clutter (one ROI meta with area, the message's
// objects list), three balls crossing in I420 (ids held, one meta each), init-box learning a range that holds
// under +-30% brightness, the mask overlay, and bad settings (clear errors; warnings and old values while
// playing).
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <algorithm>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "balls.hpp"
#include "gst_test_util.hpp"

#include <gst/app/gstappsink.h>
#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace {

using colortrack::balls::Ball;
using colortrack::balls::BallScene;
using colortrack::balls::BallSceneConfig;
using colortrack::balls::BallTruth;
using namespace colortrack::gst_test_util;

// A BGR frame as a buffer of `format` (BGR or I420) with GStreamer's strides and frame `index`'s timestamps.
GstBuffer *frameBuffer(const cv::Mat &bgr, int index, GstVideoFormat format = GST_VIDEO_FORMAT_BGR) {
  GstVideoInfo info;
  gst_video_info_set_format(&info, format, bgr.cols, bgr.rows);
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, info.size, nullptr);
  GstVideoFrame frame;
  fail_unless(gst_video_frame_map(&frame, &info, buffer, GST_MAP_WRITE));
  const auto plane = [&frame](int p, cv::Size size) {
    return cv::Mat(size, CV_8UC(p == 0 && GST_VIDEO_FRAME_FORMAT(&frame) == GST_VIDEO_FORMAT_BGR ? 3 : 1),
                   GST_VIDEO_FRAME_PLANE_DATA(&frame, p), GST_VIDEO_FRAME_PLANE_STRIDE(&frame, p));
  };
  if (format == GST_VIDEO_FORMAT_BGR) {
    bgr.copyTo(plane(0, bgr.size()));
  } else {
    cv::Mat i420;
    cv::cvtColor(bgr, i420, cv::COLOR_BGR2YUV_I420);
    const cv::Size half(bgr.cols / 2, bgr.rows / 2);
    i420.rowRange(0, bgr.rows).copyTo(plane(0, bgr.size()));
    cv::Mat(half, CV_8UC1, i420.ptr(bgr.rows)).copyTo(plane(1, half));
    cv::Mat(half, CV_8UC1, i420.ptr(bgr.rows) + half.area()).copyTo(plane(2, half));
  }
  gst_video_frame_unmap(&frame);
  GST_BUFFER_PTS(buffer) = gst_util_uint64_scale_int(index, GST_SECOND, kFps);
  GST_BUFFER_DURATION(buffer) = gst_util_uint64_scale_int(1, GST_SECOND, kFps);
  return buffer;
}

struct ObjectMeta {
  int id = 0;
  cv::Rect box;
  double area = 0;
  std::string state;
  cv::Point2d centre() const { return {box.x + box.width / 2.0, box.y + box.height / 2.0}; }
};

std::vector<ObjectMeta> readMetas(GstBuffer *buffer) {
  std::vector<ObjectMeta> metas;
  for (GstVideoRegionOfInterestMeta *roi : colortrackRois(buffer)) {
    ObjectMeta m;
    m.id = roi->id;
    m.box = cv::Rect(roi->x, roi->y, roi->w, roi->h);
    const GstStructure *p = gst_video_region_of_interest_meta_get_param(roi, "colortrack");
    fail_unless(p != nullptr);
    fail_unless(gst_structure_get_double(p, "area", &m.area), "no area in the meta params");
    fail_unless(gst_structure_has_field_typed(p, "score", G_TYPE_DOUBLE) &&
                gst_structure_has_field_typed(p, "verified", G_TYPE_BOOLEAN) &&
                gst_structure_has_field_typed(p, "vx", G_TYPE_DOUBLE));
    m.state = gst_structure_get_string(p, "state");
    metas.push_back(m);
  }
  return metas;
}

// A harness around "colortrack name=ct <properties>" with a bus for its messages.
class Harness : public BusHarness {
 public:
  Harness(const std::string &properties, cv::Size size, const char *format = "BGR")
      : BusHarness("colortrack name=ct " + properties, videoCaps(format, size)) {}

  std::vector<ObjectMeta> processMetas(GstBuffer *in) {
    GstBuffer *out = process(in);
    std::vector<ObjectMeta> metas = readMetas(out);
    gst_buffer_unref(out);
    return metas;
  }
};

// The meta nearest to `point` within `radius`, or nullptr.
const ObjectMeta *nearest(const std::vector<ObjectMeta> &metas, cv::Point2d point, double radius) {
  const ObjectMeta *best = nullptr;
  for (const ObjectMeta &m : metas)
    if (cv::norm(m.centre() - point) < radius &&
        (!best || cv::norm(m.centre() - point) < cv::norm(best->centre() - point)))
      best = &m;
  return best;
}

BallScene redBallScene(double brightness = 0) {
  BallSceneConfig config;
  config.brightness = brightness;
  config.brightnessPeriod = 40;
  Ball ball;
  ball.hue = 358;
  ball.radius = 24;
  ball.path = {{0, {100, 90}}, {60, {520, 380}}};
  return BallScene(config, {ball});
}

}  // namespace

// The paper's case through the element: centroid within 2 px on average, one meta with area, and the
// message's objects list agreeing with the single-target fields.
GST_START_TEST(test_red_ball_meta_and_message) {
  const BallScene scene = redBallScene();
  Harness h("mode=threshold hsv-lower=345,0.5,0.25 hsv-upper=15,1,1 post-messages=true draw=0", {640, 480});
  double errorSum = 0;
  int frames = 0;
  for (int i = 0; i <= 60; ++i) {
    std::vector<BallTruth> truth;
    const cv::Mat bgr = scene.render(i, &truth);
    const std::vector<ObjectMeta> metas = h.processMetas(frameBuffer(bgr, i));
    GstMessage *msg = h.popTrackMessage();
    fail_unless(msg != nullptr);
    const GstStructure *s = gst_message_get_structure(msg);
    const GValue *objects = gst_structure_get_value(s, "objects");
    fail_unless(objects != nullptr && GST_VALUE_HOLDS_LIST(objects), "no objects list");
    if (i < 2) {  // tentative: nothing reported yet
      fail_unless_equals_int(metas.size(), 0);
      fail_unless_equals_int(gst_value_list_get_size(objects), 0);
      fail_unless_equals_string(gst_structure_get_string(s, "state"), "searching");
      gst_message_unref(msg);
      continue;
    }
    fail_unless_equals_int(metas.size(), 1);
    fail_unless_equals_int(metas[0].id, 1);
    fail_unless_equals_string(metas[0].state.c_str(), "tracking");
    const double disc = CV_PI * 24 * 24;
    fail_unless(std::abs(metas[0].area - disc) < 0.12 * disc, "area %f", metas[0].area);
    fail_unless_equals_int(gst_value_list_get_size(objects), 1);
    const GstStructure *o = gst_value_get_structure(gst_value_list_get_value(objects, 0));
    int id = 0;
    double cx = 0, cy = 0, area = 0, x = 0, width = 0, px = 0, score = 0;
    fail_unless(gst_structure_get_int(o, "id", &id) && gst_structure_get_double(o, "cx", &cx) &&
                gst_structure_get_double(o, "cy", &cy) && gst_structure_get_double(o, "area", &area) &&
                gst_structure_get_double(o, "x", &x) && gst_structure_get_double(o, "width", &width) &&
                gst_structure_get_double(o, "score", &score) && gst_structure_has_field(o, "y") &&
                gst_structure_has_field(o, "height") && gst_structure_get_string(o, "state"));
    fail_unless_equals_int(id, 1);
    fail_unless(gst_structure_get_double(s, "x", &px));
    fail_unless(std::abs(px - x) < 1e-9, "primary x %f vs object x %f", px, x);
    fail_unless(std::abs(area - metas[0].area) < 1e-9);
    fail_unless(score > 0.6 && score <= 1.0, "fill %f", score);  // a disc fills ~pi/4 of its box
    errorSum += std::hypot(cx - truth[0].centre.x, cy - truth[0].centre.y);
    ++frames;
    gst_message_unref(msg);
  }
  GST_INFO("red ball: mean centroid error %.3f px over %d frames", errorSum / frames, frames);
  fail_unless(errorSum / frames <= 2.0, "mean centroid error %f", errorSum / frames);
}
GST_END_TEST;

// Three balls of different colours crossing, as I420 (read through the YUV table): every ball keeps its id.
GST_START_TEST(test_three_balls_crossing_i420) {
  const BallScene scene = colortrack::balls::threeCrossingBalls();
  Harness h("mode=threshold hsv-lower=0,0.5,0.25 hsv-upper=360,1,1 draw=box+label+trail", {640, 480}, "I420");
  std::map<int, int> idOfBall;
  int checked = 0;
  for (int i = 0; i <= 90; ++i) {
    std::vector<BallTruth> truth;
    const cv::Mat bgr = scene.render(i, &truth);
    const std::vector<ObjectMeta> metas = h.processMetas(frameBuffer(bgr, i, GST_VIDEO_FORMAT_I420));
    if (i < 3) continue;
    fail_unless_equals_int(metas.size(), 3);
    for (int b = 0; b < 3; ++b) {
      bool apart = true;
      for (int o = 0; o < 3; ++o)
        if (o != b && cv::norm(truth[b].centre - truth[o].centre) < 2 * truth[b].radius + 4) apart = false;
      if (!apart) continue;
      const ObjectMeta *m = nearest(metas, truth[b].centre, truth[b].radius);
      fail_unless(m != nullptr, "ball %d lost at frame %d", b, i);
      if (!idOfBall.count(b)) idOfBall[b] = m->id;
      fail_unless_equals_int(m->id, idOfBall[b]);
      ++checked;
    }
  }
  fail_unless(checked > 200, "%d", checked);
  fail_unless(idOfBall[0] != idOfBall[1] && idOfBall[1] != idOfBall[2] && idOfBall[0] != idOfBall[2]);
}
GST_END_TEST;

// Balls crossing, leaving and coming in at the frame's edges (issue 12): on every frame the bus message lists
// exactly the tracks that have a ROI meta, with the same ids and boxes, and every box lies inside the frame.
GST_START_TEST(test_meta_and_message_agree_through_exits) {
  BallSceneConfig config;
  config.clutterHueClearance = 0;
  config.clutterSaturation = 0.35;
  std::vector<Ball> balls(4);
  balls[0].path = {{0, {40, 240}}, {60, {700, 240}}, {120, {300, 240}}};  // leaves right, comes back
  balls[1].hue = 20;
  balls[1].radius = 14;
  balls[1].path = {{0, {600, 230}}, {120, {-40, 250}}};  // passes over ball 0, leaves left
  balls[2].path = {{0, {320, -30}}, {120, {320, 520}}};  // enters at the top, leaves at the bottom
  balls[3].radius = 30;
  balls[3].path = {{0, {100, 400}}, {120, {560, 80}}};
  const BallScene scene(config, balls);
  const cv::Size size = config.frameSize;
  Harness h("mode=threshold hsv-lower=345,0.5,0.25 hsv-upper=30,1,1 post-messages=true draw=0", size);
  int compared = 0;
  for (int i = 0; i < 120; ++i) {
    GstBuffer *out = h.process(frameBuffer(scene.render(i), i));
    const std::vector<ObjectMeta> metas = readMetas(out);
    gst_buffer_unref(out);
    GstMessage *msg = h.popTrackMessage();
    fail_unless(msg != nullptr, "no message for frame %d", i);
    const GValue *objects = gst_structure_get_value(gst_message_get_structure(msg), "objects");
    fail_unless(objects != nullptr && GST_VALUE_HOLDS_LIST(objects));
    const guint listed = gst_value_list_get_size(objects);
    fail_unless_equals_int(listed, metas.size());
    for (guint k = 0; k < listed; ++k) {
      const GstStructure *o = gst_value_get_structure(gst_value_list_get_value(objects, k));
      int id = 0;
      double x = 0, y = 0, w = 0, h2 = 0;
      fail_unless(gst_structure_get_int(o, "id", &id) && gst_structure_get_double(o, "x", &x) &&
                  gst_structure_get_double(o, "y", &y) && gst_structure_get_double(o, "width", &w) &&
                  gst_structure_get_double(o, "height", &h2));
      const auto meta =
          std::find_if(metas.begin(), metas.end(), [&](const ObjectMeta &m) { return m.id == id; });
      fail_unless(meta != metas.end(), "frame %d: track %d in the message has no meta", i, id);
      // The meta's box is the message's rounded to whole pixels.
      fail_unless(std::abs(meta->box.x - x) <= 1 && std::abs(meta->box.y - y) <= 1 &&
                      std::abs(meta->box.width - w) <= 1.5 && std::abs(meta->box.height - h2) <= 1.5,
                  "frame %d: track %d meta %d,%d %dx%d, message %.1f,%.1f %.1fx%.1f", i, id, meta->box.x,
                  meta->box.y, meta->box.width, meta->box.height, x, y, w, h2);
      fail_unless(x >= 0 && y >= 0 && x + w <= size.width + 1e-6 && y + h2 <= size.height + 1e-6,
                  "frame %d: track %d outside the frame", i, id);
      ++compared;
    }
    gst_message_unref(msg);
  }
  fail_unless(compared > 200, "only %d tracks compared", compared);
}
GST_END_TEST;

// init-box on the ball: the element learns a range (readable back from the properties, hue wrapping
// through 0) that follows the ball while the scene gets 30% darker and brighter.
GST_START_TEST(test_init_box_learns_range) {
  const BallScene scene = redBallScene(0.3);
  Harness h("mode=threshold draw=0 init-box=" + boxString(scene.boxOf(0, 0)), {640, 480});
  double errorSum = 0;
  int frames = 0;
  for (int i = 0; i <= 60; ++i) {
    std::vector<BallTruth> truth;
    const std::vector<ObjectMeta> metas = h.processMetas(frameBuffer(scene.render(i, &truth), i));
    if (i < 3) continue;
    fail_unless_equals_int(metas.size(), 1);
    fail_unless_equals_int(metas[0].id, 1);
    errorSum += cv::norm(metas[0].centre() - truth[0].centre);
    ++frames;
  }
  gchar *lower = nullptr, *upper = nullptr;
  g_object_get(h.element(), "hsv-lower", &lower, "hsv-upper", &upper, nullptr);
  GST_INFO("learnt %s .. %s, mean box-centre error %.2f px", lower, upper, errorSum / frames);
  fail_unless(std::stod(lower) > std::stod(upper), "learnt hue %s .. %s should wrap through 0", lower, upper);
  g_free(lower);
  g_free(upper);
  fail_unless(errorSum / frames < 2.0, "mean error %f", errorSum / frames);
}
GST_END_TEST;

// draw=mask tints the selected pixels (the ball) magenta and leaves the rest alone.
GST_START_TEST(test_mask_overlay) {
  const BallScene scene = redBallScene();
  const cv::Mat bgr = scene.render(0);
  const cv::Point ball(100, 90), far(600, 20);
  Harness h("mode=threshold hsv-lower=345,0.5,0.25 hsv-upper=15,1,1 draw=mask", {640, 480});
  GstBuffer *out = h.process(frameBuffer(bgr, 0));
  GstVideoInfo info;
  gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, 640, 480);
  GstVideoFrame frame;
  fail_unless(gst_video_frame_map(&frame, &info, out, GST_MAP_READ));
  const cv::Mat drawn(480, 640, CV_8UC3, GST_VIDEO_FRAME_PLANE_DATA(&frame, 0),
                      GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0));
  const cv::Vec3b before = bgr.at<cv::Vec3b>(ball), after = drawn.at<cv::Vec3b>(ball);
  fail_unless(after[0] > before[0] + 80, "blue %d -> %d: not tinted", before[0],
              after[0]);  // magenta adds blue
  fail_unless(drawn.at<cv::Vec3b>(far) == bgr.at<cv::Vec3b>(far), "background changed");
  gst_video_frame_unmap(&frame);
  gst_buffer_unref(out);
}
GST_END_TEST;

namespace {

using Outcome = BusOutcome;

// appsrc ! colortrack name=ct <properties> ! appsink; plays `frames` frames then waits for EOS or an error.
class Pipeline {
 public:
  explicit Pipeline(const std::string &properties) {
    const std::string launch = "appsrc name=src format=time ! colortrack name=ct " + properties +
                               " ! appsink name=sink sync=false wait-on-eos=false drop=true max-buffers=2";
    GError *error = nullptr;
    pipeline_ = gst_parse_launch(launch.c_str(), &error);
    fail_unless(pipeline_ != nullptr && error == nullptr, "cannot parse %s", launch.c_str());
    src_ = gst_bin_get_by_name(GST_BIN(pipeline_), "src");
    element_ = gst_bin_get_by_name(GST_BIN(pipeline_), "ct");
    GstCaps *caps = gst_caps_from_string("video/x-raw,format=BGR,width=640,height=480,framerate=30/1");
    gst_app_src_set_caps(GST_APP_SRC(src_), caps);
    gst_caps_unref(caps);
    bus_ = gst_element_get_bus(pipeline_);
  }
  ~Pipeline() {
    gst_element_set_state(pipeline_, GST_STATE_NULL);
    gst_object_unref(bus_);
    gst_object_unref(element_);
    gst_object_unref(src_);
    gst_object_unref(pipeline_);
  }
  Pipeline(const Pipeline &) = delete;
  Pipeline &operator=(const Pipeline &) = delete;

  bool play() { return gst_element_set_state(pipeline_, GST_STATE_PLAYING) != GST_STATE_CHANGE_FAILURE; }
  void push(const cv::Mat &bgr, int index) {
    gst_app_src_push_buffer(GST_APP_SRC(src_), frameBuffer(bgr, index));
  }
  GstElement *element() const { return element_; }

  Outcome finish(bool endStream = true) {
    if (endStream) gst_app_src_end_of_stream(GST_APP_SRC(src_));
    return waitForEnd(bus_);
  }

 private:
  GstElement *pipeline_ = nullptr, *src_ = nullptr, *element_ = nullptr;
  GstBus *bus_ = nullptr;
};

Outcome run(const std::string &properties, int frames = 3) {
  const BallScene scene = redBallScene();
  Pipeline p(properties);
  if (!p.play()) return p.finish(false);
  for (int i = 0; i < frames; ++i) p.push(scene.render(i), i);
  return p.finish();
}

}  // namespace

GST_START_TEST(test_bad_settings_are_clear_errors) {
  struct Case {
    std::string properties, mustName, value;
  };
  const Case cases[] = {
      {"hsv-lower=\"red\"", "hsv-lower", "red"},
      {"hsv-lower=\"10,0.5\"", "hsv-lower", "10,0.5"},
      {"hsv-upper=\"400,1,1\"", "hsv-upper", "400"},
      {"hsv-upper=\"20,1.5,1\"", "saturation", "1.5"},
      {"hsv-lower=\"10,0.5,-1\"", "hsv-lower", "-1"},
      {"hsv-lower=\"10,0.9,0.2\" hsv-upper=\"30,0.5,1\"", "hsv-lower", "saturation"},
      {"min-area=400000", "min-area", "640x480"},
  };
  for (const Case &c : cases) {
    const Outcome o = run("mode=threshold " + c.properties);
    fail_unless(o.error, "no error for %s", c.properties.c_str());
    fail_unless(contains(o.errorText, c.mustName) && contains(o.errorText, c.value),
                "unclear error for %s: %s", c.properties.c_str(), o.errorText.c_str());
  }
  // A valid wrap-around range and a min-area of exactly the frame are fine.
  const Outcome ok = run("mode=threshold hsv-lower=350,0.5,0.2 hsv-upper=10,1,1 min-area=307200");
  fail_unless(!ok.error, "%s", ok.errorText.c_str());
}
GST_END_TEST;

GST_START_TEST(test_bad_values_while_playing_keep_old) {
  const BallScene scene = redBallScene();
  Pipeline p("mode=threshold hsv-lower=345,0.5,0.25 hsv-upper=15,1,1");
  fail_unless(p.play());
  for (int i = 0; i < 5; ++i) p.push(scene.render(i), i);
  // Wait until the caps are known (the element judges min-area against them).
  for (int tries = 0; tries < 200; ++tries) {
    GstPad *pad = gst_element_get_static_pad(p.element(), "sink");
    GstCaps *caps = gst_pad_get_current_caps(pad);
    gst_object_unref(pad);
    if (caps) {
      gst_caps_unref(caps);
      break;
    }
    g_usleep(10000);
  }
  g_object_set(p.element(), "hsv-lower", "1,2,3", "hsv-upper", "10,0.1,1", "min-area", 500000, nullptr);
  for (int i = 5; i < 10; ++i) p.push(scene.render(i), i);
  const Outcome o = p.finish();
  fail_unless(!o.error, "%s", o.errorText.c_str());
  fail_unless(o.warned("hsv-lower") && o.warned("1,2,3"), "no warning naming hsv-lower");
  fail_unless(o.warned("hsv-upper") && o.warned("10,0.1,1"), "no warning naming hsv-upper");
  fail_unless(o.warned("min-area") && o.warned("500000"), "no warning naming min-area");
  gchar *lower = nullptr, *upper = nullptr;
  int minArea = 0;
  g_object_get(p.element(), "hsv-lower", &lower, "hsv-upper", &upper, "min-area", &minArea, nullptr);
  fail_unless_equals_string(lower, "345,0.5,0.25");
  fail_unless_equals_string(upper, "15,1,1");
  fail_unless_equals_int(minArea, 50);
  g_free(lower);
  g_free(upper);
}
GST_END_TEST;

static Suite *colortrack_threshold_suite(void) {
  Suite *s = suite_create("colortrack_threshold");
  TCase *tc = tcase_create("threshold");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_red_ball_meta_and_message);
  tcase_add_test(tc, test_three_balls_crossing_i420);
  tcase_add_test(tc, test_meta_and_message_agree_through_exits);
  tcase_add_test(tc, test_init_box_learns_range);
  tcase_add_test(tc, test_mask_overlay);
  tcase_add_test(tc, test_bad_settings_are_clear_errors);
  tcase_add_test(tc, test_bad_values_while_playing_keep_old);
  return s;
}

GST_CHECK_MAIN(colortrack_threshold)
