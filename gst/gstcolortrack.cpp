/**
 * SECTION:element-colortrack
 * @title: colortrack
 *
 * Tracks one coloured object through a video by modified colour indexing: a template gives per-channel
 * histograms (HSV by default), a window slides over a search region around the Kalman prediction and the
 * best histogram intersection wins; its size is refined between #GstColorTrack:scale-min and
 * #GstColorTrack:scale-max, and an edge density/energy check marks same-coloured but untextured look-alikes
 * as unverified.
 *
 * The template comes from an image file (#GstColorTrack:template-location, PNG alpha selects the object's
 * pixels) or from a box of the next frame (#GstColorTrack:init-box). Without either, buffers pass through
 * untouched and a warning is posted once.
 *
 * Every buffer with a track carries a #GstVideoRegionOfInterestMeta of type "colortrack" whose id is the
 * track id and whose "colortrack" parameter structure holds state (string), score, scale, vx, vy (double)
 * and verified (boolean). The meta follows the frame through videoconvert and videoscale, which scales its
 * box (GStreamer 1.22's transform of this meta drops the parameter structure, so each buffer also carries a
 * "GstColorTrackParamsMeta" custom meta with every track's parameters under "id-<track id>", which survives
 * those elements). With
 * #GstColorTrack:post-messages, an element message "colortrack" is posted for every frame with timestamp,
 * stream-time, running-time, duration, frame, state, x, y, width, height, score, verified and scale.
 *
 * The overlay (#GstColorTrack:draw) shows the box in red for a colour-only match, green when verified and
 * orange while coasting on the prediction, the path of the box centre in red, the search window in blue
 * and an "id score state" label. YUV input is read and drawn with the BT.601 matrix.
 *
 * Click to track (#GstColorTrack:click-to-track): a left click in the window of a video sink that sends
 * GstNavigation events (xvimagesink, glimagesink, autovideosink ...) takes the template from the
 * #GstColorTrack:click-box-size square around the click on the next frame and tracks from there, as
 * #GstColorTrack:init-box does (mode=threshold: learns the colour there). Another left click re-targets
 * with a new id. A right click stops: no meta and no overlay, and messages report state "idle", until a left
 * click, init-box, template-location or (mode=threshold) hsv-lower/hsv-upper gives a new target. A
 * videoscale between the element and the sink maps the click back to this element's frame.
 *
 * ## Example launch lines
 * |[
 * gst-launch-1.0 v4l2src ! videoconvert ! colortrack template-location=ball.png ! videoconvert !
 * autovideosink
 * ]| Tracks the object of ball.png in a camera stream and shows the overlay.
 * |[
 * gst-launch-1.0 filesrc location=clip.mp4 ! decodebin ! videoconvert ! \
 *     colortrack init-box=120,80,64,64 post-messages=true draw=box+search-window ! \
 *     videoconvert ! autovideosink
 * ]| Takes the template from the box 120,80 64x64 of the first frame and posts one message per frame.
 * |[
 * gst-launch-1.0 v4l2src ! videoconvert ! colortrack click-box-size=48 ! videoconvert ! xvimagesink
 * ]| Tracks whatever is left-clicked in the window; a right click stops.
 */

#include "gstcolortrack.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "colortrack/blobs.hpp"
#include "colortrack/multi_tracker.hpp"
#include "colortrack/settings.hpp"
#include "colortrack/tracker.hpp"
#include "colortrack-settings.h"
#include "frame-view.h"
#include "overlay.h"
#include "track-params.h"

GST_DEBUG_CATEGORY_STATIC(gst_color_track_debug);
#define GST_CAT_DEFAULT gst_color_track_debug

namespace {

using colortrack_gst::ClickRequest;
using colortrack_gst::Settings;

constexpr int kLeftButton = 1, kRightButton = 3;
// The state reported in messages after a right click, until a new target is given.
constexpr const char *kIdleState = "idle";
constexpr int kBoxThickness = 2;
constexpr int kTrailThickness = 2;

// The settings as one frame sees them, with the store's counters at that moment.
struct Snapshot : Settings {
  guint64 trackerGeneration = 0, templateGeneration = 0, blobsGeneration = 0, rangeGeneration = 0;
};

// What the streaming thread owns (and start()/stop(), which never run concurrently with it).
struct State {
  std::unique_ptr<colortrack::Tracker> tracker;
  guint64 appliedTrackerGeneration = 0;
  guint64 appliedTemplateGeneration = 0;
  std::string templateOrigin;  // "template-location 'x.png'" or "init-box '1,2,3,4'", for error messages
  std::deque<cv::Point2d> trail;
  int trailTrackId = 0;
  guint64 frameCount = 0;
  bool warnedNoTemplate = false;
  bool capsChanged = false;
  // After a right click: nothing is tracked (no meta, no overlay) until a left click, init-box,
  // template-location (template mode) or hsv-lower/hsv-upper (threshold mode) gives a new target.
  bool idle = false;
  GstClockTime lastPts = GST_CLOCK_TIME_NONE;
  // mode=threshold.
  std::unique_ptr<colortrack::BlobDetector> blobDetector;
  colortrack::MultiTracker multiTracker;
  guint64 appliedBlobsGeneration = 0;
  guint64 appliedRangeGeneration = 0;
  std::map<int, std::deque<cv::Point2d>> trails;  // per track id
};

}  // namespace

struct _GstColorTrackPrivate {
  colortrack_gst::PropertyStore store;
  State state;
  std::atomic<bool> resetRequested{false};
};

enum { SIGNAL_RESET, LAST_SIGNAL };
static guint gst_color_track_signals[LAST_SIGNAL] = {0};

#define VIDEO_CAPS GST_VIDEO_CAPS_MAKE(COLORTRACK_VIDEO_FORMATS)

static GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS(VIDEO_CAPS));
static GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS(VIDEO_CAPS));

#define gst_color_track_parent_class parent_class
G_DEFINE_TYPE(GstColorTrack, gst_color_track, GST_TYPE_VIDEO_FILTER);
GST_ELEMENT_REGISTER_DEFINE(colortrack, "colortrack", GST_RANK_NONE, GST_TYPE_COLOR_TRACK);

// ---------------------------------------------------------------------------------------------------------
// Enum and flags types

GType gst_color_track_mode_get_type(void) {
  static gsize type = 0;
  static const GEnumValue values[] = {
      {GST_COLOR_TRACK_MODE_TEMPLATE, "Track the object of a template (template-location or init-box)",
       "template"},
      {GST_COLOR_TRACK_MODE_THRESHOLD,
       "Track every blob inside an HSV range (hsv-lower/hsv-upper, or learnt from init-box), each with an id",
       "threshold"},
      {0, nullptr, nullptr},
  };
  if (g_once_init_enter(&type)) g_once_init_leave(&type, g_enum_register_static("GstColorTrackMode", values));
  return type;
}

