// SPDX-License-Identifier: LGPL-2.1-or-later
// Click to track: mouse-button presses sent upstream as GstNavigation events, the way a video sink's window
// sends them, through "colortrack ! videoscale ! half-size caps". The clicks are given in the half-size
// coordinates a user would click in the window, so the tests only pass when videoscale maps them back to
// colortrack's frame. Template mode: a left click starts tracking the object, a second one on the decoy
// re-targets (new id), a right click stops (no meta, state "idle"), init-box set while playing starts again
// on the next frame. Threshold mode: a left click learns one ball's colour, a second the other ball's, a
// right click stops. Every event must come out upstream of colortrack unchanged in colortrack's coordinates.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "balls.hpp"
#include "gst_test_util.hpp"
#include "scene.hpp"

#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/navigation.h>
#include <gst/video/video.h>

namespace {

using colortrack::balls::Ball;
using colortrack::balls::BallScene;
using colortrack::balls::BallSceneConfig;
using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;
using namespace colortrack::gst_test_util;

const cv::Size kFrame(640, 480);
const cv::Size kWindow(320, 240);  // what the sink shows: videoscale halves the frame
constexpr int kLeft = 1, kRight = 3;

// One frame as seen downstream of videoscale (metas) and on the bus (colortrack's message).
struct FrameResult {
  std::vector<int> ids;           // ROI meta ids (videoscale keeps them)
  std::vector<cv::Rect2d> boxes;  // ROI meta boxes scaled back to colortrack's frame
  std::string state;              // from the message
  int messageId = -1;
  cv::Rect2d messageBox;
};

// "colortrack name=ct <properties> ! videoscale ! video/x-raw,width=320,height=240" in a harness, BGR 640x480
// in, with a bus for colortrack's messages.
class ClickHarness : public BusHarness {
 public:
  explicit ClickHarness(const std::string &properties)
      : BusHarness("colortrack name=ct post-messages=true draw=0 " + properties +
                       " ! videoscale ! capsfilter caps=video/x-raw,width=" + std::to_string(kWindow.width) +
                       ",height=" + std::to_string(kWindow.height),
                   videoCaps("BGR", kFrame)) {}

  FrameResult process(const cv::Mat &bgr) {
    GstBuffer *out = BusHarness::process(bgrBuffer(bgr, frame_++));
    FrameResult r;
    const double sx = static_cast<double>(kFrame.width) / kWindow.width;
    const double sy = static_cast<double>(kFrame.height) / kWindow.height;
    for (GstVideoRegionOfInterestMeta *roi : colortrackRois(out)) {
      r.ids.push_back(roi->id);
      r.boxes.emplace_back(roi->x * sx, roi->y * sy, roi->w * sx, roi->h * sy);
    }
    gst_buffer_unref(out);
    while (GstMessage *msg = popTrackMessage()) {
      const GstStructure *s = gst_message_get_structure(msg);
      r.state = gst_structure_get_string(s, "state");
      fail_unless(gst_structure_get_int(s, "id", &r.messageId));
      fail_unless(gst_structure_get_double(s, "x", &r.messageBox.x) &&
                  gst_structure_get_double(s, "y", &r.messageBox.y) &&
                  gst_structure_get_double(s, "width", &r.messageBox.width) &&
                  gst_structure_get_double(s, "height", &r.messageBox.height));
      gst_message_unref(msg);
    }
    return r;
  }

