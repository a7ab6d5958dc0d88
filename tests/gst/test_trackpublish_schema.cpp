// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's documents read by a consumer written against DL Streamer's gvametaconvert schema, field by
// field as DL Streamer documents it (objects[] with detection {bounding_box {x_min, y_min, x_max, y_max},
// confidence, label, label_id}, x, y, w, h, roi_type; resolution {width, height}; source; timestamp in
// nanoseconds of stream time; tags when set), and what gvametaconvert users expect around it: no document
// for an empty frame unless add-empty-results=true, and a run id that changes when the pipeline starts again.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <unistd.h>

#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gst_test_util.hpp"

#include <glib/gstdio.h>
#include <gst/check/gstcheck.h>
#include <gst/check/gstharness.h>
#include <gst/video/video.h>

namespace {

using Json = nlohmann::json;
constexpr int kWidth = 320, kHeight = 240;

// The consumer: what a gvametaconvert reader takes from one document, or a failure naming the field.
struct Detection {
  std::string label, roiType;
  int labelId = -1, x = 0, y = 0, w = 0, h = 0;
  double confidence = 0, xMin = 0, yMin = 0, xMax = 0, yMax = 0;
};
struct Frame {
  std::string source;
  guint64 timestamp = 0;
  int width = 0, height = 0;
  Json tags;
  std::vector<Detection> objects;
};

double unitNumber(const Json &box, const char *name) {
  fail_unless(box.contains(name) && box[name].is_number(), "bounding_box.%s missing", name);
  const double v = box[name].get<double>();
  fail_unless(v >= 0 && v <= 1, "bounding_box.%s = %g, not in 0-1", name, v);
  return v;
}

Detection readObject(const Json &o) {
  Detection d;
  for (const char *field : {"x", "y", "w", "h"})
    fail_unless(o.contains(field) && o[field].is_number_integer(), "object.%s missing", field);
  d.x = o["x"], d.y = o["y"], d.w = o["w"], d.h = o["h"];
  fail_unless(o.contains("roi_type") && o["roi_type"].is_string(), "object.roi_type missing");
  d.roiType = o["roi_type"];
  const Json &det = o.at("detection");
  fail_unless(det.contains("label") && det["label"].is_string(), "detection.label missing");
  fail_unless(det.contains("label_id") && det["label_id"].is_number_integer(), "detection.label_id missing");
  fail_unless(det.contains("confidence") && det["confidence"].is_number(), "detection.confidence missing");
  d.label = det["label"], d.labelId = det["label_id"], d.confidence = det["confidence"];
  const Json &box = det.at("bounding_box");
  d.xMin = unitNumber(box, "x_min"), d.yMin = unitNumber(box, "y_min");
  d.xMax = unitNumber(box, "x_max"), d.yMax = unitNumber(box, "y_max");
  return d;
}

Frame readFrame(const std::string &line) {
  const Json doc = Json::parse(line, nullptr, false);
  fail_if(doc.is_discarded(), "not JSON: %s", line.c_str());
  Frame f;
  fail_unless(doc.contains("source") && doc["source"].is_string());
  fail_unless(doc.contains("timestamp") && doc["timestamp"].is_number_unsigned(), "timestamp: %s",
              line.c_str());
  f.source = doc["source"], f.timestamp = doc["timestamp"];
  const Json &resolution = doc.at("resolution");
  f.width = resolution.at("width"), f.height = resolution.at("height");
  if (doc.contains("tags")) f.tags = doc["tags"];
  // No "objects" key on an empty frame, as gvametaconvert; never an empty array.
  if (doc.contains("objects")) {
    fail_unless(doc["objects"].is_array() && !doc["objects"].empty(), "objects: %s", line.c_str());
    for (const Json &o : doc["objects"]) f.objects.push_back(readObject(o));
  }
  return f;
}

// A GRAY8 frame at `pts` with one colortrack box (or none).
GstBuffer *frame(GstClockTime pts, bool withBox) {
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, kWidth * kHeight, nullptr);
  gst_buffer_memset(buffer, 0, 0, kWidth * kHeight);
  if (withBox) {
    GstVideoRegionOfInterestMeta *roi =
        gst_buffer_add_video_region_of_interest_meta(buffer, "colortrack", 32, 24, 64, 48);
    roi->id = 7;
  }
  GST_BUFFER_PTS(buffer) = pts;
  return buffer;
}

// Runs trackpublish with `properties` over frames with a box, an empty one and a box again, in a segment
// whose PTS start at 10 s (stream time 0 there), and returns the document lines.
std::vector<std::string> run(const std::string &properties, const std::string &path) {
  GstHarness *h = gst_harness_new_parse(("trackpublish location=" + path + " " + properties).c_str());
  gst_harness_set_src_caps_str(h, ("video/x-raw,format=GRAY8,width=" + std::to_string(kWidth) +
                                   ",height=" + std::to_string(kHeight) + ",framerate=30/1")
                                      .c_str());
  GstSegment segment;
  gst_segment_init(&segment, GST_FORMAT_TIME);
  segment.start = segment.time = 0;
  segment.start = 10 * GST_SECOND;  // PTS from 10 s; stream time from 0
  gst_harness_push_event(h, gst_event_new_segment(&segment));
  const bool boxes[] = {true, false, true};
  for (int i = 0; i < 3; ++i)
    fail_unless_equals_int(gst_harness_push(h, frame(10 * GST_SECOND + i * GST_SECOND / 30, boxes[i])),
                           GST_FLOW_OK);
  gst_harness_teardown(h);
  std::vector<std::string> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string tempPath() {
  gchar *path = g_build_filename(g_get_tmp_dir(), "trackpublish-schema-XXXXXX.jsonl", nullptr);
  close(g_mkstemp(path));
  const std::string text = path;
  g_free(path);
  return text;
}

}  // namespace

