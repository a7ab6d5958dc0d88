// SPDX-License-Identifier: LGPL-2.1-or-later
// colortrack's two modes alone, against a fake ElementSink (no element, no pipeline): what each posts, what
// it tells the element about the target, what it writes back, and that it tracks a drawn object. C++ headers
// first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include <gst/check/gstcheck.h>
#include <gst/video/video.h>

#include "colortrack-element-sink.h"
#include "colortrack-mode.h"
#include "frame-view.h"

namespace {

using colortrack_gst::ElementSink;
using colortrack_gst::Mode;
using colortrack_gst::Requests;
using colortrack_gst::Snapshot;

// What a mode did to the element, recorded.
struct Record {
  std::vector<std::string> errors, warnings, infos;
  std::vector<std::string> errorPlaces;  // the source file of each error's call
  int targetChanged = 0, resumed = 0, stopped = 0, tracksReset = 0;
  bool resetRequested = false;
  std::vector<colortrack::HsvRange> learnt;
  std::vector<std::string> restored;
};

// Writes back into `store` as the element writes into its property store: the next frame's snapshot carries
// the learnt range, not marked as a change (the mode has applied it).
class FakeSink final : public ElementSink {
 public:
  FakeSink(Record &record, Snapshot &store) : r_(record), store_(store) {}
  void error(GQuark, gint, const std::string &text, const char *, const char *file, const char *,
             int) const override {
    r_.errors.push_back(text);
    r_.errorPlaces.push_back(file);
  }
  void warning(GQuark, gint, const std::string &text, const char *, const char *, const char *,
               int) const override {
    r_.warnings.push_back(text);
  }
  void info(const std::string &text) const override { r_.infos.push_back(text); }
  void targetChanged() const override { ++r_.targetChanged; }
  void resumed() const override { ++r_.resumed; }
  void stopped() const override { ++r_.stopped; }
  void tracksReset() const override { ++r_.tracksReset; }
  bool takeResetRequest() const override { return std::exchange(r_.resetRequested, false); }
  colortrack::BlobSettings writeLearntRange(const colortrack::HsvRange &range) const override {
    r_.learnt.push_back(range);
    store_.blobs.range = range;
    store_.changed.remove(colortrack_gst::Settings::Change::Blobs);
    return store_.blobs;
  }
  void restoreTemplateLocation(const std::string &, const std::string &inUse) const override {
    r_.restored.push_back(inUse);
  }

 private:
  Record &r_;
  Snapshot &store_;
};

// A BGRx frame holding `bgr`, mapped for reading while the object lives.
class Frame {
 public:
  explicit Frame(const cv::Mat &bgr) {
    gst_video_info_set_format(&info_, GST_VIDEO_FORMAT_BGRx, bgr.cols, bgr.rows);
    buffer_ = gst_buffer_new_allocate(nullptr, GST_VIDEO_INFO_SIZE(&info_), nullptr);
    fail_unless(gst_video_frame_map(&frame_, &info_, buffer_, GST_MAP_READWRITE));
    const cv::Mat pixels(bgr.rows, bgr.cols, CV_8UC4, GST_VIDEO_FRAME_PLANE_DATA(&frame_, 0),
                         GST_VIDEO_FRAME_PLANE_STRIDE(&frame_, 0));
    cv::cvtColor(bgr, pixels, cv::COLOR_BGR2BGRA);
    view_ = std::make_unique<colortrack_gst::FrameView>(&frame_);
  }
  ~Frame() {
    view_.reset();
    gst_video_frame_unmap(&frame_);
    gst_buffer_unref(buffer_);
  }
  const colortrack_gst::FrameView &view() const { return *view_; }

