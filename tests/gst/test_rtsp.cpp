// SPDX-License-Identifier: LGPL-2.1-or-later
// End-to-end test with a real RTSP server: a child process (this binary with --serve) runs gst-rtsp-server on
// 127.0.0.1, serving the synthetic scene as MJPEG or H.264 (what nearly every IP camera sends: openh264 from
// gst-plugins-bad) over RTP; the test runs
//   rtspsrc protocols=tcp ! rtpjpegdepay ! jpegdec ! videoconvert ! colortrack init-box=... ! appsink
// (rtph264depay ! h264parse ! openh264dec for H.264)
// and checks the track against the scene's ground truth. Then the server is killed and started again on the
// same port: the client restarts its source on the error (the pattern docs/sources.md recommends), and the
// test checks that frames come back and the target is re-acquired within a bounded time, without a crash.
//
// Frames are matched to ground truth by a frame index the server paints into the top rows of every frame
// (24 black/white 8x8 cells: 16 bits of index and an 8-bit check), so latency and dropped frames do not
// matter and no assumption is made about how RTP timestamps map to buffer PTS.
// C++ headers first: gstcheck.h defines macros (fail, ...) that clash with names in the standard library.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>

#include "scene.hpp"

#include <signal.h>
#include <sys/prctl.h>
#include <sys/select.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gst/app/gstappsink.h>
#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>
#include <gst/rtsp-server/rtsp-server.h>
#include <gst/video/video.h>

#include "rtsp_scene_server.hpp"

namespace {

using namespace rtsp_scene;

// ---------------------------------------------------------------------------------------------------------
// Client side (the test)

// The server child process: started, read from, killed like a crashing camera.
class ServerProcess {
 public:
  ServerProcess(int port, gint64 epochNs, const Codec &codec) {
    gchar *self = g_file_read_link("/proc/self/exe", nullptr);
    const std::string portText = std::to_string(port), epochText = std::to_string(epochNs);
    gchar *argv[] = {self,
                     const_cast<gchar *>("--serve"),
                     const_cast<gchar *>(portText.c_str()),
                     const_cast<gchar *>(epochText.c_str()),
                     const_cast<gchar *>(codec.name),
                     nullptr};
    GError *error = nullptr;
    // The child dies with the test (a failed assertion must not leave a server behind).
    auto dieWithParent = [](gpointer) { prctl(PR_SET_PDEATHSIG, SIGKILL); };
    const gboolean spawned =
        g_spawn_async_with_pipes(nullptr, argv, nullptr, G_SPAWN_DO_NOT_REAP_CHILD, dieWithParent, nullptr,
                                 &pid_, &stdin_, &stdout_, nullptr, &error);
    g_free(self);
    fail_unless(spawned, "cannot start the RTSP server process: %s", error ? error->message : "?");
  }
  ~ServerProcess() { kill(); }
  ServerProcess(const ServerProcess &) = delete;
  ServerProcess &operator=(const ServerProcess &) = delete;

  // The next line the server prints starting with `key`, as a number; -1 after `timeoutMs`.
  gint64 read(const std::string &key, int timeoutMs) {
    const auto deadline = Clock::now() + std::chrono::milliseconds(timeoutMs);
    while (true) {
      for (size_t end; (end = pending_.find('\n')) != std::string::npos;) {
        const std::string line = pending_.substr(0, end);
        pending_.erase(0, end + 1);
        if (line.rfind(key + " ", 0) == 0) return g_ascii_strtoll(line.c_str() + key.size() + 1, nullptr, 10);
      }
      const auto left =
          std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
      if (left <= 0 || !waitReadable(static_cast<int>(left))) return -1;
      char chunk[256];
      const ssize_t n = ::read(stdout_, chunk, sizeof chunk);
      if (n <= 0) return -1;
      pending_.append(chunk, static_cast<size_t>(n));
    }
  }

