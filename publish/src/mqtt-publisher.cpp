// SPDX-License-Identifier: LGPL-2.1-or-later
#include "mqtt-publisher.h"

#include <MQTTAsync.h>

#include <algorithm>
#include <cstdlib>
#include <utility>

namespace trackpublish {

namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

// Documents sent and not yet acknowledged at once: enough to keep a remote broker busy at a frame rate, few
// enough that a reconnect resends little, and under Paho's own limit of buffered messages (100 by default).
constexpr std::size_t kWindow = 32;
constexpr milliseconds kFirstBackoff{250}, kMaxBackoff{5000};
constexpr int kConnectTimeoutSeconds = 5;
constexpr int kKeepAliveSeconds = 20;
// A document sent and not answered for this long while connected: the peer took the connection but does not
// speak MQTT back (or is stuck), which Paho's keep-alive may never notice (a peer that sent half a packet
// holds its reader): the connection is dropped and made again, the document resent.
constexpr milliseconds kAnswerTimeout{10000};
// A connection lost sooner than this after it was made counts as failing again: the retries back off and the
// loss is not announced again.
constexpr milliseconds kStableConnection{30000};  // longer than kAnswerTimeout: a silent peer is news once

std::string textOf(const char *text, int code) {
  if (text && *text) return text;
  const char *known = MQTTAsync_strerror(code);
  return known ? known : "error " + std::to_string(code);
}

// A broker that answered and refused says why in its CONNACK return code (MQTT 3.1.1, 1-5), which Paho
// gives as the failure's code; its own errors are negative.
ConnectFailure failureOf(const MQTTAsync_failureData *data) {
  if (!data) return {"connection failed", ConnectFault::Unreachable};
  switch (data->code) {
    case 1:
      return {"the broker refused MQTT 3.1.1 (CONNACK return code 1)", ConnectFault::Broker};
    case 2:
      return {"the broker rejected the client id (CONNACK return code 2)", ConnectFault::ClientId};
    case 3:
      return {"the broker's MQTT service is unavailable (CONNACK return code 3)", ConnectFault::Broker};
    case 4:
      return {"bad user name or password (CONNACK return code 4)", ConnectFault::Credentials};
    case 5:
      return {"not authorised (CONNACK return code 5)", ConnectFault::Credentials};
    default:
      return {textOf(data->message, data->code), ConnectFault::Unreachable};
  }
}

}  // namespace

struct MqttPublisher::SendContext {
  MqttPublisher *publisher;
  void *client;  // the client it was sent through
  std::uint64_t sequence, attempt;
};

// Paho's C callbacks, which reach the publisher's private members.
struct MqttPublisher::Callback {
  using Send = SendContext;

  static void connected(void *context, MQTTAsync_successData *) {
    static_cast<MqttPublisher *>(context)->connectDone(true);
  }
  static void connectFailed(void *context, MQTTAsync_failureData *data) {
    static_cast<MqttPublisher *>(context)->connectDone(false, failureOf(data));
  }
  static void lost(void *context, char *cause) {
    static_cast<MqttPublisher *>(context)->lost(cause && *cause ? cause : "the broker closed the connection");
  }
  static void sent(void *context, MQTTAsync_successData *) {
    const Send send = take(context);
    send.publisher->sent(send.sequence, send.attempt);
  }
  static void sendFailed(void *context, MQTTAsync_failureData *) {
    const Send send = take(context);
    send.publisher->sendFailed(send.sequence, send.attempt);
  }

  static Send take(void *context) {
    auto *send = static_cast<Send *>(context);
    const Send copy = *send;
    {
      std::lock_guard<std::mutex> lock(copy.publisher->mutex_);
      copy.publisher->sends_.erase(send);
    }
    delete send;
    return copy;
  }
};

MqttPublisher::MqttPublisher(const MqttConfig &config, MqttListener &listener)
    : config_(config), listener_(listener), documents_(config.maxQueued), backoff_(kFirstBackoff) {}

MqttPublisher::~MqttPublisher() {
  stop(milliseconds(0));
}

colortrack::Status MqttPublisher::start() {
  if (const colortrack::Status address = checkAddress(config_.address); !address) return address;
  std::string why;
  if (!createClient(why)) return colortrack::Status::failure(why);
  nextAttempt_ = Clock::now();
  worker_ = std::thread([this] { run(); });
  return {};
}

bool MqttPublisher::createClient(std::string &why) {
  MQTTAsync client = nullptr;
  MQTTAsync_createOptions options = MQTTAsync_createOptions_initializer;
  options.sendWhileDisconnected = 0;  // the queue is ours
  const int rc = MQTTAsync_createWithOptions(&client, config_.address.c_str(), config_.clientId.c_str(),
                                             MQTTCLIENT_PERSISTENCE_NONE, nullptr, &options);
  if (rc != MQTTASYNC_SUCCESS) {
    why = textOf(nullptr, rc);
    return false;
  }
  client_ = client;
  MQTTAsync_setConnectionLostCallback(client, this, &Callback::lost);
  return true;
}

