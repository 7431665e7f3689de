#pragma once
/// @file transform.hpp
/// Transform: a rigid placement, position + unit quaternion. A point with local
/// coordinates l is at `rotation * l + position` in the parent (world) frame.

#include <proxima/core/math.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/validate.hpp>

#include <optional>

namespace proxima {

/// Rigid transform from a local frame to its parent frame (rotation then translation).
struct Transform {
  Vec3 position{Real(0)};        ///< origin of the local frame, in parent coordinates
  Quat rotation{kIdentityQuat};  ///< unit quaternion, local-to-parent rotation

  /// The identity placement.
  static Transform identity() { return {}; }

  /// Validated construction: finite position, finite quaternion of length ~1 (within
  /// 1e-3; it is then renormalised). Errors name "position" or "rotation".
  static Result<Transform> create(const Vec3& position, const Quat& rotation);

  /// The transform create() returns for these values, or nothing where create() returns an
  /// Error: the form for loops over many poses (no Error built, one square root).
  static std::optional<Transform> from_values(const Vec3& position, const Quat& rotation) {
    if (!validate::is_acceptable(position) || !is_finite(rotation)) return std::nullopt;
    const Real length = glm::length(rotation);
    if (!validate::is_unit_length(length)) return std::nullopt;
    const Real inverse = Real(1) / length;  // glm::normalize's arithmetic, without its second square root
    return Transform{position,
                     Quat{rotation.w * inverse, rotation.x * inverse, rotation.y * inverse, rotation.z * inverse}};
  }

  /// Maps a local point to the parent frame.
  Vec3 apply(const Vec3& local_point) const { return rotation * local_point + position; }
  /// Rotates a local direction into the parent frame (no translation).
  Vec3 apply_vector(const Vec3& local_vector) const { return rotation * local_vector; }
  /// Maps a parent-frame point to local coordinates.
  Vec3 inverse_apply(const Vec3& point) const { return glm::conjugate(rotation) * (point - position); }
  /// Rotates a parent-frame direction into the local frame.
  Vec3 inverse_apply_vector(const Vec3& vector) const { return glm::conjugate(rotation) * vector; }

  /// The rotation as a matrix whose columns are the local axes in the parent frame.
  Mat3 rotation_matrix() const { return glm::mat3_cast(rotation); }

  /// The inverse placement (parent-to-local).
  Transform inverse() const {
    const Quat inv = glm::conjugate(rotation);
    return {inv * -position, inv};
  }
};

/// Composition: `(a * b).apply(p) == a.apply(b.apply(p))` — b is expressed in a's frame.
inline Transform operator*(const Transform& a, const Transform& b) {
  return {a.apply(b.position), glm::normalize(a.rotation * b.rotation)};
}

/// The placement of frame b relative to frame a: `a.inverse() * b`.
inline Transform relative(const Transform& a, const Transform& b) { return a.inverse() * b; }

}  // namespace proxima
