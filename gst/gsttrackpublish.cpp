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
 * MQTT never holds up the stream: documents go into a queue that a worker thread delivers in order. While
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
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include "document-file.h"
#include "mqtt-publisher.h"
#include "output-file.h"
#include "track-document.h"
#include "trackpublish-settings.h"

GST_DEBUG_CATEGORY_STATIC(gst_track_publish_debug);
#define GST_CAT_DEFAULT gst_track_publish_debug

namespace {

using std::chrono::milliseconds;

// The publisher's news as the element's warnings and log.
class ElementMqttListener : public trackpublish::MqttListener {
 public:
  ElementMqttListener(GstElement *element, guint maxQueued) : element_(element), maxQueued_(maxQueued) {}

  void connected(const std::string &address, bool again) override {
    GST_INFO_OBJECT(element_, "%s MQTT broker %s", again ? "reconnected to" : "connected to",
                    address.c_str());
  }
  void connectFailed(const std::string &address, const std::string &why, bool first,
                     milliseconds retryIn) override {
    GST_DEBUG_OBJECT(element_, "cannot reach %s: %s; retrying in %lld ms", address.c_str(), why.c_str(),
                     static_cast<long long>(retryIn.count()));
    if (!first) return;
    // Over TLS a CA that does not sign the broker's certificate, or a certificate that does not match its
    // key, fails the same way as a wrong address: the message names every property that may be at fault.
    const char *suspects = trackpublish::usesTls(address)
                               ? "property 'address', or the TLS settings 'tls-ca-file', 'tls-cert-file', "
                                 "'tls-key-file', 'tls-verify'"
                               : "property 'address'";
    GST_ELEMENT_WARNING(element_, RESOURCE, OPEN_WRITE,
                        ("Cannot reach MQTT broker %s (%s): %s. Retrying; documents are queued (up to "
                         "max-queued=%u).",
                         gstglue::validUtf8(address).c_str(), suspects, why.c_str(), maxQueued_),
                        (nullptr));
  }
  void connectionLost(const std::string &address, const std::string &why, std::size_t queued,
                      bool first) override {
    GST_DEBUG_OBJECT(element_, "lost %s: %s", address.c_str(), why.c_str());
    if (!first) return;
    GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                        ("Lost the connection to MQTT broker %s: %s. Reconnecting; %zu documents queued.",
                         gstglue::validUtf8(address).c_str(), why.c_str(), queued),
                        (nullptr));
  }
  void dropped(std::uint64_t total, std::size_t maxQueued) override {
    // One warning a second at most: the count says how many so far.
    const gint64 now = g_get_monotonic_time();
    gint64 last = lastDropWarning_.load();
    if (total > 1 && now - last < G_USEC_PER_SEC) return;
    if (!lastDropWarning_.compare_exchange_strong(last, now)) return;
    GST_ELEMENT_WARNING(element_, RESOURCE, WRITE,
                        ("MQTT queue full (max-queued=%zu): %" G_GUINT64_FORMAT
                         " documents dropped so far, the oldest first.",
                         maxQueued, total),
                        (nullptr));
  }

 private:
  GstElement *element_;
  const guint maxQueued_;
  std::atomic<gint64> lastDropWarning_{0};
};

// What start() opens and the streaming thread uses; reset at stop().
struct State {
  std::unique_ptr<trackpublish::DocumentFile> file;  // stdout or a file of ours
  std::string location;
  std::uint64_t fileDropsReported = 0;
  gint64 fileDropWarning = 0;                     // monotonic µs of the last warning about them
  std::unique_ptr<ElementMqttListener> listener;  // outlives the publisher
  std::unique_ptr<trackpublish::MqttPublisher> mqtt;
  std::string topic;
  milliseconds drain{0};
  GQuark roiType = 0;
  trackpublish::FrameFacts facts;
};

std::string replaceAll(std::string text, const std::string &what, const std::string &with) {
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + with.size()))
    text.replace(at, what.size(), with);
  return text;
}

}  // namespace

struct _GstTrackPublishPrivate {
  trackpublish::PropertyStore properties;
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
  trackpublish::properties().set(GST_ELEMENT(self), GST_CAT_DEFAULT, self->priv->properties, prop_id, value,
                                 pspec);
}

