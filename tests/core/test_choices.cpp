// SPDX-License-Identifier: LGPL-2.1-or-later
// The core's choice tables (colortrack/choice.hpp) and the method registry, from which the elements' enum
// types are generated: each row's value is its position (so a property's number never changes when a row is
// added at the end), and each nick is a distinct, non-empty name gst-launch-1.0 can take.
#include <gtest/gtest.h>

#include <iterator>
#include <set>
#include <string>

#include "colortrack/color.hpp"
#include "colortrack/controller.hpp"
#include "colortrack/detection_method.hpp"
#include "colortrack/edges.hpp"
#include "colortrack/frame_tracker.hpp"
#include "colortrack/protocol.hpp"
#include "colortrack/target_lock.hpp"

using namespace colortrack;

namespace {

template <typename Rows>
void expectWellFormed(const Rows &choices) {
  std::set<std::string> nicks;
  const std::size_t n = static_cast<std::size_t>(std::end(choices) - std::begin(choices));
  for (std::size_t i = 0; i < n; ++i) {
    SCOPED_TRACE(choices[i].nick);
    EXPECT_EQ(static_cast<std::size_t>(choices[i].value), i);
    const std::string nick = choices[i].nick;
    EXPECT_FALSE(nick.empty());
    EXPECT_EQ(nick.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789-"), std::string::npos);
    EXPECT_TRUE(nicks.insert(nick).second);
    EXPECT_FALSE(std::string(choices[i].description).empty());
  }
}

}  // namespace

TEST(Choices, EveryTableIsInOrderWithDistinctNicks) {
  expectWellFormed(kControllerKinds);
  expectWellFormed(kDistanceCues);
  expectWellFormed(protocolDescriptors());
  expectWellFormed(kMavlinkModes);
  expectWellFormed(kLockOns);
  expectWellFormed(kTrackingModes);
  expectWellFormed(kColorSpaces);
  expectWellFormed(kVerifyModes);
  expectWellFormed(methodDescriptors());
  for (const MethodDescriptor &d : methodDescriptors()) EXPECT_NE(d.make, nullptr) << d.nick;
}

TEST(Choices, NickOfFindsTheRow) {
  EXPECT_STREQ(nickOf(kMavlinkModes, MavlinkMode::Follow), "follow");
  EXPECT_STREQ(nickOf(kLockOns, LockOn::NearestCentre), "nearest-centre");
  EXPECT_STREQ(toString(ControllerKind::Auto), "auto");
  EXPECT_STREQ(nickOf(kDistanceCues, static_cast<DistanceCue>(7)), "?");
}
