// SPDX-License-Identifier: LGPL-2.1-or-later
// The RTSP test's camera: gst-rtsp-server on 127.0.0.1 serving the synthetic scene as MJPEG or H.264, each
// frame carrying its index in its top rows (so a client matches frames to ground truth whatever the latency),
// and the scene clock shared across a restart. Run as `test-gst-rtsp --serve PORT EPOCH_NS CODEC` (see
// serve()); included by test_rtsp.cpp only, after gstcheck.h.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "scene.hpp"

#include <unistd.h>

#include <gst/app/gstappsrc.h>
#include <gst/check/gstcheck.h>
#include <gst/rtsp-server/rtsp-server.h>
#include <gst/video/video.h>

namespace rtsp_scene {

using colortrack::scene::Scene;
using colortrack::scene::SceneConfig;
using Clock = std::chrono::steady_clock;

inline constexpr int kFps = 30;
inline constexpr int kCell = 8;  // one JPEG block: a flat block survives compression untouched
inline constexpr int kIndexBits = 16, kCheckBits = 8;
inline constexpr const char *kMount = "/scene";

// How the server encodes the scene and how the client decodes it. H.264: a key frame every second (a client
// that joins, or comes back, waits at most that long for a picture) and the parameter sets with each one.
struct Codec {
  const char *name, *encode, *decode;
  std::vector<const char *> elements;  // what both sides need
};
inline const Codec kMjpeg{"mjpeg",
                          "jpegenc quality=90 ! rtpjpegpay name=pay0 pt=26",
                          "rtpjpegdepay name=depay ! jpegdec",
                          {"jpegenc", "jpegdec"}};
inline const Codec kH264{"h264",
                         "openh264enc bitrate=2000000 gop-size=30 complexity=low ! h264parse ! "
                         "rtph264pay name=pay0 pt=96 config-interval=-1",
                         "rtph264depay name=depay ! h264parse ! openh264dec",
                         {"openh264enc", "openh264dec", "h264parse"}};

inline const Codec &codecNamed(const std::string &name) {
  return name == kH264.name ? kH264 : kMjpeg;
}

// Whether this machine has what `codec` needs (openh264 comes with Debian's gstreamer1.0-plugins-bad).
inline bool available(const Codec &codec) {
  for (const char *element : codec.elements) {
    GstElementFactory *factory = gst_element_factory_find(element);
    if (!factory) return false;
    gst_object_unref(factory);
  }
  return true;
}

inline SceneConfig sceneConfig() {
  SceneConfig config;
  config.frameSize = cv::Size(320, 240);  // small: encode + decode + track stay well under a frame period
  config.objectSize = cv::Size(40, 40);
  config.frames = 240;  // one pass of the motion script every 8 s
  return config;
}

inline int checkBits(int index) {
  return (index ^ (index >> 8) ^ 0x5a) & 0xff;
}

// Paints `index` into the top kCell rows of a BGR frame.
inline void paintFrameIndex(cv::Mat &bgr, int index) {
  const int word = index | (checkBits(index) << kIndexBits);
  for (int bit = 0; bit < kIndexBits + kCheckBits; ++bit) {
    const cv::Scalar colour = (word >> bit) & 1 ? cv::Scalar::all(255) : cv::Scalar::all(0);
    bgr(cv::Rect(bit * kCell, 0, kCell, kCell)).setTo(colour);
  }
}

// Reads the index back from a luma plane; -1 when the check bits do not match.
inline int readFrameIndex(const cv::Mat &luma) {
  int word = 0;
  for (int bit = 0; bit < kIndexBits + kCheckBits; ++bit) {
    // The cell's centre: its borders take some ringing from the neighbours.
    const double mean = cv::mean(luma(cv::Rect(bit * kCell + 2, 2, kCell - 4, kCell - 4)))[0];
    if (mean > 128) word |= 1 << bit;
  }
  const int index = word & ((1 << kIndexBits) - 1);
  return (word >> kIndexBits) == checkBits(index) ? index : -1;
}

inline gint64 monotonicNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now().time_since_epoch()).count();
}

// ---------------------------------------------------------------------------------------------------------
// Server side (child process)

// Pushes scene frames into the media's appsrc at kFps, the frame index following the wall clock from a
// shared epoch, as a live camera would: after a restart the scene has moved on. Until the epoch is set the
// scene holds still on frame 0; the first server sets it when the test says it has seen a frame ("GO" on the
// server's stdin), so the client's first frame is frame 0 and the init-box (frame 0's box) is exact however
// slowly the client connects.
class SceneFeeder {
 public:
  SceneFeeder(GstAppSrc *appsrc, std::atomic<gint64> &epochNs, const std::atomic<bool> &go)
      : appsrc_(appsrc), epochNs_(epochNs), go_(go) {
    thread_ = std::thread([this] { run(); });
  }
  ~SceneFeeder() {
    stop_ = true;
    thread_.join();
    gst_object_unref(appsrc_);
  }

