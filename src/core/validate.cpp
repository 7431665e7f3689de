#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>

#include <cmath>

namespace proxima::validate {

std::optional<Error> finite(Real x, const std::string& field) {
  if (!std::isfinite(x)) return make_error(ErrorCode::NotFinite, field, "must be a finite number");
  if (std::abs(x) > kMaxCoordinate) {
    return make_error(ErrorCode::OutOfRange, field, "magnitude exceeds the supported range");
  }
  return std::nullopt;
}

std::optional<Error> finite(const Vec3& v, const std::string& field) {
  if (is_acceptable(v)) return std::nullopt;
  static const char* const kAxis[] = {".x", ".y", ".z"};
  for (int i = 0; i < 3; ++i) {
    if (auto e = finite(v[i], field + kAxis[i])) return e;
  }
  return std::nullopt;
}

std::optional<Error> positive(Real x, const std::string& field) {
  if (auto e = finite(x, field)) return e;
  if (!(x > Real(0))) return make_error(ErrorCode::NonPositive, field, "must be greater than zero");
  return std::nullopt;
}

std::optional<Error> non_negative(Real x, const std::string& field) {
  if (auto e = finite(x, field)) return e;
  if (x < Real(0)) return make_error(ErrorCode::Negative, field, "must not be negative");
  return std::nullopt;
}

std::optional<Error> unit_quaternion(const Quat& q, const std::string& field) {
  if (!is_finite(q)) return make_error(ErrorCode::NotFinite, field, "must be four finite numbers");
  if (!is_unit_length(glm::length(q))) {
    return make_error(ErrorCode::InvalidArgument, field, "must be a unit quaternion (length within 1e-3 of 1)");
  }
  return std::nullopt;
}

}  // namespace proxima::validate
