// trackpublish: the JSON document of every frame against the ROI metas of the same buffer (file output), and
// MQTT against a real broker the test starts: Debian's mosquitto on a free loopback port with its own config,
// read back by a subscriber (Paho). Covers delivery in order at QoS 1, eight sources at once, a broker
// restart mid-stream with a live source, and bad addresses, topics and a full queue. C++ headers first:
// gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <MQTTAsync.h>
#include <gio/gio.h>
#include <glib/gstdio.h>
#include <nlohmann/json.hpp>

#include "gst_test_util.hpp"

#include <gst/app/gstappsink.h>
#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>
#include <gst/video/video.h>

namespace {

using Clock = std::chrono::steady_clock;
using colortrack::gst_test_util::contains;
using colortrack::gst_test_util::kFps;

constexpr int kWidth = 320, kHeight = 240;

// ---------------------------------------------------------------------------------------------------------
// Frames with known tracks

struct TrackBox {
  int id;
  int x, y, w, h;
  const char *state;
  double score;
};

// The tracks of frame `frame`: 1 to 3 objects moving, so every document differs.
std::vector<TrackBox> tracksOf(int frame) {
  std::vector<TrackBox> tracks;
  for (int id = 1; id <= 1 + frame % 3; ++id)
    tracks.push_back({id, (frame * 3 + id * 50) % 250, 20 + id * 40, 20 + id, 30,
                      id == 2 ? "coasting" : "tracking", 0.25 * id});
  return tracks;
}

GstBuffer *frameBuffer(int frame) {
  GstBuffer *buffer = gst_buffer_new_allocate(nullptr, kWidth * kHeight, nullptr);
  gst_buffer_memset(buffer, 0, 0, kWidth * kHeight);
  for (const TrackBox &t : tracksOf(frame)) {
    GstVideoRegionOfInterestMeta *roi =
        gst_buffer_add_video_region_of_interest_meta(buffer, "colortrack", t.x, t.y, t.w, t.h);
    roi->id = t.id;
    gst_video_region_of_interest_meta_add_param(
        roi, gst_structure_new("colortrack", "state", G_TYPE_STRING, t.state, "score", G_TYPE_DOUBLE, t.score,
                               "verified", G_TYPE_BOOLEAN, TRUE, "vx", G_TYPE_DOUBLE, 3.0, "vy",
                               G_TYPE_DOUBLE, 0.0, nullptr));
  }
  // Another element's box: not published with the default roi-type.
  gst_buffer_add_video_region_of_interest_meta(buffer, "object", 1, 1, 5, 5);
  GST_BUFFER_PTS(buffer) = gst_util_uint64_scale_int(frame, GST_SECOND, kFps);
  GST_BUFFER_DURATION(buffer) = gst_util_uint64_scale_int(1, GST_SECOND, kFps);
  return buffer;
}

std::string caps() {
  return "video/x-raw,format=GRAY8,width=" + std::to_string(kWidth) + ",height=" + std::to_string(kHeight) +
         ",framerate=" + std::to_string(kFps) + "/1";
}

// A text member equal to `expected` (compared as std::string: fail_unless_equals_string would keep a pointer
// into a temporary).
void expectText(const nlohmann::json &value, const std::string &expected) {
  const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  fail_unless(text == expected, "'%s' instead of '%s'", text.c_str(), expected.c_str());
}

// One parsed document; fails the test when it is not what frame `frame` of `source` should give.
void checkDocument(const std::string &text, const std::string &source, int frame) {
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  fail_if(doc.is_discarded(), "not JSON: %s", text.c_str());
  expectText(doc["source"], source);
  fail_unless_equals_int(doc["frame"].get<int>(), frame);
  fail_unless_equals_uint64(doc["timestamp"].get<guint64>(),
                            gst_util_uint64_scale_int(frame, GST_SECOND, kFps));
  fail_unless_equals_int(doc["resolution"]["width"].get<int>(), kWidth);
  fail_unless_equals_int(doc["resolution"]["height"].get<int>(), kHeight);
  const nlohmann::json &objects = doc["objects"];
  const std::vector<TrackBox> expected = tracksOf(frame);
  fail_unless_equals_int(objects.size(), expected.size());
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const nlohmann::json &o = objects[i];
    const TrackBox &t = expected[i];
    fail_unless_equals_int(o["id"].get<int>(), t.id);
    fail_unless_equals_int(o["x"].get<int>(), t.x);
    fail_unless_equals_int(o["y"].get<int>(), t.y);
    fail_unless_equals_int(o["w"].get<int>(), t.w);
    fail_unless_equals_int(o["h"].get<int>(), t.h);
    expectText(o["state"], t.state);
    fail_unless_equals_float(o["score"].get<double>(), t.score);
    fail_unless(o["verified"].get<bool>());
    fail_unless_equals_float(o["vx"].get<double>(), 3.0);
    const nlohmann::json &detection = o["detection"];
    expectText(detection["label"], "colortrack");
    fail_unless_equals_float(detection["confidence"].get<double>(), t.score);
    const nlohmann::json &box = detection["bounding_box"];
    fail_unless(std::abs(box["x_min"].get<double>() - t.x / double(kWidth)) < 1e-9);
    fail_unless(std::abs(box["y_max"].get<double>() - (t.y + t.h) / double(kHeight)) < 1e-9);
  }
}

