// SPDX-License-Identifier: LGPL-2.1-or-later
// What the trackpublish tests share: frames with ROI metas and the documents expected of them, a broker
// (Debian's mosquitto on a free loopback port), a subscriber (Paho) and a publishing pipeline. Included by
// test_trackpublish.cpp and test_trackpublish_errors.cpp, after gstcheck.h (it uses fail_unless).
#pragma once

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

namespace trackpublish_rig {

using Clock = std::chrono::steady_clock;
using colortrack::gst_test_util::contains;
using colortrack::gst_test_util::kFps;

inline constexpr int kWidth = 320, kHeight = 240;

// ---------------------------------------------------------------------------------------------------------
// Frames with known tracks

struct TrackBox {
  int id;
  int x, y, w, h;
  const char *state;
  double score;
};

// The tracks of frame `frame`: 1 to 3 objects moving, so every document differs.
inline std::vector<TrackBox> tracksOf(int frame) {
  std::vector<TrackBox> tracks;
  for (int id = 1; id <= 1 + frame % 3; ++id)
    tracks.push_back({id, (frame * 3 + id * 50) % 250, 20 + id * 40, 20 + id, 30,
                      id == 2 ? "coasting" : "tracking", 0.25 * id});
  return tracks;
}

inline GstBuffer *frameBuffer(int frame) {
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

inline std::string caps() {
  return "video/x-raw,format=GRAY8,width=" + std::to_string(kWidth) + ",height=" + std::to_string(kHeight) +
         ",framerate=" + std::to_string(kFps) + "/1";
}

// A text member equal to `expected` (compared as std::string: fail_unless_equals_string would keep a pointer
// into a temporary).
inline void expectText(const nlohmann::json &value, const std::string &expected) {
  const std::string text = value.is_string() ? value.get<std::string>() : value.dump();
  fail_unless(text == expected, "'%s' instead of '%s'", text.c_str(), expected.c_str());
}

// One parsed document; fails the test when it is not what frame `frame` of `source` should give.
inline void checkDocument(const std::string &text, const std::string &source, int frame) {
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
inline int frameOf(const std::string &text) {
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  return doc.is_object() && doc.contains("frame") ? doc["frame"].get<int>() : -1;
}

// ---------------------------------------------------------------------------------------------------------
// A broker and a subscriber

inline int freePort() {
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
// certificate for 127.0.0.1 signed by a certificate authority of the test's own (ca.pem in dir()). With
// `user`, only that user with `password` may connect (mosquitto_passwd's password file).
class Broker {
 public:
  explicit Broker(int port, int tlsPort = 0, const std::string &user = "", const std::string &password = "")
      : port_(port) {
    gchar *dir = g_dir_make_tmp("trackpublish-broker-XXXXXX", nullptr);
    dir_ = dir;
    g_free(dir);
    const std::string config = dir_ + "/mosquitto.conf";
    std::ofstream out(config);
    // `user`: started by root, mosquitto would switch to its own user, which cannot write our directory.
    out << "user " << g_get_user_name() << "\nlistener " << port << " 127.0.0.1\nallow_anonymous "
        << (user.empty() ? "true" : "false") << "\npersistence true\n"
        << "persistence_location " << dir_ << "/\nmax_queued_messages 100000\n";
    if (!user.empty()) {
      const std::string command = "mosquitto_passwd -b -c '" + dir_ + "/passwords' '" + user + "' '" +
                                  password + "' > /dev/null 2>&1";
      fail_unless(std::system(command.c_str()) == 0, "mosquitto_passwd (package mosquitto) failed");
      out << "password_file " << dir_ << "/passwords\n";
    }
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
  void end() { gst_app_src_end_of_stream(GST_APP_SRC(src_)); }
  // EOS, then waits for it on the bus (trackpublish passes EOS on once its queue is delivered).
  void endAndWait() {
    end();
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

inline bool anyContains(const std::vector<std::string> &texts, const std::string &part) {
  return std::any_of(texts.begin(), texts.end(), [&](const std::string &t) { return contains(t, part); });
}

}  // namespace trackpublish_rig