  // Sends one line to the server's stdin.
  void send(const std::string &line) {
    const std::string text = line + "\n";
    fail_unless(::write(stdin_, text.data(), text.size()) == static_cast<ssize_t>(text.size()),
                "cannot write to the RTSP server process");
  }

  void kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    waitpid(pid_, nullptr, 0);
    g_spawn_close_pid(pid_);
    close(stdout_);
    close(stdin_);
    pid_ = 0;
  }

 private:
  bool waitReadable(int timeoutMs) {
    fd_set fds;
    FD_ZERO(&fds);
    FD_SET(stdout_, &fds);
    timeval tv{timeoutMs / 1000, (timeoutMs % 1000) * 1000};
    return select(stdout_ + 1, &fds, nullptr, nullptr, &tv) > 0;
  }

  GPid pid_ = 0;
  int stdin_ = -1, stdout_ = -1;
  std::string pending_;
};

// What the appsink saw for one frame.
struct Observation {
  int index = -1;        // scene frame index painted by the server (-1: unreadable)
  double seconds = 0;    // wall clock since the client started
  int connection = 0;    // how many times the source had been (re)started when the frame arrived
  bool hasMeta = false;  // colortrack attached a ROI meta
  cv::Rect2d box;
  std::string state;
};

// The application: the pipeline, and the reconnection policy a real user would run around it. rtspsrc does
// not reconnect by itself after the server went away, so on an error from it (or when no frame came for
// kStallSeconds) only the source is restarted, with back-off: colortrack and everything downstream keep
// running, so the template taken from init-box, the track numbering and the sinks survive the outage.
class RtspClient {
 public:
  static constexpr double kStallSeconds = 2.0;
  static constexpr double kFirstBackoff = 0.2, kMaxBackoff = 1.0;
  static constexpr const char *kSourceEos = "source-eos";

  RtspClient(const std::string &location, const cv::Rect &initBox, const Codec &codec)
      : start_(Clock::now()) {
    GError *error = nullptr;
    pipeline_ = gst_parse_launch(
        (std::string(codec.decode) + " ! videoconvert ! video/x-raw,format=I420 ! colortrack name=tracker ! "
                                     "appsink name=sink sync=false")
            .c_str(),
        &error);
    fail_unless(pipeline_ != nullptr, "client pipeline: %s", error ? error->message : "?");
    source_ = gst_element_factory_make("rtspsrc", "source");
    fail_unless(source_ != nullptr, "rtspsrc is missing (gstreamer1.0-plugins-good)");
    // TCP: a server that goes away closes the connection, which rtspsrc reports at once as an error.
    g_object_set(source_, "location", location.c_str(), "latency", 100, nullptr);
    gst_util_set_object_arg(G_OBJECT(source_), "protocols", "tcp");
    gst_bin_add(GST_BIN(pipeline_), source_);
    g_signal_connect(source_, "pad-added", G_CALLBACK(onPadAdded), this);

    GstElement *depay = gst_bin_get_by_name(GST_BIN(pipeline_), "depay");
    depaySink_ = gst_element_get_static_pad(depay, "sink");
    gst_object_unref(depay);
    // rtspsrc answers a server that closed the connection with a warning and EOS, not an error. The EOS
    // must not end the stream for everything downstream: it is dropped here and turned into a message.
    gst_pad_add_probe(depaySink_, GST_PAD_PROBE_TYPE_EVENT_DOWNSTREAM, sourceEosToMessage, source_, nullptr);

    GstElement *tracker = gst_bin_get_by_name(GST_BIN(pipeline_), "tracker");
    const std::string box = std::to_string(initBox.x) + "," + std::to_string(initBox.y) + "," +
                            std::to_string(initBox.width) + "," + std::to_string(initBox.height);
    g_object_set(tracker, "init-box", box.c_str(), nullptr);
    GstPad *trackerSink = gst_element_get_static_pad(tracker, "sink");
    gst_pad_add_probe(trackerSink, GST_PAD_PROBE_TYPE_BUFFER, readIndexProbe, this, nullptr);
    gst_object_unref(trackerSink);
    gst_object_unref(tracker);

    GstElement *sink = gst_bin_get_by_name(GST_BIN(pipeline_), "sink");
    GstAppSinkCallbacks callbacks{};
    callbacks.new_sample = onSample;
    gst_app_sink_set_callbacks(GST_APP_SINK(sink), &callbacks, this, nullptr);
    gst_object_unref(sink);

    bus_ = gst_element_get_bus(pipeline_);
    connections_ = 1;
    fail_if(gst_element_set_state(pipeline_, GST_STATE_PLAYING) == GST_STATE_CHANGE_FAILURE);
  }