// The frame number of a document, -1 when it is not one.
int frameOf(const std::string &text) {
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  return doc.is_object() && doc.contains("frame") ? doc["frame"].get<int>() : -1;
}

// ---------------------------------------------------------------------------------------------------------
// A broker and a subscriber

int freePort() {
  GSocket *socket = g_socket_new(G_SOCKET_FAMILY_IPV4, G_SOCKET_TYPE_STREAM, G_SOCKET_PROTOCOL_TCP, nullptr);
  GInetAddress *loopback = g_inet_address_new_loopback(G_SOCKET_FAMILY_IPV4);
  GSocketAddress *address = g_inet_socket_address_new(loopback, 0);
  fail_unless(g_socket_bind(socket, address, TRUE, nullptr));
  GSocketAddress *bound = g_socket_get_local_address(socket, nullptr);
  const int port = g_inet_socket_address_get_port(G_INET_SOCKET_ADDRESS(bound));
  g_object_unref(bound);
  g_object_unref(address);
  g_object_unref(loopback);
  g_object_unref(socket);  // closed: the port is free again
  return port;
}

// Debian's mosquitto on 127.0.0.1:`port`, persistent (a restart keeps the subscriber's session and the
// messages queued for it), in a directory of its own. With `tlsPort`, also a TLS listener there, with a
// certificate for 127.0.0.1 signed by a certificate authority of the test's own (ca.pem in dir()).
class Broker {
 public:
  explicit Broker(int port, int tlsPort = 0) : port_(port) {
    gchar *dir = g_dir_make_tmp("trackpublish-broker-XXXXXX", nullptr);
    dir_ = dir;
    g_free(dir);
    const std::string config = dir_ + "/mosquitto.conf";
    std::ofstream out(config);
    // `user`: started by root, mosquitto would switch to its own user, which cannot write our directory.
    out << "user " << g_get_user_name() << "\nlistener " << port
        << " 127.0.0.1\nallow_anonymous true\npersistence true\n"
        << "persistence_location " << dir_ << "/\nmax_queued_messages 100000\n";
    if (tlsPort) {
      makeCertificates();
      out << "listener " << tlsPort << " 127.0.0.1\ncafile " << dir_ << "/ca.pem\ncertfile " << dir_
          << "/server.pem\nkeyfile " << dir_ << "/server.key\n";
    }
    out.close();
    start();
  }
  const std::string &dir() const { return dir_; }
  ~Broker() {
    stop();
    const std::string command = "rm -rf '" + dir_ + "'";
    fail_unless(std::system(command.c_str()) == 0);
  }
  void start() {
    const std::string config = dir_ + "/mosquitto.conf";
    gchar *argv[] = {const_cast<gchar *>("/usr/sbin/mosquitto"), const_cast<gchar *>("-c"),
                     const_cast<gchar *>(config.c_str()), nullptr};
    GError *error = nullptr;
    auto dieWithParent = [](gpointer) { prctl(PR_SET_PDEATHSIG, SIGKILL); };
    fail_unless(
        g_spawn_async(nullptr, argv, nullptr,
                      static_cast<GSpawnFlags>(G_SPAWN_DO_NOT_REAP_CHILD | G_SPAWN_STDOUT_TO_DEV_NULL |
                                               G_SPAWN_STDERR_TO_DEV_NULL),
                      dieWithParent, nullptr, &pid_, &error),
        "cannot start mosquitto (package mosquitto): %s", error ? error->message : "?");
    // Listening once a TCP connect succeeds.
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (Clock::now() < deadline) {
      GSocketClient *client = g_socket_client_new();
      GSocketConnection *connection =
          g_socket_client_connect_to_host(client, "127.0.0.1", static_cast<guint16>(port_), nullptr, nullptr);
      g_object_unref(client);
      if (connection) {
        g_object_unref(connection);
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    fail("mosquitto did not listen on port %d", port_);
  }
  // SIGTERM: mosquitto saves its persistent state and exits, as a restarted broker service would.
  void stop() {
    if (pid_ <= 0) return;
    kill(pid_, SIGTERM);
    waitpid(pid_, nullptr, 0);
    g_spawn_close_pid(pid_);
    pid_ = 0;
  }
  std::string address() const { return "tcp://127.0.0.1:" + std::to_string(port_); }

 private:
  // A CA and a server certificate for IP 127.0.0.1 signed by it (openssl's command line, as an administrator
  // would make them).
  void makeCertificates() {
    const std::string d = "'" + dir_ + "'";
    const std::string commands =
        "openssl req -x509 -newkey rsa:2048 -nodes -days 2 -subj /CN=colortrack-test-ca -keyout " + d +
        "/ca.key -out " + d + "/ca.pem && openssl req -newkey rsa:2048 -nodes -subj /CN=127.0.0.1 -keyout " +
        d + "/server.key -out " + d + "/server.csr && printf 'subjectAltName=IP:127.0.0.1\\n' > " + d +
        "/san.ext && openssl x509 -req -in " + d + "/server.csr -CA " + d + "/ca.pem -CAkey " + d +
        "/ca.key -CAcreateserial -days 2 -extfile " + d + "/san.ext -out " + d + "/server.pem";
    fail_unless(std::system((commands + " >/dev/null 2>&1").c_str()) == 0,
                "openssl could not make the test's certificates (package openssl)");
  }

  int port_;
  std::string dir_;
  GPid pid_ = 0;
};

// A persistent-session subscriber at QoS 1 that reconnects by itself, collecting payloads by topic.
class Subscriber {
 public:
  Subscriber(const std::string &address, const std::string &filter) : filter_(filter) {
    MQTTAsync_create(&client_, address.c_str(), "trackpublish-test-subscriber", MQTTCLIENT_PERSISTENCE_NONE,
                     nullptr);
    MQTTAsync_setCallbacks(client_, this, nullptr, &Subscriber::arrived, nullptr);
    MQTTAsync_setConnected(client_, this, &Subscriber::connected);
    MQTTAsync_connectOptions options = MQTTAsync_connectOptions_initializer;
    options.cleansession = 0;
    options.automaticReconnect = 1;
    options.minRetryInterval = 1;
    options.maxRetryInterval = 1;
    fail_unless_equals_int(MQTTAsync_connect(client_, &options), MQTTASYNC_SUCCESS);
    fail_unless(waitFor([&] { return subscribed_.load(); }, 10), "the subscriber did not subscribe");
  }
  ~Subscriber() {
    MQTTAsync_disconnectOptions options = MQTTAsync_disconnectOptions_initializer;
    MQTTAsync_disconnect(client_, &options);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    MQTTAsync_destroy(&client_);
  }
  std::map<std::string, std::vector<std::string>> received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }
  std::size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    std::size_t n = 0;
    for (const auto &[topic, payloads] : received_) n += payloads.size();
    return n;
  }
  template <typename Predicate>
  static bool waitFor(Predicate done, double seconds) {
    const auto deadline = Clock::now() + std::chrono::duration<double>(seconds);
    while (!done() && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return done();
  }

 private:
  static void connected(void *context, char *) {
    auto *self = static_cast<Subscriber *>(context);
    MQTTAsync_responseOptions response = MQTTAsync_responseOptions_initializer;
    response.context = self;
    response.onSuccess = [](void *c, MQTTAsync_successData *) {
      static_cast<Subscriber *>(c)->subscribed_ = true;
    };
    MQTTAsync_subscribe(self->client_, self->filter_.c_str(), 1, &response);
  }
  static int arrived(void *context, char *topic, int, MQTTAsync_message *message) {
    auto *self = static_cast<Subscriber *>(context);
    {
      std::lock_guard<std::mutex> lock(self->mutex_);
      self->received_[topic].emplace_back(static_cast<const char *>(message->payload), message->payloadlen);
    }
    MQTTAsync_freeMessage(&message);
    MQTTAsync_free(topic);
    return 1;
  }

  MQTTAsync client_ = nullptr;
  std::string filter_;
  std::atomic<bool> subscribed_{false};
  std::mutex mutex_;
  std::map<std::string, std::vector<std::string>> received_;
};

// ---------------------------------------------------------------------------------------------------------
// Pipelines

// appsrc ! trackpublish <properties> ! appsink, with its own bus.
class Publisher {
 public:
  explicit Publisher(const std::string &properties, bool live = false) {
    const std::string launch = "appsrc name=src format=time is-live=" + std::string(live ? "true" : "false") +
                               " caps=\"" + caps() + "\" ! trackpublish name=tp " + properties +
                               " ! appsink name=sink sync=false wait-on-eos=false";
    GError *error = nullptr;
    pipeline_ = gst_parse_launch(launch.c_str(), &error);
    fail_unless(pipeline_ != nullptr, "%s", error ? error->message : "?");
    src_ = gst_bin_get_by_name(GST_BIN(pipeline_), "src");
    sink_ = gst_bin_get_by_name(GST_BIN(pipeline_), "sink");
    bus_ = gst_element_get_bus(pipeline_);
  }
  ~Publisher() {
    gst_element_set_state(pipeline_, GST_STATE_NULL);
    gst_object_unref(bus_);
    gst_object_unref(sink_);
    gst_object_unref(src_);
    gst_object_unref(pipeline_);
  }
  GstStateChangeReturn play() { return gst_element_set_state(pipeline_, GST_STATE_PLAYING); }
  void push(int frame) {
    fail_unless_equals_int(gst_app_src_push_buffer(GST_APP_SRC(src_), frameBuffer(frame)), GST_FLOW_OK);
  }
  // Pulls what reached the sink (non-blocking); returns how many.
  int drainSink() {
    int n = 0;
    while (GstSample *sample = gst_app_sink_try_pull_sample(GST_APP_SINK(sink_), 0)) {
      gst_sample_unref(sample);
      ++n;
    }
    return n;
  }
  // EOS, then waits for it on the bus (trackpublish passes EOS on once its queue is delivered).
  void endAndWait() {
    gst_app_src_end_of_stream(GST_APP_SRC(src_));
    const auto deadline = Clock::now() + std::chrono::seconds(30);
    while (Clock::now() < deadline) {
      GstMessage *msg = gst_bus_timed_pop_filtered(
          bus_, GST_SECOND / 10,
          static_cast<GstMessageType>(GST_MESSAGE_EOS | GST_MESSAGE_ERROR | GST_MESSAGE_WARNING));
      if (!msg) continue;
      const GstMessageType type = GST_MESSAGE_TYPE(msg);
      keep(msg);
      if (type == GST_MESSAGE_EOS) return;
      fail_if(type == GST_MESSAGE_ERROR, "error before EOS: %s", errors_.back().c_str());
    }
    fail("no EOS");
  }
  // Every warning (or error) text posted so far.
  std::vector<std::string> messages(GstMessageType type) {
    while (GstMessage *msg = gst_bus_pop_filtered(
               bus_, static_cast<GstMessageType>(GST_MESSAGE_ERROR | GST_MESSAGE_WARNING)))
      keep(msg);
    return type == GST_MESSAGE_WARNING ? warnings_ : errors_;
  }

