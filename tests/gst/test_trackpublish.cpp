// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish: the JSON document of every frame against the ROI metas of the same buffer (file output), and
// MQTT against a real broker the test starts: Debian's mosquitto on a free loopback port with its own config,
// read back by a subscriber (Paho). Covers delivery in order at QoS 1, eight sources at once, a broker
// restart mid-stream with a live source, TLS. Bad addresses and topics, an unreachable or false broker and a
// full queue are in test_trackpublish_errors.cpp. C++ headers first: gstcheck.h defines macros (fail, ...)
// that clash with names in the standard library.
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

#include "trackpublish_rig.hpp"

namespace {

using namespace trackpublish_rig;

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

// A FIFO whose reader stops reading holds trackpublish's writer thread, not the stream: 2000 documents (about
// ten times the pipe's 64 KiB) all pass and EOS arrives; with max-queued=100 the oldest are dropped, in a
// warning naming the location, and EOS says what is not written after drain-timeout. (Written on the
// streaming thread, the stream stopped once the pipe was full, and EOS never came.) A file that fails
// (/dev/full) is an error naming the location, also when the failure comes after the last document.
GST_START_TEST(test_slow_reader_never_holds_the_stream) {
  gchar *dir = g_dir_make_tmp("trackpublish-XXXXXX", nullptr);
  fail_unless(dir != nullptr);
  const std::string fifo = std::string(dir) + "/tracks.fifo";
  fail_unless(mkfifo(fifo.c_str(), 0600) == 0);
  const int reader = open(fifo.c_str(), O_RDONLY | O_NONBLOCK);
  fail_unless(reader >= 0);
  {
    Publisher p("location=" + fifo + " max-queued=100 drain-timeout=200");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    constexpr int kFrames = 2000;
    for (int i = 0; i < kFrames; ++i) p.push(i);
    p.endAndWait();
    fail_unless_equals_int(p.drainSink(), kFrames);
    const std::vector<std::string> warnings = p.messages(GST_MESSAGE_WARNING);
    for (const std::string &w : warnings) g_print("slow reader: warning \"%s\"\n", w.c_str());
    fail_unless(anyContains(warnings, "does not keep up") && anyContains(warnings, fifo),
                "no warning about the dropped documents");
    fail_unless(anyContains(warnings, "not yet written"), "no warning about what EOS left unwritten");
  }
  close(reader);
  unlink(fifo.c_str());
  g_rmdir(dir);
  g_free(dir);
  if (g_file_test("/dev/full", G_FILE_TEST_EXISTS)) {
    // One document: its write fails on the writer thread after the only publish, so the error must come
    // with EOS (it was lost there, once in a loaded run, when 20 documents had all been queued first).
    Publisher p("location=/dev/full");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    p.push(0);
    p.end();
    const auto deadline = Clock::now() + std::chrono::seconds(10);
    while (p.messages(GST_MESSAGE_ERROR).empty() && Clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const std::vector<std::string> errors = p.messages(GST_MESSAGE_ERROR);
    fail_unless(anyContains(errors, "'/dev/full' (property 'location')"), "no error naming /dev/full");
    g_print("/dev/full: error \"%s\"\n", errors.front().c_str());
  }
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
  tcase_add_test(tc, test_fifo_location_never_blocks);
  tcase_add_test(tc, test_slow_reader_never_holds_the_stream);
  return s;
}

GST_CHECK_MAIN(trackpublish);
