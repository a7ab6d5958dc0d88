// SPDX-License-Identifier: LGPL-2.1-or-later
/**
 * SECTION:element-trackpublish
 * @title: trackpublish
 *
 * Publishes the tracks on each buffer as one JSON document per frame with an object (every frame with
 * #GstTrackPublish:add-empty-results), for fleets of cameras and anything
 * else that wants tracks outside the pipeline: to a file of JSON lines or stdout (#GstTrackPublish:location)
 * and/or to an MQTT broker (#GstTrackPublish:address, #GstTrackPublish:topic). The buffers pass through
 * untouched, so it can sit before a display sink or robotctl.
 *
 * A document follows DL Streamer's gvametaconvert schema: "timestamp" (the buffer's stream time in ns),
 * "source", "run" (an id drawn at every start), "frame" (from 0), "resolution" {"width", "height"}, "tags"
 * (#GstTrackPublish:tags, when set), and "objects", one per region-of-interest meta of
 * #GstTrackPublish:roi-type, each with "roi_type", the pixel box "x", "y", "w", "h", the track "id",
 * "state", "score", "verified", "vx", "vy" (those colortrack attaches), and "detection" {"bounding_box"
 * {"x_min", "y_min", "x_max", "y_max"} normalised to the frame, "confidence", "label", "label_id"}.
 *
 * Neither output holds up the stream: documents go into a queue that a worker thread delivers in order (a
 * file that a slow reader holds back keeps up to #GstTrackPublish:max-queued too). While
 * the broker is unreachable they stay queued, up to #GstTrackPublish:max-queued (the oldest are then dropped
 * and counted in a warning), and the queue drains in order after reconnecting. A broker unreachable at start
 * is a warning and the element keeps retrying, or an error with #GstTrackPublish:fail-on-connect. With QoS 1
 * a document may arrive twice after a reconnect: ("source", "run", "frame") identifies it. At EOS the
 * element waits up to #GstTrackPublish:drain-timeout for the queue to be delivered before passing EOS on.
 *
 * ## Example launch lines
 * |[
 * gst-launch-1.0 v4l2src ! videoconvert ! colortrack mode=threshold ! \
 *     trackpublish address=tcp://broker.local:1883 source=cam1 ! fakesink
 * ]| Publishes the tracks of every frame with an object to colortrack/cam1.
 * |[
 * gst-launch-1.0 filesrc location=clip.mp4 ! decodebin ! videoconvert ! colortrack init-box=120,80,64,64 ! \
 *     trackpublish location=tracks.jsonl ! fakesink
 * ]| Writes the tracks of a clip as JSON lines.
 */

#include "gsttrackpublish.h"
#include "property-table.h"

#include <gst/video/video.h>

#include <chrono>
#include <memory>
#include <optional>
#include <vector>
#include <string>

#include "track-document.h"
#include "trackpublish-output.h"
#include "trackpublish-properties.h"

GST_DEBUG_CATEGORY(gst_track_publish_debug);
#define GST_CAT_DEFAULT gst_track_publish_debug

namespace {

using std::chrono::milliseconds;

// What start() opens and the streaming thread uses; reset at stop().
struct State {
  std::vector<std::unique_ptr<trackpublish::DocumentOutput>> outputs;
  milliseconds drain{0};
  GQuark roiType = 0;
  trackpublish::FrameFacts facts;
};

}  // namespace

struct _GstTrackPublishPrivate {
  explicit _GstTrackPublishPrivate(GstElement *element)
      : core(element, gst_track_publish_debug, trackpublish::properties()) {}
  trackpublish::ElementCore core;
  State state;
};

static GstStaticPadTemplate sink_template =
    GST_STATIC_PAD_TEMPLATE("sink", GST_PAD_SINK, GST_PAD_ALWAYS, GST_STATIC_CAPS("video/x-raw(ANY)"));
static GstStaticPadTemplate src_template =
    GST_STATIC_PAD_TEMPLATE("src", GST_PAD_SRC, GST_PAD_ALWAYS, GST_STATIC_CAPS("video/x-raw(ANY)"));

#define gst_track_publish_parent_class parent_class
G_DEFINE_TYPE(GstTrackPublish, gst_track_publish, GST_TYPE_BASE_TRANSFORM);
GST_ELEMENT_REGISTER_DEFINE(trackpublish, "trackpublish", GST_RANK_NONE, GST_TYPE_TRACK_PUBLISH);

static void gst_track_publish_set_property(GObject *object, guint prop_id, const GValue *value,
                                           GParamSpec *pspec) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(object);
  self->priv->core.set(prop_id, value, pspec);
}

static void gst_track_publish_get_property(GObject *object, guint prop_id, GValue *value, GParamSpec *pspec) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(object);
  self->priv->core.get(prop_id, value, pspec);
}

static void gst_track_publish_finalize(GObject *object) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(object);
  delete self->priv;
  self->priv = nullptr;
  G_OBJECT_CLASS(parent_class)->finalize(object);
}

namespace {

void closeOutputs(State &state) {
  for (const auto &output : state.outputs) output->close(state.drain);
  state.outputs.clear();
}

}  // namespace