 private:
  // Takes `msg`, keeping the text of a warning or an error.
  void keep(GstMessage *msg) {
    GError *error = nullptr;
    if (GST_MESSAGE_TYPE(msg) == GST_MESSAGE_WARNING) {
      gst_message_parse_warning(msg, &error, nullptr);
      warnings_.push_back(error ? error->message : "");
    } else if (GST_MESSAGE_TYPE(msg) == GST_MESSAGE_ERROR) {
      gst_message_parse_error(msg, &error, nullptr);
      errors_.push_back(error ? error->message : "");
    }
    g_clear_error(&error);
    gst_message_unref(msg);
  }

  GstElement *pipeline_, *src_, *sink_;
  GstBus *bus_;
  std::vector<std::string> warnings_, errors_;
};

bool anyContains(const std::vector<std::string> &texts, const std::string &part) {
  return std::any_of(texts.begin(), texts.end(), [&](const std::string &t) { return contains(t, part); });
}

}  // namespace

// ---------------------------------------------------------------------------------------------------------

GST_START_TEST(test_file_has_one_document_per_frame) {
  gchar *path = g_build_filename(g_get_tmp_dir(), "trackpublish-test-XXXXXX.jsonl", nullptr);
  const int fd = g_mkstemp(path);
  close(fd);
  {
    Publisher p(std::string("location=") + path + " source=file-cam");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 30; ++i) p.push(i);
    p.endAndWait();
    fail_unless_equals_int(p.drainSink(), 30);  // the buffers pass through
  }
  std::ifstream in(path);
  std::string line;
  int frame = 0;
  while (std::getline(in, line)) checkDocument(line, "file-cam", frame++);
  fail_unless_equals_int(frame, 30);
  unlink(path);
  g_free(path);
}
GST_END_TEST;

