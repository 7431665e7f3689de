#pragma once
/// @file result.hpp
/// Error and Result<T>: how construction reports bad input. A Result holds either a value
/// or an Error naming the offending field; queries on valid objects never fail this way.

#include <stdexcept>
#include <string>
#include <utility>
#include <variant>

namespace proxima {

/// Why an input was rejected.
enum class ErrorCode {
  NotFinite,        ///< a NaN or infinite number
  NonPositive,      ///< a size that must be > 0 is <= 0
  Negative,         ///< a size that must be >= 0 is < 0
  OutOfRange,       ///< a value beyond the supported range (e.g. |x| > kMaxCoordinate)
  Degenerate,       ///< geometry of too low dimension (collinear triangle, flat hull, zero normal)
  TooFew,           ///< not enough elements (fewer than 4 hull points, empty point set)
  InvalidArgument,  ///< anything else that makes the input unusable
  Internal          ///< a dependency (e.g. qhull) failed on input that passed validation
};

/// Short name of an error code ("not_finite", "non_positive", ...).
const char* to_string(ErrorCode code);

/// A rejected input: the code, the field that was bad ("radius", "points[3].y") and a
/// sentence for humans.
struct Error {
  ErrorCode code = ErrorCode::InvalidArgument;  ///< what kind of problem
  std::string field;                            ///< the input field at fault
  std::string message;                          ///< human-readable explanation

  /// "field: message" — what the CLI and exceptions print.
  std::string what() const { return field.empty() ? message : field + ": " + message; }
};

/// Thrown by Result<T>::value() when the Result holds an Error.
class BadResultAccess : public std::runtime_error {
 public:
  explicit BadResultAccess(const Error& e) : std::runtime_error(e.what()), error_(e) {}
  /// The error that was held.
  const Error& error() const { return error_; }

 private:
  Error error_;
};

/// Either a T or an Error (a minimal std::expected for C++20).
template <class T>
class [[nodiscard]] Result {
 public:
  /// A successful result.
  Result(T value) : data_(std::in_place_index<0>, std::move(value)) {}  // NOLINT(google-explicit-constructor)
  /// A failed result.
  Result(Error error) : data_(std::in_place_index<1>, std::move(error)) {}  // NOLINT(google-explicit-constructor)

  /// True when a value is held.
  bool ok() const { return data_.index() == 0; }
  /// True when a value is held.
  explicit operator bool() const { return ok(); }

  /// The value; throws BadResultAccess if an Error is held.
  const T& value() const& {
    if (!ok()) throw BadResultAccess(std::get<1>(data_));
    return std::get<0>(data_);
  }
  /// The value; throws BadResultAccess if an Error is held.
  T& value() & {
    if (!ok()) throw BadResultAccess(std::get<1>(data_));
    return std::get<0>(data_);
  }
  /// The value, moved out; throws BadResultAccess if an Error is held.
  T&& value() && {
    if (!ok()) throw BadResultAccess(std::get<1>(data_));
    return std::get<0>(std::move(data_));
  }
  /// The value (unchecked: only after ok()).
  const T& operator*() const& { return std::get<0>(data_); }
  /// Member access to the value (unchecked: only after ok()).
  const T* operator->() const { return &std::get<0>(data_); }

  /// The error (only when !ok()).
  const Error& error() const { return std::get<1>(data_); }

 private:
  std::variant<T, Error> data_;
};

/// Makes an Error (helper for validation code).
inline Error make_error(ErrorCode code, std::string field, std::string message) {
  return Error{code, std::move(field), std::move(message)};
}

}  // namespace proxima
