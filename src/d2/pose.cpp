/// @file pose.cpp
/// Validated construction of a 2D pose.

#include <proxima/core/tolerance.hpp>
#include <proxima/d2/math.hpp>

#include <string>

namespace proxima::d2 {

Result<Pose> Pose::create(const Vec2& position, Real angle) {
  if (!is_finite(position) || max_abs_component(position) > kMaxCoordinate) {
    return Error{is_finite(position) ? ErrorCode::OutOfRange : ErrorCode::NotFinite, "position",
                 "must be finite with |x|, |y| <= kMaxCoordinate"};
  }
  if (!std::isfinite(angle)) return Error{ErrorCode::NotFinite, "angle", "must be finite"};
  return Pose::from(position, angle);
}

}  // namespace proxima::d2
