// colortrack-eval: accuracy and speed of GStreamer tracker elements on OTB-layout sequences, side by side.
//
//   colortrack-eval [options] SEQUENCE_DIR... --tracker FRAGMENT [--tracker FRAGMENT ...]
//
// A SEQUENCE_DIR holds img/<n>.jpg and groundtruth.txt (or OTB's groundtruth_rect.txt); a folder of such
// folders stands for all of them. Each tracker is a gst-launch fragment whose last element is the tracker,
// e.g. "colortrack" or "cvtracker algorithm=CSRT". For every sequence and tracker a real pipeline runs:
//
//   multifilesrc location=<dir>/img/%04d.jpg start-index=<first> stop-index=<last>
//       caps=image/jpeg,framerate=30/1 ! jpegdec ! videoconvert ! <fragment> ! appsink sync=false
//
// The tracker is initialised with frame 1's ground-truth box (colortrack: init-box; cvtracker:
// object-initial-x/y/width/height) and every buffer reaching the appsink is scored by its
// GstVideoRegionOfInterestMeta (colortrack: type "colortrack", cvtracker: "object", any other element: its
// first ROI meta). A buffer without one is a miss. Drawing is switched off (colortrack draw=0, cvtracker
// draw-rect=false) unless the fragment sets it, and so is QoS, so no frame is dropped.
//
// Conventions, chosen to match the OTB toolkit (Wu, Lim, Yang, "Online Object Tracking: A Benchmark"):
// - Ground truth is 1-based as published (MATLAB); x and y are shifted by --gt-origin (default 1) into the
//   0-based pixel coordinates the elements use, for initialisation and scoring alike. w and h are kept.
// - The init box is the shifted frame-1 box rounded to whole pixels and clipped to the frame; frame 1 is
//   scored with that box for every tracker (its result by definition, as in OTB), frames 2.. with the meta.
// - Frames whose ground truth is NaN or has no area are left out of the scores.
// - Success AUC = mean over IoU thresholds 0, 0.05, ..., 1 of the fraction of frames with IoU > threshold;
//   precision = fraction of frames with centre error <= 20 px. The mean row averages sequences equally.
// - ROI meta coordinates are guint; they are read back as signed 32-bit, since cvtracker casts negative
//   positions (box partly left of or above the frame) to guint.
// - fps pipeline = frames / wall time from setting PLAYING to the appsink's EOS (decoding included).
//   fps element = frames / time spent inside the tracker element: for each buffer, the time between its
//   arrival at the element's sink pad and its departure from the src pad (pad probes, same thread), summed.
//   It includes everything the element does per frame (colortrack's colour conversion, cvtracker's wrap of
//   the frame) and, on frame 1, initialisation and caps negotiation.
//
// --overhead renders a 1920x1080 JPEG sequence of the synthetic scene into a temporary directory and compares
// `... ! jpegdec ! videoconvert ! colortrack ! appsink` with the same pipeline with identity in its place.

#include <gst/app/gstappsink.h>
#include <gst/gst.h>
#include <gst/video/video.h>

#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdarg>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "metrics.hpp"
#include "sequences.hpp"
#include "scene.hpp"

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

namespace colortrack::eval {
namespace {

constexpr const char *kUsage =
    "usage: colortrack-eval [options] SEQUENCE_DIR... --tracker FRAGMENT [--tracker FRAGMENT ...]\n"
    "\n"
    "  SEQUENCE_DIR          OTB layout (img/*.jpg + groundtruth.txt), or a folder of such folders\n"
    "  --tracker FRAGMENT    gst-launch fragment ending in the tracker, e.g. colortrack or\n"
    "                        \"cvtracker algorithm=CSRT\" (repeatable; order kept)\n"
    "  --all-cvtracker       add cvtracker with every algorithm it offers\n"
    "  --out DIR             results.md, results.csv, curves.csv, success.png, precision.png, frames/\n"
    "                        (default eval-out)\n"
    "  --gt-origin N         subtracted from ground-truth x and y (default 1: OTB's 1-based boxes)\n"
    "  --opencv-threads N    cv::setNumThreads(N) for the whole process, trackers included (default: "
    "OpenCV's)\n"
    "  --no-frames           do not write the per-frame boxes to DIR/frames/\n"
    "  --no-build-plugin     do not add this build's gst/ directory to the plugin path\n"
    "  --overhead            also measure 1920x1080 decode + colortrack against decode + identity\n"
    "  --overhead-frames N   frames of the synthetic 1080p sequence (default 300)\n"
    "  --overhead-repeats N  runs of each variant; the median counts (default 3)\n"
    "  --overhead-tracker F  fragment measured against identity (default colortrack)\n";

struct Options {
  std::vector<std::string> inputs;
  std::vector<std::string> trackers;
  bool allCvtracker = false;
  std::string outDir = "eval-out";
  double gtOrigin = 1.0;
  int openCvThreads = -1;
  bool writeFrames = true;
  bool useBuildPlugin = true;
  bool overhead = false;
  int overheadFrames = 300;
  int overheadRepeats = 3;
  std::string overheadTracker = "colortrack";
  std::string commandLine;
};

// What one pipeline run produced.
struct RunResult {
  std::string error;                             // empty when the run reached EOS
  std::vector<std::optional<cv::Rect2d>> boxes;  // per received frame
  std::vector<std::string> states;               // colortrack's "state" param per frame ("" elsewhere)
  double wallSeconds = 0;
  double elementSeconds = 0;
  int frames() const { return static_cast<int>(boxes.size()); }
  double pipelineFps() const { return wallSeconds > 0 ? frames() / wallSeconds : 0; }
  double elementFps() const { return elementSeconds > 0 ? frames() / elementSeconds : 0; }
};

struct Evaluation {
  RunResult run;
  SequenceScore score;
  std::string warning;  // frame-count mismatch and the like; error text when the run failed
  bool ok = false;
};

// ---------------------------------------------------------------------------------------------------------
// Small helpers

std::string fpsText(double fps) {
  if (fps <= 0) return "-";
  return fps >= 100 ? format("%.0f", fps) : format("%.1f", fps);
}

// A file-name-safe form of a tracker fragment.
std::string slug(const std::string &text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '.')
      out += c;
    else if (!out.empty() && out.back() != '_')
      out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "tracker" : out;
}

// The lines a user sees: a live progress line on a terminal, one line per finished run otherwise.
class Progress {
 public:
  Progress() : live_(isatty(STDERR_FILENO)) {}
  void update(const std::string &line) {
    if (!live_) return;
    std::fprintf(stderr, "\r%-100.100s", line.c_str());
    std::fflush(stderr);
  }
  void finish(const std::string &line) {
    if (live_)
      std::fprintf(stderr, "\r%-100.100s\n", line.c_str());
    else
      std::fprintf(stderr, "%s\n", line.c_str());
    std::fflush(stderr);
  }