GType gst_color_track_color_space_get_type(void) {
  static gsize type = 0;
  static const GEnumValue values[] = {
      {GST_COLOR_TRACK_COLOR_SPACE_RGB, "RGB histograms (original colour indexing)", "rgb"},
      {GST_COLOR_TRACK_COLOR_SPACE_HSV, "HSV histograms (modified colour indexing, lighting-robust)", "hsv"},
      {0, nullptr, nullptr},
  };
  if (g_once_init_enter(&type))
    g_once_init_leave(&type, g_enum_register_static("GstColorTrackColorSpace", values));
  return type;
}

GType gst_color_track_verify_get_type(void) {
  static gsize type = 0;
  static const GEnumValue values[] = {
      {GST_COLOR_TRACK_VERIFY_NONE, "No check: every colour match is verified", "none"},
      {GST_COLOR_TRACK_VERIFY_EDGE_DENSITY, "Edge density close to the template's", "edge-density"},
      {GST_COLOR_TRACK_VERIFY_EDGE_ENERGY, "Edge energy close to the template's", "edge-energy"},
      {GST_COLOR_TRACK_VERIFY_BOTH, "Edge density and energy both close to the template's", "both"},
      {0, nullptr, nullptr},
  };
  if (g_once_init_enter(&type))
    g_once_init_leave(&type, g_enum_register_static("GstColorTrackVerify", values));
  return type;
}

GType gst_color_track_method_get_type(void) {
  static gsize type = 0;
  static const GEnumValue values[] = {
      {GST_COLOR_TRACK_METHOD_INDEXING, "Modified colour indexing: template histograms by intersection",
       "indexing"},
      {GST_COLOR_TRACK_METHOD_DISCRIMINATIVE,
       "Colour only: object-versus-surroundings colour likelihood with a motion prior (fastest)",
       "discriminative"},
      {GST_COLOR_TRACK_METHOD_FUSED,
       "Shape (correlation filter) and colour fused, with confidence and re-detection (most accurate)",
       "fused"},
      {0, nullptr, nullptr},
  };
  if (g_once_init_enter(&type))
    g_once_init_leave(&type, g_enum_register_static("GstColorTrackMethod", values));
  return type;
}

GType gst_color_track_draw_get_type(void) {
  static gsize type = 0;
  static const GFlagsValue values[] = {
      {GST_COLOR_TRACK_DRAW_BOX, "Box (red: colour match, green: verified, orange: coasting)", "box"},
      {GST_COLOR_TRACK_DRAW_TRAIL, "Trail of the box centre (yellow)", "trail"},
      {GST_COLOR_TRACK_DRAW_SEARCH_WINDOW, "Region searched this frame (blue)", "search-window"},
      {GST_COLOR_TRACK_DRAW_LABEL, "Label \"id score state\" (threshold: \"id area state\")", "label"},
      {GST_COLOR_TRACK_DRAW_MASK, "mode=threshold: pixels inside the HSV range, tinted magenta", "mask"},
      {0, nullptr, nullptr},
  };
  if (g_once_init_enter(&type))
    g_once_init_leave(&type, g_flags_register_static("GstColorTrackDraw", values));
  return type;
}

// ---------------------------------------------------------------------------------------------------------
// Helpers

namespace {

colortrack_gst::PropertyStore &storeOf(GstColorTrack *self) {
  return self->priv->store;
}
// Call with the object lock held.
Snapshot snapshotOf(const colortrack_gst::PropertyStore &store) {
  Snapshot snapshot;
  static_cast<Settings &>(snapshot) = store.settings;
  snapshot.trackerGeneration = store.versions[colortrack_gst::kTrackerVersion];
  snapshot.templateGeneration = store.versions[colortrack_gst::kTemplateVersion];
  snapshot.blobsGeneration = store.versions[colortrack_gst::kBlobsVersion];
  snapshot.rangeGeneration = store.versions[colortrack_gst::kRangeVersion];
  return snapshot;
}

State &stateOf(GstColorTrack *self) {
  return self->priv->state;
}

// Reads a template file; on failure fills `why` and reports whether the file exists at all.
bool loadTemplateFile(const std::string &path, cv::Mat &bgr, cv::Mat &mask, std::string &why, bool &missing) {
  missing = !g_file_test(path.c_str(), G_FILE_TEST_EXISTS);
  // Said here, before OpenCV is asked: it would log its own "can't open/read file" warning first.
  if (missing) {
    why = "no such file";
    return false;
  }
  try {
    colortrack::loadTemplate(path, bgr, mask);
    return true;
  } catch (const std::exception &e) {
    why = e.what();
    return false;
  }
}

// Frame duration in nanoseconds, from the caps' frame rate or the buffer's duration (0 when unknown).
GstClockTime frameDuration(const GstVideoInfo *info, GstBuffer *buffer) {
  if (GST_VIDEO_INFO_FPS_N(info) > 0 && GST_VIDEO_INFO_FPS_D(info) > 0)
    return gst_util_uint64_scale_int(GST_SECOND, GST_VIDEO_INFO_FPS_D(info), GST_VIDEO_INFO_FPS_N(info));
  if (GST_BUFFER_DURATION_IS_VALID(buffer)) return GST_BUFFER_DURATION(buffer);
  return 0;
}

// The filtered box rounded to whole pixels and clipped to the frame (empty when it lies outside).
cv::Rect roundedClippedBox(const cv::Rect2d &box, cv::Size frame) {
  const int x0 = static_cast<int>(std::lround(box.x)), y0 = static_cast<int>(std::lround(box.y));
  const int x1 = static_cast<int>(std::lround(box.x + box.width));
  const int y1 = static_cast<int>(std::lround(box.y + box.height));
  return cv::Rect(cv::Point(x0, y0), cv::Point(x1, y1)) & cv::Rect(cv::Point(), frame);
}

// The square of side `side` centred on `point`, clipped to the frame (so it stays centred on what was
// clicked, only smaller, near an edge). Empty when the point lies outside the frame, e.g. a click on a
// sink's letterbox border.
cv::Rect boxAround(const cv::Point2d &point, int side, cv::Size frame) {
  const cv::Rect frameRect(cv::Point(), frame);
  if (!(point.x >= 0 && point.y >= 0 && point.x < frame.width && point.y < frame.height)) return cv::Rect();
  const cv::Point topLeft(static_cast<int>(std::lround(point.x - side / 2.0)),
                          static_cast<int>(std::lround(point.y - side / 2.0)));
  return cv::Rect(topLeft, cv::Size(side, side)) & frameRect;
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------
// GObject

static void gst_color_track_reset_action(GstColorTrack *self) {
  GST_DEBUG_OBJECT(self, "reset requested");
  self->priv->resetRequested = true;
}

static void gst_color_track_set_property(GObject *object, guint prop_id, const GValue *value,
                                         GParamSpec *pspec) {
  GstColorTrack *self = GST_COLOR_TRACK(object);
  colortrack_gst::properties().set(GST_ELEMENT(self), GST_CAT_DEFAULT, storeOf(self), prop_id, value, pspec);
}

static void gst_color_track_get_property(GObject *object, guint prop_id, GValue *value, GParamSpec *pspec) {
  GstColorTrack *self = GST_COLOR_TRACK(object);
  colortrack_gst::properties().get(GST_ELEMENT(self), storeOf(self), prop_id, value, pspec);
}

static void gst_color_track_finalize(GObject *object) {
  GstColorTrack *self = GST_COLOR_TRACK(object);
  delete self->priv;
  self->priv = nullptr;
  G_OBJECT_CLASS(parent_class)->finalize(object);
}

// ---------------------------------------------------------------------------------------------------------
// Streaming

// The first value refused before start, in the order the checks have always run; empty when none. Call with
// the object lock held.
static std::string first_refusal(GstColorTrack *self) {
  const colortrack_gst::PropertyStore &store = storeOf(self);
  for (const char *name : colortrack_gst::kCheckedAtStart) {
    const GParamSpec *pspec = g_object_class_find_property(G_OBJECT_GET_CLASS(self), name);
    const auto refused = store.refused.find(pspec->param_id);
    if (refused != store.refused.end()) return refused->second;
  }
  return store.refused.empty() ? std::string() : store.refused.begin()->second;
}

// Validates what was set before streaming, loads the template file and creates the tracker.
static gboolean gst_color_track_start(GstBaseTransform *trans) {
  GstColorTrack *self = GST_COLOR_TRACK(trans);
  State &state = stateOf(self);

  GST_OBJECT_LOCK(self);
  const Snapshot snapshot = snapshotOf(storeOf(self));
  const std::string refusal = first_refusal(self);
  GST_OBJECT_UNLOCK(self);

  if (!refusal.empty()) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("%s", refusal.c_str()), (nullptr));
    return FALSE;
  }

