#pragma once
/// @file conversions.hpp
/// Conversions between Python objects and the library's value types, shared by every
/// binding file: vectors and quaternions from any sequence of numbers, Result<T> and Error
/// to Python exceptions (proxima.Error, a ValueError naming the field), vectors to numpy.
#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>

#include <optional>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <string>
#include <vector>

namespace proxima::python {

namespace py = pybind11;

/// Raises proxima.Error (a ValueError) with `code`, `field` and `message` attributes.
[[noreturn]] void raise_error(const Error& error);

/// Raises proxima.Error for an argument: field `field`, ErrorCode InvalidArgument.
[[noreturn]] void raise_argument_error(const std::string& field, const std::string& message);

/// The value of a Result, or proxima.Error.
template <class T>
T take(Result<T>&& result) {
  if (!result.ok()) raise_error(result.error());
  return std::move(result).value();
}

/// Raises proxima.Error when `error` holds one.
inline void check(const std::optional<Error>& error) {
  if (error) raise_error(*error);
}

/// `size` finite numbers from a sequence, else proxima.Error naming `field`.
std::vector<double> to_numbers(py::handle value, std::size_t size, const char* field);

/// Points from an (N, 3) array-like (copied: the library owns its geometry), else
/// proxima.Error naming `field`.
std::vector<Vec3> to_points(py::handle value, const char* field);

/// A vector of 3 finite numbers from any sequence (tuple, list, numpy array), else
/// proxima.Error naming `field`.
Vec3 to_vec3(py::handle value, const char* field);
/// A quaternion from (x, y, z, w) (glTF order, as in the query protocol).
Quat to_quat(py::handle value, const char* field);
/// A Real from a Python number, else proxima.Error naming `field`.
Real to_real(py::handle value, const char* field);

/// A new float64 numpy array of shape (3,).
py::array_t<double> to_numpy(const Vec3& v);
/// A new float64 numpy array of shape (4,): (x, y, z, w).
py::array_t<double> to_numpy(const Quat& q);

/// Thread count of a batched call: 0 means every hardware thread, 1 runs on the caller.
std::size_t resolve_threads(long threads);

}  // namespace proxima::python

namespace proxima::python {

/// A pose from None (identity), a proxima.Transform, or 7 numbers (px, py, pz, qx, qy, qz, qw);
/// the quaternion must be unit (within the library's tolerance). proxima.Error names `field`.
Transform to_transform(py::handle value, const char* field);

}  // namespace proxima::python

namespace proxima::python {
/// "(x, y, z)" with 9 significant digits, for __repr__.
std::string repr_vec3(const Vec3& v);
/// A number with 9 significant digits, for __repr__.
std::string repr_real(Real x);
}  // namespace proxima::python