static gboolean gst_track_publish_start(GstBaseTransform *trans) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  const std::optional<trackpublish::Settings> settings = self->priv->core.start();
  if (!settings) return FALSE;
  const trackpublish::Settings &s = *settings;

  State &state = self->priv->state;
  state = State{};
  gchar *name = gst_object_get_name(GST_OBJECT(self));
  const std::string source = s.source.empty() ? name : s.source;
  g_free(name);
  state.facts.source = source;
  gchar *run = g_uuid_string_random();
  state.facts.run = run;
  g_free(run);
  state.facts.tags =
      s.tags.empty() ? nlohmann::ordered_json() : nlohmann::ordered_json::parse(s.tags, nullptr, false);
  state.facts.addEmptyResults = s.addEmptyResults;
  state.roiType = g_quark_from_string(s.roiType.c_str());
  state.drain = milliseconds(s.drainTimeoutMs);
  for (const trackpublish::OutputKind &kind : trackpublish::outputKinds()) {
    if (!kind.wanted(s)) continue;
    std::unique_ptr<trackpublish::DocumentOutput> output =
        kind.open(trackpublish::OutputContext{GST_ELEMENT(self), s, source});
    if (!output) {
      closeOutputs(state);
      self->priv->core.stop();
      return FALSE;
    }
    state.outputs.push_back(std::move(output));
  }
  return TRUE;
}

static gboolean gst_track_publish_stop(GstBaseTransform *trans) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  self->priv->core.stop();
  closeOutputs(self->priv->state);
  return TRUE;
}

static gboolean gst_track_publish_set_caps(GstBaseTransform *trans, GstCaps *incaps, GstCaps *) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  GstVideoInfo info;
  // Any video: memory other than system memory still has a size in its caps.
  const bool known = gst_video_info_from_caps(&info, incaps);
  self->priv->state.facts.width = known ? GST_VIDEO_INFO_WIDTH(&info) : 0;
  self->priv->state.facts.height = known ? GST_VIDEO_INFO_HEIGHT(&info) : 0;
  return TRUE;
}

static gboolean gst_track_publish_sink_event(GstBaseTransform *trans, GstEvent *event) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  State &state = self->priv->state;
  // Whoever waits for EOS may take it that every document is out, or is told what is not.
  if (GST_EVENT_TYPE(event) == GST_EVENT_EOS && !state.outputs.empty()) {
    for (const auto &output : state.outputs) output->drainAtEos(state.drain);
    // The queues had their drain-timeout: stopping after EOS does not wait for it a second time.
    state.drain = milliseconds(0);
  }
  return GST_BASE_TRANSFORM_CLASS(parent_class)->sink_event(trans, event);
}

static GstFlowReturn gst_track_publish_transform_ip(GstBaseTransform *trans, GstBuffer *buffer) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  State &state = self->priv->state;
  // Stream time, as gvametaconvert gives it (docs/trackpublish.md: the position in the stream).
  // A segment in another format (appsrc's default is bytes) has no stream time: the PTS then.
  state.facts.timestamp =
      trans->segment.format == GST_FORMAT_TIME
          ? gst_segment_to_stream_time(&trans->segment, GST_FORMAT_TIME, GST_BUFFER_PTS(buffer))
          : GST_BUFFER_PTS(buffer);
  const std::string document = trackpublish::trackDocument(buffer, state.roiType, state.facts);
  ++state.facts.frame;
  if (document.empty()) return GST_FLOW_OK;  // no object, and add-empty-results=false
  for (const auto &output : state.outputs) {
    const GstFlowReturn ret = output->publish(document);
    if (ret != GST_FLOW_OK) return ret;
  }
  return GST_FLOW_OK;
}

static void gst_track_publish_class_init(GstTrackPublishClass *klass) {
  GObjectClass *gobject_class = G_OBJECT_CLASS(klass);
  GstElementClass *element_class = GST_ELEMENT_CLASS(klass);
  GstBaseTransformClass *transform_class = GST_BASE_TRANSFORM_CLASS(klass);

  GST_DEBUG_CATEGORY_INIT(gst_track_publish_debug, "trackpublish", 0, "Track publishing (JSON, MQTT)");

  gobject_class->set_property = gst_track_publish_set_property;
  gobject_class->get_property = gst_track_publish_get_property;
  gobject_class->finalize = gst_track_publish_finalize;
  trackpublish::properties().install(gobject_class);

  gst_element_class_set_static_metadata(element_class, "Track publisher", "Filter/Video/Analyzer",
                                        "Publishes each frame's tracks as a JSON document to a file, stdout "
                                        "or an MQTT broker",
                                        "colortrack developers");
  gst_element_class_add_static_pad_template(element_class, &sink_template);
  gst_element_class_add_static_pad_template(element_class, &src_template);

  transform_class->start = GST_DEBUG_FUNCPTR(gst_track_publish_start);
  transform_class->stop = GST_DEBUG_FUNCPTR(gst_track_publish_stop);
  transform_class->set_caps = GST_DEBUG_FUNCPTR(gst_track_publish_set_caps);
  transform_class->sink_event = GST_DEBUG_FUNCPTR(gst_track_publish_sink_event);
  transform_class->transform_ip = GST_DEBUG_FUNCPTR(gst_track_publish_transform_ip);
  transform_class->passthrough_on_same_caps = TRUE;
}

static void gst_track_publish_init(GstTrackPublish *self) {
  self->priv = new GstTrackPublishPrivate(GST_ELEMENT(self));
  gst_base_transform_set_passthrough(GST_BASE_TRANSFORM(self), TRUE);
  gst_base_transform_set_in_place(GST_BASE_TRANSFORM(self), TRUE);
}