 private:
  bool live_;
};

// ---------------------------------------------------------------------------------------------------------
// Pipelines

GstElement *makeElement(const char *factory) {
  GstElement *element = gst_element_factory_make(factory, nullptr);
  if (!element) throw std::runtime_error(std::string("GStreamer element '") + factory + "' is not installed");
  return element;
}

bool hasProperty(GstElement *element, const char *name) {
  return g_object_class_find_property(G_OBJECT_GET_CLASS(element), name) != nullptr;
}

// Which ROI meta a tracker's box travels in (0: the first ROI meta of any type).
GQuark roiTypeOf(GstElement *tracker) {
  GstElementFactory *factory = gst_element_get_factory(tracker);
  const std::string name = factory ? GST_OBJECT_NAME(factory) : "";
  if (name == "colortrack") return g_quark_from_static_string("colortrack");
  if (name == "cvtracker") return g_quark_from_static_string("object");
  return 0;
}

// State shared with the streaming thread; read by the main thread only after the pipeline stopped, apart
// from the frame counter for the progress line.
struct RunContext {
  GQuark roiType = 0;
  RunResult *result = nullptr;
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
  gpointer iterator = nullptr;
  while (GstMeta *meta = gst_buffer_iterate_meta_filtered(buffer, &iterator,
                                                          GST_VIDEO_REGION_OF_INTEREST_META_API_TYPE)) {
    auto *roi = reinterpret_cast<GstVideoRegionOfInterestMeta *>(meta);
    if (context->roiType != 0 && roi->roi_type != context->roiType) continue;
    box = cv::Rect2d(static_cast<gint32>(roi->x), static_cast<gint32>(roi->y), roi->w, roi->h);
    if (const GstStructure *params = gst_video_region_of_interest_meta_get_param(roi, "colortrack"))
      if (const char *text = gst_structure_get_string(params, "state")) state = text;
    break;
  }
  context->result->boxes.push_back(box);
  context->result->states.push_back(state);
  ++context->framesReceived;
  gst_sample_unref(sample);
  return GST_FLOW_OK;
}

void onEos(GstAppSink *, gpointer data) {
  static_cast<RunContext *>(data)->eosTime = Clock::now();
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
}

// Runs `fragment` over the sequence's frames and collects the boxes and timings. `progress` is called about
// four times a second with the number of frames received so far.
template <typename ProgressFn>
RunResult runPipeline(const Sequence &sequence, const std::string &fragment, bool initialise,
                      bool keepDrawing, const ProgressFn &progress) {
  RunResult result;
  GError *error = nullptr;
  GstElement *bin = gst_parse_bin_from_description(fragment.c_str(), TRUE, &error);
  if (!bin) {
    result.error = std::string("cannot parse \"") + fragment + "\": " + (error ? error->message : "?");
    g_clear_error(&error);
    return result;
  }
  // The last element of the fragment is the tracker: the one behind the bin's ghost src pad.
  GstPad *ghostSrc = gst_element_get_static_pad(bin, "src");
  GstPad *ghostSink = gst_element_get_static_pad(bin, "sink");
  if (!ghostSrc || !ghostSink) {
    if (ghostSrc) gst_object_unref(ghostSrc);
    if (ghostSink) gst_object_unref(ghostSink);
    gst_object_unref(gst_object_ref_sink(bin));
    result.error = "\"" + fragment + "\" must have one unlinked sink pad and one unlinked src pad";
    return result;
  }
  GstPad *trackerSrc = gst_ghost_pad_get_target(GST_GHOST_PAD(ghostSrc));
  GstElement *tracker = gst_pad_get_parent_element(trackerSrc);
  GstPad *trackerSink = gst_element_get_static_pad(tracker, "sink");
  gst_object_unref(ghostSrc);
  gst_object_unref(ghostSink);

  GstElement *pipeline = gst_pipeline_new("colortrack-eval");
  GstElement *source = makeElement("multifilesrc");
  GstElement *decoder = makeElement("jpegdec");
  GstElement *convert = makeElement("videoconvert");
  GstElement *sink = makeElement("appsink");
  gst_bin_add_many(GST_BIN(pipeline), source, decoder, convert, bin, sink, nullptr);

  // multifilesrc formats the location with printf, so a '%' in the folder name must be doubled.
  std::string dir;
  for (char c : (sequence.dir / "img").string()) dir += c == '%' ? std::string("%%") : std::string(1, c);
  const std::string location = dir + "/" + sequence.pattern.printfPattern();
  GstCaps *jpegCaps = gst_caps_from_string("image/jpeg,framerate=30/1");
  g_object_set(source, "location", location.c_str(), "start-index", sequence.pattern.startIndex, "stop-index",
               sequence.pattern.startIndex + sequence.pattern.count - 1, "caps", jpegCaps, nullptr);
  gst_caps_unref(jpegCaps);
  // Every frame is pulled: no clock, no queue limit, no dropping.
  g_object_set(sink, "sync", FALSE, "max-buffers", 0u, "drop", FALSE, "enable-last-sample", FALSE, "qos",
               FALSE, nullptr);
  configureTracker(tracker, fragment, initialise ? std::optional<cv::Rect>(sequence.initBox) : std::nullopt,
                   keepDrawing);

  RunContext context;
  context.roiType = roiTypeOf(tracker);
  context.result = &result;
  GstAppSinkCallbacks callbacks{};
  callbacks.eos = onEos;
  callbacks.new_sample = onNewSample;
  gst_app_sink_set_callbacks(GST_APP_SINK(sink), &callbacks, &context, nullptr);
  if (trackerSink)
    gst_pad_add_probe(trackerSink, GST_PAD_PROBE_TYPE_BUFFER, onTrackerSink, &context, nullptr);
  gst_pad_add_probe(trackerSrc, GST_PAD_PROBE_TYPE_BUFFER, onTrackerSrc, &context, nullptr);

  if (!gst_element_link_many(source, decoder, convert, bin, sink, nullptr)) {
    result.error = "cannot link multifilesrc ! jpegdec ! videoconvert ! " + fragment + " ! appsink";
  } else {
    GstBus *bus = gst_element_get_bus(pipeline);
    const Clock::time_point start = Clock::now();
    if (gst_element_set_state(pipeline, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE)
      result.error = "the pipeline does not start";
    // Frames arrive in the streaming thread; this loop only watches the bus and reports progress. A run that
    // delivers nothing for a minute is stuck.
    int lastCount = -1;
    Clock::time_point lastChange = Clock::now();
    while (result.error.empty()) {
      GstMessage *message = gst_bus_timed_pop_filtered(bus, 250 * GST_MSECOND,
                                                       GstMessageType(GST_MESSAGE_EOS | GST_MESSAGE_ERROR));
      if (message) {
        if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_ERROR) {
          GError *gerror = nullptr;
          gchar *debug = nullptr;
          gst_message_parse_error(message, &gerror, &debug);
          result.error = std::string(GST_OBJECT_NAME(GST_MESSAGE_SRC(message))) + ": " +
                         (gerror ? gerror->message : "error") +
                         (debug ? std::string(" (") + debug + ")" : "");
          g_clear_error(&gerror);
          g_free(debug);
        }
        const bool eos = GST_MESSAGE_TYPE(message) == GST_MESSAGE_EOS;
        gst_message_unref(message);
        if (eos) break;
        continue;
      }
      const int count = context.framesReceived.load();
      progress(count);
      if (count != lastCount) {
        lastCount = count;
        lastChange = Clock::now();
      } else if (Clock::now() - lastChange > std::chrono::seconds(60)) {
        result.error = "no frame for 60 s";
      }
    }
    const Clock::time_point end = context.eosTime.value_or(Clock::now());
    gst_element_set_state(pipeline, GST_STATE_NULL);  // joins the streaming thread
    gst_object_unref(bus);
    result.wallSeconds = std::chrono::duration<double>(end - start).count();
    result.elementSeconds = std::chrono::duration<double>(context.insideTracker).count();
  }
  gst_element_set_state(pipeline, GST_STATE_NULL);
  if (trackerSink) gst_object_unref(trackerSink);
  gst_object_unref(trackerSrc);
  gst_object_unref(tracker);
  gst_object_unref(pipeline);
  return result;
}

Evaluation evaluate(const Sequence &sequence, const std::string &fragment, const std::string &label,
                    Progress &progress) {
  Evaluation evaluation;
  const int expected = static_cast<int>(sequence.groundTruth.size());
  evaluation.run = runPipeline(sequence, fragment, true, false, [&](int frames) {
    progress.update(format("%s  %s  frame %d/%d", label.c_str(), fragment.c_str(), frames, expected));
  });
  RunResult &run = evaluation.run;
  if (!run.error.empty()) {
    evaluation.warning = run.error;
    return evaluation;
  }
  std::vector<std::optional<cv::Rect2d>> scored = run.boxes;
  if (!scored.empty()) scored[0] = cv::Rect2d(sequence.initBox);  // frame 1's result is the init box (OTB)
  evaluation.score = scoreSequence(sequence.groundTruth, scored);
  if (run.frames() != expected)
    evaluation.warning = format("%d frames received, %d ground-truth lines", run.frames(), expected);
  evaluation.ok = true;
  return evaluation;
}

// "cvtracker algorithm=<nick>" for every value of cvtracker's algorithm enum, as installed.
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

// ---------------------------------------------------------------------------------------------------------
// Plots (OpenCV drawing, laid out like the OTB paper's figures: legend sorted by score)

struct Curve {
  std::string label;
  std::vector<double> values;
  double score;
};

cv::Scalar curveColour(std::size_t index) {
  static const cv::Scalar palette[] = {{40, 40, 220}, {200, 90, 20},   {40, 160, 40},  {180, 40, 180},
                                       {0, 140, 255}, {170, 160, 0},   {40, 70, 130},  {120, 120, 120},
                                       {0, 0, 0},     {220, 120, 160}, {30, 120, 120}, {110, 30, 60}};
  return palette[index % (sizeof palette / sizeof palette[0])];
}

void drawPlot(const std::string &title, const std::string &xLabel, double xMax, double xTickStep,
              const char *tickFormat, std::vector<Curve> curves, const fs::path &path) {
  const cv::Size canvasSize(1000, 620);
  const cv::Rect plot(80, 50, 560, 500);
  cv::Mat canvas(canvasSize, CV_8UC3, cv::Scalar::all(255));
  const int font = cv::FONT_HERSHEY_SIMPLEX;
  auto toPixel = [&](double x, double y) {
    return cv::Point(plot.x + cvRound(x / xMax * plot.width),
                     plot.y + plot.height - cvRound(y * plot.height));
  };
  // Grid and tick labels.
  for (double x = 0; x <= xMax + 1e-9; x += xTickStep) {
    cv::line(canvas, toPixel(x, 0), toPixel(x, 1), cv::Scalar::all(225), 1);
    const std::string text = format(tickFormat, x);
    const cv::Size size = cv::getTextSize(text, font, 0.45, 1, nullptr);
    cv::putText(canvas, text, toPixel(x, 0) + cv::Point(-size.width / 2, 20), font, 0.45, cv::Scalar::all(0),
                1, cv::LINE_AA);
  }
  for (int i = 0; i <= 10; ++i) {
    const double y = i / 10.0;
    cv::line(canvas, toPixel(0, y), toPixel(xMax, y), cv::Scalar::all(225), 1);
    cv::putText(canvas, format("%.1f", y), toPixel(0, y) + cv::Point(-34, 5), font, 0.45, cv::Scalar::all(0),
                1, cv::LINE_AA);
  }
  cv::rectangle(canvas, plot, cv::Scalar::all(0), 1);
  const cv::Size titleSize = cv::getTextSize(title, font, 0.7, 2, nullptr);
  cv::putText(canvas, title, cv::Point(plot.x + (plot.width - titleSize.width) / 2, 32), font, 0.7,
              cv::Scalar::all(0), 2, cv::LINE_AA);
  const cv::Size xLabelSize = cv::getTextSize(xLabel, font, 0.55, 1, nullptr);
  cv::putText(canvas, xLabel, cv::Point(plot.x + (plot.width - xLabelSize.width) / 2, plot.br().y + 50), font,
              0.55, cv::Scalar::all(0), 1, cv::LINE_AA);
  cv::Mat yLabel(24, 200, CV_8UC3, cv::Scalar::all(255));
  cv::putText(yLabel, xMax > 1 ? "Precision" : "Success rate", cv::Point(40, 18), font, 0.55,
              cv::Scalar::all(0), 1, cv::LINE_AA);
  cv::rotate(yLabel, yLabel, cv::ROTATE_90_COUNTERCLOCKWISE);
  yLabel.copyTo(canvas(cv::Rect(6, plot.y + plot.height / 2 - 100, 24, 200)));

  // Colours follow the order given on the command line; the legend follows the score.
  for (std::size_t i = 0; i < curves.size(); ++i) {
    std::vector<cv::Point> points;
    const std::size_t n = curves[i].values.size();
    for (std::size_t k = 0; k < n; ++k)
      points.push_back(toPixel(xMax * k / double(n - 1), std::clamp(curves[i].values[k], 0.0, 1.0)));
    cv::polylines(canvas, points, false, curveColour(i), i == 0 ? 3 : 2, cv::LINE_AA);
  }
  std::vector<std::size_t> order(curves.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return curves[a].score > curves[b].score; });
  int y = plot.y + 14;
  for (std::size_t i : order) {
    const cv::Point left(plot.br().x + 20, y);
    cv::line(canvas, left, left + cv::Point(30, 0), curveColour(i), i == 0 ? 3 : 2, cv::LINE_AA);
    cv::putText(canvas, format("%s [%.3f]", curves[i].label.c_str(), curves[i].score),
                left + cv::Point(38, 5), font, 0.45, cv::Scalar::all(0), 1, cv::LINE_AA);
    y += 24;
  }
  if (!cv::imwrite(path.string(), canvas)) throw std::runtime_error("cannot write " + path.string());
}