  // Presses `button` at `windowPoint` (the sink's 320x240 coordinates) and checks that the event left
  // colortrack upstream, mapped by videoscale to colortrack's 640x480 frame.
  void click(int button, cv::Point2d windowPoint) {
    GstEvent *event = gst_navigation_event_new_mouse_button_press(button, windowPoint.x, windowPoint.y,
                                                                  GST_NAVIGATION_MODIFIER_NONE);
    fail_unless(gst_harness_push_upstream_event(harness(), event),
                "the navigation event was not forwarded upstream");
    GstEvent *forwarded = nullptr;
    while (GstEvent *e = gst_harness_try_pull_upstream_event(harness())) {
      if (GST_EVENT_TYPE(e) == GST_EVENT_NAVIGATION && !forwarded)
        forwarded = e;
      else
        gst_event_unref(e);
    }
    fail_unless(forwarded != nullptr, "no navigation event came out upstream of colortrack");
    gint forwardedButton = 0;
    gdouble x = 0, y = 0;
    fail_unless(gst_navigation_event_parse_mouse_button_event(forwarded, &forwardedButton, &x, &y));
    fail_unless_equals_int(forwardedButton, button);
    const cv::Point2d expected(windowPoint.x * kFrame.width / kWindow.width,
                               windowPoint.y * kFrame.height / kWindow.height);
    fail_unless(std::abs(x - expected.x) <= 1.0 && std::abs(y - expected.y) <= 1.0,
                "videoscale mapped %.1f,%.1f to %.1f,%.1f, expected %.1f,%.1f", windowPoint.x, windowPoint.y,
                x, y, expected.x, expected.y);
    gst_event_unref(forwarded);
  }

 private:
  int frame_ = 0;
};

cv::Point2d centreOf(const cv::Rect2d &box) {
  return {box.x + box.width / 2, box.y + box.height / 2};
}

// Where the user clicks in the half-size window to hit `point` of the full frame.
cv::Point2d inWindow(const cv::Point2d &point) {
  return {point.x * kWindow.width / kFrame.width, point.y * kWindow.height / kFrame.height};
}

// The frames a track needs after a click before its box is judged (the box starts as the click square).
constexpr int kSettleFrames = 3;
constexpr double kMinIou = 0.5;

}  // namespace

