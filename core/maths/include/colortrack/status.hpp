// SPDX-License-Identifier: LGPL-2.1-or-later
// The one way code that can fail on what a user gave it says so, in core/, robot/, publish/ and the elements
// alike: a Status (ok, or a message saying what is wrong and what to do, with the property it names when one
// does), or a Result<T> (a value, or the Status why there is none). A message is whole: the caller adds only
// where it came from. Exceptions stay for what no setting can cause (an OpenCV failure, a broken invariant);
// a GStreamer vfunc still answers FALSE once it has posted the Status as an element error.
#pragma once

#include <optional>
#include <string>
#include <utility>

namespace colortrack {

class Status {
 public:
  Status() = default;  // ok
  static Status failure(std::string message, std::string property = {}) {
    Status status;
    status.failed_ = true;
    status.message_ = std::move(message);
    status.property_ = std::move(property);
    return status;
  }

  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const std::string &message() const { return message_; }
  // The property the failure is about, or empty.
  const std::string &property() const { return property_; }

 private:
  bool failed_ = false;
  std::string message_, property_;
};

template <typename T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: a value converts, as std::optional's does
  Result(Status failure) : status_(std::move(failure)) {}  // NOLINT: so does a failure

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }
  const T &operator*() const { return *value_; }
  const T *operator->() const { return &*value_; }
  // Why there is no value (ok when there is one).
  const Status &status() const { return status_; }
  const std::string &error() const { return status_.message(); }

 private:
  std::optional<T> value_;
  Status status_;
};

}  // namespace colortrack