// ---------------------------------------------------------------------------------------------------------
// Reports

std::string machineDescription() {
  std::string cpu = "unknown CPU";
  std::ifstream cpuinfo("/proc/cpuinfo");
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  struct utsname system {};
  uname(&system);
  gchar *gstVersion = gst_version_string();
  std::string text = format("%s, %u logical cores (OpenCV threads: %d); %s %s; %s; OpenCV %s", cpu.c_str(),
                            std::thread::hardware_concurrency(), cv::getNumThreads(), system.sysname,
                            system.release, gstVersion, cv::getVersionString().c_str());
  g_free(gstVersion);
  // Other processes compete for the cores; the load says how much the fps figures can be trusted.
  std::ifstream loadavg("/proc/loadavg");
  double load1 = 0;
  if (loadavg >> load1) text += format("; load average %.2f at the start", load1);
  return text;
}

std::string pluginOf(const char *factoryName) {
  GstElementFactory *factory = gst_element_factory_find(factoryName);
  if (!factory) return "not found";
  GstPlugin *plugin = gst_plugin_feature_get_plugin(GST_PLUGIN_FEATURE(factory));
  std::string text = plugin && gst_plugin_get_filename(plugin) ? gst_plugin_get_filename(plugin) : "?";
  if (plugin) {
    text += std::string(" (") + gst_plugin_get_version(plugin) + ")";
    gst_object_unref(plugin);
  }
  gst_object_unref(factory);
  return text;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[64];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", std::gmtime(&now));
  return text;
}

