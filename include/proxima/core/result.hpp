#pragma once
/// @file result.hpp
/// Error and Result<T>: how construction reports bad input. A Result holds either a value
/// or an Error naming the offending field; queries on valid objects never fail this way.
///
/// Check ok() (or test the Result as a bool) before using the value. Asking for value()
/// of a Result that holds an Error is a programming error with one policy per build of
/// the library (PROXIMA_EXCEPTIONS in core/config.hpp):
///   - PROXIMA_EXCEPTIONS == 1 (the default): value() throws BadResultAccess, which
///     carries the Error;
///   - PROXIMA_EXCEPTIONS == 0 (configured with -DPROXIMA_EXCEPTIONS=OFF, the library
///     compiled with -fno-exceptions): value() calls the assert handler (core/assert.hpp,
///     replaceable with set_assert_handler) with the text
///     "Result::value() on an error (<code>): <field>: <message>", then std::abort() if
///     the handler returns. value() never returns in this case.
/// The failure path lives in the library (not in this header), so code built with or
/// without exceptions against one library gets the same policy. operator* and operator->
/// do not check: use them only after ok().

#include <proxima/core/config.hpp>

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

/// Thrown by Result<T>::value() when the Result holds an Error (only in a library built
/// with exceptions, PROXIMA_EXCEPTIONS == 1; declared in both builds).
class BadResultAccess : public std::runtime_error {
 public:
  explicit BadResultAccess(const Error& e) : std::runtime_error(e.what()), error_(e) {}
  /// The error that was held.
  const Error& error() const { return error_; }

 private:
  Error error_;
};

namespace detail {

/// The failure of Result<T>::value() on an Error, out of line: throws BadResultAccess
/// (PROXIMA_EXCEPTIONS == 1), or calls the assert handler with a text naming the error's
/// code and field and then aborts (PROXIMA_EXCEPTIONS == 0). Never returns.
[[noreturn]] void bad_result_access(const Error& error);

}  // namespace detail

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

  /// The value; if an Error is held, throws BadResultAccess (or, without exceptions, calls
  /// the assert handler and aborts: see the file comment).
  const T& value() const& {
    if (!ok()) detail::bad_result_access(std::get<1>(data_));
    return std::get<0>(data_);
  }
  /// The value; if an Error is held, throws BadResultAccess (or, without exceptions, calls
  /// the assert handler and aborts: see the file comment).
  T& value() & {
    if (!ok()) detail::bad_result_access(std::get<1>(data_));
    return std::get<0>(data_);
  }
  /// The value, moved out; if an Error is held, throws BadResultAccess (or, without
  /// exceptions, calls the assert handler and aborts: see the file comment).
  T&& value() && {
    if (!ok()) detail::bad_result_access(std::get<1>(data_));
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