// location= a FIFO: refused at once while nobody reads it (the open would otherwise wait for a reader with
// the state change held), written to once somebody does; a directory is refused naming what it is.
GST_START_TEST(test_fifo_location_never_blocks) {
  gchar *dir = g_dir_make_tmp("trackpublish-XXXXXX", nullptr);
  fail_unless(dir != nullptr);
  const std::string fifo = std::string(dir) + "/tracks.fifo";
  fail_unless(mkfifo(fifo.c_str(), 0600) == 0);
  {
    Publisher p("location=" + fifo);
    const auto start = Clock::now();
    fail_unless_equals_int(p.play(), GST_STATE_CHANGE_FAILURE);
    fail_unless(Clock::now() - start < std::chrono::seconds(1), "the refusal took over a second");
    const std::vector<std::string> errors = p.messages(GST_MESSAGE_ERROR);
    fail_unless(anyContains(errors, "property 'location'") && anyContains(errors, "FIFO"),
                "no error naming location and the FIFO");
  }
  {
    const int reader = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
    fail_unless(reader >= 0);
    Publisher p("location=" + fifo + " source=fifo-cam");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 5; ++i) p.push(i);
    p.endAndWait();
    std::string text(65536, '\0');
    const ssize_t n = read(reader, text.data(), text.size());
    fail_unless(n > 0);
    text.resize(static_cast<std::size_t>(n));
    fail_unless_equals_int(std::count(text.begin(), text.end(), '\n'), 5);
    close(reader);
  }
  {
    Publisher p(std::string("location=") + dir);
    fail_unless_equals_int(p.play(), GST_STATE_CHANGE_FAILURE);
    fail_unless(anyContains(p.messages(GST_MESSAGE_ERROR), "property 'location'"));
  }
  unlink(fifo.c_str());
  g_rmdir(dir);
  g_free(dir);
}
GST_END_TEST;