std::string markdownTables(const std::vector<Sequence> &sequences, const std::vector<std::string> &trackers,
                           const std::vector<std::vector<Evaluation>> &results) {
  std::ostringstream md;
  for (std::size_t s = 0; s < sequences.size(); ++s) {
    const Sequence &seq = sequences[s];
    md << "### " << seq.name << " (" << seq.groundTruth.size() << " frames, " << seq.frameSize.width << "x"
       << seq.frameSize.height << ")\n\n";
    md << "| Tracker | AUC | Precision@20 | fps pipeline | fps element |\n|---|---:|---:|---:|---:|\n";
    std::vector<std::string> notes;
    for (std::size_t t = 0; t < trackers.size(); ++t) {
      const Evaluation &e = results[s][t];
      if (!e.ok) {
        md << "| " << trackers[t] << " | failed | | | |\n";
      } else {
        md << "| " << trackers[t] << " | " << format("%.3f", e.score.auc) << " | "
           << format("%.3f", e.score.precisionAt20) << " | " << fpsText(e.run.pipelineFps()) << " | "
           << fpsText(e.run.elementFps()) << " |\n";
      }
      if (!e.warning.empty()) notes.push_back(trackers[t] + ": " + e.warning);
    }
    if (!notes.empty()) md << "\n";
    for (const std::string &note : notes) md << "- " << note << "\n";
    md << "\n";
  }

  md << "### Mean over " << sequences.size() << (sequences.size() == 1 ? " sequence" : " sequences")
     << "\n\n";
  md << "| Tracker | AUC | Precision@20 | fps pipeline | fps element | slowest element fps |\n"
        "|---|---:|---:|---:|---:|---:|\n";
  for (std::size_t t = 0; t < trackers.size(); ++t) {
    std::vector<SequenceScore> scores;
    double frames = 0, wall = 0, inside = 0, slowest = 0;
    std::string slowestName;
    for (std::size_t s = 0; s < sequences.size(); ++s) {
      const Evaluation &e = results[s][t];
      if (!e.ok) continue;
      scores.push_back(e.score);
      frames += e.run.frames();
      wall += e.run.wallSeconds;
      inside += e.run.elementSeconds;
      if (slowestName.empty() || e.run.elementFps() < slowest) {
        slowest = e.run.elementFps();
        slowestName = sequences[s].name;
      }
    }
    if (scores.empty()) {
      md << "| " << trackers[t] << " | failed | | | | |\n";
      continue;
    }
    const SequenceScore mean = averageScores(scores);
    const std::string coverage = scores.size() == sequences.size()
                                     ? ""
                                     : format(" (%zu of %zu sequences)", scores.size(), sequences.size());
    md << "| " << trackers[t] << coverage << " | " << format("%.3f", mean.auc) << " | "
       << format("%.3f", mean.precisionAt20) << " | " << fpsText(wall > 0 ? frames / wall : 0) << " | "
       << fpsText(inside > 0 ? frames / inside : 0) << " | " << fpsText(slowest) << " (" << slowestName
       << ") |\n";
  }
  md << "\nAUC and precision: mean of the sequences. fps: all frames over all time. fps element: time inside "
        "the "
        "tracker element only (sink pad to src pad).\n";
  return md.str();
}