GST_START_TEST(test_gvametaconvert_consumer_reads_our_documents) {
  const std::string path = tempPath();
  const std::vector<std::string> lines = run("source=cam1 tags={\"site\":\"dock-3\",\"floor\":2}", path);
  fail_unless_equals_int(lines.size(), 2);  // the empty frame gives none
  std::printf("%s\n", lines[0].c_str());
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Frame f = readFrame(lines[i]);
    fail_unless(f.source == "cam1" && f.width == kWidth && f.height == kHeight);
    fail_unless_equals_uint64(f.timestamp, i == 0 ? 0 : 2 * GST_SECOND / 30);  // stream time
    fail_unless(f.tags == Json::parse(R"({"site":"dock-3","floor":2})"), "tags %s", f.tags.dump().c_str());
    fail_unless_equals_int(f.objects.size(), 1);
    const Detection &d = f.objects[0];
    fail_unless(d.label == "colortrack" && d.roiType == "colortrack" && d.labelId == 0);
    fail_unless(d.x == 32 && d.y == 24 && d.w == 64 && d.h == 48);
    fail_unless(std::abs(d.xMin - 0.1) < 1e-9 && std::abs(d.yMax - 0.3) < 1e-9 && d.confidence == 1.0);
  }
  g_unlink(path.c_str());
}
GST_END_TEST;

// add-empty-results=true: the empty frame too, without an "objects" key (gvametaconvert's rule); two
// starts: two run ids.
GST_START_TEST(test_empty_results_and_run_ids) {
  const std::string path = tempPath();
  const std::vector<std::string> runOne = run("add-empty-results=true", path);
  fail_unless_equals_int(runOne.size(), 3);
  fail_unless(readFrame(runOne[1]).objects.empty());
  fail_if(Json::parse(runOne[1]).contains("objects"), "an empty frame's document has objects: %s",
          runOne[1].c_str());
  const std::string again = tempPath();
  const std::vector<std::string> runTwo = run("add-empty-results=true", again);
  const std::string runA = Json::parse(runOne[0])["run"], runB = Json::parse(runTwo[0])["run"];
  fail_unless(!runA.empty() && runA != runB, "runs '%s' and '%s'", runA.c_str(), runB.c_str());
  fail_unless(Json::parse(runOne[2])["run"] == runA);
  g_unlink(path.c_str());
  g_unlink(again.c_str());
}
GST_END_TEST;

// Threshold mode's blob area reaches the document (issue 48): a red ball, the default range.
GST_START_TEST(test_threshold_area_is_published) {
  const std::string path = tempPath();
  const std::string launch =
      "videotestsrc num-buffers=10 pattern=ball foreground-color=0xffe02020 ! "
      "video/x-raw,format=BGR,width=320,height=240 ! colortrack mode=threshold ! "
      "trackpublish location=" +
      path + " ! fakesink";
  GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(pipeline != nullptr);
  gst_element_set_state(pipeline, GST_STATE_PLAYING);
  GstBus *bus = gst_element_get_bus(pipeline);
  GstMessage *end = gst_bus_timed_pop_filtered(
      bus, 10 * GST_SECOND, static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
  fail_unless(end && GST_MESSAGE_TYPE(end) == GST_MESSAGE_EOS);
  gst_message_unref(end);
  gst_object_unref(bus);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(pipeline);
  std::ifstream in(path);
  int withArea = 0;
  for (std::string line; std::getline(in, line);)
    for (const Json &o : Json::parse(line).value("objects", Json::array()))
      withArea += o.contains("area") && o["area"].is_number() && o["area"].get<double>() > 100;
  std::printf("threshold mode: %d objects with an area\n", withArea);
  fail_unless(withArea >= 5, "%d objects with an area in 10 frames", withArea);
  g_unlink(path.c_str());
}
GST_END_TEST;

// tags that are not a JSON object are refused at start, naming the property.
GST_START_TEST(test_bad_tags_are_refused) {
  for (const char *tags : {"{", "[1,2]", "\"text\""}) {
    GstElement *element = gst_element_factory_make("trackpublish", nullptr);
    g_object_set(element, "tags", tags, "location", "/dev/null", nullptr);
    GstBus *bus = gst_bus_new();
    gst_element_set_bus(element, bus);
    fail_unless_equals_int(gst_element_set_state(element, GST_STATE_PAUSED), GST_STATE_CHANGE_FAILURE);
    GstMessage *m = gst_bus_pop_filtered(bus, GST_MESSAGE_ERROR);
    fail_unless(m != nullptr, "no error for tags=%s", tags);
    GError *error = nullptr;
    gst_message_parse_error(m, &error, nullptr);
    fail_unless(std::string(error->message).find("'tags'") != std::string::npos, "%s", error->message);
    g_error_free(error);
    gst_message_unref(m);
    gst_element_set_state(element, GST_STATE_NULL);
    gst_object_unref(bus);
    gst_object_unref(element);
  }
}
GST_END_TEST;

static Suite *trackpublish_schema_suite(void) {
  colortrack::gst_test_util::preloadPlugins({"colortrack", "videotestsrc", "coreelements"});
  Suite *s = suite_create("trackpublish_schema");
  TCase *tc = tcase_create("schema");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_gvametaconvert_consumer_reads_our_documents);
  tcase_add_test(tc, test_empty_results_and_run_ids);
  tcase_add_test(tc, test_bad_tags_are_refused);
  tcase_add_test(tc, test_threshold_area_is_published);
  return s;
}

GST_CHECK_MAIN(trackpublish_schema);