  ~RtspClient() {
    gst_element_set_state(pipeline_, GST_STATE_NULL);
    gst_object_unref(depaySink_);
    gst_object_unref(bus_);
    gst_object_unref(pipeline_);
  }

  double now() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

  // Runs the application's loop until `done()` or `timeout` seconds; returns done().
  template <typename Predicate>
  bool runUntil(Predicate done, double timeout) {
    const double until = now() + timeout;
    while (!done() && now() < until) step();
    return done();
  }

  std::vector<Observation> observations() {
    std::lock_guard<std::mutex> lock(mutex_);
    return observations_;
  }
  int sourceErrors() const { return sourceErrors_; }
  int sourceEnds() const { return sourceEnds_; }
  int stalls() const { return stalls_; }
  int connections() const { return connections_; }
  const std::vector<std::string> &otherErrors() const { return otherErrors_; }
  GstState pipelineState() {
    GstState state = GST_STATE_VOID_PENDING;
    gst_element_get_state(pipeline_, &state, nullptr, 0);
    return state;
  }

 private:
  // One turn of the loop: a bus message (or 20 ms), then the restart timer and the stall watchdog.
  void step() {
    if (GstMessage *message = gst_bus_timed_pop(bus_, 20 * GST_MSECOND)) {
      handle(message);
      gst_message_unref(message);
    }
    const double t = now();
    if (restartAt_ >= 0 && t >= restartAt_) {
      restartAt_ = -1;
      ++connections_;
      // The pipeline's clock and base time, so the new session's timestamps continue the running time.
      GstClock *clock = gst_pipeline_get_clock(GST_PIPELINE(pipeline_));
      gst_element_set_clock(source_, clock);
      gst_object_unref(clock);
      gst_element_set_base_time(source_, gst_element_get_base_time(pipeline_));
      gst_element_sync_state_with_parent(source_);
    } else if (restartAt_ < 0 && t - lastFrameAt() > kStallSeconds) {
      ++stalls_;  // a silent server (power cut, cable pulled) closes nothing: only time tells
      scheduleRestart();
    }
  }

  void handle(GstMessage *message) {
    if (GST_MESSAGE_TYPE(message) == GST_MESSAGE_APPLICATION && gst_message_has_name(message, kSourceEos)) {
      ++sourceEnds_;
      GST_INFO("the source ended (server closed the connection): restarting it");
      if (restartAt_ < 0) scheduleRestart();
      return;
    }
    if (GST_MESSAGE_TYPE(message) != GST_MESSAGE_ERROR) return;
    GError *error = nullptr;
    gst_message_parse_error(message, &error, nullptr);
    if (gst_object_has_as_ancestor(GST_MESSAGE_SRC(message), GST_OBJECT(source_))) {
      ++sourceErrors_;
      GST_INFO("source error (%s): restarting the source", error->message);
      if (restartAt_ < 0) scheduleRestart();
    } else {
      otherErrors_.push_back(std::string(GST_OBJECT_NAME(GST_MESSAGE_SRC(message))) + ": " + error->message);
    }
    g_error_free(error);
  }