  const std::string rangeError = colortrack::validateRange(snapshot.blobs.range);
  if (!rangeError.empty()) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Properties 'hsv-lower' '%s' and 'hsv-upper' '%s' do not make a range: %s",
                       snapshot.hsvLower.c_str(), snapshot.hsvUpper.c_str(), rangeError.c_str()),
                      (nullptr));
    return FALSE;
  }

  try {
    state = State{};
    state.tracker = std::make_unique<colortrack::Tracker>(snapshot.tracker);
    state.appliedTrackerGeneration = snapshot.trackerGeneration;
    state.appliedTemplateGeneration = snapshot.templateGeneration;
    state.blobDetector = std::make_unique<colortrack::BlobDetector>(snapshot.blobs);
    state.appliedBlobsGeneration = snapshot.blobsGeneration;
    state.appliedRangeGeneration = snapshot.rangeGeneration;
    // Threshold mode has no template: a template-location is not even read.
    if (snapshot.mode == GST_COLOR_TRACK_MODE_TEMPLATE && !snapshot.templateLocation.empty()) {
      cv::Mat bgr, mask;
      std::string why;
      bool missing = false;
      if (!loadTemplateFile(snapshot.templateLocation, bgr, mask, why, missing)) {
        if (missing)
          GST_ELEMENT_ERROR(self, RESOURCE, NOT_FOUND,
                            ("Template file '%s' (property 'template-location') does not exist.",
                             snapshot.templateLocation.c_str()),
                            ("%s", why.c_str()));
        else
          GST_ELEMENT_ERROR(self, RESOURCE, OPEN_READ,
                            ("Could not read the template image '%s' (property 'template-location'): %s",
                             snapshot.templateLocation.c_str(), why.c_str()),
                            (nullptr));
        state = State{};
        return FALSE;
      }
      if (const std::string problem = colortrack::templateSizeProblem(bgr.size()); !problem.empty()) {
        GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                          ("Cannot use the template image '%s' (property 'template-location'): %s.",
                           snapshot.templateLocation.c_str(), problem.c_str()),
                          (nullptr));
        state = State{};
        return FALSE;
      }
      state.tracker->setTemplate(bgr, mask);
      state.templateOrigin = "template-location '" + snapshot.templateLocation + "'";
    }
  } catch (const std::exception &e) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("Could not set up the tracker: %s", e.what()), (nullptr));
    state = State{};
    return FALSE;
  }

  GST_OBJECT_LOCK(self);
  storeOf(self).running = true;
  GST_OBJECT_UNLOCK(self);
  self->priv->resetRequested = false;
  return TRUE;
}

static gboolean gst_color_track_stop(GstBaseTransform *trans) {
  GstColorTrack *self = GST_COLOR_TRACK(trans);
  GST_OBJECT_LOCK(self);
  storeOf(self).running = false;
  GST_OBJECT_UNLOCK(self);
  stateOf(self) = State{};
  return TRUE;
}

static gboolean gst_color_track_set_info(GstVideoFilter *filter, GstCaps *, GstVideoInfo *in_info, GstCaps *,
                                         GstVideoInfo *) {
  GstColorTrack *self = GST_COLOR_TRACK(filter);
  if (!colortrack::isSupportedFormat(GST_VIDEO_INFO_FORMAT(in_info))) return FALSE;
  // Two fields woven into one frame move apart with the object: the tracker would see combed edges and a
  // doubled object. Said plainly instead of tracking badly.
  if (GST_VIDEO_INFO_IS_INTERLACED(in_info)) {
    GST_ELEMENT_ERROR(
        self, STREAM, FORMAT,
        ("Interlaced video is not supported: put a deinterlacer before colortrack, e.g. "
         "'deinterlace ! colortrack'."),
        ("interlace-mode %s", gst_video_interlace_mode_to_string(GST_VIDEO_INFO_INTERLACE_MODE(in_info))));
    return FALSE;
  }
  GST_DEBUG_OBJECT(self, "caps %dx%d %s", GST_VIDEO_INFO_WIDTH(in_info), GST_VIDEO_INFO_HEIGHT(in_info),
                   GST_VIDEO_INFO_NAME(in_info));
  // New geometry: positions and velocities no longer mean anything; the template stays.
  stateOf(self).capsChanged = true;
  GST_OBJECT_LOCK(self);
  storeOf(self).shared.frameSize = cv::Size(GST_VIDEO_INFO_WIDTH(in_info), GST_VIDEO_INFO_HEIGHT(in_info));
  GST_OBJECT_UNLOCK(self);
  return TRUE;
}

