#pragma once
// "Could not compute" as a returned value (the second of radrecon's three kinds of error,
// error.h): a value, or the reason there is none, in plain words that name no file or option.
// The caller decides what the failure means: the command line turns it into a UserError naming
// its input, the paper report prints it beside a fallback.

#include <optional>
#include <string>
#include <utility>

#include "core/check.h"

namespace radrecon {

/// Why a result could not be computed ("3 samples lie on one line").
struct Failure {
  std::string reason;
};

template <typename T>
class Result {
 public:
  Result(T value) : value_(std::move(value)) {}  // NOLINT: implicit, as std::expected
  Result(Failure failure) : failure_(std::move(failure.reason)) {}  // NOLINT

  bool ok() const { return value_.has_value(); }
  explicit operator bool() const { return ok(); }

  T& value() & {
    RR_CHECK(ok(), "value() of a failed Result");
    return *value_;
  }
  const T& value() const& {
    RR_CHECK(ok(), "value() of a failed Result");
    return *value_;
  }
  T&& value() && {
    RR_CHECK(ok(), "value() of a failed Result");
    return std::move(*value_);
  }
  /// The reason of a failure ("" for a success).
  const std::string& reason() const { return failure_; }

 private:
  std::optional<T> value_;
  std::string failure_;
};

}  // namespace radrecon
