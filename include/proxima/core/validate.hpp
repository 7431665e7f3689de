#pragma once
/// @file validate.hpp
/// Checks shared by every constructor that validates its input. Each returns an empty
/// optional when the value is acceptable, or the Error that names `field`.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/tolerance.hpp>

#include <cmath>
#include <optional>
#include <string>

namespace proxima::validate {

/// True when `v` passes finite(v, ...): the allocation-free test for hot paths, which build
/// the Error (and its field name) only when this fails.
inline bool is_acceptable(const Vec3& v) { return is_finite(v) && max_abs_component(v) <= kMaxCoordinate; }
/// True when a finite quaternion of length `length` (glm::length) passes unit_quaternion:
/// within 1e-3 of 1. (Test finiteness first: comparing a NaN raises the invalid-operation flag,
/// which the tests trap.)
inline bool is_unit_length(Real length) { return std::abs(length - Real(1)) <= Real(1e-3); }
/// True when `q` passes unit_quaternion(q, ...).
inline bool is_unit(const Quat& q) { return is_finite(q) && is_unit_length(glm::length(q)); }

/// A finite number with |x| <= kMaxCoordinate.
std::optional<Error> finite(Real x, const std::string& field);
/// A finite vector with every |component| <= kMaxCoordinate.
std::optional<Error> finite(const Vec3& v, const std::string& field);
/// A finite size > 0 (radius, half extent, half length).
std::optional<Error> positive(Real x, const std::string& field);
/// A finite size >= 0.
std::optional<Error> non_negative(Real x, const std::string& field);
/// A finite quaternion whose length is within 1e-3 of 1 (it is renormalised afterwards).
std::optional<Error> unit_quaternion(const Quat& q, const std::string& field);

}  // namespace proxima::validate