// Template mode, no template at start: left click on the object, left click on the decoy, right click,
// then init-box while playing.
GST_START_TEST(test_template_click_retarget_stop) {
  SceneConfig config;
  config.decoy = true;
  const Scene scene(config);
  ClickHarness h("");
  int index = 0;

  // Nothing to track yet: buffers pass without meta.
  for (; index < 5; ++index) fail_unless(h.process(scene.render(index).bgr).ids.empty());

  // Left click on the object as it will be in the next frame.
  h.click(kLeft, inWindow(centreOf(scene.render(index).box)));
  int objectId = 0;
  double minIou = 1.0;
  for (int n = 0; n < 30; ++n, ++index) {
    const colortrack::scene::SceneFrame truth = scene.render(index);
    const FrameResult r = h.process(truth.bgr);
    fail_unless_equals_int(r.ids.size(), 1);
    if (n == 0) objectId = r.ids[0];
    fail_unless_equals_int(r.ids[0], objectId);  // one track, no re-acquisition
    fail_unless(r.state == "tracking" || r.state == "coasting", "state %s", r.state.c_str());
    if (n >= kSettleFrames) minIou = std::min(minIou, colortrack::scene::iou(r.boxes[0], truth.box));
  }
  GST_INFO("click on the object: id %d, min IoU %.3f", objectId, minIou);
  fail_unless(objectId >= 1);
  fail_unless(minIou >= kMinIou, "object: min IoU %f", minIou);

  // A second left click, on the decoy: a new track there.
  const cv::Rect2d decoy = scene.render(index).decoyBox;
  fail_unless(!decoy.empty());
  h.click(kLeft, inWindow(centreOf(decoy)));
  int decoyId = 0;
  minIou = 1.0;
  for (int n = 0; n < 20; ++n, ++index) {
    const FrameResult r = h.process(scene.render(index).bgr);
    fail_unless_equals_int(r.ids.size(), 1);
    if (n == 0) decoyId = r.ids[0];
    fail_unless_equals_int(r.ids[0], decoyId);
    if (n >= kSettleFrames) minIou = std::min(minIou, colortrack::scene::iou(r.boxes[0], decoy));
  }
  GST_INFO("click on the decoy: id %d, min IoU %.3f", decoyId, minIou);
  fail_unless(decoyId > objectId, "re-target kept id %d", decoyId);
  fail_unless(minIou >= kMinIou, "decoy: min IoU %f", minIou);

  // Right click: idle, and the reset action does not bring the track back.
  h.click(kRight, inWindow(centreOf(scene.render(index).box)));
  for (int n = 0; n < 10; ++n, ++index) {
    if (n == 5) g_signal_emit_by_name(h.element(), "reset");
    const FrameResult r = h.process(scene.render(index).bgr);
    fail_unless(r.ids.empty(), "a meta after the right click (frame %d)", n);
    fail_unless_equals_string(r.state.c_str(), "idle");
    fail_unless_equals_int(r.messageId, 0);
  }

  // init-box set while playing: tracking starts on the next frame, at that box, with a new id.
  const colortrack::scene::SceneFrame next = scene.render(index);
  g_object_set(h.element(), "init-box", boxString(scene.render(index).box).c_str(), nullptr);
  const FrameResult started = h.process(next.bgr);
  ++index;
  fail_unless_equals_int(started.ids.size(), 1);
  fail_unless(started.ids[0] > decoyId, "init-box kept id %d", started.ids[0]);
  fail_unless_equals_string(started.state.c_str(), "tracking");
  const double firstIou = colortrack::scene::iou(started.messageBox, next.box);
  fail_unless(firstIou >= 0.8, "init-box: first IoU %f", firstIou);
  for (int n = 0; n < 5; ++n, ++index) {
    const colortrack::scene::SceneFrame truth = scene.render(index);
    const FrameResult r = h.process(truth.bgr);
    fail_unless_equals_int(r.ids.size(), 1);
    fail_unless_equals_int(r.ids[0], started.ids[0]);
    fail_unless(colortrack::scene::iou(r.boxes[0], truth.box) >= kMinIou);
  }
  gchar *left = nullptr;
  g_object_get(h.element(), "init-box", &left, nullptr);
  fail_unless(left == nullptr, "init-box not cleared once used: %s", left);
}
GST_END_TEST;

// A click outside the frame (a sink's letterbox) is ignored; click-to-track=false ignores clicks but still
// forwards them; click-box-size sets the template's size.
GST_START_TEST(test_click_properties) {
  const Scene scene{SceneConfig()};
  {
    ClickHarness h("click-to-track=false");
    h.process(scene.render(0).bgr);
    h.click(kLeft, inWindow(centreOf(scene.render(1).box)));
    const FrameResult r = h.process(scene.render(1).bgr);
    fail_unless(r.ids.empty(), "clicked although click-to-track=false");
  }
  {
    ClickHarness h("click-box-size=40");
    h.process(scene.render(0).bgr);
    h.click(kLeft, cv::Point2d(-10, -10));
    fail_unless(h.process(scene.render(1).bgr).ids.empty(), "a click outside the frame started a track");
    const cv::Point2d centre = centreOf(scene.render(2).box);
    h.click(kLeft, inWindow(centre));
    const FrameResult r = h.process(scene.render(2).bgr);
    fail_unless_equals_int(r.ids.size(), 1);
    // The track starts from the 40x40 click square (the first frame's search may refine it a little).
    fail_unless(std::abs(r.messageBox.width - 40) <= 4 && std::abs(r.messageBox.height - 40) <= 4,
                "first box %.1fx%.1f", r.messageBox.width, r.messageBox.height);
    // A 40 px square inside the 72 px object may slide a little when the first frame is searched.
    fail_unless(cv::norm(centreOf(r.messageBox) - centre) <= 8, "first box centre %.1f,%.1f, click %.1f,%.1f",
                centreOf(r.messageBox).x, centreOf(r.messageBox).y, centre.x, centre.y);
  }
}
GST_END_TEST;

