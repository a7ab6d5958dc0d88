// SPDX-License-Identifier: LGPL-2.1-or-later
// trackpublish's MQTT side: documents handed over by the streaming thread, delivered in order by a worker
// thread through Eclipse Paho's asynchronous C client, with a bounded queue that keeps everything while the
// broker is unreachable (the oldest are dropped, and counted, past `maxQueued`) and drains in order after
// reconnecting. No GStreamer here.
//
// Why our own queue in front of Paho's: Paho can buffer while disconnected and drop the oldest, but it does
// not say how many it dropped, and its buffer only exists after a first successful connect.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <set>
#include <string>
#include <thread>

#include "mqtt-checks.h"  // checkAddress, checkTopic, ... (the settings check with them)
#include "colortrack/status.hpp"
#include "send-queue.h"

namespace trackpublish {

struct MqttConfig {
  std::string address;  // tcp://HOST:PORT, ssl://HOST:PORT (also mqtt://, mqtts://)
  std::string clientId;
  std::string username, password;         // empty: none
  std::string caFile, certFile, keyFile;  // TLS (ssl://): trust store, client certificate and key
  bool verifyServer = true;               // TLS: check the broker's certificate and host name
  int qos = 1;
  std::size_t maxQueued = 1000;  // documents waiting for the broker, beyond which the oldest are dropped
};

// What a failed connection points at: the network or address, or a broker that answered and refused (its
// CONNACK return code says why).
enum class ConnectFault { Unreachable, Credentials, ClientId, Broker };

struct ConnectFailure {
  std::string why;
  ConnectFault fault = ConnectFault::Unreachable;
};

// What the publisher reports, from its own threads (never the streaming thread).
class MqttListener {
 public:
  virtual ~MqttListener() = default;
  virtual void connected(const std::string &address, bool again) = 0;
  // `first`: the first failure since the last success (later ones repeat the same news).
  virtual void connectFailed(const std::string &address, const ConnectFailure &failure, bool first,
                             std::chrono::milliseconds retryIn) = 0;
  // `first`: not the repeat of a connection that keeps failing soon after it is made (a peer that answers
  // CONNECT and then nothing an MQTT client understands): that news is given once.
  virtual void connectionLost(const std::string &address, const std::string &why, std::size_t queued,
                              bool first) = 0;
  // `total` documents dropped so far because the queue was full.
  virtual void dropped(std::uint64_t total, std::size_t maxQueued) = 0;
};

class MqttPublisher {
 public:
  MqttPublisher(const MqttConfig &config, MqttListener &listener);
  ~MqttPublisher();  // stop(0)
  MqttPublisher(const MqttPublisher &) = delete;
  MqttPublisher &operator=(const MqttPublisher &) = delete;

  // Creates the client and starts connecting (in the background); why not when the configuration cannot work
  // at all (a bad address).
  colortrack::Status start();
  // Waits up to `timeout` for the first connection attempt to end; true when connected.
  bool waitFirstAttempt(std::chrono::milliseconds timeout, ConnectFailure &failure);
  // Queues a document; never waits for the network.
  void publish(std::string topic, std::string payload);
  // Waits up to `timeout` until everything queued has been delivered; true when it has.
  bool waitDelivered(std::chrono::milliseconds timeout);
  // Tries for up to `drain` to deliver what is queued, then disconnects and stops the worker.
  void stop(std::chrono::milliseconds drain);

  std::uint64_t delivered() const;
  std::uint64_t droppedCount() const;
  std::size_t queued() const;  // waiting or in flight

 private:
  struct Callback;     // Paho's C callbacks, which call the members below
  struct SendContext;  // one document's send, until Paho answers it

  bool createClient(std::string &why);
  void destroyClient(void *&client);  // and frees its unanswered sends
  void run();
  void connect(std::unique_lock<std::mutex> &lock);
  bool replaceClient(std::unique_lock<std::mutex> &lock);
  void send(std::unique_lock<std::mutex> &lock);
  void sent(std::uint64_t sequence, std::uint64_t attempt);
  void sendFailed(std::uint64_t sequence, std::uint64_t attempt);
  void connectDone(bool ok, const ConnectFailure &failure = {});
  void lost(const std::string &why);
  void abandonUnanswered(std::unique_lock<std::mutex> &lock);

  const MqttConfig config_;
  MqttListener &listener_;
  void *client_ = nullptr;   // MQTTAsync, this connection's
  void *retired_ = nullptr;  // the client of the connection before, never connected again

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  SendQueue documents_;
  std::uint64_t delivered_ = 0;
  bool connected_ = false, connecting_ = false, everConnected_ = false, stopping_ = false;
  bool attempted_ = false;      // the first connection attempt has ended
  bool replaceClient_ = false;  // the connection was lost: the next one gets a new client
  ConnectFailure lastFailure_;
  bool failedSinceSuccess_ = false;
  bool flapping_ = false;  // the last connection was lost soon after it was made
  std::chrono::steady_clock::time_point connectedAt_;
  std::chrono::milliseconds backoff_;
  std::chrono::steady_clock::time_point nextAttempt_, drainUntil_;
  std::set<SendContext *> sends_;  // not yet answered by Paho; freed when their client is destroyed
  std::thread worker_;
};

}  // namespace trackpublish
