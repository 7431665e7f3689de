#pragma once
/// @file validate.hpp
/// Checks shared by every constructor that validates its input. Each returns an empty
/// optional when the value is acceptable, or the Error that names `field`.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <optional>
#include <string>

namespace proxima::validate {

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