GST_START_TEST(test_mqtt_delivers_every_frame_in_order) {
  const int port = freePort();
  Broker broker(port);
  Subscriber subscriber(broker.address(), "colortrack/#");
  constexpr int kFrames = 300;
  {
    Publisher p("address=" + broker.address() + " source=cam1 mqtt-qos=1 drain-timeout=20000");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < kFrames; ++i) p.push(i);
    const auto pushed = Clock::now();
    p.endAndWait();
    g_print("delivered at EOS %.3f s after the last push\n",
            std::chrono::duration<double>(Clock::now() - pushed).count());
    const std::vector<std::string> warnings = p.messages(GST_MESSAGE_WARNING);
    fail_unless(warnings.empty(), "warning: %s", warnings.empty() ? "" : warnings.front().c_str());
  }
  fail_unless(Subscriber::waitFor([&] { return subscriber.count() >= kFrames; }, 10), "received %zu of %d",
              subscriber.count(), kFrames);
  const auto received = subscriber.received();
  fail_unless_equals_int(received.size(), 1);
  const std::vector<std::string> &documents = received.at("colortrack/cam1");
  fail_unless_equals_int(documents.size(), kFrames);
  for (int i = 0; i < kFrames; ++i) checkDocument(documents[i], "cam1", i);
}
GST_END_TEST;

GST_START_TEST(test_mqtt_eight_sources_at_once) {
  const int port = freePort();
  Broker broker(port);
  Subscriber subscriber(broker.address(), "fleet/#");
  constexpr int kSources = 8, kFrames = 150;
  {
    std::vector<std::unique_ptr<Publisher>> publishers;
    for (int s = 0; s < kSources; ++s) {
      // Half of them name the broker HOST:PORT, as gvametapublish users do: the same as tcp://HOST:PORT.
      const std::string address =
          s % 2 ? broker.address().substr(std::string("tcp://").size()) : broker.address();
      publishers.push_back(std::make_unique<Publisher>(
          "address=" + address + " topic=fleet/{source} source=cam" + std::to_string(s)));
      fail_unless(publishers.back()->play() != GST_STATE_CHANGE_FAILURE);
    }
    for (int i = 0; i < kFrames; ++i)
      for (auto &p : publishers) p->push(i);
    for (auto &p : publishers) p->endAndWait();
  }
  fail_unless(Subscriber::waitFor([&] { return subscriber.count() >= kSources * kFrames; }, 15),
              "received %zu of %d", subscriber.count(), kSources * kFrames);
  const auto received = subscriber.received();
  fail_unless_equals_int(received.size(), kSources);
  for (int s = 0; s < kSources; ++s) {
    const std::string source = "cam" + std::to_string(s);
    const std::vector<std::string> &documents = received.at("fleet/" + source);
    fail_unless_equals_int(documents.size(), kFrames);
    for (int i = 0; i < kFrames; ++i) fail_unless_equals_int(frameOf(documents[i]), i);
    checkDocument(documents[kFrames / 2], source, kFrames / 2);
  }
}
GST_END_TEST;