void MqttPublisher::destroyClient(void *&client) {
  if (!client) return;
  MQTTAsync handle = static_cast<MQTTAsync>(client);
  if (MQTTAsync_isConnected(handle)) {
    MQTTAsync_disconnectOptions options = MQTTAsync_disconnectOptions_initializer;
    options.timeout = 0;
    MQTTAsync_disconnect(handle, &options);
  }
  MQTTAsync_destroy(&handle);  // no callback of this client runs after this
  std::lock_guard<std::mutex> lock(mutex_);
  for (auto it = sends_.begin(); it != sends_.end();) {  // its sends it discarded unanswered
    if ((*it)->client != client) {
      ++it;
      continue;
    }
    delete *it;
    it = sends_.erase(it);
  }
  client = nullptr;
}

bool MqttPublisher::waitFirstAttempt(milliseconds timeout, ConnectFailure &failure) {
  std::unique_lock<std::mutex> lock(mutex_);
  wake_.wait_for(lock, timeout, [this] { return attempted_ || connected_; });
  if (connected_)
    failure = {};
  else if (attempted_)
    failure = lastFailure_;
  else
    failure = {"no answer within " + std::to_string(timeout.count()) + " ms", ConnectFault::Unreachable};
  return connected_;
}

void MqttPublisher::publish(std::string topic, std::string payload) {
  std::uint64_t droppedNow = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (documents_.add(std::move(topic), std::move(payload))) droppedNow = documents_.dropped();
  }
  wake_.notify_all();
  if (droppedNow) listener_.dropped(droppedNow, config_.maxQueued);
}

bool MqttPublisher::waitDelivered(milliseconds timeout) {
  std::unique_lock<std::mutex> lock(mutex_);
  return wake_.wait_for(lock, timeout, [this] { return documents_.empty(); });
}

void MqttPublisher::stop(milliseconds drain) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (stopping_ && !worker_.joinable()) return;
    stopping_ = true;
    drainUntil_ = Clock::now() + drain;
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
  destroyClient(client_);
  destroyClient(retired_);
}

std::uint64_t MqttPublisher::delivered() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return delivered_;
}

std::uint64_t MqttPublisher::droppedCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return documents_.dropped();
}

std::size_t MqttPublisher::queued() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return documents_.size();
}

void MqttPublisher::run() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    const auto now = Clock::now();
    if (stopping_ && (documents_.empty() || now >= drainUntil_)) break;
    if (!connected_ && !connecting_ && now >= nextAttempt_) connect(lock);
    if (connected_) send(lock);
    const auto oldestSent = documents_.oldestSentAt();
    if (connected_ && oldestSent && now - *oldestSent > kAnswerTimeout) abandonUnanswered(lock);
    auto until = now + milliseconds(100);
    if (!connected_ && !connecting_) until = std::min(until, nextAttempt_);
    if (stopping_) until = std::min(until, drainUntil_);
    wake_.wait_until(lock, until);
  }
}

void MqttPublisher::connect(std::unique_lock<std::mutex> &lock) {
  connecting_ = true;
  if (replaceClient_ && !replaceClient(lock)) return;
  MQTTAsync_connectOptions options = MQTTAsync_connectOptions_initializer;
  options.keepAliveInterval = kKeepAliveSeconds;
  options.cleansession = 1;  // what was in flight is resent from our queue
  options.connectTimeout = kConnectTimeoutSeconds;
  // MQTT 3.1.1 only: Paho's default tries 3.1.1, then 3.1 on a second connection, so a peer that never
  // answers was reported after two timeouts (12 s) instead of one.
  options.MQTTVersion = MQTTVERSION_3_1_1;
  options.onSuccess = &Callback::connected;
  options.onFailure = &Callback::connectFailed;
  options.context = this;
  if (!config_.username.empty()) options.username = config_.username.c_str();
  if (!config_.password.empty()) options.password = config_.password.c_str();
  MQTTAsync_SSLOptions ssl = MQTTAsync_SSLOptions_initializer;
  const bool tls = usesTls(config_.address);
  if (tls) {
    if (!config_.caFile.empty()) ssl.trustStore = config_.caFile.c_str();
    if (!config_.certFile.empty()) ssl.keyStore = config_.certFile.c_str();
    if (!config_.keyFile.empty()) ssl.privateKey = config_.keyFile.c_str();
    ssl.enableServerCertAuth = config_.verifyServer ? 1 : 0;
    ssl.verify = config_.verifyServer ? 1 : 0;
    options.ssl = &ssl;
  }
  lock.unlock();
  const int rc = MQTTAsync_connect(static_cast<MQTTAsync>(client_), &options);
  lock.lock();
  if (rc != MQTTASYNC_SUCCESS) {
    lock.unlock();
    connectDone(false, {textOf(nullptr, rc), ConnectFault::Unreachable});
    lock.lock();
  }
}