void writeCsv(const fs::path &path, const std::vector<Sequence> &sequences,
              const std::vector<std::string> &trackers, const std::vector<std::vector<Evaluation>> &results) {
  std::ofstream csv(path);
  csv << "sequence,tracker,gt_frames,frames,scored_frames,frames_with_box,auc,precision20,fps_pipeline,fps_"
         "element,"
         "wall_s,element_s,status\n";
  auto quoted = [](const std::string &text) {
    std::string out = "\"";
    for (char c : text) out += c == '"' ? std::string("\"\"") : std::string(1, c);
    return out + "\"";
  };
  for (std::size_t s = 0; s < sequences.size(); ++s)
    for (std::size_t t = 0; t < trackers.size(); ++t) {
      const Evaluation &e = results[s][t];
      const long withBox =
          std::count_if(e.run.boxes.begin(), e.run.boxes.end(), [](const auto &b) { return b; });
      csv << quoted(sequences[s].name) << "," << quoted(trackers[t]) << "," << sequences[s].groundTruth.size()
          << "," << e.run.frames() << "," << e.score.scoredFrames << "," << withBox << ","
          << format("%.4f", e.score.auc) << "," << format("%.4f", e.score.precisionAt20) << ","
          << format("%.2f", e.run.pipelineFps()) << "," << format("%.2f", e.run.elementFps()) << ","
          << format("%.3f", e.run.wallSeconds) << "," << format("%.3f", e.run.elementSeconds) << ","
          << quoted(e.ok ? (e.warning.empty() ? "ok" : e.warning) : "failed: " + e.warning) << "\n";
    }
}