// A live source at 30 fps; the broker goes away for 2 s mid-stream and comes back on the same port. Nothing
// is lost (a document resent after the reconnect may arrive twice: the test dedupes by frame, as
// docs/trackpublish.md tells consumers to), the order holds, and the stream does not slow down while the
// broker is away.
GST_START_TEST(test_mqtt_survives_a_broker_restart) {
  const int port = freePort();
  auto broker = std::make_unique<Broker>(port);
  auto subscriber = std::make_unique<Subscriber>(broker->address(), "colortrack/#");
  constexpr int kFrames = 180, kStopAt = 60, kDownFrames = 60;  // 2 s down
  int passedWhileDown = 0;
  double downSeconds = 0;
  {
    Publisher p("address=" + broker->address() + " source=live mqtt-qos=1", true);
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    // Connected first (Paho takes ~2 s, more under a sanitizer), so that the broker goes away from a live
    // connection.
    p.push(0);
    fail_unless(Subscriber::waitFor([&] { return subscriber->count() >= 1; }, 15), "never connected");
    auto next = Clock::now();
    Clock::time_point downSince;
    for (int i = 1; i < kFrames; ++i) {
      if (i == kStopAt) {
        p.drainSink();
        broker->stop();
        downSince = Clock::now();
      }
      if (i == kStopAt + kDownFrames) {
        passedWhileDown = p.drainSink();
        downSeconds = std::chrono::duration<double>(Clock::now() - downSince).count();
        broker->start();
      }
      p.push(i);
      next += std::chrono::microseconds(1000000 / kFps);
      std::this_thread::sleep_until(next);
    }
    p.endAndWait();
    const std::vector<std::string> warnings = p.messages(GST_MESSAGE_WARNING);
    fail_unless(anyContains(warnings, "Lost the connection"), "no warning about the lost broker");
  }
  Subscriber::waitFor([&] { return subscriber->count() >= kFrames; }, 15);
  const std::vector<std::string> documents = subscriber->received().at("colortrack/live");
  std::vector<int> frames;
  int duplicates = 0;
  for (const std::string &d : documents) {
    const int frame = frameOf(d);
    if (std::find(frames.begin(), frames.end(), frame) != frames.end()) {
      ++duplicates;
      continue;
    }
    frames.push_back(frame);
  }
  g_print(
      "broker restart: %zu documents for %d frames (%d duplicates); %d frames passed in %.2f s while the "
      "broker was down\n",
      documents.size(), kFrames, duplicates, passedWhileDown, downSeconds);
  for (int i = 0; i < kFrames; ++i)
    if (std::find(frames.begin(), frames.end(), i) == frames.end())
      g_print("broker restart: frame %d lost\n", i);
  fail_unless_equals_int(frames.size(), kFrames);
  for (int i = 0; i < kFrames; ++i) fail_unless_equals_int(frames[i], i);
  // The stream kept its rate: at least 90 % of the frames pushed while the broker was down came through.
  fail_unless(passedWhileDown >= kDownFrames * 9 / 10,
              "only %d of %d frames passed while the broker was down", passedWhileDown, kDownFrames);
}
GST_END_TEST;

// ssl://: documents arrive through a TLS listener whose certificate the CA file vouches for; without that
// CA the broker is not trusted (a warning, nothing delivered), unless tls-verify=false.
GST_START_TEST(test_mqtt_over_tls) {
  const int port = freePort(), tlsPort = freePort();
  Broker broker(port, tlsPort);
  Subscriber subscriber(broker.address(), "colortrack/#");
  const std::string address = "ssl://127.0.0.1:" + std::to_string(tlsPort);
  constexpr int kFrames = 30;
  {
    Publisher p("address=" + address + " source=tls tls-ca-file=" + broker.dir() + "/ca.pem");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < kFrames; ++i) p.push(i);
    p.endAndWait();
    const std::vector<std::string> warnings = p.messages(GST_MESSAGE_WARNING);
    fail_unless(warnings.empty(), "warning: %s", warnings.empty() ? "" : warnings.front().c_str());
  }
  {
    // The system's CAs do not know the test's CA.
    Publisher p("address=" + address + " source=untrusted drain-timeout=0");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < kFrames; ++i) p.push(i);
    fail_unless(Subscriber::waitFor(
                    [&] {
                      return anyContains(p.messages(GST_MESSAGE_WARNING),
                                         "Cannot reach MQTT broker " + address);
                    },
                    7),
                "an untrusted broker was not reported");
    p.endAndWait();
  }
  {
    Publisher p("address=" + address + " source=unverified tls-verify=false");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < kFrames; ++i) p.push(i);
    p.endAndWait();
  }
  fail_unless(Subscriber::waitFor([&] { return subscriber.count() >= 2 * kFrames; }, 10), "received %zu",
              subscriber.count());
  const auto received = subscriber.received();
  fail_unless_equals_int(received.at("colortrack/tls").size(), kFrames);
  fail_unless_equals_int(received.at("colortrack/unverified").size(), kFrames);
  fail_unless(received.find("colortrack/untrusted") == received.end(),
              "documents went to an untrusted broker");
  for (int i = 0; i < kFrames; ++i) checkDocument(received.at("colortrack/tls")[i], "tls", i);
}
GST_END_TEST;