static gboolean gst_color_track_sink_event(GstBaseTransform *trans, GstEvent *event) {
  GstColorTrack *self = GST_COLOR_TRACK(trans);
  if (GST_EVENT_TYPE(event) == GST_EVENT_FLUSH_STOP || GST_EVENT_TYPE(event) == GST_EVENT_SEGMENT)
    stateOf(self).lastPts = GST_CLOCK_TIME_NONE;  // a seek: no meaningful time step to the next frame
  return GST_BASE_TRANSFORM_CLASS(parent_class)->sink_event(trans, event);
}

// Click to track: a mouse-button press travelling upstream from a video sink's window. Runs on whatever
// thread the sink sends it from, so it only records the request; the streaming thread applies it to the next
// frame. The coordinates are this element's frame coordinates: a videoscale between here and the sink maps
// them back in its own src_event.
static void handle_navigation(GstColorTrack *self, GstEvent *event) {
  if (gst_navigation_event_get_type(event) != GST_NAVIGATION_EVENT_MOUSE_BUTTON_PRESS) return;
  gint button = 0;
  gdouble x = 0, y = 0;
  if (!gst_navigation_event_parse_mouse_button_event(event, &button, &x, &y)) return;
  if (button != kLeftButton && button != kRightButton) return;

  GST_OBJECT_LOCK(self);
  colortrack_gst::PropertyStore &store = storeOf(self);
  const bool enabled = store.settings.clickToTrack;
  if (enabled) {
    ClickRequest click;
    click.kind = button == kLeftButton ? ClickRequest::Kind::Track : ClickRequest::Kind::Stop;
    click.point = cv::Point2d(x, y);
    store.shared.requests.click = click;
    // The latest request wins over an init-box that has not been used yet.
    if (store.shared.requests.initBox) {
      store.shared.requests.initBox.reset();
      store.settings.initBox.clear();
    }
  }
  GST_OBJECT_UNLOCK(self);
  if (enabled)
    GST_INFO_OBJECT(self, "mouse button %d pressed at %.1f,%.1f: %s on the next frame", button, x, y,
                    button == kLeftButton ? "tracking from there" : "stopping");
}

static gboolean gst_color_track_src_event(GstBaseTransform *trans, GstEvent *event) {
  if (GST_EVENT_TYPE(event) == GST_EVENT_NAVIGATION) handle_navigation(GST_COLOR_TRACK(trans), event);
  // Always forwarded: other elements upstream (a DVD menu, another filter) may want it too.
  return GST_BASE_TRANSFORM_CLASS(parent_class)->src_event(trans, event);
}

// Time since the previous frame in frame periods, 1 when the timestamps do not tell.
static double frame_step(GstColorTrack *self, GstVideoFilter *filter, GstBuffer *buffer) {
  State &state = stateOf(self);
  const GstClockTime pts = GST_BUFFER_PTS(buffer);
  const GstClockTime period = frameDuration(&filter->in_info, buffer);
  double dt = 1.0;
  if (GST_CLOCK_TIME_IS_VALID(pts) && GST_CLOCK_TIME_IS_VALID(state.lastPts) && pts > state.lastPts &&
      period > 0) {
    // Clamped: a long gap says nothing reliable about motion, and a tiny one is jitter.
    dt = std::clamp(static_cast<double>(pts - state.lastPts) / static_cast<double>(period), 0.25, 8.0);
  }
  state.lastPts = pts;
  return dt;
}

// One ROI meta of type "colortrack" with its params (on the meta and in the params meta, see track-params.h);
// `area` only in threshold mode.
static void attach_track_meta(GstBuffer *buffer, const cv::Rect &box, gint id, colortrack::TrackState state,
                              double score, bool verified, double scale, double vx, double vy,
                              const double *area = nullptr) {
  GstVideoRegionOfInterestMeta *meta = gst_buffer_add_video_region_of_interest_meta(
      buffer, "colortrack", static_cast<guint>(box.x), static_cast<guint>(box.y),
      static_cast<guint>(box.width), static_cast<guint>(box.height));
  meta->id = id;
  GstStructure *params = gst_structure_new("colortrack", "state", G_TYPE_STRING, colortrack::toString(state),
                                           "score", G_TYPE_DOUBLE, score, "verified", G_TYPE_BOOLEAN,
                                           static_cast<gboolean>(verified), "scale", G_TYPE_DOUBLE, scale,
                                           "vx", G_TYPE_DOUBLE, vx, "vy", G_TYPE_DOUBLE, vy, nullptr);
  if (area) gst_structure_set(params, "area", G_TYPE_DOUBLE, *area, nullptr);
  colortrack_add_roi_params(buffer, meta, params);
}

static void attach_meta(GstBuffer *buffer, const colortrack::TrackOutput &out, const cv::Rect &box) {
  attach_track_meta(buffer, box, out.id, out.state, out.score, out.verified, out.scale, out.vx, out.vy);
}

// `objects` (threshold mode) adds the "objects" field: a GST_TYPE_LIST of "colortrack-object" structures.
// `stateName` replaces the tracker's state (kIdleState after a right click).
static void post_track_message(GstColorTrack *self, GstBuffer *buffer, guint64 frame,
                               const colortrack::TrackOutput &out,
                               const std::vector<colortrack::TrackedObject> *objects = nullptr,
                               const char *stateName = nullptr) {
  const GstSegment *segment = &GST_BASE_TRANSFORM(self)->segment;
  const GstClockTime pts = GST_BUFFER_PTS(buffer);
  GstClockTime streamTime = GST_CLOCK_TIME_NONE, runningTime = GST_CLOCK_TIME_NONE;
  if (GST_CLOCK_TIME_IS_VALID(pts) && segment->format == GST_FORMAT_TIME) {
    streamTime = gst_segment_to_stream_time(segment, GST_FORMAT_TIME, pts);
    runningTime = gst_segment_to_running_time(segment, GST_FORMAT_TIME, pts);
  }
  const cv::Rect2d box = out.hasBox ? out.box : cv::Rect2d();
  GstStructure *s = gst_structure_new(
      "colortrack", "timestamp", G_TYPE_UINT64, static_cast<guint64>(pts), "stream-time", G_TYPE_UINT64,
      static_cast<guint64>(streamTime), "running-time", G_TYPE_UINT64, static_cast<guint64>(runningTime),
      "duration", G_TYPE_UINT64, static_cast<guint64>(GST_BUFFER_DURATION(buffer)), "frame", G_TYPE_UINT64,
      frame, "id", G_TYPE_INT, out.id, "state", G_TYPE_STRING,
      stateName ? stateName : colortrack::toString(out.state), "x", G_TYPE_DOUBLE, box.x, "y", G_TYPE_DOUBLE,
      box.y, "width", G_TYPE_DOUBLE, box.width, "height", G_TYPE_DOUBLE, box.height, "score", G_TYPE_DOUBLE,
      out.score, "verified", G_TYPE_BOOLEAN, static_cast<gboolean>(out.verified), "scale", G_TYPE_DOUBLE,
      out.scale, nullptr);
  if (objects) {
    GValue list = G_VALUE_INIT;
    g_value_init(&list, GST_TYPE_LIST);
    for (const colortrack::TrackedObject &o : *objects) {
      GValue item = G_VALUE_INIT;
      g_value_init(&item, GST_TYPE_STRUCTURE);
      GstStructure *object = gst_structure_new(
          "colortrack-object", "id", G_TYPE_INT, o.id, "x", G_TYPE_DOUBLE, o.box.x, "y", G_TYPE_DOUBLE,
          o.box.y, "width", G_TYPE_DOUBLE, o.box.width, "height", G_TYPE_DOUBLE, o.box.height, "cx",
          G_TYPE_DOUBLE, o.centre.x, "cy", G_TYPE_DOUBLE, o.centre.y, "area", G_TYPE_DOUBLE, o.area, "state",
          G_TYPE_STRING, colortrack::toString(o.state), "score", G_TYPE_DOUBLE, o.score, nullptr);
      gst_value_set_structure(&item, object);
      gst_structure_free(object);
      gst_value_list_append_and_take_value(&list, &item);
    }
    gst_structure_take_value(s, "objects", &list);
  }
  gst_element_post_message(GST_ELEMENT(self), gst_message_new_element(GST_OBJECT(self), s));
}

