// SPDX-License-Identifier: LGPL-2.1-or-later
// What changed among an element's settings since the streaming thread last looked, as a set of the element's
// own change groups (an enum of its settings: `Settings::Change`). An accepted property value adds the groups
// its table row marks; the streaming thread takes the set with each frame's settings and applies just those
// parts, so a gain change does not rebuild a tracker.
#pragma once

#include <initializer_list>

namespace gstglue {

template <typename Group>
class ChangeSet {
 public:
  ChangeSet() = default;
  ChangeSet(std::initializer_list<Group> groups) {
    for (Group group : groups) add(group);
  }

  bool has(Group group) const { return (bits_ & bit(group)) != 0; }
  bool empty() const { return bits_ == 0; }
  void add(Group group) { bits_ |= bit(group); }
  void remove(Group group) { bits_ &= ~bit(group); }
  ChangeSet &operator|=(const ChangeSet &other) {
    bits_ |= other.bits_;
    return *this;
  }

 private:
  static unsigned bit(Group group) { return 1u << static_cast<unsigned>(group); }
  unsigned bits_ = 0;
};

}  // namespace gstglue