GST_START_TEST(test_bad_addresses_and_topics) {
  // Set before start: an error at start naming the property.
  for (const auto &[properties, part] : std::vector<std::pair<std::string, std::string>>{
           {"address=http://127.0.0.1:1883", "property 'address'"},
           {"address=tcp://127.0.0.1:99999", "property 'address'"},
           {"address=tcp:/127.0.0.1:1883", "property 'address'"},
           {"address=127.0.0.1", "property 'address'"},
           {"address=tcp://127.0.0.1:1883 topic=cams/+/tracks", "property 'topic'"},
           {"address=tcp://127.0.0.1:1883 source=a/# topic=x/{source}", "property 'topic'"},
           {"address=tcp://127.0.0.1:1883 topic=$SYS/x", "property 'topic'"},
           {"address=tcp://127.0.0.1:1883 topic=" + std::string(70000, 't'), "property 'topic'"},
           {"address=tcp://127.0.0.1:1883 topic=x/{source} source=" + std::string(65535, 's'),
            "property 'topic'"},
           {"address=tcp://127.0.0.1:1883 client-id=" + std::string(70000, 'c'), "property 'client-id'"},
           {"address=tcp://127.0.0.1:1883 tls-ca-file=/etc/hostname", "property 'tls-ca-file'"},
           {"address=tcp://127.0.0.1:1883 tls-key-file=/etc/hostname", "property 'tls-key-file'"},
           {"location=/nonexistent/x", "property 'location'"},
           {"location=/tmp", "property 'location'"},
           {"", "No output"}}) {
    Publisher p(properties);
    fail_unless_equals_int(p.play(), GST_STATE_CHANGE_FAILURE);
    const std::vector<std::string> errors = p.messages(GST_MESSAGE_ERROR);
    fail_unless(anyContains(errors, part), "'%s': no error with '%s'", properties.c_str(), part.c_str());
  }
  // Unreachable with fail-on-connect: an error at start, within the connect timeout.
  {
    Publisher p("address=tcp://127.0.0.1:" + std::to_string(freePort()) + " fail-on-connect=true");
    const auto start = Clock::now();
    fail_unless_equals_int(p.play(), GST_STATE_CHANGE_FAILURE);
    fail_unless(Clock::now() - start < std::chrono::seconds(8));
    fail_unless(anyContains(p.messages(GST_MESSAGE_ERROR), "Cannot reach MQTT broker"));
  }
  // Unreachable (refused, then an unresolvable host) without it: a warning, and the stream flows.
  for (const std::string &address :
       {"tcp://127.0.0.1:" + std::to_string(freePort()), std::string("tcp://no-such-host.invalid:1883")}) {
    Publisher p("address=" + address + " drain-timeout=0");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 10; ++i) p.push(i);
    // The warning comes when the first attempt fails (within the client's 5 s connect timeout).
    const std::string expected = "Cannot reach MQTT broker " + address;
    fail_unless(
        Subscriber::waitFor([&] { return anyContains(p.messages(GST_MESSAGE_WARNING), expected); }, 7),
        "no warning for %s", address.c_str());
    p.endAndWait();
    fail_unless_equals_int(p.drainSink(), 10);
  }
}
GST_END_TEST;

// A password in the address never reaches a message: it reads as ***.
GST_START_TEST(test_password_in_address_is_never_shown) {
  const std::string address = "tcp://robot:s3cret@127.0.0.1:" + std::to_string(freePort());
  Publisher p("address=" + address + " drain-timeout=0");
  if (p.play() != GST_STATE_CHANGE_FAILURE) {
    p.push(0);
    Subscriber::waitFor([&] { return !p.messages(GST_MESSAGE_WARNING).empty(); }, 7);
  }
  std::vector<std::string> all = p.messages(GST_MESSAGE_WARNING);
  for (const std::string &e : p.messages(GST_MESSAGE_ERROR)) all.push_back(e);
  fail_unless(anyContains(all, "tcp://robot:***@127.0.0.1"), "no message names the broker");
  fail_unless(!anyContains(all, "s3cret"), "a message shows the password");
}
GST_END_TEST;

// With the broker unreachable, EOS waits drain-timeout for the queue once; stopping afterwards does not wait
// for it again.
GST_START_TEST(test_unreachable_broker_drains_once) {
  auto p = std::make_unique<Publisher>("address=tcp://127.0.0.1:" + std::to_string(freePort()) +
                                       " drain-timeout=1000");
  fail_unless(p->play() != GST_STATE_CHANGE_FAILURE);
  for (int i = 0; i < 5; ++i) p->push(i);
  const auto eos = Clock::now();
  p->endAndWait();
  fail_unless(Clock::now() - eos >= std::chrono::milliseconds(900), "EOS did not wait for the queue");
  const auto stop = Clock::now();
  p.reset();  // to NULL
  const auto stopping = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - stop).count();
  fail_unless(stopping < 500, "stopping took %lld ms: drain-timeout waited a second time",
              static_cast<long long>(stopping));
}
GST_END_TEST;

GST_START_TEST(test_full_queue_drops_the_oldest_and_says_how_many) {
  Publisher p("address=tcp://127.0.0.1:" + std::to_string(freePort()) + " max-queued=10 drain-timeout=0");
  fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
  for (int i = 0; i < 50; ++i) p.push(i);
  p.endAndWait();
  const std::vector<std::string> warnings = p.messages(GST_MESSAGE_WARNING);
  fail_unless(anyContains(warnings, "MQTT queue full (max-queued=10)"),
              "no warning when the queue overflowed");
  fail_unless(anyContains(warnings, "40 documents dropped in all"),
              "no final count of the dropped documents");
}
GST_END_TEST;