// Threshold mode: a left click learns the clicked ball's colour (only that ball is tracked), a second left
// click the other ball's (new id), a right click stops until hsv-lower/hsv-upper are set.
GST_START_TEST(test_threshold_click_retarget_stop) {
  BallSceneConfig config;
  std::vector<Ball> balls(2);
  balls[0].hue = 120;  // green
  balls[0].radius = 22;
  balls[0].path = {{0, {120, 120}}, {80, {300, 360}}};
  balls[1].hue = 220;  // blue
  balls[1].radius = 22;
  balls[1].path = {{0, {520, 100}}, {80, {400, 380}}};
  const BallScene scene(config, balls);
  ClickHarness h("mode=threshold");
  int index = 0;
  for (; index < 3; ++index) h.process(scene.render(index));

  // Clicks ball `b` at the next frame, then checks that ball alone is tracked, under one id.
  const auto clickAndFollow = [&](int b, int frames) {
    h.click(kLeft, inWindow(scene.truthOf(b, index).centre));
    int id = 0;
    double minIou = 1.0;
    for (int n = 0; n < frames; ++n, ++index) {
      const cv::Mat bgr = scene.render(index);
      const FrameResult r = h.process(bgr);
      if (n < kSettleFrames) continue;  // a new track is confirmed after 3 detections
      fail_unless_equals_int(r.ids.size(), 1);
      if (id == 0) id = r.ids[0];
      fail_unless_equals_int(r.ids[0], id);
      minIou = std::min(minIou, colortrack::scene::iou(r.boxes[0], cv::Rect2d(scene.boxOf(b, index))));
    }
    GST_INFO("click on ball %d: id %d, min IoU %.3f", b, id, minIou);
    fail_unless(minIou >= kMinIou, "ball %d: min IoU %f", b, minIou);
    return id;
  };

  const int greenId = clickAndFollow(0, 15);
  gchar *lower = nullptr, *upper = nullptr;
  g_object_get(h.element(), "hsv-lower", &lower, "hsv-upper", &upper, nullptr);
  GST_INFO("learnt from the green ball: %s .. %s", lower, upper);
  fail_unless(std::stod(lower) < 120 && std::stod(upper) > 120 && std::stod(upper) < 220,
              "learnt hue %s .. %s does not select green alone", lower, upper);
  g_free(lower);
  g_free(upper);

  const int blueId = clickAndFollow(1, 15);
  fail_unless(blueId > greenId, "re-target kept id %d", blueId);

  h.click(kRight, cv::Point2d(10, 10));
  for (int n = 0; n < 5; ++n, ++index) {
    const FrameResult r = h.process(scene.render(index));
    fail_unless(r.ids.empty(), "a meta after the right click");
    fail_unless_equals_string(r.state.c_str(), "idle");
  }

  // A range set by hand is a new target too: tracking resumes (the blue ball, a new id).
  g_object_set(h.element(), "hsv-lower", "200,0.5,0.25", "hsv-upper", "240,1,1", nullptr);
  for (int n = 0; n < 5; ++n, ++index) {
    const FrameResult r = h.process(scene.render(index));
    if (n < kSettleFrames) continue;
    fail_unless_equals_int(r.ids.size(), 1);
    fail_unless(r.ids[0] > blueId);
    fail_unless(colortrack::scene::iou(r.boxes[0], cv::Rect2d(scene.boxOf(1, index))) >= kMinIou);
  }
}
GST_END_TEST;

static Suite *colortrack_click_suite(void) {
  Suite *s = suite_create("colortrack_click");
  TCase *tc = tcase_create("click");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_template_click_retarget_stop);
  tcase_add_test(tc, test_click_properties);
  tcase_add_test(tc, test_threshold_click_retarget_stop);
  return s;
}

GST_CHECK_MAIN(colortrack_click)