 private:
  void run() {
    const Scene scene(sceneConfig());
    const GstClockTime period = GST_SECOND / kFps;
    GstVideoInfo info;
    gst_video_info_set_format(&info, GST_VIDEO_FORMAT_BGR, scene.config().frameSize.width,
                              scene.config().frameSize.height);
    bool delivered = false;
    while (!stop_) {
      const auto wakeUp = Clock::now() + std::chrono::nanoseconds(period);
      const gint64 now = monotonicNs();
      gint64 unset = 0;
      if (go_ && epochNs_.compare_exchange_strong(unset, now)) {  // the first feeder to start the clock
        std::printf("EPOCH %" G_GINT64_FORMAT "\n", now);
        std::fflush(stdout);
      }
      const gint64 epoch = epochNs_.load();
      const double sinceEpoch = epoch == 0 ? 0 : (now - epoch) / 1e9;
      const int index = sinceEpoch <= 0 ? 0 : static_cast<int>(sinceEpoch * kFps);

      cv::Mat bgr = scene.render(index).bgr;
      paintFrameIndex(bgr, index);
      GstBuffer *buffer = gst_buffer_new_allocate(nullptr, info.size, nullptr);
      GstMapInfo map;
      gst_buffer_map(buffer, &map, GST_MAP_WRITE);
      cv::Mat target(bgr.size(), CV_8UC3, map.data, GST_VIDEO_INFO_PLANE_STRIDE(&info, 0));
      bgr.copyTo(target);
      gst_buffer_unmap(buffer, &map);
      const GstFlowReturn flow = gst_app_src_push_buffer(appsrc_, buffer);
      // FLUSHING until the media pipeline runs; after it ran, FLUSHING or EOS mean the media is going away.
      if (flow == GST_FLOW_OK)
        delivered = true;
      else if (delivered)
        break;
      std::this_thread::sleep_until(wakeUp);
    }
  }

  GstAppSrc *appsrc_;
  std::atomic<gint64> &epochNs_;  // shared by the feeders of every client
  const std::atomic<bool> &go_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

struct ServerState {
  std::atomic<gint64> epochNs{0};
  std::atomic<bool> go{false};
  std::vector<std::unique_ptr<SceneFeeder>> feeders;
};

inline void onMediaConfigure(GstRTSPMediaFactory *, GstRTSPMedia *media, gpointer data) {
  auto *state = static_cast<ServerState *>(data);
  GstElement *bin = gst_rtsp_media_get_element(media);
  GstElement *appsrc = gst_bin_get_by_name_recurse_up(GST_BIN(bin), "scene");
  gst_object_unref(bin);
  state->feeders.push_back(std::make_unique<SceneFeeder>(GST_APP_SRC(appsrc), state->epochNs, state->go));
}

// Any line on stdin ("GO") starts the scene clock.
inline gboolean onCommand(GIOChannel *channel, GIOCondition, gpointer data) {
  gchar *line = nullptr;
  const GIOStatus status = g_io_channel_read_line(channel, &line, nullptr, nullptr, nullptr);
  g_free(line);
  if (status == G_IO_STATUS_NORMAL) static_cast<ServerState *>(data)->go = true;
  return status == G_IO_STATUS_NORMAL || status == G_IO_STATUS_AGAIN;
}

// `--serve PORT EPOCH_NS CODEC`: PORT 0 takes an ephemeral port; EPOCH_NS 0 holds frame 0 until a line on
// stdin, then starts the scene clock and prints it ("EPOCH n") so a restarted server can continue the same
// scene. CODEC: mjpeg or h264. Prints "INITBOX x,y,w,h" (the object in frame 0) and "PORT n" once listening.
// Runs until killed.
inline int serve(int port, gint64 epochNs, const Codec &codec) {
  gst_init(nullptr, nullptr);
  ServerState state;
  state.epochNs = epochNs;
  GstRTSPServer *server = gst_rtsp_server_new();
  gst_rtsp_server_set_address(server, "127.0.0.1");
  const std::string service = std::to_string(port);
  gst_rtsp_server_set_service(server, service.c_str());

  const cv::Size size = sceneConfig().frameSize;
  // I420 into jpegenc: RTP/JPEG (RFC 2435) carries only 4:2:0 and 4:2:2 JPEGs.
  const std::string launch =
      "( appsrc name=scene is-live=true format=time do-timestamp=true "
      "caps=video/x-raw,format=BGR,width=" +
      std::to_string(size.width) + ",height=" + std::to_string(size.height) +
      ",framerate=" + std::to_string(kFps) + "/1 ! videoconvert ! video/x-raw,format=I420 ! " + codec.encode +
      " )";
  GstRTSPMediaFactory *factory = gst_rtsp_media_factory_new();
  gst_rtsp_media_factory_set_launch(factory, launch.c_str());
  gst_rtsp_media_factory_set_shared(factory, TRUE);
  g_signal_connect(factory, "media-configure", G_CALLBACK(onMediaConfigure), &state);
  GstRTSPMountPoints *mounts = gst_rtsp_server_get_mount_points(server);
  gst_rtsp_mount_points_add_factory(mounts, kMount, factory);
  g_object_unref(mounts);

  if (gst_rtsp_server_attach(server, nullptr) == 0) {
    std::fprintf(stderr, "rtsp server: cannot listen on 127.0.0.1:%d\n", port);
    return 1;
  }
  // Where the object is in frame 0, for a client that is not this test
  // (examples/python/check_rtsp_follow.py).
  const cv::Rect initBox = Scene(sceneConfig()).initBox();
  std::printf("INITBOX %d,%d,%d,%d\n", initBox.x, initBox.y, initBox.width, initBox.height);
  std::printf("PORT %d\n", gst_rtsp_server_get_bound_port(server));
  std::fflush(stdout);
  GIOChannel *commands = g_io_channel_unix_new(STDIN_FILENO);
  g_io_add_watch(commands, static_cast<GIOCondition>(G_IO_IN | G_IO_HUP), onCommand, &state);
  GMainLoop *loop = g_main_loop_new(nullptr, FALSE);
  g_main_loop_run(loop);  // until SIGKILL: the test simulates a crash, not a clean shutdown
  return 0;
}

}  // namespace rtsp_scene