// Not a broker: on 127.0.0.1:`port` it answers each CONNECT with a CONNACK and then with `after` (bytes no
// MQTT client can use), and holds the connection.
class FalseBroker {
 public:
  FalseBroker(int port, std::string after) : after_(std::move(after)) {
    fd_ = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    const int on = 1;
    setsockopt(fd_, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    address.sin_port = htons(static_cast<std::uint16_t>(port));
    fail_unless(bind(fd_, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0 &&
                listen(fd_, 8) == 0);
    thread_ = std::thread([this] { serve(); });
  }
  ~FalseBroker() {
    shutdown(fd_, SHUT_RDWR);  // ends accept()
    thread_.join();
    for (int c : clients_) close(c);
    close(fd_);
  }
  int connections() const { return connections_.load(); }

 private:
  void serve() {
    int client;
    while ((client = accept(fd_, nullptr, nullptr)) >= 0) {
      clients_.push_back(client);
      ++connections_;
      char connect[512];
      if (recv(client, connect, sizeof connect, 0) <= 0) continue;
      const std::string reply = std::string("\x20\x02\x00\x00", 4) + after_;
      send(client, reply.data(), reply.size(), MSG_NOSIGNAL);
    }
  }
  int fd_ = -1;
  std::string after_;
  std::thread thread_;
  std::vector<int> clients_;  // serve() only, then the destructor
  std::atomic<int> connections_{0};
};

// The warnings among `messages` that hold `part`.
int countContaining(const std::vector<std::string> &messages, const std::string &part) {
  return static_cast<int>(std::count_if(messages.begin(), messages.end(), [&](const std::string &m) {
    return m.find(part) != std::string::npos;
  }));
}

// A peer that accepts the connection and then sends half a packet: nothing acknowledges a document, Paho's
// keep-alive never notices, and the element says so within the answer timeout (10 s), not at EOS.
GST_START_TEST(test_false_broker_that_goes_silent_is_reported) {
  const int port = freePort();
  FalseBroker peer(port, std::string("\x30\x7f\x00", 3));  // a PUBLISH of 127 bytes, 1 of them sent
  Publisher p("address=127.0.0.1:" + std::to_string(port) + " drain-timeout=0");
  fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
  const auto start = Clock::now();
  int frame = 0;
  while (countContaining(p.messages(GST_MESSAGE_WARNING), "answered no document") == 0 &&
         Clock::now() - start < std::chrono::seconds(15)) {
    p.push(frame++);
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const double after = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("false broker, half a packet: warned after %.1f s, %d frames through\n", after, frame);
  fail_unless(countContaining(p.messages(GST_MESSAGE_WARNING), "answered no document") == 1,
              "no warning within 15 s");
  fail_unless(after > 9.5);
  p.endAndWait();
}
GST_END_TEST;

// A peer that answers with garbage right after the CONNACK: Paho drops every connection at once. One
// warning, not one per attempt, and the attempts back off.
GST_START_TEST(test_false_broker_that_talks_garbage_warns_once) {
  const int port = freePort();
  FalseBroker peer(port, std::string("\xf0\xff\xff\xff\xff\x7f", 6) + std::string(20, 'U'));
  Publisher p("address=tcp://127.0.0.1:" + std::to_string(port) + " drain-timeout=0");
  fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
  for (int i = 0; i < 60; ++i) {
    p.push(i);
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
  }
  const std::vector<std::string> warnings = p.messages(GST_MESSAGE_WARNING);
  for (const std::string &w : warnings) std::printf("warning: %s\n", w.c_str());
  std::printf("false broker, garbage: %d connections in 6 s\n", peer.connections());
  fail_unless_equals_int(countContaining(warnings, "Lost the connection"), 1);
  fail_unless(peer.connections() <= 10, "%d connections in 6 s: no back-off", peer.connections());
  p.endAndWait();
}
GST_END_TEST;

static Suite *trackpublish_suite(void) {
  Suite *s = suite_create("trackpublish");
  TCase *tc = tcase_create("general");
  tcase_set_timeout(tc, 120);
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_file_has_one_document_per_frame);
  tcase_add_test(tc, test_mqtt_delivers_every_frame_in_order);
  tcase_add_test(tc, test_mqtt_eight_sources_at_once);
  tcase_add_test(tc, test_mqtt_survives_a_broker_restart);
  tcase_add_test(tc, test_mqtt_over_tls);
  tcase_add_test(tc, test_bad_addresses_and_topics);
  tcase_add_test(tc, test_full_queue_drops_the_oldest_and_says_how_many);
  tcase_add_test(tc, test_fifo_location_never_blocks);
  tcase_add_test(tc, test_password_in_address_is_never_shown);
  tcase_add_test(tc, test_unreachable_broker_drains_once);
  tcase_add_test(tc, test_false_broker_that_goes_silent_is_reported);
  tcase_add_test(tc, test_false_broker_that_talks_garbage_warns_once);
  return s;
}

GST_CHECK_MAIN(trackpublish);