static void draw_overlay(GstVideoFrame *frame, const Settings &settings, const State &state,
                         const colortrack::TrackOutput &out, const cv::Rect &box) {
  if (settings.draw == 0) return;
  colortrack::FrameCanvas canvas(frame);
  if ((settings.draw & GST_COLOR_TRACK_DRAW_SEARCH_WINDOW) && !out.searchRegion.empty())
    canvas.boxOutline(out.searchRegion, colortrack::colors::kBlue, 1);
  if ((settings.draw & GST_COLOR_TRACK_DRAW_TRAIL) && state.trail.size() >= 2) {
    std::vector<cv::Point> points;
    points.reserve(state.trail.size());
    for (const cv::Point2d &p : state.trail) points.emplace_back(cvRound(p.x), cvRound(p.y));
    canvas.polyline(points, colortrack::colors::kYellow, kTrailThickness);
  }
  if (!out.hasBox || box.empty()) return;
  if (settings.draw & GST_COLOR_TRACK_DRAW_BOX) {
    const colortrack::Rgb colour = out.state == colortrack::TrackState::Coasting ? colortrack::colors::kOrange
                                   : out.verified                                ? colortrack::colors::kGreen
                                                                                 : colortrack::colors::kRed;
    canvas.boxOutline(box, colour, kBoxThickness);
  }
  if (settings.draw & GST_COLOR_TRACK_DRAW_LABEL) {
    char text[64];
    std::snprintf(text, sizeof text, "%d %.2f %s", out.id, out.score, colortrack::toString(out.state));
    canvas.label(text, cv::Point(box.x, box.y - 4));
  }
}

enum class InitBoxFit { Fits, Ignored, Error };

// An init-box that does not lie inside the frame: an element error before streaming, a warning (and the box
// ignored) when it was set while playing.
static InitBoxFit check_init_box(GstColorTrack *self, const cv::Rect &box, cv::Size frame,
                                 bool whileStreaming, const std::string &text) {
  if ((box & cv::Rect(cv::Point(), frame)) == box) return InitBoxFit::Fits;
  if (whileStreaming) {
    GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS,
                        ("Property 'init-box' '%s' does not fit in the %dx%d frame: ignored.", text.c_str(),
                         frame.width, frame.height),
                        (nullptr));
    return InitBoxFit::Ignored;
  }
  GST_ELEMENT_ERROR(
      self, RESOURCE, SETTINGS,
      ("Property 'init-box' '%s' does not fit in the %dx%d frame.", text.c_str(), frame.width, frame.height),
      (nullptr));
  return InitBoxFit::Error;
}

// Applies the settings snapshot to the tracker: everything that changed since the last frame.
// Returns false (after posting an error) when streaming must stop.
static bool apply_settings(GstColorTrack *self, const Snapshot &snapshot,
                           const std::optional<cv::Rect> &initBox, bool initBoxWhileStreaming,
                           const std::string &initBoxText, const colortrack::FrameView &view) {
  State &state = stateOf(self);
  colortrack::Tracker &tracker = *state.tracker;

  if (snapshot.trackerGeneration != state.appliedTrackerGeneration) {
    tracker.setSettings(snapshot.tracker);
    state.appliedTrackerGeneration = snapshot.trackerGeneration;
  }

  if (snapshot.templateGeneration != state.appliedTemplateGeneration) {
    state.appliedTemplateGeneration = snapshot.templateGeneration;
    if (!snapshot.templateLocation.empty()) {
      cv::Mat bgr, mask;
      std::string why;
      bool missing = false;
      if (loadTemplateFile(snapshot.templateLocation, bgr, mask, why, missing)) {
        tracker.setTemplate(bgr, mask);
        state.templateOrigin = "template-location '" + snapshot.templateLocation + "'";
        state.trail.clear();
        state.warnedNoTemplate = false;
        state.idle = false;
      } else {
        // Not fatal while streaming: the previous template keeps working.
        GST_ELEMENT_WARNING(self, RESOURCE, OPEN_READ,
                            ("Could not read the template image '%s' (property 'template-location'): %s. "
                             "Keeping the previous template.",
                             snapshot.templateLocation.c_str(), why.c_str()),
                            (missing ? "the file does not exist" : nullptr));
      }
    }
  }

  if (state.capsChanged || self->priv->resetRequested.exchange(false)) {
    state.capsChanged = false;
    tracker.reset();
    state.trail.clear();
  }

  if (initBox) {
    const InitBoxFit fit = check_init_box(self, *initBox, view.size(), initBoxWhileStreaming, initBoxText);
    if (fit == InitBoxFit::Error) return false;
    if (fit == InitBoxFit::Fits) {
      tracker.setTemplateFromBox(view, *initBox);
      state.templateOrigin = "init-box '" + initBoxText + "'";
      state.trail.clear();
      state.warnedNoTemplate = false;
      state.idle = false;
    }
  }
  return true;
}

static std::string describeClick(const ClickRequest &click, const cv::Rect &box) {
  char text[96];
  std::snprintf(text, sizeof text, "the click at %.0f,%.0f (box %d,%d,%d,%d)", click.point.x, click.point.y,
                box.x, box.y, box.width, box.height);
  return text;
}