  void scheduleRestart() {
    gst_element_set_state(source_, GST_STATE_NULL);
    std::lock_guard<std::mutex> lock(mutex_);
    // Quick after a session that delivered frames; doubling up to kMaxBackoff while the server stays away.
    backoff_ = framesSinceRestart_ > 0 ? kFirstBackoff : std::min(backoff_ * 2, kMaxBackoff);
    framesSinceRestart_ = 0;
    restartAt_ = now() + backoff_;
    lastFrame_ = now();  // the stall watchdog counts from the restart
  }

  double lastFrameAt() {
    std::lock_guard<std::mutex> lock(mutex_);
    return lastFrame_;
  }

  static void onPadAdded(GstElement *, GstPad *pad, gpointer data) {
    auto *self = static_cast<RtspClient *>(data);
    if (!gst_pad_is_linked(self->depaySink_) && gst_pad_link(pad, self->depaySink_) != GST_PAD_LINK_OK)
      GST_WARNING("cannot link %s to the depayloader", GST_PAD_NAME(pad));
  }

  static GstPadProbeReturn sourceEosToMessage(GstPad *, GstPadProbeInfo *info, gpointer source) {
    if (GST_EVENT_TYPE(GST_PAD_PROBE_INFO_EVENT(info)) != GST_EVENT_EOS) return GST_PAD_PROBE_OK;
    gst_element_post_message(
        GST_ELEMENT(source),
        gst_message_new_application(GST_OBJECT(source), gst_structure_new_empty(kSourceEos)));
    return GST_PAD_PROBE_DROP;
  }

  // Reads the painted index before colortrack draws its overlay over the frame.
  static GstPadProbeReturn readIndexProbe(GstPad *pad, GstPadProbeInfo *info, gpointer data) {
    auto *self = static_cast<RtspClient *>(data);
    GstBuffer *buffer = GST_PAD_PROBE_INFO_BUFFER(info);
    GstCaps *caps = gst_pad_get_current_caps(pad);
    GstVideoInfo videoInfo;
    int index = -1;
    GstVideoFrame frame;
    if (caps && gst_video_info_from_caps(&videoInfo, caps) &&
        gst_video_frame_map(&frame, &videoInfo, buffer, GST_MAP_READ)) {
      const cv::Mat luma(GST_VIDEO_FRAME_HEIGHT(&frame), GST_VIDEO_FRAME_WIDTH(&frame), CV_8UC1,
                         GST_VIDEO_FRAME_PLANE_DATA(&frame, 0), GST_VIDEO_FRAME_PLANE_STRIDE(&frame, 0));
      index = readFrameIndex(luma);
      gst_video_frame_unmap(&frame);
    }
    if (caps) gst_caps_unref(caps);
    std::lock_guard<std::mutex> lock(self->mutex_);
    self->pendingIndex_.emplace_back(GST_BUFFER_PTS(buffer), index);
    return GST_PAD_PROBE_OK;
  }

  static GstFlowReturn onSample(GstAppSink *sink, gpointer data) {
    auto *self = static_cast<RtspClient *>(data);
    GstSample *sample = gst_app_sink_pull_sample(sink);
    GstBuffer *buffer = gst_sample_get_buffer(sample);
    Observation o;
    o.seconds = self->now();
    o.connection = self->connections_;
    if (GstVideoRegionOfInterestMeta *roi = gst_buffer_get_video_region_of_interest_meta(buffer);
        roi && roi->roi_type == g_quark_from_string("colortrack")) {
      o.hasMeta = true;
      o.box = cv::Rect2d(roi->x, roi->y, roi->w, roi->h);
      const GstStructure *params = gst_video_region_of_interest_meta_get_param(roi, "colortrack");
      const char *state = params ? gst_structure_get_string(params, "state") : nullptr;
      o.state = state ? state : "";
    }
    {
      std::lock_guard<std::mutex> lock(self->mutex_);
      // Buffers leave colortrack in the order they entered: drop the probe's entries of any that did not.
      while (!self->pendingIndex_.empty() && self->pendingIndex_.front().first != GST_BUFFER_PTS(buffer))
        self->pendingIndex_.pop_front();
      if (!self->pendingIndex_.empty()) {
        o.index = self->pendingIndex_.front().second;
        self->pendingIndex_.pop_front();
      }
      self->observations_.push_back(o);
      self->lastFrame_ = o.seconds;
      ++self->framesSinceRestart_;
    }
    gst_sample_unref(sample);
    return GST_FLOW_OK;
  }