static void gst_track_publish_get_property(GObject *object, guint prop_id, GValue *value, GParamSpec *pspec) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(object);
  trackpublish::properties().get(GST_ELEMENT(self), self->priv->properties, prop_id, value, pspec);
}

static void gst_track_publish_finalize(GObject *object) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(object);
  delete self->priv;
  self->priv = nullptr;
  G_OBJECT_CLASS(parent_class)->finalize(object);
}

namespace {

bool openFile(GstTrackPublish *self, State &state, const std::string &location, std::size_t maxQueued) {
  if (location == "-") {
    state.location = "stdout";
    state.file = std::make_unique<trackpublish::DocumentFile>(STDOUT_FILENO, false, maxQueued);
    return true;
  }
  state.location = location;
  // Opened without waiting: a FIFO nobody reads is refused at once instead of holding the state change in
  // open(). It stays non-blocking: the writer thread waits for a slow reader, never the stream.
  std::string why;
  mode_t kind = 0;
  const int fd = colortrack_gst::openOutputFile(location, O_CREAT | O_APPEND, kind, why);
  if (fd < 0) {
    GST_ELEMENT_ERROR(self, RESOURCE, OPEN_WRITE,
                      ("Could not open '%s' (property 'location') for writing: %s",
                       gstglue::validUtf8(location).c_str(), gstglue::validUtf8(why).c_str()),
                      (nullptr));
    return false;
  }
  state.file = std::make_unique<trackpublish::DocumentFile>(fd, true, maxQueued);
  return true;
}

// A write that failed is an error (once the writer thread has seen it: a document or a few later); drops
// (the file did not keep up with max-queued documents waiting) a warning at most once a second.
GstFlowReturn checkFile(GstTrackPublish *self, State &state) {
  const std::string failure = state.file->failure();
  if (!failure.empty()) {
    GST_ELEMENT_ERROR(self, RESOURCE, WRITE,
                      ("Could not write to '%s' (property 'location'): %s",
                       gstglue::validUtf8(state.location).c_str(), failure.c_str()),
                      (nullptr));
    return GST_FLOW_ERROR;
  }
  const std::uint64_t dropped = state.file->droppedCount();
  const gint64 now = g_get_monotonic_time();
  if (dropped > state.fileDropsReported && now - state.fileDropWarning >= G_USEC_PER_SEC) {
    GST_ELEMENT_WARNING(
        self, RESOURCE, WRITE,
        ("'%s' (property 'location') does not keep up: documents dropped so far: %" G_GUINT64_FORMAT
         ", the oldest first (max-queued waiting).",
         gstglue::validUtf8(state.location).c_str(), dropped),
        (nullptr));
    state.fileDropsReported = dropped;
    state.fileDropWarning = now;
  }
  return GST_FLOW_OK;
}

// What MQTT will carry, checked before connecting: the topic after {source} is put in, the client id, and
// TLS files only where TLS is used (with tcp:// they would be ignored, and the link not encrypted).
bool checkMqttSettings(GstTrackPublish *self, const trackpublish::Settings &s,
                       const trackpublish::MqttConfig &config, const std::string &topic,
                       const std::string &source) {
  const std::string badTopic = trackpublish::checkTopic(topic);
  if (!badTopic.empty()) {
    // Text too long to show is cut; `badTopic` gives the topic's length.
    const auto shown = [](const std::string &text) {
      return text.size() > 200 ? text.substr(0, 200) + "..." : text;
    };
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Invalid topic '%s' (property 'topic', with source '%s'): %s.",
                       gstglue::validUtf8(shown(topic)).c_str(), gstglue::validUtf8(shown(source)).c_str(),
                       badTopic.c_str()),
                      (nullptr));
    return false;
  }
  const std::string badClientId = trackpublish::checkClientId(config.clientId);
  if (!badClientId.empty()) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS, ("Invalid property 'client-id': %s.", badClientId.c_str()),
                      (nullptr));
    return false;
  }
  const bool tls = trackpublish::usesTls(s.address);
  for (const auto &[property, file] :
       {std::pair<const char *, const std::string &>{"tls-ca-file", s.tlsCaFile},
        {"tls-cert-file", s.tlsCertFile},
        {"tls-key-file", s.tlsKeyFile}}) {
    if (tls || file.empty()) continue;
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("TLS file '%s' (property '%s') is set but address '%s' does not use TLS: use "
                       "ssl://HOST:PORT, or unset '%s'.",
                       gstglue::validUtf8(file).c_str(), property,
                       gstglue::validUtf8(trackpublish::redactedAddress(s.address)).c_str(), property),
                      (nullptr));
    return false;
  }
  if (!tls && !s.tlsVerify) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("TLS verification is off (property 'tls-verify') but address '%s' does not use TLS: "
                       "use ssl://HOST:PORT, "
                       "or leave 'tls-verify' alone.",
                       gstglue::validUtf8(trackpublish::redactedAddress(s.address)).c_str()),
                      (nullptr));
    return false;
  }
  // MQTT 3.1.1 (3.1.2.9): a password is only sent with a user name.
  if (!s.password.empty() && s.username.empty()) {
    GST_ELEMENT_ERROR(
        self, RESOURCE, SETTINGS,
        ("Property 'password' is set without 'username': MQTT sends a password only with a user "
         "name."),
        (nullptr));
    return false;
  }
  return true;
}