 private:
  GstVideoInfo info_;
  GstBuffer *buffer_ = nullptr;
  GstVideoFrame frame_;
  std::unique_ptr<colortrack_gst::FrameView> view_;
};

// Grey noise-free background with filled circles of `color` at `centres` (radius 20).
cv::Mat scene(const std::vector<cv::Point> &centres, const cv::Scalar &color) {
  cv::Mat bgr(240, 320, CV_8UC3, cv::Scalar(90, 110, 100));
  cv::rectangle(bgr, cv::Rect(0, 0, 160, 240), cv::Scalar(60, 70, 80), cv::FILLED);  // texture for the filter
  for (const cv::Point &c : centres) cv::circle(bgr, c, 20, color, cv::FILLED);
  return bgr;
}

const cv::Scalar kRed(30, 30, 220), kGreen(40, 200, 40);

double iou(const cv::Rect2d &a, const cv::Rect2d &b) {
  const double inter = (a & b).area();
  return inter / (a.area() + b.area() - inter);
}

std::unique_ptr<Mode> startMode(Snapshot &snapshot, Record &record) {
  std::unique_ptr<Mode> mode =
      colortrack_gst::makeMode(snapshot.mode, std::make_unique<FakeSink>(record, snapshot));
  fail_unless(mode->start(snapshot), "start failed: %s",
              record.errors.empty() ? "" : record.errors[0].c_str());
  return mode;
}

GST_START_TEST(test_template_mode_waits_for_a_template_and_says_so_once) {
  Record record;
  Snapshot snapshot;
  std::unique_ptr<Mode> mode = startMode(snapshot, record);
  fail_if(mode->listsTracks());
  for (int i = 0; i < 3; ++i) {
    Frame frame(scene({{200, 120}}, kRed));
    fail_unless(mode->prepare(snapshot, Requests{}, frame.view()));
    fail_unless(mode->readiness(frame.view().size()) == Mode::Readiness::Waiting);
  }
  fail_unless_equals_int(record.warnings.size(), 1);
  std::printf("no template: \"%s\"\n", record.warnings[0].c_str());
  fail_unless(record.warnings[0].find("init-box") != std::string::npos);
  fail_unless_equals_int(record.targetChanged, 0);
}
GST_END_TEST;

GST_START_TEST(test_template_mode_follows_the_init_box) {
  Record record;
  Snapshot snapshot;
  snapshot.initBox = "180,100,40,40";
  std::unique_ptr<Mode> mode = startMode(snapshot, record);
  Requests first;
  first.initBox = cv::Rect(180, 100, 40, 40);
  double worst = 1;
  for (int i = 0; i < 30; ++i) {
    const cv::Point centre(200 + 2 * i, 120 + i);
    Frame frame(scene({centre}, kRed));
    fail_unless(mode->prepare(snapshot, i == 0 ? first : Requests{}, frame.view()));
    fail_unless(mode->readiness(frame.view().size()) == Mode::Readiness::Ready);
    const colortrack::FrameReport report = mode->tracker().track(frame.view(), 1.0);
    worst = std::min(worst, iou(report.primary.box, cv::Rect2d(centre.x - 20, centre.y - 20, 40, 40)));
  }
  std::printf("template mode on a moving ball: worst IoU %.3f\n", worst);
  fail_unless(worst >= 0.6, "worst IoU %.3f", worst);
  fail_unless_equals_int(record.targetChanged, 1);
  fail_unless(record.errors.empty() && record.warnings.empty());
}
GST_END_TEST;

GST_START_TEST(test_init_box_outside_the_frame_is_an_error_before_streaming_and_a_warning_after) {
  for (const bool whileStreaming : {false, true}) {
    Record record;
    Snapshot snapshot;
    snapshot.initBox = "300,220,40,40";
    std::unique_ptr<Mode> mode = startMode(snapshot, record);
    Requests requests;
    requests.initBox = cv::Rect(300, 220, 40, 40);
    requests.initBoxWhileStreaming = whileStreaming;
    Frame frame(scene({}, kRed));
    fail_unless(mode->prepare(snapshot, requests, frame.view()) == whileStreaming);
    const std::vector<std::string> &said = whileStreaming ? record.warnings : record.errors;
    fail_unless_equals_int(said.size(), 1);
    std::printf("init-box outside (%s): \"%s\"\n", whileStreaming ? "while streaming" : "before",
                said[0].c_str());
    fail_unless(said[0].find("'init-box'") != std::string::npos);
    fail_unless_equals_int(record.targetChanged, 0);
  }
}
GST_END_TEST;

GST_START_TEST(test_threshold_mode_learns_a_clicked_colour_and_follows_every_ball) {
  Record record;
  Snapshot snapshot;
  snapshot.mode = colortrack::TrackingMode::Threshold;
  std::unique_ptr<Mode> mode = startMode(snapshot, record);
  fail_unless(mode->listsTracks());
  const std::vector<cv::Point> balls = {{60, 60}, {250, 180}};
  {
    // The default range is red: green balls are not found.
    Frame frame(scene(balls, kGreen));
    fail_unless(mode->prepare(snapshot, Requests{}, frame.view()));
    fail_unless(mode->tracker().track(frame.view(), 1.0).tracks.empty());
  }
  Requests click;
  click.click = colortrack_gst::ClickRequest{colortrack_gst::ClickRequest::Kind::Track, {250, 180}};
  size_t found = 0;
  for (int i = 0; i < 5; ++i) {
    Frame frame(scene(balls, kGreen));
    fail_unless(mode->prepare(snapshot, i == 0 ? click : Requests{}, frame.view()));
    found = mode->tracker().track(frame.view(), 1.0).tracks.size();
  }
  fail_unless_equals_int(record.learnt.size(), 1);
  const colortrack::HsvRange &range = record.learnt[0];
  std::printf("learnt from a click on green: h %.0f..%.0f; %zu balls followed\n", range.lower.h,
              range.upper.h, found);
  fail_unless(range.lower.h < 120 && range.upper.h > 120, "the range misses green's hue 120");
  fail_unless_equals_int(found, balls.size());
  fail_unless_equals_int(record.targetChanged, 1);
  // A right click: the element is told to stop, and the tracks go.
  Requests stop;
  stop.click = colortrack_gst::ClickRequest{colortrack_gst::ClickRequest::Kind::Stop, {0, 0}};
  Frame frame(scene(balls, kGreen));
  fail_unless(mode->prepare(snapshot, stop, frame.view()));
  fail_unless_equals_int(record.stopped, 1);
}
GST_END_TEST;

GST_START_TEST(test_threshold_mode_refuses_a_min_area_larger_than_the_frame) {
  Record record;
  Snapshot snapshot;
  snapshot.mode = colortrack::TrackingMode::Threshold;
  snapshot.blobs.minArea = 320 * 240 + 1;
  std::unique_ptr<Mode> mode = startMode(snapshot, record);
  Frame frame(scene({}, kRed));
  fail_if(mode->prepare(snapshot, Requests{}, frame.view()));
  fail_unless_equals_int(record.errors.size(), 1);
  fail_unless(record.errors[0].find("'min-area'") != std::string::npos, "%s", record.errors[0].c_str());
  // The message is stamped with the mode's place, not the sink's.
  fail_unless(g_str_has_suffix(record.errorPlaces[0].c_str(), "colortrack-threshold-mode.cpp"), "stamped %s",
              record.errorPlaces[0].c_str());
}
GST_END_TEST;

GST_START_TEST(test_a_reset_request_forgets_the_tracks_and_keeps_the_target) {
  Record record;
  Snapshot snapshot;
  snapshot.mode = colortrack::TrackingMode::Threshold;
  std::unique_ptr<Mode> mode = startMode(snapshot, record);
  // A new track is reported from its third frame (MultiTracker's confirmFrames).
  std::vector<int> ids;
  for (int i = 0; i < 8; ++i) {
    if (i == 4) record.resetRequested = true;
    Frame frame(scene({{160, 120}}, kRed));
    fail_unless(mode->prepare(snapshot, Requests{}, frame.view()));
    const colortrack::FrameReport report = mode->tracker().track(frame.view(), 1.0);
    ids.push_back(report.tracks.empty() ? 0 : report.tracks[0].id);
  }
  const int firstId = ids[3], afterReset = ids[7];
  fail_unless(firstId > 0 && afterReset > 0, "no track: ids %d %d", firstId, afterReset);
  std::printf("track id %d, after the reset %d\n", firstId, afterReset);
  fail_unless(afterReset != firstId, "the reset kept the track");
  fail_unless_equals_int(record.tracksReset, 1);
  fail_unless(record.learnt.empty());
}
GST_END_TEST;

}  // namespace

static Suite *colortrack_modes_suite(void) {
  Suite *s = suite_create("colortrack_modes");
  TCase *tc = tcase_create("general");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_template_mode_waits_for_a_template_and_says_so_once);
  tcase_add_test(tc, test_template_mode_follows_the_init_box);
  tcase_add_test(tc, test_init_box_outside_the_frame_is_an_error_before_streaming_and_a_warning_after);
  tcase_add_test(tc, test_threshold_mode_learns_a_clicked_colour_and_follows_every_ball);
  tcase_add_test(tc, test_threshold_mode_refuses_a_min_area_larger_than_the_frame);
  tcase_add_test(tc, test_a_reset_request_forgets_the_tracks_and_keeps_the_target);
  return s;
}

GST_CHECK_MAIN(colortrack_modes);