// Per-frame boxes, for looking into a tracker's failures: one file per sequence and tracker.
void writeFrames(const fs::path &dir, const Sequence &sequence, const Evaluation &e) {
  fs::create_directories(dir);
  std::ofstream out(dir / (sequence.name + ".csv"));
  out << "frame,gt_x,gt_y,gt_w,gt_h,x,y,w,h,iou,centre_error,state\n";
  const std::size_t n = std::max(sequence.groundTruth.size(), e.run.boxes.size());
  for (std::size_t i = 0; i < n; ++i) {
    const GroundTruthBox gt = i < sequence.groundTruth.size() ? sequence.groundTruth[i] : std::nullopt;
    std::optional<cv::Rect2d> box = i < e.run.boxes.size() ? e.run.boxes[i] : std::nullopt;
    if (i == 0) box = cv::Rect2d(sequence.initBox);
    out << i + 1;
    for (const auto &b : {gt, box}) {
      if (b)
        out << format(",%.2f,%.2f,%.2f,%.2f", b->x, b->y, b->width, b->height);
      else
        out << ",,,,";
    }
    if (gt && box)
      out << format(",%.4f,%.2f", overlap(*box, *gt), centreDistance(*box, *gt));
    else
      out << (gt ? ",0,inf" : ",,");
    out << "," << (i < e.run.states.size() ? e.run.states[i] : "") << "\n";
  }
}

void writeCurves(const fs::path &path, const std::vector<std::string> &trackers,
                 const std::vector<SequenceScore> &means) {
  std::ofstream csv(path);
  csv << "tracker,curve,threshold,value\n";
  for (std::size_t t = 0; t < trackers.size(); ++t) {
    for (int k = 0; k < kSuccessSteps; ++k)
      csv << "\"" << trackers[t] << "\",success," << format("%.2f", k / double(kSuccessSteps - 1)) << ","
          << format("%.4f", means[t].success[k]) << "\n";
    for (int k = 0; k < kPrecisionSteps; ++k)
      csv << "\"" << trackers[t] << "\",precision," << k << "," << format("%.4f", means[t].precision[k])
          << "\n";
  }
}

// ---------------------------------------------------------------------------------------------------------
// Overhead at 1080p

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values.empty() ? 0 : values[values.size() / 2];
}

