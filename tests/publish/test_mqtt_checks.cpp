// SPDX-License-Identifier: LGPL-2.1-or-later
// What trackpublish checks before it connects (publish/'s mqtt-checks, GoogleTest, no GStreamer, no broker):
// the broker's address, topics and client ids as MQTT takes them, and an address shown without its password.
#include <gtest/gtest.h>

#include <string>

#include "mqtt-checks.h"

using namespace trackpublish;

TEST(MqttChecks, AddressesPahoAccepts) {
  EXPECT_TRUE(checkAddress("localhost:1883"));
  EXPECT_TRUE(checkAddress("tcp://localhost:1883"));
  EXPECT_TRUE(checkAddress("ssl://broker.example:8883"));
  EXPECT_TRUE(checkAddress("mqtts://user:secret@broker.example:8883"));
  EXPECT_FALSE(checkAddress("http://localhost:1883"));  // an unknown scheme
  EXPECT_FALSE(checkAddress("localhost"));              // no port
  EXPECT_FALSE(checkAddress("tcp:/localhost:1883"));    // a typo of the scheme: not a host
  EXPECT_FALSE(checkAddress("tcp://localhost:0"));
  EXPECT_FALSE(checkAddress("tcp://localhost:65536"));
  EXPECT_FALSE(checkAddress("tcp://localhost:18x3"));
}

TEST(MqttChecks, AddressErrorsNeverShowThePassword) {
  const std::string why = checkAddress("tcp://user:secret@host/path:1883").message();
  EXPECT_NE(why, "");
  EXPECT_EQ(why.find("secret"), std::string::npos) << why;
}

TEST(MqttChecks, BrokerUriAndTls) {
  EXPECT_EQ(brokerUri("localhost:1883"), "tcp://localhost:1883");
  EXPECT_EQ(brokerUri("ssl://host:8883"), "ssl://host:8883");
  EXPECT_TRUE(usesTls("ssl://host:8883"));
  EXPECT_TRUE(usesTls("mqtts://host:8883"));
  EXPECT_FALSE(usesTls("tcp://host:1883"));
  EXPECT_FALSE(usesTls("host:8883"));
}

TEST(MqttChecks, Topics) {
  EXPECT_TRUE(checkTopic("colortrack/camera1"));
  EXPECT_FALSE(checkTopic(""));
  EXPECT_FALSE(checkTopic("   "));
  EXPECT_FALSE(checkTopic("a/+/b"));
  EXPECT_FALSE(checkTopic("a/#"));
  EXPECT_FALSE(checkTopic("a\nb"));
  EXPECT_FALSE(checkTopic("$SYS/x"));
  EXPECT_FALSE(checkTopic(std::string("a\0b", 3)));
  EXPECT_FALSE(checkTopic("\xff\xfe"));  // not UTF-8
  EXPECT_FALSE(checkTopic(std::string(65536, 'a')));
  EXPECT_TRUE(checkTopic(std::string(65535, 'a')));
}

TEST(MqttChecks, ClientIds) {
  EXPECT_TRUE(checkClientId("colortrack-1"));
  EXPECT_TRUE(checkClientId(""));  // an empty string is an MQTT string
  EXPECT_FALSE(checkClientId(std::string("a\0b", 3)));
  EXPECT_FALSE(checkClientId("\xc3"));
}

TEST(MqttChecks, RedactedAddress) {
  EXPECT_EQ(redactedAddress("tcp://host:1883"), "tcp://host:1883");
  EXPECT_EQ(redactedAddress("tcp://user:secret@host:1883"), "tcp://user:***@host:1883");
  EXPECT_EQ(redactedAddress("user:secret@host:1883"), "user:***@host:1883");
  EXPECT_EQ(redactedAddress("ssl://user@host:8883"), "ssl://user@host:8883");
}