// Template mode: a left click takes the template from the box around it and starts tracking there, exactly
// as init-box does; a right click stops until a new target is given.
static void apply_click(GstColorTrack *self, const ClickRequest &click, int boxSize,
                        const colortrack::FrameView &view) {
  State &state = stateOf(self);
  if (click.kind == ClickRequest::Kind::Stop) {
    state.tracker->reset();
    state.trail.clear();
    state.idle = true;
    return;
  }
  const cv::Rect box = boxAround(click.point, boxSize, view.size());
  if (box.empty()) {
    GST_INFO_OBJECT(self, "click at %.1f,%.1f lies outside the %dx%d frame: ignored", click.point.x,
                    click.point.y, view.size().width, view.size().height);
    return;
  }
  state.tracker->setTemplateFromBox(view, box);
  state.templateOrigin = describeClick(click, box);
  state.trail.clear();
  state.warnedNoTemplate = false;
  state.idle = false;
  GST_INFO_OBJECT(self, "template from %s", state.templateOrigin.c_str());
}

// ---------------------------------------------------------------------------------------------------------
// Threshold mode

// The frame's bytes described channel by channel, so the segmentation reads any supported format in place
// (YUV through a YUV lookup table) instead of converting the whole frame to BGR first.
static colortrack::SampledFrame sampled_frame(const GstVideoFrame *frame) {
  const int w = GST_VIDEO_FRAME_WIDTH(frame), h = GST_VIDEO_FRAME_HEIGHT(frame);
  const int cw = (w + 1) / 2, ch = (h + 1) / 2;
  const auto bytes = [frame](int plane, int rows, int rowBytes) {
    return cv::Mat(rows, rowBytes, CV_8UC1, GST_VIDEO_FRAME_PLANE_DATA(frame, plane),
                   static_cast<size_t>(GST_VIDEO_FRAME_PLANE_STRIDE(frame, plane)));
  };
  colortrack::SampledFrame out;
  out.size = cv::Size(w, h);
  out.encoding = colortrack::PixelEncoding::Yuv601;
  switch (GST_VIDEO_FRAME_FORMAT(frame)) {
    case GST_VIDEO_FORMAT_I420:
      out.channels = {colortrack::ChannelSampler{bytes(0, h, w), 0, 1, 1, 1},
                      colortrack::ChannelSampler{bytes(1, ch, cw), 0, 1, 2, 2},
                      colortrack::ChannelSampler{bytes(2, ch, cw), 0, 1, 2, 2}};
      break;
    case GST_VIDEO_FORMAT_NV12: {
      const cv::Mat uv = bytes(1, ch, 2 * cw);
      out.channels = {colortrack::ChannelSampler{bytes(0, h, w), 0, 1, 1, 1},
                      colortrack::ChannelSampler{uv, 0, 2, 2, 2}, colortrack::ChannelSampler{uv, 1, 2, 2, 2}};
      break;
    }
    case GST_VIDEO_FORMAT_YUY2: {
      const cv::Mat packed = bytes(0, h, 4 * cw);  // Y0 U Y1 V per two pixels
      out.channels = {colortrack::ChannelSampler{packed, 0, 2, 1, 1},
                      colortrack::ChannelSampler{packed, 1, 4, 2, 1},
                      colortrack::ChannelSampler{packed, 3, 4, 2, 1}};
      break;
    }
    default: {
      const colortrack::PackedLayout layout = colortrack::packedLayout(frame->info.finfo);
      const cv::Mat packed = bytes(0, h, w * layout.pixelBytes);
      out.encoding = colortrack::PixelEncoding::Rgb;
      out.channels = {colortrack::ChannelSampler{packed, layout.red, layout.pixelBytes, 1, 1},
                      colortrack::ChannelSampler{packed, layout.green, layout.pixelBytes, 1, 1},
                      colortrack::ChannelSampler{packed, layout.blue, layout.pixelBytes, 1, 1}};
      break;
    }
  }
  return out;
}

static colortrack::MultiTrackerSettings multi_tracker_settings(const Settings &settings) {
  colortrack::MultiTrackerSettings m;
  m.kalman = settings.tracker.kalman;
  m.maxCoastFrames = settings.tracker.maxCoastFrames;
  return m;
}

// The primary target (largest reported track) in the single-target shape of template mode.
static colortrack::TrackOutput primary_output(const std::vector<colortrack::TrackedObject> &objects) {
  colortrack::TrackOutput out;
  const int primary = colortrack::primaryIndex(objects);
  if (primary < 0) return out;  // searching, no box
  const colortrack::TrackedObject &o = objects[primary];
  out.state = o.state;
  out.hasBox = true;
  out.id = o.id;
  out.box = o.box;
  out.score = o.score;
  out.verified = true;  // no edge check in threshold mode
  out.scale = o.scale;
  out.vx = o.vx;
  out.vy = o.vy;
  return out;
}

static void attach_object_meta(GstBuffer *buffer, const colortrack::TrackedObject &o, const cv::Rect &box) {
  // Blobs are found by colour alone; there is no edge check in threshold mode.
  attach_track_meta(buffer, box, o.id, o.state, o.score, true, o.scale, o.vx, o.vy, &o.area);
}

static void draw_threshold_overlay(GstVideoFrame *frame, const Settings &settings, const State &state,
                                   const std::vector<colortrack::TrackedObject> &objects,
                                   const std::vector<cv::Rect> &boxes) {
  if (settings.draw == 0) return;
  colortrack::FrameCanvas canvas(frame);
  if (settings.draw & GST_COLOR_TRACK_DRAW_MASK)
    canvas.tintMask(state.blobDetector->mask(), state.blobDetector->lastDecimation(),
                    colortrack::colors::kMagenta);
  for (size_t i = 0; i < objects.size(); ++i) {
    const colortrack::TrackedObject &o = objects[i];
    const colortrack::Rgb colour = colortrack::idColour(o.id);
    const auto trail = state.trails.find(o.id);
    if ((settings.draw & GST_COLOR_TRACK_DRAW_TRAIL) && trail != state.trails.end() &&
        trail->second.size() >= 2) {
      std::vector<cv::Point> points;
      for (const cv::Point2d &p : trail->second) points.emplace_back(cvRound(p.x), cvRound(p.y));
      canvas.polyline(points, colour, kTrailThickness);
    }
    if (boxes[i].empty()) continue;
    // Coasting tracks get a thin outline: the id colour says who, the weight says how sure.
    if (settings.draw & GST_COLOR_TRACK_DRAW_BOX)
      canvas.boxOutline(boxes[i], colour, o.state == colortrack::TrackState::Coasting ? 1 : kBoxThickness);
    if (settings.draw & GST_COLOR_TRACK_DRAW_LABEL) {
      char text[64];
      std::snprintf(text, sizeof text, "%d %.0f %s", o.id, o.area, colortrack::toString(o.state));
      canvas.label(text, cv::Point(boxes[i].x, boxes[i].y - 4));
    }
  }
}

