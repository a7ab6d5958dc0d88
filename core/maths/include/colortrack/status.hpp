// SPDX-License-Identifier: LGPL-2.1-or-later
// The one way code that can fail on what a user gave it says so, in core/, robot/, publish/ and the elements
// alike: a Status (ok, or a message saying what is wrong and what to do), or a Result<T> (a value, or the
// Status why there is none). The message does not name the property: the caller that knows it (the
// element's property table, a start rule) puts it around the message. Exceptions stay for what no setting
// can cause (an OpenCV failure, a broken invariant); a GStreamer vfunc still answers FALSE once it has posted
// a failure as an element error.
#pragma once

#include <optional>
#include <string>
#include <utility>

namespace colortrack {

class Status {
 public:
  Status() = default;  // ok
  // A failure always says something, so that a caller testing for an empty message cannot take it for ok.
  static Status failure(std::string message) {
    Status status;
    status.failed_ = true;
    status.message_ = message.empty() ? "failed, for no reason given" : std::move(message);
    return status;
  }

  bool ok() const { return !failed_; }
  explicit operator bool() const { return ok(); }
  const std::string &message() const { return message_; }  // empty when ok

 private:
  bool failed_ = false;
  std::string message_;
};

template <typename T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: a value converts, as std::optional's does
  // NOLINTNEXTLINE: so does a failure; an ok Status with no value is made a failure rather than "ok, empty".
  Result(Status failure) : status_(failure ? Status::failure("no value") : std::move(failure)) {}

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
