// SPDX-License-Identifier: LGPL-2.1-or-later
// DL Streamer's elements read colortrack's boxes (issue 48): each ROI meta carries a "detection" and an
// "object_id" structure. Read back here as DL Streamer's gva_utils and gvametaconvert's JSON converter do
// (walk the meta's params list, pick the structures by name, read the fields with the getters of their
// types), and compared with trackpublish's JSON for the same frames. C++ headers first: gstcheck.h defines
// macros (fail, ...) that clash with names in the standard library.
#include <glib/gstdio.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <gst/check/gstcheck.h>
#include <gst/video/video.h>

namespace {

using Json = nlohmann::json;

// What a DL Streamer element sees of one box.
struct DlsObject {
  int id = -1;
  double xMin = -1, yMin = -1, xMax = -1, yMax = -1, confidence = -1;
  int labelId = -1;
  std::string label;
};

// As gva_utils: the structures are found by name in roi->params.
DlsObject readAsDlStreamer(GstVideoRegionOfInterestMeta *roi) {
  DlsObject o;
  for (GList *l = roi->params; l; l = l->next) {
    const GstStructure *s = GST_STRUCTURE(l->data);
    if (gst_structure_has_name(s, "detection")) {
      fail_unless(
          gst_structure_get_double(s, "x_min", &o.xMin) && gst_structure_get_double(s, "y_min", &o.yMin) &&
          gst_structure_get_double(s, "x_max", &o.xMax) && gst_structure_get_double(s, "y_max", &o.yMax) &&
          gst_structure_get_double(s, "confidence", &o.confidence) &&
          gst_structure_get_int(s, "label_id", &o.labelId));
      if (const char *label = gst_structure_get_string(s, "label")) o.label = label;
    } else if (gst_structure_has_name(s, "object_id")) {
      fail_unless(gst_structure_get_int(s, "id", &o.id));
    }
  }
  return o;
}

GstPadProbeReturn collect(GstPad *, GstPadProbeInfo *info, gpointer data) {
  auto *frames = static_cast<std::vector<std::vector<DlsObject>> *>(data);
  GstBuffer *buffer = GST_PAD_PROBE_INFO_BUFFER(info);
  std::vector<DlsObject> objects;
  gpointer state = nullptr;
  while (GstMeta *meta =
             gst_buffer_iterate_meta_filtered(buffer, &state, GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE))
    objects.push_back(readAsDlStreamer(reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta)));
  frames->push_back(objects);
  return GST_PAD_PROBE_OK;
}

// Runs `launch` (ending in "fakesink name=sink") to EOS, collecting what DL Streamer sees on each buffer.
std::vector<std::vector<DlsObject>> run(const std::string &launch) {
  GstElement *pipeline = gst_parse_launch(launch.c_str(), nullptr);
  fail_unless(pipeline != nullptr, "cannot parse %s", launch.c_str());
  GstElement *sink = gst_bin_get_by_name(GST_BIN(pipeline), "sink");
  GstPad *pad = gst_element_get_static_pad(sink, "sink");
  std::vector<std::vector<DlsObject>> frames;
  gst_pad_add_probe(pad, GST_PAD_PROBE_TYPE_BUFFER, collect, &frames, nullptr);
  gst_element_set_state(pipeline, GST_STATE_PLAYING);
  GstBus *bus = gst_element_get_bus(pipeline);
  GstMessage *end = gst_bus_timed_pop_filtered(
      bus, 30 * GST_SECOND, static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
  fail_unless(end && GST_MESSAGE_TYPE(end) == GST_MESSAGE_EOS, "no EOS: %s", launch.c_str());
  gst_message_unref(end);
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(bus);
  gst_object_unref(pad);
  gst_object_unref(sink);
  gst_object_unref(pipeline);
  return frames;
}

// Template mode (one target) and threshold mode (every red ball): every box has both structures, and they
// say what trackpublish's document for that frame says.
GST_START_TEST(test_dlstreamer_reads_what_trackpublish_publishes) {
  for (const std::string mode : {"init-box=140,100,40,40", "mode=threshold"}) {
    gchar *path = g_build_filename(g_get_tmp_dir(), "colortrack-dls-XXXXXX.jsonl", nullptr);
    close(g_mkstemp(path));
    const auto frames =
        run("videotestsrc num-buffers=60 pattern=ball foreground-color=0xffe02020 ! "
            "video/x-raw,format=BGR,width=320,height=240,framerate=30/1 ! colortrack " +
            mode + " ! trackpublish location=" + path + " ! fakesink name=sink");
    std::map<int, Json> documents;  // by frame
    std::ifstream in(path);
    for (std::string line; std::getline(in, line);) {
      const Json doc = Json::parse(line);
      documents[doc["frame"].get<int>()] = doc;
    }
    g_unlink(path);
    g_free(path);
    int compared = 0;
    for (int f = 0; f < static_cast<int>(frames.size()); ++f) {
      const Json objects = documents.count(f) ? documents[f].value("objects", Json::array()) : Json::array();
      fail_unless_equals_int(static_cast<int>(frames[f].size()), static_cast<int>(objects.size()));
      for (size_t i = 0; i < frames[f].size(); ++i) {
        const DlsObject &o = frames[f][i];
        const Json &theirs = objects[i];
        const Json &box = theirs["detection"]["bounding_box"];
        fail_unless_equals_int(o.id, theirs["id"].get<int>());
        fail_unless(o.id >= 1 && o.labelId == 0 && o.label == "colortrack", "frame %d: id %d, label %s", f,
                    o.id, o.label.c_str());
        for (const auto &[mine, field] : {std::pair<double, const char *>{o.xMin, "x_min"},
                                          {o.yMin, "y_min"},
                                          {o.xMax, "x_max"},
                                          {o.yMax, "y_max"}})
          fail_unless(std::abs(mine - box[field].get<double>()) < 1e-9, "frame %d: %s %f against %f", f,
                      field, mine, box[field].get<double>());
        fail_unless(std::abs(o.confidence - theirs["detection"]["confidence"].get<double>()) < 1e-9);
        fail_unless(o.xMin >= 0 && o.xMax <= 1 && o.xMin < o.xMax && o.confidence >= 0 && o.confidence <= 1);
        ++compared;
      }
    }
    std::printf("%s: %d boxes read as DL Streamer reads them, all as published\n", mode.c_str(), compared);
    fail_unless(compared >= 50, "%s: only %d boxes", mode.c_str(), compared);
  }
}
GST_END_TEST;

}  // namespace

static Suite *dlstreamer_params_suite(void) {
  Suite *s = suite_create("dlstreamer_params");
  TCase *tc = tcase_create("params");
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_dlstreamer_reads_what_trackpublish_publishes);
  return s;
}

GST_CHECK_MAIN(dlstreamer_params);
