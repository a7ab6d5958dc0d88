// SPDX-License-Identifier: LGPL-2.1-or-later
#include "eval_pipeline.hpp"

#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <atomic>
#include <chrono>
#include <stdexcept>

#include "metrics.hpp"

using Clock = std::chrono::steady_clock;

namespace colortrack::eval {

namespace {

GstElement *makeElement(const char *factory) {
  GstElement *element = gst_element_factory_make(factory, nullptr);
  if (!element) throw std::runtime_error(std::string("GStreamer element '") + factory + "' is not installed");
  return element;
}

bool hasProperty(GstElement *element, const char *name) {
  return g_object_class_find_property(G_OBJECT_GET_CLASS(element), name) != nullptr;
}

std::string factoryName(GstElement *element) {
  GstElementFactory *factory = gst_element_get_factory(element);
  return factory ? GST_OBJECT_NAME(factory) : "";
}

// Which ROI meta a tracker's box travels in (0: the first ROI meta of any type).
GQuark roiTypeOf(GstElement *tracker) {
  const std::string name = factoryName(tracker);
  if (name == "colortrack") return g_quark_from_static_string("colortrack");
  if (name == "cvtracker") return g_quark_from_static_string("object");
  return 0;
}

// State shared with the streaming thread; read by the main thread only after the pipeline stopped, apart
// from the frame counter for the progress line.
struct RunContext {
  GQuark roiType = 0;
  RunResult *result = nullptr;
  std::vector<std::string> messageStates;  // colortrack's element messages, by their frame number
  std::vector<double> messageScores;
  std::atomic<int> framesReceived{0};
  Clock::time_point enteredTracker;
  Clock::duration insideTracker{};
  std::optional<Clock::time_point> eosTime;
};

GstPadProbeReturn onTrackerSink(GstPad *, GstPadProbeInfo *, gpointer data) {
  static_cast<RunContext *>(data)->enteredTracker = Clock::now();
  return GST_PAD_PROBE_OK;
}

GstPadProbeReturn onTrackerSrc(GstPad *, GstPadProbeInfo *, gpointer data) {
  auto *context = static_cast<RunContext *>(data);
  context->insideTracker += Clock::now() - context->enteredTracker;
  return GST_PAD_PROBE_OK;
}

GstFlowReturn onNewSample(GstAppSink *sink, gpointer data) {
  auto *context = static_cast<RunContext *>(data);
  GstSample *sample = gst_app_sink_pull_sample(sink);
  if (!sample) return GST_FLOW_EOS;
  GstBuffer *buffer = gst_sample_get_buffer(sample);
  std::optional<cv::Rect2d> box;
  std::string state;
  double score = 0;
  gpointer iterator = nullptr;
  while (GstMeta *meta = gst_buffer_iterate_meta_filtered(buffer, &iterator,
                                                          GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (context->roiType != 0 && roi->roi_type != context->roiType) continue;
    box = cv::Rect2d(static_cast<gint32>(roi->x), static_cast<gint32>(roi->y), roi->w, roi->h);
    if (const GstStructure *params = gst_video_region_of_interest_meta_get_param(roi, "colortrack")) {
      if (const char *text = gst_structure_get_string(params, "state")) state = text;
      gst_structure_get_double(params, "score", &score);
    }
    break;
  }
  context->result->boxes.push_back(box);
  context->result->states.push_back(state);
  context->result->scores.push_back(score);
  ++context->framesReceived;
  gst_sample_unref(sample);
  return GST_FLOW_OK;
}

void onEos(GstAppSink *, gpointer data) {
  static_cast<RunContext *>(data)->eosTime = Clock::now();
}

// colortrack's message names its state on every frame, also the frames without a box (lost, searching),
// which have no ROI meta. Called in the posting (streaming) thread; the message goes no further.
GstBusSyncReply onSyncMessage(GstBus *, GstMessage *message, gpointer data) {
  const GstStructure *s = gst_message_get_structure(message);
  if (GST_MESSAGE_TYPE(message) != GST_MESSAGE_ELEMENT || !s || !gst_structure_has_name(s, "colortrack"))
    return GST_BUS_PASS;
  auto *context = static_cast<RunContext *>(data);
  guint64 frame = 0;
  const char *state = gst_structure_get_string(s, "state");
  if (state && gst_structure_get_uint64(s, "frame", &frame) && frame < 1000000) {
    if (context->messageStates.size() <= frame) context->messageStates.resize(frame + 1);
    if (context->messageScores.size() <= frame) context->messageScores.resize(frame + 1);
    context->messageStates[frame] = state;
    gst_structure_get_double(s, "score", &context->messageScores[frame]);
  }
  return GST_BUS_DROP;
}

// Sets the tracker's initial box and switches QoS off, and drawing too unless `keepDrawing` or the fragment
// mentions drawing itself (then what the element costs with its overlay is the user's question).
void configureTracker(GstElement *tracker, const std::string &fragment,
                      const std::optional<cv::Rect> &initBox, bool keepDrawing) {
  if (initBox && hasProperty(tracker, "init-box")) {
    const std::string text = format("%d,%d,%d,%d", initBox->x, initBox->y, initBox->width, initBox->height);
    g_object_set(tracker, "init-box", text.c_str(), nullptr);
  } else if (initBox && hasProperty(tracker, "object-initial-x")) {
    g_object_set(tracker, "object-initial-x", static_cast<guint>(initBox->x), "object-initial-y",
                 static_cast<guint>(initBox->y), "object-initial-width", static_cast<guint>(initBox->width),
                 "object-initial-height", static_cast<guint>(initBox->height), nullptr);
  }
  const bool fragmentDraws = keepDrawing || fragment.find("draw") != std::string::npos;
  if (!fragmentDraws && hasProperty(tracker, "draw-rect")) g_object_set(tracker, "draw-rect", FALSE, nullptr);
  if (!fragmentDraws && hasProperty(tracker, "draw")) {
    GParamSpec *spec = g_object_class_find_property(G_OBJECT_GET_CLASS(tracker), "draw");
    if (G_IS_PARAM_SPEC_FLAGS(spec)) g_object_set(tracker, "draw", 0u, nullptr);
  }
  if (hasProperty(tracker, "qos")) g_object_set(tracker, "qos", FALSE, nullptr);
  // The states of frames without a box come only in the element messages.
  if (factoryName(tracker) == "colortrack" && hasProperty(tracker, "post-messages"))
    g_object_set(tracker, "post-messages", TRUE, nullptr);
}

// The parsed fragment and its last element, the tracker (the one behind the bin's ghost src pad).
struct TrackerBin {
  GstElement *bin = nullptr;  // floating until added to the pipeline
  GstElement *tracker = nullptr;
  GstPad *trackerSrc = nullptr;
  GstPad *trackerSink = nullptr;  // may be null

  ~TrackerBin() {
    if (trackerSink) gst_object_unref(trackerSink);
    if (trackerSrc) gst_object_unref(trackerSrc);
    if (tracker) gst_object_unref(tracker);
  }
};

// Fills `out` from the fragment; returns the error, or "".
std::string openFragment(const std::string &fragment, TrackerBin &out) {
  GError *error = nullptr;
  GstElement *bin = gst_parse_bin_from_description(fragment.c_str(), TRUE, &error);
  if (!bin) {
    const std::string text = "cannot parse \"" + fragment + "\": " + (error ? error->message : "?");
    g_clear_error(&error);
    return text;
  }
  GstPad *ghostSrc = gst_element_get_static_pad(bin, "src");
  GstPad *ghostSink = gst_element_get_static_pad(bin, "sink");
  const bool padsOk = ghostSrc && ghostSink;
  if (padsOk) {
    out.trackerSrc = gst_ghost_pad_get_target(GST_GHOST_PAD(ghostSrc));
    out.tracker = gst_pad_get_parent_element(out.trackerSrc);
    out.trackerSink = gst_element_get_static_pad(out.tracker, "sink");
  }
  if (ghostSrc) gst_object_unref(ghostSrc);
  if (ghostSink) gst_object_unref(ghostSink);
  if (!padsOk) {
    gst_object_unref(gst_object_ref_sink(bin));
    return "\"" + fragment + "\" must have one unlinked sink pad and one unlinked src pad";
  }
  out.bin = bin;
  return "";
}

void configureSource(GstElement *source, const Sequence &sequence) {
  // multifilesrc formats the location with printf, so a '%' in the folder name must be doubled.
  std::string dir;
  for (char c : (sequence.dir / "img").string()) dir += c == '%' ? std::string("%%") : std::string(1, c);
  const std::string location = dir + "/" + sequence.pattern.printfPattern();
  GstCaps *jpegCaps = gst_caps_from_string("image/jpeg,framerate=30/1");
  g_object_set(source, "location", location.c_str(), "start-index", sequence.pattern.startIndex, "stop-index",
               sequence.pattern.startIndex + sequence.pattern.count - 1, "caps", jpegCaps, nullptr);
  gst_caps_unref(jpegCaps);
}

// Watches the bus until EOS or an error and reports progress; returns the error, or "".
std::string watchBus(GstBus *bus, const RunContext &context, const std::function<void(int)> &progress) {
  // Frames arrive in the streaming thread; this loop only watches the bus and reports progress. A run that
  // delivers nothing for a minute is stuck.
  int lastCount = -1;
  Clock::time_point lastChange = Clock::now();
  for (;;) {
    GstMessage *message = gst_bus_timed_pop_filtered(bus, 250 * GST_MSECOND,
                                                     GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
    if (message) {
      std::string error;
      if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR) {
        GError *gerror = nullptr;
        gchar *debug = nullptr;
        gst_message_parse_error(message, &gerror, &debug);
        error = std::string(GST_OBJECT_NAME(GST_MESSAGE_SRC(message))) + ": " +
                (gerror ? gerror->message : "error") + (debug ? std::string(" (") + debug + ")" : "");
        g_clear_error(&gerror);
        g_free(debug);
      }
      gst_message_unref(message);
      return error;
    }
    const int count = context.framesReceived.load();
    progress(count);
    if (count != lastCount) {
      lastCount = count;
      lastChange = Clock::now();
    } else if (Clock::now() - lastChange > std::chrono::seconds(60)) {
      return "no frame for 60 s";
    }
  }
}

// Plays the linked pipeline to its end; fills the result's error and times.
void play(GstElement *pipeline, RunContext &context, const std::function<void(int)> &progress) {
  RunResult &result = *context.result;
  GstBus *bus = gst_element_get_bus(pipeline);
  gst_bus_set_sync_handler(bus, onSyncMessage, &context, nullptr);
  const Clock::time_point start = Clock::now();
  if (gst_element_set_state(pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE)
    result.error = "the pipeline does not start";
  if (result.error.empty()) result.error = watchBus(bus, context, progress);
  const Clock::time_point end = context.eosTime.value_or(Clock::now());
  gst_element_set_state(pipeline, GST_STATE_NULL);  // joins the streaming thread
  gst_bus_set_sync_handler(bus, nullptr, nullptr, nullptr);
  gst_object_unref(bus);
  result.wallSeconds = std::chrono::duration<double>(end - start).count();
  result.elementSeconds = std::chrono::duration<double>(context.insideTracker).count();
  // The message names the state also where no ROI meta came (no box); the meta's is the fallback.
  for (std::size_t i = 0; i < result.states.size() && i < context.messageStates.size(); ++i)
    if (!context.messageStates[i].empty()) {
      result.states[i] = context.messageStates[i];
      result.scores[i] = context.messageScores[i];
    }
}

}  // namespace

RunResult runPipeline(const Sequence &sequence, const PipelineRequest &request,
                      const std::function<void(int)> &progress) {
  RunResult result;
  TrackerBin tracker;
  result.error = openFragment(request.fragment, tracker);
  if (!result.error.empty()) return result;

  GstElement *pipeline = gst_pipeline_new("colortrack-eval");
  GstElement *source = makeElement("multifilesrc");
  GstElement *decoder = makeElement("jpegdec");
  GstElement *convert = makeElement("videoconvert");
  GstElement *filter = makeElement("capsfilter");
  GstElement *sink = makeElement("appsink");
  gst_bin_add_many(GST_BIN(pipeline), source, decoder, convert, filter, tracker.bin, sink, nullptr);
  configureSource(source, sequence);
  if (!request.format.empty()) {
    GstCaps *caps =
        gst_caps_new_simple("video/x-raw", "format", G_TYPE_STRING, request.format.c_str(), nullptr);
    g_object_set(filter, "caps", caps, nullptr);
    gst_caps_unref(caps);
  }
  // Every frame is pulled: no clock, no queue limit, no dropping.
  g_object_set(sink, "sync", FALSE, "max-buffers", 0u, "drop", FALSE, "enable-last-sample", FALSE, "qos",
               FALSE, nullptr);
  configureTracker(tracker.tracker, request.fragment, request.initBox, request.keepDrawing);

  RunContext context;
  context.roiType = roiTypeOf(tracker.tracker);
  context.result = &result;
  GstAppSinkCallbacks callbacks{};
  callbacks.eos = onEos;
  callbacks.new_sample = onNewSample;
  gst_app_sink_set_callbacks(GST_APP_SINK(sink), &callbacks, &context, nullptr);
  if (tracker.trackerSink)
    gst_pad_add_probe(tracker.trackerSink, GST_PAD_PROBE_TYPE_BUFFER, onTrackerSink, &context, nullptr);
  gst_pad_add_probe(tracker.trackerSrc, GST_PAD_PROBE_TYPE_BUFFER, onTrackerSrc, &context, nullptr);

  if (!gst_element_link_many(source, decoder, convert, filter, tracker.bin, sink, nullptr)) {
    const std::string caps = request.format.empty() ? "" : "video/x-raw,format=" + request.format + " ! ";
    result.error =
        "cannot link multifilesrc ! jpegdec ! videoconvert ! " + caps + request.fragment + " ! appsink";
  } else {
    play(pipeline, context, progress);
  }
  gst_element_set_state(pipeline, GST_STATE_NULL);
  gst_object_unref(pipeline);
  return result;
}

std::string trackerFactory(const std::string &fragment) {
  TrackerBin tracker;
  const std::string error = openFragment(fragment, tracker);
  if (!error.empty()) throw std::runtime_error(error);
  const std::string name = factoryName(tracker.tracker);
  gst_object_unref(gst_object_ref_sink(tracker.bin));
  return name;
}

std::vector<std::string> cvtrackerFragments() {
  GstElement *element = makeElement("cvtracker");
  GParamSpec *spec = g_object_class_find_property(G_OBJECT_GET_CLASS(element), "algorithm");
  std::vector<std::string> fragments;
  if (spec && G_IS_PARAM_SPEC_ENUM(spec)) {
    GEnumClass *enumClass = G_PARAM_SPEC_ENUM(spec)->enum_class;
    for (guint i = 0; i < enumClass->n_values; ++i)
      fragments.push_back(std::string("cvtracker algorithm=") + enumClass->values[i].value_nick);
  }
  gst_object_unref(gst_object_ref_sink(element));
  if (fragments.empty()) throw std::runtime_error("cvtracker has no 'algorithm' enum property");
  return fragments;
}

}  // namespace colortrack::eval