std::string measureOverhead(const Options &options, Progress &progress) {
  const fs::path dir = [] {
    char pattern[] = "/tmp/colortrack-eval-1080p-XXXXXX";
    if (!mkdtemp(pattern)) throw std::runtime_error("cannot create a temporary directory");
    return fs::path(pattern);
  }();
  struct Cleanup {
    fs::path dir;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(dir, ignored);
    }
  } cleanup{dir};
  fs::create_directories(dir / "img");

  // The benchmarks' scene, scaled to 1080p: a textured object that moves, turns, changes size and lighting.
  scene::SceneConfig config;
  config.frameSize = cv::Size(1920, 1080);
  config.frames = options.overheadFrames;
  const int side = cvRound(72.0 * 1080 / 480);
  config.objectSize = cv::Size(side, side);
  config.scaleMin = 0.8;
  config.scaleMax = 1.25;
  config.rotationDegrees = 45;
  config.brightness = 0.2;
  const scene::Scene scene(config);
  Sequence sequence;
  sequence.name = "synthetic 1920x1080";
  sequence.dir = dir;
  sequence.frameSize = config.frameSize;
  for (int i = 0; i < options.overheadFrames; ++i) {
    const scene::SceneFrame frame = scene.render(i);
    cv::imwrite((dir / "img" / format("%04d.jpg", i + 1)).string(), frame.bgr,
                {cv::IMWRITE_JPEG_QUALITY, 90});
    sequence.groundTruth.push_back(frame.objectVisible ? GroundTruthBox(frame.box) : std::nullopt);
    progress.update(format("overhead: writing 1080p frame %d/%d", i + 1, options.overheadFrames));
  }
  sequence.pattern = {"", ".jpg", 4, 1, options.overheadFrames};
  sequence.initBox = scene.initBox();

  struct Variant {
    std::string label, fragment;
    bool draws;
    std::vector<double> fps, elementMs;
    RunResult last;
  };
  std::vector<Variant> variants = {
      {"identity", "identity", false, {}, {}, {}},
      {options.overheadTracker, options.overheadTracker, false, {}, {}, {}},
      {options.overheadTracker + " (draw=box+trail+label)", options.overheadTracker, true, {}, {}, {}}};
  // One unmeasured run warms the page cache and the plugin loading.
  runPipeline(sequence, "identity", false, false, [](int) {});
  for (int repeat = 0; repeat < options.overheadRepeats; ++repeat)
    for (Variant &v : variants) {
      RunResult run = runPipeline(sequence, v.fragment, true, v.draws, [&](int frames) {
        progress.update(format("overhead %d/%d: %s  frame %d/%d", repeat + 1, options.overheadRepeats,
                               v.label.c_str(), frames, options.overheadFrames));
      });
      if (!run.error.empty()) throw std::runtime_error("overhead run " + v.label + ": " + run.error);
      v.fps.push_back(run.pipelineFps());
      v.elementMs.push_back(1000.0 * run.elementSeconds / std::max(run.frames(), 1));
      v.last = std::move(run);
    }

  const double baseFps = median(variants[0].fps);
  std::ostringstream md;
  md << "### Overhead at 1920x1080\n\n"
     << "`multifilesrc ! jpegdec ! videoconvert ! X ! appsink sync=false`, " << options.overheadFrames
     << " JPEG frames (quality 90) of the synthetic scene in a temporary directory; median of "
     << options.overheadRepeats << " runs per variant, runs interleaved.\n\n"
     << "| X | fps pipeline | ratio to identity | ms/frame in X | frames tracking | AUC |\n"
     << "|---|---:|---:|---:|---:|---:|\n";
  for (const Variant &v : variants) {
    const long tracking = std::count(v.last.states.begin(), v.last.states.end(), std::string("tracking"));
    std::vector<std::optional<cv::Rect2d>> boxes = v.last.boxes;
    if (!boxes.empty()) boxes[0] = cv::Rect2d(sequence.initBox);
    const SequenceScore score = scoreSequence(sequence.groundTruth, boxes);
    const bool isIdentity = &v == &variants[0];
    md << "| " << v.label << " | " << fpsText(median(v.fps)) << " | "
       << format("%.3f", median(v.fps) / baseFps) << " | " << format("%.2f", median(v.elementMs)) << " | "
       << (isIdentity ? "-" : format("%ld/%d", tracking, v.last.frames())) << " | "
       << (isIdentity ? "-" : format("%.3f", score.auc)) << " |\n";
  }
  progress.finish(format("overhead: identity %.1f fps, %s %.1f fps (ratio %.3f)", baseFps,
                         options.overheadTracker.c_str(), median(variants[1].fps),
                         median(variants[1].fps) / baseFps));
  return md.str();
}

// ---------------------------------------------------------------------------------------------------------

Options parseOptions(int argc, char **argv) {
  Options options;
  for (int i = 0; i < argc; ++i) options.commandLine += (i ? " " : "") + std::string(argv[i]);
  auto value = [&](int &i) -> std::string {
    if (i + 1 >= argc) throw std::invalid_argument(std::string(argv[i]) + " needs a value");
    return argv[++i];
  };
  auto positive = [&](int &i) {
    const std::string arg = argv[i];
    const int n = std::atoi(value(i).c_str());
    if (n <= 0) throw std::invalid_argument(arg + " must be a positive number");
    return n;
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--tracker")
      options.trackers.push_back(value(i));
    else if (arg == "--all-cvtracker")
      options.allCvtracker = true;
    else if (arg == "--out")
      options.outDir = value(i);
    else if (arg == "--gt-origin")
      options.gtOrigin = std::atof(value(i).c_str());
    else if (arg == "--opencv-threads")
      options.openCvThreads = positive(i);
    else if (arg == "--no-frames")
      options.writeFrames = false;
    else if (arg == "--no-build-plugin")
      options.useBuildPlugin = false;
    else if (arg == "--overhead")
      options.overhead = true;
    else if (arg == "--overhead-frames")
      options.overheadFrames = positive(i);
    else if (arg == "--overhead-repeats")
      options.overheadRepeats = positive(i);
    else if (arg == "--overhead-tracker")
      options.overheadTracker = value(i);
    else if (arg == "-h" || arg == "--help")
      throw std::invalid_argument("");
    else if (arg.rfind("--", 0) == 0)
      throw std::invalid_argument("unknown option " + arg);
    else
      options.inputs.push_back(arg);
  }
  if (options.inputs.empty() && !options.overhead) throw std::invalid_argument("no sequence folder given");
  if (!options.inputs.empty() && options.trackers.empty() && !options.allCvtracker)
    throw std::invalid_argument("no tracker given (--tracker FRAGMENT or --all-cvtracker)");
  return options;
}

// Puts this build's plugin first on the plugin path, so the colortrack just built is the one measured.
void useBuildPlugin() {
#ifdef COLORTRACK_EVAL_PLUGIN_DIR
  if (!fs::is_directory(COLORTRACK_EVAL_PLUGIN_DIR)) return;
  // GST_PLUGIN_PATH_1_0, when set, replaces GST_PLUGIN_PATH.
  const char *variable = g_getenv("GST_PLUGIN_PATH_1_0") ? "GST_PLUGIN_PATH_1_0" : "GST_PLUGIN_PATH";
  const char *current = g_getenv(variable);
  const std::string value =
      std::string(COLORTRACK_EVAL_PLUGIN_DIR) + (current && *current ? std::string(":") + current : "");
  g_setenv(variable, value.c_str(), TRUE);
#endif
}