// Paho keeps the publishes it had queued but not yet written when a connection went, and writes them first
// on its next connection (its clean session clears only what was in flight). Our queue has put those
// documents back already, to resend from the oldest; sent again by Paho they would overtake it. So each
// connection after a lost one gets a new client. The old one never connects again; it is destroyed one
// reconnect later, when none of its threads can still be in the callback that reported the loss.
bool MqttPublisher::replaceClient(std::unique_lock<std::mutex> &lock) {
  replaceClient_ = false;
  lock.unlock();  // this is the worker, the only thread that uses client_ while running
  destroyClient(retired_);
  retired_ = client_;
  client_ = nullptr;
  std::string why;
  const bool made = createClient(why);
  if (!made) connectDone(false, {why, ConnectFault::Unreachable});
  lock.lock();
  return made;
}

void MqttPublisher::send(std::unique_lock<std::mutex> &lock) {
  while (connected_) {
    // A copy: a callback may change the queue while the lock is released (Paho copies the payload too).
    const std::optional<SendQueue::Document> next = documents_.send(Clock::now(), kWindow);
    if (!next) return;
    const SendQueue::Document &document = *next;
    auto *context = new SendContext{this, client_, document.sequence, document.attempt};
    sends_.insert(context);
    lock.unlock();
    MQTTAsync_message message = MQTTAsync_message_initializer;
    message.payload = const_cast<char *>(document.payload.data());
    message.payloadlen = static_cast<int>(document.payload.size());
    message.qos = config_.qos;
    MQTTAsync_responseOptions response = MQTTAsync_responseOptions_initializer;
    response.onSuccess = &Callback::sent;
    response.onFailure = &Callback::sendFailed;
    response.context = context;
    const int rc =
        MQTTAsync_sendMessage(static_cast<MQTTAsync>(client_), document.topic.c_str(), &message, &response);
    lock.lock();
    if (rc != MQTTASYNC_SUCCESS) {
      // Not taken (the connection went meanwhile): back in the queue, no callback will come.
      sends_.erase(context);
      delete context;
      documents_.requeueInFlight();
      return;
    }
  }
}

void MqttPublisher::sent(std::uint64_t sequence, std::uint64_t attempt) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (documents_.acknowledged(sequence, attempt)) ++delivered_;
  }
  wake_.notify_all();
}

void MqttPublisher::sendFailed(std::uint64_t sequence, std::uint64_t attempt) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    documents_.failed(sequence, attempt);
  }
  wake_.notify_all();
}

void MqttPublisher::connectDone(bool ok, const ConnectFailure &failure) {
  bool again = false, first = false;
  milliseconds retryIn{0};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    connecting_ = false;
    attempted_ = true;
    if (ok) {
      connected_ = true;
      connectedAt_ = Clock::now();
      again = everConnected_;
      everConnected_ = true;
      failedSinceSuccess_ = false;
      // A peer that keeps dropping the connection soon after it is made is retried less and less often.
      if (!flapping_) backoff_ = kFirstBackoff;
    } else {
      // A new kind of failure is news too: a broker that was starting and now refuses the password.
      first = !failedSinceSuccess_ || failure.fault != lastFailure_.fault;
      lastFailure_ = failure;
      failedSinceSuccess_ = true;
      retryIn = backoff_;
      nextAttempt_ = Clock::now() + backoff_;
      backoff_ = std::min(backoff_ * 2, kMaxBackoff);
    }
  }
  wake_.notify_all();
  if (ok)
    listener_.connected(redactedAddress(config_.address), again);
  else
    listener_.connectFailed(redactedAddress(config_.address), failure, first, retryIn);
}

void MqttPublisher::lost(const std::string &why) {
  std::size_t queued = 0;
  bool first = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    connected_ = false;
    replaceClient_ = true;
    documents_.requeueInFlight();
    queued = documents_.waiting();
    const auto now = Clock::now();
    // Announced unless it repeats a connection that keeps failing soon after it is made; one that lasted is
    // news again.
    const bool quick = now - connectedAt_ < kStableConnection;
    first = !(flapping_ && quick);
    flapping_ = quick;
    if (flapping_) {
      nextAttempt_ = now + backoff_;
      backoff_ = std::min(backoff_ * 2, kMaxBackoff);
    } else {
      nextAttempt_ = now;
      backoff_ = kFirstBackoff;
    }
  }
  wake_.notify_all();
  listener_.connectionLost(redactedAddress(config_.address), why, queued, first);
}

// The oldest document in flight went unanswered for kAnswerTimeout: drop the connection (its sends are
// failed or never answered; their documents are already back in the queue) and make a new one.
void MqttPublisher::abandonUnanswered(std::unique_lock<std::mutex> &lock) {
  connected_ = false;
  lock.unlock();  // this is the worker, the only thread that connects: none can start meanwhile
  MQTTAsync_disconnectOptions options = MQTTAsync_disconnectOptions_initializer;
  options.timeout = 0;
  MQTTAsync_disconnect(static_cast<MQTTAsync>(client_), &options);
  lost("it accepted the connection but answered no document for " +
       std::to_string(kAnswerTimeout.count() / 1000) + " s (is it an MQTT broker?)");
  lock.lock();
}

}  // namespace trackpublish