  Clock::time_point start_;
  GstElement *pipeline_ = nullptr, *source_ = nullptr;
  GstPad *depaySink_ = nullptr;
  GstBus *bus_ = nullptr;
  std::atomic<int> connections_{0};
  int sourceErrors_ = 0, sourceEnds_ = 0, stalls_ = 0;
  double restartAt_ = -1, backoff_ = kFirstBackoff;
  std::vector<std::string> otherErrors_;

  std::mutex mutex_;  // guards what the streaming thread writes
  std::deque<std::pair<GstClockTime, int>> pendingIndex_;
  std::vector<Observation> observations_;
  double lastFrame_ = 0;
  int framesSinceRestart_ = 0;
};

// IoU figures of a run of observations against the scene's ground truth.
struct Quality {
  int frames = 0, unreadable = 0, tracked = 0;  // tracked: meta present and IoU >= 0.5
  double meanIou = 0;
};

Quality quality(const Scene &scene, const std::vector<Observation> &run) {
  Quality q;
  double sum = 0;
  for (const Observation &o : run) {
    if (o.index < 0) {
      ++q.unreadable;
      continue;
    }
    ++q.frames;
    const double overlap = o.hasMeta ? colortrack::scene::iou(o.box, scene.render(o.index).box) : 0.0;
    sum += overlap;
    if (overlap >= 0.5) ++q.tracked;
  }
  q.meanIou = q.frames ? sum / q.frames : 0;
  return q;
}

// Tracks over RTSP in `codec`, the server killed and started again mid-stream.
// GStreamer 1.22's rtspsrc sometimes sends an event with an unset sequence number while it tears a dead
// session down, which logs this critical from inside the library (seen once in many runs, 2026-12-04). It is
// not this project's to fix and changes nothing downstream; every other critical still fails the test.
void ignoreRtspsrcUnsetSeqnum() {
  GRegex *unsetSeqnum = g_regex_new("gst_event_set_seqnum: assertion 'seqnum != GST_SEQNUM_INVALID' failed",
                                    GRegexCompileFlags(0), GRegexMatchFlags(0), nullptr);
  gst_check_add_log_filter("GStreamer", G_LOG_LEVEL_CRITICAL, unsetSeqnum, nullptr, nullptr, nullptr);
}