int run(int argc, char **argv) {
  Options options;
  try {
    options = parseOptions(argc, argv);
  } catch (const std::invalid_argument &e) {
    if (*e.what()) std::fprintf(stderr, "colortrack-eval: %s\n\n", e.what());
    std::fputs(kUsage, stderr);
    return 2;
  }
  if (options.useBuildPlugin) useBuildPlugin();
  gst_init(nullptr, nullptr);
  if (options.openCvThreads > 0) cv::setNumThreads(options.openCvThreads);

  std::vector<std::string> trackers = options.trackers;
  if (options.allCvtracker)
    for (const std::string &fragment : cvtrackerFragments())
      if (std::find(trackers.begin(), trackers.end(), fragment) == trackers.end())
        trackers.push_back(fragment);

  const std::vector<Sequence> sequences = findSequences(options.inputs, options.gtOrigin);
  const fs::path outDir(options.outDir);
  fs::create_directories(outDir);
  Progress progress;

  std::ostringstream header;
  header << "# colortrack-eval results\n\n"
         << "- Date: " << utcNow() << "\n"
         << "- Machine: " << machineDescription() << "\n"
         << "- colortrack plugin: " << pluginOf("colortrack") << "\n"
         << "- cvtracker plugin: " << pluginOf("cvtracker") << "\n"
         << "- Command: `" << options.commandLine << "`\n";
  if (!sequences.empty())
    header << "- Protocol: OTB one-pass evaluation, initialised with frame 1's ground truth (x, y minus "
           << options.gtOrigin
           << " into 0-based pixels); frames without ground truth are not scored; a frame "
              "without the tracker's ROI meta is a miss.\n";
  header << "\n";

  std::ostringstream body;
  if (!sequences.empty()) {
    // results[sequence][tracker]
    std::vector<std::vector<Evaluation>> results(sequences.size(), std::vector<Evaluation>(trackers.size()));
    const int runs = static_cast<int>(sequences.size() * trackers.size());
    int done = 0;
    for (std::size_t s = 0; s < sequences.size(); ++s) {
      const Sequence &seq = sequences[s];
      for (std::size_t t = 0; t < trackers.size(); ++t) {
        const std::string label = format("[%d/%d] %s", ++done, runs, seq.name.c_str());
        Evaluation &e = results[s][t];
        e = evaluate(seq, trackers[t], label, progress);
        if (e.ok)
          progress.finish(format("%s  %s  AUC %.3f  P@20 %.3f  %s fps pipeline  %s fps element%s%s",
                                 label.c_str(), trackers[t].c_str(), e.score.auc, e.score.precisionAt20,
                                 fpsText(e.run.pipelineFps()).c_str(), fpsText(e.run.elementFps()).c_str(),
                                 e.warning.empty() ? "" : "  WARNING: ", e.warning.c_str()));
        else
          progress.finish(
              format("%s  %s  FAILED: %s", label.c_str(), trackers[t].c_str(), e.warning.c_str()));
        if (options.writeFrames) writeFrames(outDir / "frames" / slug(trackers[t]), seq, e);
      }
    }
    body << markdownTables(sequences, trackers, results);
    writeCsv(outDir / "results.csv", sequences, trackers, results);

    std::vector<SequenceScore> means;
    std::vector<Curve> success, precision;
    for (std::size_t t = 0; t < trackers.size(); ++t) {
      std::vector<SequenceScore> scores;
      for (std::size_t s = 0; s < sequences.size(); ++s)
        if (results[s][t].ok) scores.push_back(results[s][t].score);
      means.push_back(averageScores(scores));
      success.push_back({trackers[t], means.back().success, means.back().auc});
      precision.push_back({trackers[t], means.back().precision, means.back().precisionAt20});
    }
    writeCurves(outDir / "curves.csv", trackers, means);
    const std::string over = format("%zu sequence%s", sequences.size(), sequences.size() == 1 ? "" : "s");
    drawPlot("Success plots of OPE (" + over + ")", "Overlap threshold", 1.0, 0.1, "%.1f", success,
             outDir / "success.png");
    drawPlot("Precision plots of OPE (" + over + ")", "Location error threshold (px)", 50.0, 5.0, "%.0f",
             precision, outDir / "precision.png");
    body << "\n![success](success.png) ![precision](precision.png)\n";
  }
  if (options.overhead) body << (sequences.empty() ? "" : "\n") << measureOverhead(options, progress);

  const std::string report = header.str() + body.str();
  std::fputs(report.c_str(), stdout);
  std::ofstream(outDir / "results.md") << report;
  std::fprintf(stderr, "written to %s/\n", outDir.string().c_str());
  return 0;
}

}  // namespace
}  // namespace colortrack::eval

int main(int argc, char **argv) {
  try {
    return colortrack::eval::run(argc, argv);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "colortrack-eval: %s\n", e.what());
    return 1;
  }
}