// The default client id: colortrack-<source>-<process id>, the source's characters outside [A-Za-z0-9_-]
// replaced by '_' (some brokers refuse a client id with other characters, and the refusal would be blamed on
// the address).
std::string defaultClientId(const std::string &source) {
  std::string safe = source;
  for (char &c : safe)
    if (!g_ascii_isalnum(c) && c != '_' && c != '-') c = '_';
  return "colortrack-" + safe + "-" + std::to_string(getpid());
}

bool openMqtt(GstTrackPublish *self, State &state, const trackpublish::Settings &s,
              const std::string &source) {
  trackpublish::MqttConfig config;
  config.address = trackpublish::brokerUri(s.address);
  config.clientId = s.clientId.empty() ? defaultClientId(source) : s.clientId;
  config.username = s.username;
  config.password = s.password;
  config.caFile = s.tlsCaFile;
  config.certFile = s.tlsCertFile;
  config.keyFile = s.tlsKeyFile;
  config.verifyServer = s.tlsVerify;
  config.qos = s.qos;
  config.maxQueued = s.maxQueued;
  state.topic = replaceAll(s.topic, "{source}", source);
  if (!checkMqttSettings(self, s, config, state.topic, source)) return false;
  state.listener = std::make_unique<ElementMqttListener>(GST_ELEMENT(self), s.maxQueued);
  state.mqtt = std::make_unique<trackpublish::MqttPublisher>(config, *state.listener);
  std::string why;
  if (!state.mqtt->start(why)) {
    GST_ELEMENT_ERROR(self, RESOURCE, SETTINGS,
                      ("Invalid MQTT address '%s' (property 'address'): %s.",
                       gstglue::validUtf8(trackpublish::redactedAddress(s.address)).c_str(), why.c_str()),
                      (nullptr));
    return false;
  }
  // The client's own connect timeout is 5 s; a little more so its answer arrives first.
  if (s.failOnConnect && !state.mqtt->waitFirstAttempt(milliseconds(6000), why)) {
    GST_ELEMENT_ERROR(self, RESOURCE, OPEN_WRITE,
                      ("Cannot reach MQTT broker %s (property 'address', fail-on-connect=true): %s.",
                       gstglue::validUtf8(trackpublish::redactedAddress(s.address)).c_str(), why.c_str()),
                      (nullptr));
    return false;
  }
  return true;
}

// What was lost, said once at the end of the stream (EOS) or, in the log, at stop.
void reportLosses(GstTrackPublish *self, trackpublish::MqttPublisher &mqtt, const char *when, bool post) {
  const std::uint64_t dropped = mqtt.droppedCount();
  const std::size_t undelivered = mqtt.queued();
  if (dropped == 0 && undelivered == 0) return;
  const std::string text = "MQTT: " + std::to_string(dropped) + " documents dropped in all (queue full), " +
                           std::to_string(undelivered) + " not delivered " + when + "; " +
                           std::to_string(mqtt.delivered()) + " delivered.";
  if (post)
    GST_ELEMENT_WARNING(self, RESOURCE, WRITE, ("%s", text.c_str()), (nullptr));
  else
    GST_WARNING_OBJECT(self, "%s", text.c_str());
}