void trackAndSurviveServerRestart(const Codec &codec) {
  g_print("rtsp: %s\n", codec.name);
  ignoreRtspsrcUnsetSeqnum();
  const Scene scene(sceneConfig());
  // The frame-index strip must stay clear of the object, or the ground truth would be wrong.
  for (int i = 0; i < scene.config().frames; ++i)
    fail_unless(scene.render(i).box.y > 2 * kCell, "the object reaches the index strip at frame %d", i);

  auto server = std::make_unique<ServerProcess>(0, 0, codec);
  const gint64 port = server->read("PORT", 10000);
  fail_unless(port > 0, "the RTSP server did not start");
  const std::string location = "rtsp://127.0.0.1:" + std::to_string(port) + kMount;
  RtspClient client(location, scene.initBox(), codec);

  // Phase 1: connect, track for 3 s of motion.
  auto frames = [&] { return client.observations().size(); };
  fail_unless(client.runUntil([&] { return frames() > 0; }, 10.0), "no frame from %s", location.c_str());
  server->send("GO");
  const gint64 epoch = server->read("EPOCH", 2000);
  fail_unless(epoch > 0, "the server did not report its scene clock");
  const double firstFrameAt = client.observations().front().seconds;
  fail_unless_equals_int(client.observations().front().index, 0);  // the init-box is frame 0's box
  auto lastIndex = [&] {
    const auto seen = client.observations();
    return seen.empty() ? -1 : seen.back().index;
  };
  fail_unless(client.runUntil([&] { return lastIndex() >= 3 * kFps; }, 10.0), "the scene stopped at frame %d",
              lastIndex());
  const std::vector<Observation> before = client.observations();
  const Quality q1 = quality(scene, before);

  // Phase 2: the server dies (SIGKILL: no TEARDOWN, the kernel closes the sockets). Down for 1 s, during
  // which the client's reconnection attempts are refused.
  // A slow first connection (over kStallSeconds on a loaded machine) may have counted a stall already.
  const int stallsBeforeKill = client.stalls();
  server->kill();
  const double killedAt = client.now();
  auto disconnects = [&] { return client.sourceErrors() + client.sourceEnds() + client.stalls(); };
  const int disconnectsBefore = disconnects();
  const bool noticed = client.runUntil([&] { return disconnects() > disconnectsBefore; }, 3.0);
  const double noticedAfter = client.now() - killedAt;
  const int stallsWhenNoticed = client.stalls();
  client.runUntil([] { return false; }, std::max(0.0, 1.0 - noticedAfter));
  const int attemptsWhileDown = client.connections() - 1;

  // Phase 3: the server comes back on the same port with the same scene clock; the scene has moved on.
  server = std::make_unique<ServerProcess>(static_cast<int>(port), epoch, codec);
  fail_unless_equals_int(server->read("PORT", 10000), static_cast<int>(port));
  const double restartedAt = client.now();
  const size_t seenBefore = before.size();
  auto afterRestart = [&] {
    auto seen = client.observations();
    std::vector<Observation> later;
    for (size_t i = seenBefore; i < seen.size(); ++i)
      if (seen[i].seconds >= restartedAt) later.push_back(seen[i]);
    return later;
  };
  const bool reconnected = client.runUntil([&] { return !afterRestart().empty(); }, 8.0);
  const double reconnectSeconds = reconnected ? afterRestart().front().seconds - restartedAt : -1;
  auto reacquired = [&] {
    for (const Observation &o : afterRestart())
      if (o.index >= 0 && o.hasMeta && colortrack::scene::iou(o.box, scene.render(o.index).box) >= 0.5)
        return o.seconds;
    return -1.0;
  };
  client.runUntil([&] { return reacquired() >= 0; }, 8.0);
  const double reacquireSeconds = reacquired() >= 0 ? reacquired() - restartedAt : -1;
  // Two more seconds after re-acquisition.
  const double settledAt = client.now();
  client.runUntil([&] { return false; }, 2.0);
  std::vector<Observation> settled;
  for (const Observation &o : afterRestart())
    if (o.seconds >= settledAt) settled.push_back(o);
  const Quality q2 = quality(scene, settled);
  const int jump = afterRestart().empty() ? 0 : afterRestart().front().index - before.back().index;

  g_print(
      "rtsp: first frame %.2f s after start; before the restart %d frames (%d unreadable), mean IoU %.3f, "
      "IoU>=0.5 in %d\n",
      firstFrameAt, q1.frames, q1.unreadable, q1.meanIou, q1.tracked);
  g_print(
      "rtsp: server killed: noticed after %.2f s (%d source EOS, %d source errors, %d stalls), %d restart "
      "attempts while down\n",
      noticedAfter, client.sourceEnds(), client.sourceErrors(), client.stalls(), attemptsWhileDown);
  g_print(
      "rtsp: server back: first frame after %.2f s (scene %d frames on), target re-acquired after %.2f s; "
      "then %d frames, mean IoU %.3f, IoU>=0.5 in %d\n",
      reconnectSeconds, jump, reacquireSeconds, q2.frames, q2.meanIou, q2.tracked);
  for (const std::string &e : client.otherErrors())
    g_print("rtsp: error outside the source: %s\n", e.c_str());

  // Before the restart: at 30 fps for >= 3 s, few frames lost, the object tracked.
  fail_unless(q1.frames >= 2 * kFps, "only %d frames in the first session", q1.frames);
  fail_unless(q1.unreadable <= q1.frames / 20, "%d frames with an unreadable index", q1.unreadable);
  fail_unless(q1.meanIou >= 0.6, "mean IoU %.3f before the restart", q1.meanIou);
  fail_unless(q1.tracked >= 0.9 * q1.frames, "IoU >= 0.5 in only %d of %d frames", q1.tracked, q1.frames);
  // The outage: seen quickly, retried without giving up, nothing outside the source failed.
  // The close is seen at once (EOS), not by the stall watchdog. (A reconnection that brings no frame for
  // kStallSeconds, as on a loaded machine, may count a stall later: that is the recovery path working.)
  fail_unless(noticed && noticedAfter < 1.0, "the disconnect went unnoticed for %.2f s", noticedAfter);
  fail_unless_equals_int(stallsWhenNoticed, stallsBeforeKill);
  fail_unless(attemptsWhileDown >= 1, "no reconnection attempt while the server was down");
  fail_unless(client.otherErrors().empty(), "errors outside the source");
  // After the restart: frames again, the object (which moved meanwhile) found again, tracked again.
  fail_unless(reconnected && reconnectSeconds < 5.0, "no frame within %.1f s of the server's return",
              reconnectSeconds);
  fail_unless(jump >= kFps, "the scene moved on by only %d frames during the outage", jump);
  fail_unless(reacquireSeconds >= 0 && reacquireSeconds < 6.0, "target not re-acquired (%.2f s)",
              reacquireSeconds);
  fail_unless(q2.frames >= kFps, "only %d frames after re-acquisition", q2.frames);
  fail_unless(q2.meanIou >= 0.6, "mean IoU %.3f after re-acquisition", q2.meanIou);
  fail_unless(q2.tracked >= 0.9 * q2.frames, "IoU >= 0.5 in only %d of %d frames after re-acquisition",
              q2.tracked, q2.frames);
  fail_unless_equals_int(client.pipelineState(), GST_STATE_PLAYING);
}

