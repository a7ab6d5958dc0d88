// SPDX-License-Identifier: LGPL-2.1-or-later
/**
 * SECTION:element-colortrack
 * @title: colortrack
 *
 * Tracks one object through a video. The default #GstColorTrack:method, fused, finds it with a correlation
 * filter on its shape fused with a colour likelihood, sizes it with a scale filter, reports how confident
 * each frame is (a frame under half the track's usual confidence, or with a look-alike in the search window
 * answering nearly as well, is not a detection: the track coasts at its best guess) and re-detects it over
 * the whole frame once lost. method=indexing is the paper's modified
 * colour indexing: a template gives per-channel histograms (HSV by default), a window slides over a search
 * region around the Kalman prediction and the best histogram intersection wins, its size refined between
 * #GstColorTrack:scale-min and #GstColorTrack:scale-max. With every method an edge density/energy check
 * marks same-coloured but untextured look-alikes as unverified. With #GstColorTrack:mode threshold, every
 * blob of an HSV range is followed instead, each with its own id.
 *
 * The template comes from an image file (#GstColorTrack:template-location, PNG alpha selects the object's
 * pixels) or from a box of the next frame (#GstColorTrack:init-box). Without either, buffers pass through
 * untouched and a warning is posted once.
 *
 * Every buffer with a track carries a #GstVideoRegionOfInterestMeta of type "colortrack" whose id is the
 * track id and whose "colortrack" parameter structure holds state (string), score, scale, vx, vy (double)
 * and verified (boolean). The meta follows the frame through videoconvert and videoscale, which scales its
 * box (GStreamer 1.22's transform of this meta drops the parameter structure, so each buffer also carries a
 * "GstColorTrackParamsMeta" custom meta with every track's parameters under "id-<track id>.<element name>",
 * and under "id-<track id>" for the first element that reports that id, which survives those elements). With
 * #GstColorTrack:post-messages, an element message "colortrack" is posted for every frame with timestamp,
 * stream-time, running-time, duration, frame, state, x, y, width, height, score, verified and scale.
 *
 * The overlay (#GstColorTrack:draw) shows the box in red for a colour-only match, green when verified and
 * orange while coasting, the path of the box centre in yellow, the search window in blue and an "id score
 * state" label. YUV input is read with the matrix and range its caps' colorimetry name (BT.601 when none
 * is given, as videoconvert assumes); the overlay is drawn into YUV with BT.601.
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
#include "property-table.h"

#include <algorithm>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <opencv2/core.hpp>

#include "colortrack/blobs.hpp"
#include "colortrack/detection_method.hpp"
#include "colortrack/edges.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/tracker.hpp"
#include "colortrack-meta.h"
#include "colortrack-element-link.h"
#include "colortrack-mode.h"
#include "colortrack-preset.h"
#include "colortrack-settings.h"
#include "colortrack-state.h"
#include "frame-view.h"
#include "track-overlay.h"
#include "track-report.h"

GST_DEBUG_CATEGORY(gst_color_track_debug);
#define GST_CAT_DEFAULT gst_color_track_debug

namespace {

using colortrack_gst::ClickRequest;
using colortrack_gst::Settings;
using colortrack_gst::Snapshot;
using colortrack_gst::State;

constexpr int kLeftButton = 1, kRightButton = 3;

}  // namespace

enum { SIGNAL_RESET, LAST_SIGNAL };
static guint gst_color_track_signals[LAST_SIGNAL] = {0};

// Progressive only: a field-interleaved frame is two moments in time, and the tracker needs one.
#define VIDEO_CAPS GST_VIDEO_CAPS_MAKE(COLORTRACK_VIDEO_FORMATS) ", interlace-mode = (string) progressive"

static GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS(VIDEO_CAPS));
static GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS(VIDEO_CAPS));

#define gst_color_track_parent_class parent_class
// GstPreset: GStreamer's default implementation (presets in GstColorTrack.prs), with colortrack's own list of
// saved properties (colortrack-preset.cpp).
G_DEFINE_TYPE_WITH_CODE(GstColorTrack, gst_color_track, GST_TYPE_VIDEO_FILTER,
                        G_IMPLEMENT_INTERFACE(GST_TYPE_PRESET, gst_color_track_preset_init));
GST_ELEMENT_REGISTER_DEFINE(colortrack, "colortrack", GST_RANK_NONE, GST_TYPE_COLOR_TRACK);

// ---------------------------------------------------------------------------------------------------------
// Helpers

namespace {

colortrack_gst::ElementCore &coreOf(GstColorTrack *self) {
  return self->priv->core;
}
// Call with the object lock held.
colortrack_gst::PropertyStore &storeOf(GstColorTrack *self) {
  return coreOf(self).store();
}

State &stateOf(GstColorTrack *self) {
  return self->priv->state;
}

// Frame duration in nanoseconds, from the caps' frame rate or the buffer's duration (0 when unknown).
GstClockTime frameDuration(const GstVideoInfo *info, GstBuffer *buffer) {
  if (GST_VIDEO_INFO_FPS_N(info) > 0 && GST_VIDEO_INFO_FPS_D(info) > 0)
    return gst_util_uint64_scale_int(GST_SECOND, GST_VIDEO_INFO_FPS_D(info), GST_VIDEO_INFO_FPS_N(info));
  if (GST_BUFFER_DURATION_IS_VALID(buffer)) return GST_BUFFER_DURATION(buffer);
  return 0;
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
  coreOf(self).set(prop_id, value, pspec);
}

static void gst_color_track_get_property(GObject *object, guint prop_id, GValue *value, GParamSpec *pspec) {
  GstColorTrack *self = GST_COLOR_TRACK(object);
  coreOf(self).get(prop_id, value, pspec);
}

static void gst_color_track_finalize(GObject *object) {
  GstColorTrack *self = GST_COLOR_TRACK(object);
  delete self->priv;
  self->priv = nullptr;
  G_OBJECT_CLASS(parent_class)->finalize(object);
}

// ---------------------------------------------------------------------------------------------------------
// Streaming

// What was set before streaming is judged by the element core; then the tracker is made, with the mode's
// template file.
static gboolean gst_color_track_start(GstBaseTransform *trans) {
  GstColorTrack *self = GST_COLOR_TRACK(trans);
  State &state = stateOf(self);
  const std::optional<Settings> settings = coreOf(self).start();
  if (!settings) return FALSE;
  Snapshot snapshot;
  static_cast<Settings &>(snapshot) = *settings;
  try {
    state = State{};
    colortrack::startWorkerThreads();  // here rather than on the first frame
    auto link = std::make_unique<colortrack_gst::ElementLink>(GST_ELEMENT(self), self->priv);
    state.mode = colortrack_gst::makeMode(snapshot.mode, std::move(link));
    if (state.mode->start(snapshot)) {
      self->priv->resetRequested = false;
      return TRUE;
    }
  } catch (const std::exception &e) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("Could not set up the tracker: %s", e.what()), (nullptr));
  }
  state = State{};
  coreOf(self).stop();
  return FALSE;
}

static gboolean gst_color_track_stop(GstBaseTransform *trans) {
  GST_COLOR_TRACK(trans)->priv->core.stop();
  stateOf(GST_COLOR_TRACK(trans)) = State{};
  return TRUE;
}

static gboolean gst_color_track_set_info(GstVideoFilter *filter, GstCaps *, GstVideoInfo *in_info, GstCaps *,
                                         GstVideoInfo *) {
  GstColorTrack *self = GST_COLOR_TRACK(filter);
  if (!colortrack_gst::isSupportedFormat(GST_VIDEO_INFO_FORMAT(in_info))) return FALSE;
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

// The settings for this frame and the requests waiting for it (taken: one use only).
static Snapshot take_frame_inputs(GstColorTrack *self, colortrack_gst::Requests &requests) {
  GST_OBJECT_LOCK(self);
  colortrack_gst::PropertyStore &store = storeOf(self);
  Snapshot snapshot;
  static_cast<Settings &>(snapshot) = store.settings;
  snapshot.changed = coreOf(self).takeChanges();
  requests = std::exchange(store.shared.requests, {});
  if (requests.initBox) store.settings.initBox.clear();  // init-box reads back empty once used
  GST_OBJECT_UNLOCK(self);
  return snapshot;
}

// Tells the pipeline what `report` holds: meta on the buffer, the overlay, the message.
static void report_frame(GstColorTrack *self, GstVideoFrame *frame, const Snapshot &snapshot,
                         guint64 frameNumber, const colortrack::FrameReport &report) {
  State &state = stateOf(self);
  const cv::Size size(GST_VIDEO_FRAME_WIDTH(frame), GST_VIDEO_FRAME_HEIGHT(frame));
  state.trails.update(report.tracks, snapshot.trailLength);
  for (const colortrack::TrackReport &track : report.tracks)
    colortrack_gst::attachTrackMeta(GST_ELEMENT(self), frame->buffer, track, size);
  state.analytics.attach(frame->buffer, report, size);
  colortrack_gst::OverlayParts parts;
  parts.box = snapshot.draw & GST_COLOR_TRACK_DRAW_BOX;
  parts.trail = snapshot.draw & GST_COLOR_TRACK_DRAW_TRAIL;
  parts.searchWindow = snapshot.draw & GST_COLOR_TRACK_DRAW_SEARCH_WINDOW;
  parts.label = snapshot.draw & GST_COLOR_TRACK_DRAW_LABEL;
  parts.mask = snapshot.draw & GST_COLOR_TRACK_DRAW_MASK;
  colortrack_gst::drawTracks(frame, report, state.trails, parts);
  if (snapshot.postMessages)
    colortrack_gst::postTrackMessage(GST_ELEMENT(self), GST_BASE_TRANSFORM(self)->segment, frame->buffer,
                                     frameNumber, report);
}

// One frame, either mode: the mode brings its tracker up to date, the tracker reports, the report goes out.
static GstFlowReturn track_frame(GstColorTrack *self, GstVideoFrame *frame, const Snapshot &snapshot,
                                 const colortrack_gst::Requests &requests, guint64 frameNumber, double dt) {
  State &state = stateOf(self);
  const colortrack_gst::FrameView view(frame, &state.frameCache);
  colortrack_gst::Mode &mode = *state.mode;
  if (!mode.prepare(snapshot, requests, view)) return GST_FLOW_ERROR;

  // No track, but messages still come for every frame (an application waiting for a click sees why).
  colortrack::FrameReport empty;
  empty.listsTracks = mode.listsTracks();
  if (state.idle) {
    state.analytics.attach(frame->buffer, empty, view.size());  // the tracks stopped by the click: lost
    if (snapshot.postMessages)
      colortrack_gst::postTrackMessage(GST_ELEMENT(self), GST_BASE_TRANSFORM(self)->segment, frame->buffer,
                                       frameNumber, empty, COLORTRACK_STATE_IDLE);
    return GST_FLOW_OK;
  }
  switch (mode.readiness(view.size())) {
    case colortrack_gst::Mode::Readiness::Ready:
      break;
    case colortrack_gst::Mode::Readiness::Waiting:
      if (snapshot.postMessages)
        colortrack_gst::postTrackMessage(GST_ELEMENT(self), GST_BASE_TRANSFORM(self)->segment, frame->buffer,
                                         frameNumber, empty);
      return GST_FLOW_OK;
    case colortrack_gst::Mode::Readiness::Error:
      return GST_FLOW_ERROR;
  }
  report_frame(self, frame, snapshot, frameNumber, mode.tracker().track(view, dt));
  return GST_FLOW_OK;
}

static GstFlowReturn track_mapped_frame(GstColorTrack *self, GstVideoFrame *frame, const Snapshot &snapshot,
                                        const colortrack_gst::Requests &requests) {
  State &state = stateOf(self);
  const guint64 frameNumber = state.frameCount++;
  const double dt = frame_step(self, GST_VIDEO_FILTER(self), frame->buffer);
  try {
    if (!state.mode) {
      GST_ELEMENT_ERROR(self, CORE, FAILED, ("colortrack was not started."), (nullptr));
      return GST_FLOW_ERROR;
    }
    return track_frame(self, frame, snapshot, requests, frameNumber, dt);
  } catch (const colortrack::TrackerError &e) {
    GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Tracking failed: %s", e.what()), (nullptr));
  } catch (const cv::Exception &e) {
    GST_ELEMENT_ERROR(self, STREAM, FAILED, ("OpenCV error while tracking"), ("%s", e.what()));
  } catch (const std::exception &e) {
    GST_ELEMENT_ERROR(self, STREAM, FAILED, ("Error while tracking: %s", e.what()), (nullptr));
  }
  return GST_FLOW_ERROR;
}

// In place of GstVideoFilter's, which maps every frame for writing: a buffer whose memory is shared (behind
// a tee) is then copied whole. Only the overlay writes pixels; the metadata needs a writable buffer, which
// the base class gives without copying the memory. So with draw=none the frame is mapped for reading only.
static GstFlowReturn gst_color_track_transform_ip(GstBaseTransform *trans, GstBuffer *buffer) {
  GstColorTrack *self = GST_COLOR_TRACK(trans);
  GstVideoFilter *filter = GST_VIDEO_FILTER(trans);
  if (!filter->negotiated) {
    GST_ELEMENT_ERROR(self, CORE, NEGOTIATION, (nullptr), ("unknown format"));
    return GST_FLOW_NOT_NEGOTIATED;
  }
  colortrack_gst::Requests requests;
  const Snapshot snapshot = take_frame_inputs(self, requests);
  // NO_REF: a frame's own reference would make the buffer read-only for the metadata.
  const int access = (snapshot.draw == GST_COLOR_TRACK_DRAW_NONE ? GST_MAP_READ : GST_MAP_READWRITE) |
                     GST_VIDEO_FRAME_MAP_FLAG_NO_REF;
  GstVideoFrame frame;
  if (!gst_video_frame_map(&frame, &filter->in_info, buffer, static_cast<GstMapFlags>(access))) {
    GST_ELEMENT_ERROR(self, CORE, FAILED, ("Cannot map the video frame."), ("invalid buffer"));
    return GST_FLOW_ERROR;
  }
  const GstFlowReturn result = track_mapped_frame(self, &frame, snapshot, requests);
  gst_video_frame_unmap(&frame);
  return result;
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
                                        "Tracks a coloured object (template mode: colour likelihood and "
                                        "correlation filters, or the paper's modified colour indexing; "
                                        "threshold mode: every blob in an HSV range) with a Kalman filter; "
                                        "attaches region-of-interest meta and draws the track",
                                        "colortrack developers");
  gst_element_class_add_static_pad_template(element_class, &sink_template);
  gst_element_class_add_static_pad_template(element_class, &src_template);

  trans_class->start = GST_DEBUG_FUNCPTR(gst_color_track_start);
  trans_class->stop = GST_DEBUG_FUNCPTR(gst_color_track_stop);
  trans_class->sink_event = GST_DEBUG_FUNCPTR(gst_color_track_sink_event);
  trans_class->src_event = GST_DEBUG_FUNCPTR(gst_color_track_src_event);
  filter_class->set_info = GST_DEBUG_FUNCPTR(gst_color_track_set_info);
  trans_class->transform_ip = GST_DEBUG_FUNCPTR(gst_color_track_transform_ip);

  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_MODE, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_COLOR_SPACE, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_VERIFY, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_METHOD, static_cast<GstPluginAPIFlags>(0));
  gst_type_mark_as_plugin_api(GST_TYPE_COLOR_TRACK_DRAW, static_cast<GstPluginAPIFlags>(0));
}

static void gst_color_track_init(GstColorTrack *self) {
  self->priv = new GstColorTrackPrivate(GST_ELEMENT(self));
}