// Learns hsv-lower/hsv-upper from the pixels of `box` (init-box or a click) and starts over with that range;
// the properties then report it, so it can be reused in a launch line.
static void learn_range(GstColorTrack *self, GstVideoFrame *frame, const cv::Rect &box,
                        const std::string &origin) {
  State &state = stateOf(self);
  const colortrack::HsvRange learnt = colortrack::learnRange(colortrack::FrameView(frame), box);
  GST_OBJECT_LOCK(self);
  colortrack_gst::PropertyStore &store = storeOf(self);
  Settings &shared = store.settings;
  shared.blobs.range = learnt;
  shared.hsvLower = colortrack::formatHsv(learnt.lower);
  shared.hsvUpper = colortrack::formatHsv(learnt.upper);
  const colortrack::BlobSettings blobs = shared.blobs;
  state.appliedBlobsGeneration = ++store.versions[colortrack_gst::kBlobsVersion];
  GST_OBJECT_UNLOCK(self);
  state.blobDetector->setSettings(blobs);
  state.multiTracker.reset();
  state.trails.clear();
  state.idle = false;
  GST_INFO_OBJECT(self, "learnt hsv-lower %s hsv-upper %s from %s",
                  colortrack::formatHsv(learnt.lower).c_str(), colortrack::formatHsv(learnt.upper).c_str(),
                  origin.c_str());
  g_object_notify(G_OBJECT(self), "hsv-lower");
  g_object_notify(G_OBJECT(self), "hsv-upper");
}

// Trails are kept per id; those of tracks that ended go.
static void drop_ended_trails(State &state, const std::vector<colortrack::TrackedObject> &objects) {
  for (auto it = state.trails.begin(); it != state.trails.end();) {
    const bool alive = std::any_of(objects.begin(), objects.end(),
                                   [&](const colortrack::TrackedObject &o) { return o.id == it->first; });
    it = alive ? std::next(it) : state.trails.erase(it);
  }
}

// One frame in threshold mode: segment, clean, label, associate; meta, overlay and message per track.
static GstFlowReturn threshold_frame(GstColorTrack *self, GstVideoFrame *frame, const Snapshot &snapshot,
                                     const colortrack_gst::Requests &requests, guint64 frameNumber,
                                     double dt) {
  const std::optional<cv::Rect> &initBox = requests.initBox;
  const std::optional<ClickRequest> &click = requests.click;
  State &state = stateOf(self);
  const cv::Size size(GST_VIDEO_FRAME_WIDTH(frame), GST_VIDEO_FRAME_HEIGHT(frame));
  colortrack::BlobDetector &detector = *state.blobDetector;

  if (snapshot.blobs.minArea > size.area()) {
    GST_ELEMENT_ERROR(
        self, RESOURCE, SETTINGS,
        ("Property 'min-area' %d is larger than the %dx%d frame (%d pixels): nothing can be found.",
         snapshot.blobs.minArea, size.width, size.height, size.area()),
        (nullptr));
    return GST_FLOW_ERROR;
  }
  if (snapshot.blobsGeneration != state.appliedBlobsGeneration) {
    detector.setSettings(snapshot.blobs);
    state.appliedBlobsGeneration = snapshot.blobsGeneration;
  }
  if (snapshot.rangeGeneration != state.appliedRangeGeneration) {
    state.appliedRangeGeneration = snapshot.rangeGeneration;
    state.idle = false;  // a new range is a new target
  }
  state.multiTracker.setSettings(multi_tracker_settings(snapshot));
  if (state.capsChanged || self->priv->resetRequested.exchange(false)) {
    state.capsChanged = false;
    state.multiTracker.reset();
    state.trails.clear();
  }

  if (initBox) {
    const InitBoxFit fit =
        check_init_box(self, *initBox, size, requests.initBoxWhileStreaming, snapshot.initBox);
    if (fit == InitBoxFit::Error) return GST_FLOW_ERROR;
    if (fit == InitBoxFit::Fits) learn_range(self, frame, *initBox, "init-box " + snapshot.initBox);
  }

  if (click && click->kind == ClickRequest::Kind::Stop) {
    state.multiTracker.reset();
    state.trails.clear();
    state.idle = true;
  } else if (click) {
    // The colour is sampled from the middle half of the box: a click lands near an object's centre, and a
    // sample that reached past a small object's edge would learn the background's colours too.
    const cv::Rect sample = boxAround(click->point, std::max(1, snapshot.clickBoxSize / 2), size);
    if (sample.empty())
      GST_INFO_OBJECT(self, "click at %.1f,%.1f lies outside the %dx%d frame: ignored", click->point.x,
                      click->point.y, size.width, size.height);
    else
      learn_range(self, frame, sample, describeClick(*click, sample));
  }

  if (state.idle) {
    if (snapshot.postMessages) {
      const std::vector<colortrack::TrackedObject> none;
      post_track_message(self, frame->buffer, frameNumber, colortrack::TrackOutput(), &none, kIdleState);
    }
    return GST_FLOW_OK;
  }

  const std::vector<colortrack::Blob> blobs = detector.detect(sampled_frame(frame));
  const std::vector<colortrack::TrackedObject> objects = state.multiTracker.update(blobs, size, dt);

  drop_ended_trails(state, objects);
  std::vector<cv::Rect> boxes;
  for (const colortrack::TrackedObject &o : objects) {
    if (snapshot.trailLength > 0) {
      std::deque<cv::Point2d> &trail = state.trails[o.id];
      trail.push_back(o.centre);
      while (trail.size() > snapshot.trailLength) trail.pop_front();
    }
    boxes.push_back(roundedClippedBox(o.box, size));
    if (!boxes.back().empty()) attach_object_meta(frame->buffer, o, boxes.back());
  }
  draw_threshold_overlay(frame, snapshot, state, objects, boxes);
  if (snapshot.postMessages)
    post_track_message(self, frame->buffer, frameNumber, primary_output(objects), &objects);
  return GST_FLOW_OK;
}

// The settings for this frame and the requests waiting for it (taken: one use only).
static Snapshot take_frame_inputs(GstColorTrack *self, colortrack_gst::Requests &requests) {
  GST_OBJECT_LOCK(self);
  colortrack_gst::PropertyStore &store = storeOf(self);
  const Snapshot snapshot = snapshotOf(store);
  requests = std::exchange(store.shared.requests, {});
  if (requests.initBox) store.settings.initBox.clear();  // init-box reads back empty once used
  GST_OBJECT_UNLOCK(self);
  return snapshot;
}

