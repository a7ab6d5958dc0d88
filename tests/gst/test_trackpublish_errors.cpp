// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish when things go wrong: bad addresses, topics, client ids and TLS files refused naming the
// property, a password never shown, an unreachable broker drained once at EOS, a full queue that says how
// many it dropped, and a peer that takes the connection but is no working broker. C++ headers first:
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

#include "trackpublish_rig.hpp"

namespace {

using namespace trackpublish_rig;

GST_START_TEST(test_bad_addresses_and_topics) {
  // A TLS file that is a FIFO nobody writes to: Paho's open would wait for ever (and the pipeline's stop with
  // it); refused at once instead.
  gchar *dir = g_dir_make_tmp("trackpublish-XXXXXX", nullptr);
  const std::string fifo = std::string(dir) + "/ca.fifo";
  fail_unless(mkfifo(fifo.c_str(), 0600) == 0);
  const std::string key = std::string(dir) + "/client.key";
  fail_unless(g_file_set_contents(
      key.c_str(), "-----BEGIN PRIVATE KEY-----\nAA==\n-----END PRIVATE KEY-----\n", -1, nullptr));
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
           {"address=ssl://127.0.0.1:8883 tls-ca-file=" + fifo, "property 'tls-ca-file'"},
           {"address=ssl://127.0.0.1:8883 tls-ca-file=" + std::string(dir), "property 'tls-ca-file'"},
           {"address=ssl://127.0.0.1:8883 tls-cert-file=/etc/hostname", "property 'tls-cert-file'"},
           {"address=ssl://127.0.0.1:8883 tls-key-file=/nonexistent.pem", "property 'tls-key-file'"},
           {"address=tcp://127.0.0.1:1883 tls-verify=false", "property 'tls-verify'"},
           // Issue 48's silent accepts: a key without its certificate, a blank topic, a placeholder that is
           // not one, a source with a newline, tags with a key twice or a NUL.
           {"address=ssl://127.0.0.1:8883 tls-key-file=" + key,
            "'tls-key-file' is set without 'tls-cert-file'"},
           {"address=tcp://127.0.0.1:1883 topic=\" \"", "property 'topic'"},
           {"address=tcp://127.0.0.1:1883 topic=cams/{unknown}", "'{unknown}' is not replaced"},
           {"address=tcp://127.0.0.1:1883 source=\"cam\n1\"", "property 'source'"},
           {R"(location=/dev/null tags="{\"a\":1,\"a\":2}")", "the key \"a\" is given twice"},
           {R"(location=/dev/null tags="{\"a\":\"x\\u0000y\"}")", "NUL character"},
           {"address=tcp://127.0.0.1:1883 password=x", "Property 'password'"},
           {"address=tcp://127.0.0.1:1883 username=" + std::string(70000, 'u'), "property 'username'"},
           {"location=/nonexistent/x", "property 'location'"},
           {"location=/tmp", "property 'location'"},
           {"location=udp:1.2.3.4:5", "property 'location'"},
           {"", "No output"}}) {
    Publisher p(properties);
    fail_unless_equals_int(p.play(), GST_STATE_CHANGE_FAILURE);
    const std::vector<std::string> errors = p.messages(GST_MESSAGE_ERROR);
    fail_unless(anyContains(errors, part), "'%s': no error with '%s'",
                properties.size() > 200 ? "(long)" : properties.c_str(), part.c_str());
  }
  fail_if(g_file_test("udp:1.2.3.4:5", G_FILE_TEST_EXISTS), "a URL-like location was created as a file");
  g_unlink(fifo.c_str());
  g_unlink(key.c_str());
  g_rmdir(dir);
  g_free(dir);
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
  // An empty topic level: MQTT allows it, so it is said, not refused.
  {
    Publisher p("address=tcp://127.0.0.1:" + std::to_string(freePort()) +
                " topic=cams//tracks drain-timeout=0");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    p.push(0);
    p.endAndWait();
    fail_unless(anyContains(p.messages(GST_MESSAGE_WARNING), "has an empty level"),
                "no warning for cams//tracks");
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
  // Refused values do not show it either: a password MQTT cannot carry, an address with a typo after it.
  for (const std::string &properties :
       {"address=tcp://127.0.0.1:1883 username=u password=s3cret" + std::string(70000, 'x'),
        std::string("address=tcp://robot:s3cret@127.0.0.1/x:1883")}) {
    Publisher refused(properties);
    fail_unless_equals_int(refused.play(), GST_STATE_CHANGE_FAILURE);
    const std::vector<std::string> errors = refused.messages(GST_MESSAGE_ERROR);
    fail_unless(!errors.empty());
    fail_unless(!anyContains(errors, "s3cret"), "a refusal shows the password: %s", errors[0].c_str());
  }
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

// A broker that wants a password (issue 48): a wrong one is reported as refused, naming 'username' and
// 'password' rather than the address, as a warning and, with fail-on-connect, as the start's error; the
// password itself is never shown. The right one delivers every document.
GST_START_TEST(test_wrong_password_names_the_credentials) {
  const int port = freePort();
  Broker broker(port, 0, "alice", "right-secret");
  const std::string credentials = "refused the connection (properties 'username' and 'password')";
  {
    Publisher p("address=" + broker.address() + " username=alice password=wrong-secret drain-timeout=0");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 10; ++i) p.push(i);
    fail_unless(
        Subscriber::waitFor([&] { return anyContains(p.messages(GST_MESSAGE_WARNING), credentials); }, 7),
        "no warning naming the credentials");
    p.endAndWait();
    const std::vector<std::string> warnings = p.messages(GST_MESSAGE_WARNING);
    for (const std::string &w : warnings) std::printf("wrong password: %s\n", w.c_str());
    fail_unless_equals_int(countContaining(warnings, credentials), 1);
    fail_unless_equals_int(countContaining(warnings, "property 'address'"), 0);
    fail_unless_equals_int(countContaining(warnings, "wrong-secret"), 0);
  }
  {
    Publisher p("address=" + broker.address() + " username=alice password=wrong-secret fail-on-connect=true");
    fail_unless_equals_int(p.play(), GST_STATE_CHANGE_FAILURE);
    fail_unless(anyContains(p.messages(GST_MESSAGE_ERROR), credentials),
                "the start's error does not name them");
  }
  {
    Publisher p("address=" + broker.address() + " username=alice password=right-secret fail-on-connect=true");
    fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
    for (int i = 0; i < 10; ++i) p.push(i);
    p.endAndWait();
    fail_unless(p.messages(GST_MESSAGE_WARNING).empty(),
                "warnings with the right password (documents lost?)");
  }
}
GST_END_TEST;

// A peer that takes the TCP connection and never answers the CONNECT (a listening socket nobody accepts
// on): a warning within the client's connect timeout, not only the count at EOS (issue 48).
GST_START_TEST(test_silent_peer_is_reported_within_the_connect_timeout) {
  const int port = freePort();
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  fail_unless(bind(fd, reinterpret_cast<sockaddr *>(&address), sizeof address) == 0 && listen(fd, 8) == 0);
  Publisher p("address=tcp://127.0.0.1:" + std::to_string(port) + " drain-timeout=0");
  fail_unless(p.play() != GST_STATE_CHANGE_FAILURE);
  const auto start = Clock::now();
  for (int i = 0; i < 10; ++i) p.push(i);
  fail_unless(
      Subscriber::waitFor(
          [&] { return anyContains(p.messages(GST_MESSAGE_WARNING), "Cannot reach MQTT broker"); }, 8),
      "no warning within 8 s");
  std::printf("silent peer: warned after %.1f s\n",
              std::chrono::duration<double>(Clock::now() - start).count());
  p.endAndWait();
  close(fd);
}
GST_END_TEST;

}  // namespace

static Suite *trackpublish_errors_suite(void) {
  Suite *s = suite_create("trackpublish_errors");
  TCase *tc = tcase_create("errors");
  tcase_set_timeout(tc, 120);
  suite_add_tcase(s, tc);
  tcase_add_test(tc, test_bad_addresses_and_topics);
  tcase_add_test(tc, test_password_in_address_is_never_shown);
  tcase_add_test(tc, test_unreachable_broker_drains_once);
  tcase_add_test(tc, test_full_queue_drops_the_oldest_and_says_how_many);
  tcase_add_test(tc, test_false_broker_that_goes_silent_is_reported);
  tcase_add_test(tc, test_false_broker_that_talks_garbage_warns_once);
  tcase_add_test(tc, test_wrong_password_names_the_credentials);
  tcase_add_test(tc, test_silent_peer_is_reported_within_the_connect_timeout);
  return s;
}

GST_CHECK_MAIN(trackpublish_errors);
