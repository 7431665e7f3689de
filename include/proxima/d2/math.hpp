#pragma once
/// @file math.hpp
/// The 2D module's vocabulary: rotations, poses and boxes in the plane, and the small
/// vector helpers (cross products, perpendiculars) every 2D algorithm uses.
///
/// Conventions (the same as W9 and Box2D): x to the right, y up, angles in radians,
/// counter-clockwise positive. A local point l is at `R(angle) l + position` in the world.
/// Sprite masks (sprite_mask.hpp) use image coordinates instead (y down); they say so.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>

#include <cmath>

namespace proxima::d2 {

using proxima::Real;
using proxima::Vec2;

/// True when both components are finite.
inline bool is_finite(const Vec2& v) { return std::isfinite(v.x) && std::isfinite(v.y); }
/// 2D cross product (the z of the 3D one): a.x b.y - a.y b.x.
inline Real cross(const Vec2& a, const Vec2& b) { return a.x * b.y - a.y * b.x; }
/// The vector turned a quarter counter-clockwise: (-v.y, v.x).
inline Vec2 left_perp(const Vec2& v) { return {-v.y, v.x}; }
/// The vector turned a quarter clockwise: (v.y, -v.x). For a counter-clockwise polygon the
/// outward normal of edge (a, b) is the unit right_perp(b - a).
inline Vec2 right_perp(const Vec2& v) { return {v.y, -v.x}; }
/// Squared length.
inline Real length_squared(const Vec2& v) { return v.x * v.x + v.y * v.y; }
/// Largest absolute component.
inline Real max_abs_component(const Vec2& v) { return std::max(std::abs(v.x), std::abs(v.y)); }

/// Splits `v` into a unit vector and its length without overflow or underflow. Returns
/// false, leaving both outputs untouched, when v is zero or not finite.
inline bool unit_and_length(const Vec2& v, Vec2& unit, Real& length) {
  if (!is_finite(v)) return false;
  const Real m = max_abs_component(v);
  if (!(m > Real(0))) return false;
  const Vec2 w = v / m;
  const Real l = std::sqrt(w.x * w.x + w.y * w.y);
  unit = w / l;
  length = l * m;
  return true;
}

/// A rotation in the plane as its cosine and sine (unit length).
struct Rotation {
  Real c = Real(1);  ///< cos(angle)
  Real s = Real(0);  ///< sin(angle)

  /// The rotation by `angle` radians, counter-clockwise.
  static Rotation from_angle(Real angle) { return {std::cos(angle), std::sin(angle)}; }
  /// The angle in (-pi, pi].
  Real angle() const { return std::atan2(s, c); }
  /// Rotates a vector: (c x - s y, s x + c y).
  Vec2 apply(const Vec2& v) const { return {c * v.x - s * v.y, s * v.x + c * v.y}; }
  /// Rotates a vector by the inverse rotation: (c x + s y, -s x + c y).
  Vec2 inverse_apply(const Vec2& v) const { return {c * v.x + s * v.y, -s * v.x + c * v.y}; }
  /// The local x axis in the parent frame.
  Vec2 x_axis() const { return {c, s}; }
  /// The local y axis in the parent frame.
  Vec2 y_axis() const { return {-s, c}; }
  /// The inverse rotation.
  Rotation inverse() const { return {c, -s}; }
};

/// Composition: (a * b).apply(v) == a.apply(b.apply(v)).
inline Rotation operator*(const Rotation& a, const Rotation& b) {
  return {a.c * b.c - a.s * b.s, a.s * b.c + a.c * b.s};
}

/// A rigid placement in the plane: rotation then translation.
struct Pose {
  Vec2 position{Real(0)};  ///< origin of the local frame, in parent coordinates
  Rotation rotation{};     ///< local-to-parent rotation

  /// The identity placement.
  static Pose identity() { return {}; }
  /// The placement at `position` turned by `angle` radians (counter-clockwise).
  static Pose from(const Vec2& position, Real angle) { return {position, Rotation::from_angle(angle)}; }
  /// Validated construction: finite position within kMaxCoordinate (field "position") and
  /// finite angle (field "angle").
  static Result<Pose> create(const Vec2& position, Real angle);

  /// Maps a local point to the parent frame.
  Vec2 apply(const Vec2& local_point) const { return rotation.apply(local_point) + position; }
  /// Rotates a local direction into the parent frame.
  Vec2 apply_vector(const Vec2& local_vector) const { return rotation.apply(local_vector); }
  /// Maps a parent-frame point to local coordinates.
  Vec2 inverse_apply(const Vec2& point) const { return rotation.inverse_apply(point - position); }
  /// Rotates a parent-frame direction into the local frame.
  Vec2 inverse_apply_vector(const Vec2& vector) const { return rotation.inverse_apply(vector); }
  /// The inverse placement.
  Pose inverse() const { return {rotation.inverse_apply(-position), rotation.inverse()}; }
};

/// Composition: (a * b).apply(p) == a.apply(b.apply(p)).
inline Pose operator*(const Pose& a, const Pose& b) { return {a.apply(b.position), a.rotation * b.rotation}; }
/// The placement of frame b in frame a: a.inverse() * b.
inline Pose relative(const Pose& a, const Pose& b) {
  return {a.inverse_apply(b.position), a.rotation.inverse() * b.rotation};
}

/// Axis-aligned rectangle [min, max] (closed: rectangles that only touch overlap). An empty
/// one has min > max on some axis.
struct Aabb {
  Vec2 min{kRealMax};   ///< smallest corner
  Vec2 max{-kRealMax};  ///< largest corner

  /// The empty rectangle: grow() from it.
  static Aabb empty() { return {}; }
  /// True when min <= max on both axes.
  bool is_valid() const { return min.x <= max.x && min.y <= max.y; }
  /// Centre point.
  Vec2 center() const { return (min + max) * Real(0.5); }
  /// Half extents.
  Vec2 half_extents() const { return (max - min) * Real(0.5); }
  /// Perimeter, the 2D surface-area-heuristic cost.
  Real perimeter() const { return Real(2) * ((max.x - min.x) + (max.y - min.y)); }
  /// Grows the rectangle to contain `p`.
  void grow(const Vec2& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  /// Grows the rectangle to contain `b`.
  void grow(const Aabb& b) {
    min = glm::min(min, b.min);
    max = glm::max(max, b.max);
  }
  /// The rectangle grown by `margin` on every side.
  Aabb inflated(Real margin) const { return {min - Vec2(margin), max + Vec2(margin)}; }
  /// True when `p` is inside or on the boundary.
  bool contains(const Vec2& p) const { return p.x >= min.x && p.x <= max.x && p.y >= min.y && p.y <= max.y; }
};

/// True when the closed rectangles overlap or touch.
inline bool overlap(const Aabb& a, const Aabb& b) {
  return a.min.x <= b.max.x && b.min.x <= a.max.x && a.min.y <= b.max.y && b.min.y <= a.max.y;
}

}  // namespace proxima::d2