void closeOutputs(GstTrackPublish *self, State &state) {
  if (state.mqtt) {
    state.mqtt->stop(state.drain);
    // The bus is flushing by now: the log is where this can still be read.
    reportLosses(self, *state.mqtt, "when stopping", false);
  }
  state.mqtt.reset();
  state.listener.reset();
  if (state.file) {
    state.file->stop(state.drain);
    if (const std::size_t left = state.file->queued())
      GST_WARNING_OBJECT(self, "%zu documents not written to '%s' when stopping (drain-timeout)", left,
                         state.location.c_str());
  }
  state.file.reset();
}

}  // namespace

static gboolean gst_track_publish_start(GstBaseTransform *trans) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  GST_OBJECT_LOCK(self);
  trackpublish::PropertyStore &store = self->priv->properties;
  const trackpublish::Settings s = store.settings;
  trackpublish::properties().recheckRefused(store);
  const std::string refusal = store.firstRefusal();
  GST_OBJECT_UNLOCK(self);
  if (!refusal.empty()) {
    gstglue::postStartRefusal(GST_ELEMENT(self), GST_CAT_DEFAULT, refusal);
    return FALSE;
  }
  if (s.location.empty() && s.address.empty()) {
    GST_ELEMENT_ERROR(
        self, RESOURCE, NOT_FOUND,
        ("No output: set 'location' (a file, or '-' for stdout) and/or 'address' (an MQTT broker, "
         "tcp://HOST:PORT)."),
        (nullptr));
    return FALSE;
  }

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
  if (!s.location.empty() && !openFile(self, state, s.location, s.maxQueued)) return FALSE;
  if (!s.address.empty() && !openMqtt(self, state, s, source)) {
    closeOutputs(self, state);
    return FALSE;
  }
  GST_OBJECT_LOCK(self);
  store.running = true;
  GST_OBJECT_UNLOCK(self);
  return TRUE;
}

static gboolean gst_track_publish_stop(GstBaseTransform *trans) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  GST_OBJECT_LOCK(self);
  self->priv->properties.running = false;
  GST_OBJECT_UNLOCK(self);
  closeOutputs(self, self->priv->state);
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
  if (GST_EVENT_TYPE(event) == GST_EVENT_EOS && (state.mqtt || state.file)) {
    if (state.file && !state.file->waitWritten(state.drain))
      GST_ELEMENT_WARNING(self, RESOURCE, WRITE,
                          ("%zu documents not yet written to '%s' (property 'location') at EOS after "
                           "drain-timeout.",
                           state.file->queued(), gstglue::validUtf8(state.location).c_str()),
                          (nullptr));
    if (state.mqtt) {
      state.mqtt->waitDelivered(state.drain);
      reportLosses(self, *state.mqtt, "at EOS after drain-timeout", true);
    }
    // The queues had their drain-timeout: stopping after EOS does not wait for it a second time.
    state.drain = milliseconds(0);
  }
  return GST_BASE_TRANSFORM_CLASS(parent_class)->sink_event(trans, event);
}

static GstFlowReturn gst_track_publish_transform_ip(GstBaseTransform *trans, GstBuffer *buffer) {
  GstTrackPublish *self = GST_TRACK_PUBLISH(trans);
  State &state = self->priv->state;
  // Stream time, as gvametaconvert gives it: from 0 at the start of the stream whatever the PTS origin.
  // A segment in another format (appsrc's default is bytes) has no stream time: the PTS then.
  state.facts.timestamp =
      trans->segment.format == GST_FORMAT_TIME
          ? gst_segment_to_stream_time(&trans->segment, GST_FORMAT_TIME, GST_BUFFER_PTS(buffer))
          : GST_BUFFER_PTS(buffer);
  const std::string document = trackpublish::trackDocument(buffer, state.roiType, state.facts);
  ++state.facts.frame;
  if (document.empty()) return GST_FLOW_OK;  // no object, and add-empty-results=false
  if (state.file) {
    const GstFlowReturn fileState = checkFile(self, state);
    if (fileState != GST_FLOW_OK) return fileState;
    // One line per document, written whole by the writer thread.
    state.file->write(document);
  }
  if (state.mqtt) state.mqtt->publish(state.topic, document);
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
  self->priv = new GstTrackPublishPrivate();
  gst_base_transform_set_passthrough(GST_BASE_TRANSFORM(self), TRUE);
  gst_base_transform_set_in_place(GST_BASE_TRANSFORM(self), TRUE);
}