GST_START_TEST(test_mjpeg_over_rtsp_survives_server_restart) {
  trackAndSurviveServerRestart(kMjpeg);
}
GST_END_TEST;

GST_START_TEST(test_h264_over_rtsp_survives_server_restart) {
  trackAndSurviveServerRestart(kH264);
}
GST_END_TEST;

// Without openh264 the H.264 test is left out, said SKIPPED, and the binary exits 77 (meson: skipped) once
// the rest has passed.
Suite *rtsp_suite(bool withH264) {
  Suite *s = suite_create("rtsp");
  TCase *tc = tcase_create("rtsp");
  tcase_set_timeout(tc, 60);
  tcase_add_test(tc, test_mjpeg_over_rtsp_survives_server_restart);
  if (withH264) tcase_add_test(tc, test_h264_over_rtsp_survives_server_restart);
  suite_add_tcase(s, tc);
  return s;
}

}  // namespace

int main(int argc, char **argv) {
  if (argc == 5 && std::string(argv[1]) == "--serve")
    return serve(std::atoi(argv[2]), g_ascii_strtoll(argv[3], nullptr, 10), codecNamed(argv[4]));
  gst_check_init(&argc, &argv);
  const bool withH264 = available(kH264);
  if (!withH264)
    g_print("rtsp: SKIPPED: H.264 needs openh264enc, openh264dec and h264parse (gstreamer1.0-plugins-bad)\n");
  Suite *suite = rtsp_suite(withH264);
  SRunner *runner = srunner_create(suite);
  srunner_run_all(runner, CK_NORMAL);
  const int failed = srunner_ntests_failed(runner);
  srunner_free(runner);
  if (failed != 0) return 1;
  return withH264 ? 0 : 77;
}