static GstFlowReturn gst_color_track_transform_frame_ip(GstVideoFilter *filter, GstVideoFrame *frame) {
  GstColorTrack *self = GST_COLOR_TRACK(filter);
  State &state = stateOf(self);
  GstBuffer *buffer = frame->buffer;

  // Snapshot of the settings; the init-box is taken (one use only).
  colortrack_gst::Requests requests;
  const Snapshot snapshot = take_frame_inputs(self, requests);
  const std::optional<cv::Rect> &initBox = requests.initBox;
  const std::optional<ClickRequest> &click = requests.click;

  const guint64 frameNumber = state.frameCount++;
  const double dt = frame_step(self, filter, buffer);

  try {
    if (!state.tracker || !state.blobDetector) {
      GST_ELEMENT_ERROR(self, CORE, FAILED, ("colortrack was not started."), (nullptr));
      return GST_FLOW_ERROR;
    }
    if (snapshot.mode == GST_COLOR_TRACK_MODE_THRESHOLD)
      return threshold_frame(self, frame, snapshot, requests, frameNumber, dt);
    const colortrack::FrameView view(frame);
    if (!apply_settings(self, snapshot, initBox, requests.initBoxWhileStreaming, snapshot.initBox, view))
      return GST_FLOW_ERROR;
    if (click) apply_click(self, *click, snapshot.clickBoxSize, view);

    if (state.idle) {
      if (snapshot.postMessages)
        post_track_message(self, buffer, frameNumber, colortrack::TrackOutput(), nullptr, kIdleState);
      return GST_FLOW_OK;
    }

    colortrack::Tracker &tracker = *state.tracker;
    if (!tracker.hasTemplate()) {
      if (!state.warnedNoTemplate) {
        state.warnedNoTemplate = true;
        GST_ELEMENT_WARNING(self, RESOURCE, SETTINGS,
                            ("No template: set 'template-location' or 'init-box', or click the object in the "
                             "video window. Passing video through."),
                            (nullptr));
      }
      // Messages still come for every frame (an application waiting for a click sees "searching").
      if (snapshot.postMessages) post_track_message(self, buffer, frameNumber, colortrack::TrackOutput());
      return GST_FLOW_OK;
    }

    const cv::Size templateSize = tracker.templateSize();
    if (templateSize.width > view.size().width || templateSize.height > view.size().height) {
      GST_ELEMENT_ERROR(
          self, RESOURCE, SETTINGS,
          ("The template from %s (%dx%d) is larger than the %dx%d frame.", state.templateOrigin.c_str(),
           templateSize.width, templateSize.height, view.size().width, view.size().height),
          (nullptr));
      return GST_FLOW_ERROR;
    }

    const colortrack::TrackOutput out = tracker.process(view, dt);

    if (!out.hasBox || out.id != state.trailTrackId) state.trail.clear();
    state.trailTrackId = out.id;
    if (out.hasBox && snapshot.trailLength > 0) {
      state.trail.emplace_back(out.box.x + out.box.width / 2, out.box.y + out.box.height / 2);
      while (state.trail.size() > snapshot.trailLength) state.trail.pop_front();
    }

    const cv::Rect box = out.hasBox ? roundedClippedBox(out.box, view.size()) : cv::Rect();
    if (out.hasBox && !box.empty()) attach_meta(buffer, out, box);
    draw_overlay(frame, snapshot, state, out, box);
    if (snapshot.postMessages) post_track_message(self, buffer, frameNumber, out);
    return GST_FLOW_OK;
  } catch (const colortrack::TrackerError &e) {
    GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Tracking failed: %s", e.what()), (nullptr));
  } catch (const cv::Exception &e) {
    GST_ELEMENT_ERROR(self, STREAM, FAILED, ("OpenCV error while tracking"), ("%s", e.what()));
  } catch (const std::exception &e) {
    GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Error while tracking: %s", e.what()), (nullptr));
  }
  return GST_FLOW_ERROR;
}

// ---------------------------------------------------------------------------------------------------------
// Class

static void gst_color_track_class_init(GstColorTrackClass *klass) {
  GObjectClass *gobject_class = G_OBJECT_CLASS(klass);
  GstElementClass *element_class = GST_ELEMENT_CLASS(klass);
  GstBaseTransformClass *trans_class = GST_BASE_TRANSFORM_CLASS(klass);
  GstVideoFilterClass *filter_class = GST_VIDEO_FILTER_CLASS(klass);

  GST_DEBUG_CATEGORY_INIT(gst_color_track_debug, "colortrack", 0, "Colour-indexing object tracker");

  gobject_class->set_property = gst_color_track_set_property;
  gobject_class->get_property = gst_color_track_get_property;
  gobject_class->finalize = gst_color_track_finalize;

  colortrack_gst::properties().install(gobject_class);

  /**
   * GstColorTrack::reset:
   * @colortrack: the element
   *
   * Forgets the track (the template stays): the next frame searches the whole frame. After a right click
   * (see #GstColorTrack:click-to-track) there is no target and the element stays idle.
   */
  gst_color_track_signals[SIGNAL_RESET] = g_signal_new(
      "reset", G_TYPE_FROM_CLASS(klass), static_cast<GSignalFlags>(G_SIGNAL_RUN_LAST | G_SIGNAL_ACTION),
      G_STRUCT_OFFSET(GstColorTrackClass, reset), nullptr, nullptr, nullptr, G_TYPE_NONE, 0);
  klass->reset = gst_color_track_reset_action;

  gst_element_class_set_static_metadata(element_class, "Colour object tracker", "Filter/Analyzer/Video",
                                        "Tracks a coloured object by modified colour indexing with a Kalman "
                                        "filter; attaches region-of-interest meta and draws the track",
                                        "colortrack developers");
  gst_element_class_add_static_pad_template(element_class, &sink_template);
  gst_element_class_add_static_pad_template(element_class, &src_template);

  trans_class->start = GST_DEBUG_FUNCPTR(gst_color_track_start);
  trans_class->stop = GST_DEBUG_FUNCPTR(gst_color_track_stop);
  trans_class->sink_event = GST_DEBUG_FUNCPTR(gst_color_track_sink_event);
  trans_class->src_event = GST_DEBUG_FUNCPTR(gst_color_track_src_event);
  filter_class->set_info = GST_DEBUG_FUNCPTR(gst_color_track_set_info);
  filter_class->transform_frame_ip = GST_DEBUG_FUNCPTR(gst_color_track_transform_frame_ip);

  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_MODE, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_COLOR_SPACE, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_VERIFY, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_METHOD, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_DRAW, static_cast<GstPluginAPIFlags>(0));
}

static void gst_color_track_init(GstColorTrack *self) {
  self->priv = new GstColorTrackPrivate();
}
