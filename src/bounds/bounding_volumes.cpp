// Construction, support and box of the simple bounding volumes (sphere, OBB, capsule).
//
// Steps: validate the fields (core/validate.hpp); for the OBB re-orthonormalise the axes by
// Gram-Schmidt; supports are the analytic farthest points (Ericson, Real-Time Collision
// Detection, 4.3-4.5).
#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/core/validate.hpp>

#include <algorithm>
#include <string>

namespace proxima {

Result<BoundingSphere> BoundingSphere::create(const Vec3& center, Real radius) {
  if (auto e = validate::finite(center, "center")) return *e;
  if (auto e = validate::non_negative(radius, "radius")) return *e;
  return BoundingSphere{center, radius};
}

Vec3 BoundingSphere::support(const Vec3& direction) const {
  const Real len2 = glm::dot(direction, direction);
  if (!(len2 > Real(0)) || !std::isfinite(len2)) {
    const Real len = std::max({std::abs(direction.x), std::abs(direction.y), std::abs(direction.z)});
    if (!(len > Real(0))) return center + Vec3(Real(0), Real(0), radius);
    return support(direction / len);
  }
  return center + direction * (radius / std::sqrt(len2));
}

Result<Obb> Obb::create(const Vec3& center, const Mat3& axes, const Vec3& half_extents) {
  if (auto e = validate::finite(center, "center")) return *e;
  for (int i = 0; i < 3; ++i) {
    if (auto e = validate::finite(axes[i], "axes[" + std::to_string(i) + "]")) return *e;
  }
  static const char* const kAxis[] = {"half_extents.x", "half_extents.y", "half_extents.z"};
  for (int i = 0; i < 3; ++i) {
    if (auto e = validate::non_negative(half_extents[i], kAxis[i])) return *e;
  }
  constexpr Real kOrthoTolerance = Real(1e-3);
  for (int i = 0; i < 3; ++i) {
    if (std::abs(glm::length(axes[i]) - Real(1)) > kOrthoTolerance) {
      return make_error(ErrorCode::InvalidArgument, "axes", "columns must be unit vectors (within 1e-3)");
    }
    for (int j = i + 1; j < 3; ++j) {
      if (std::abs(glm::dot(axes[i], axes[j])) > kOrthoTolerance) {
        return make_error(ErrorCode::InvalidArgument, "axes", "columns must be mutually orthogonal (within 1e-3)");
      }
    }
  }
  Mat3 q;
  q[0] = glm::normalize(axes[0]);
  q[1] = glm::normalize(axes[1] - glm::dot(axes[1], q[0]) * q[0]);
  const Vec3 c = glm::cross(q[0], q[1]);
  q[2] = glm::dot(c, axes[2]) >= Real(0) ? c : -c;
  return Obb{center, q, half_extents};
}

Obb Obb::from_aabb(const Aabb& box, const Transform& pose) {
  // Centre and half extents without forming max - min (which could overflow for the
  // +-kRealMax boxes of unbounded shapes).
  const Vec3 c = box.max * Real(0.5) + box.min * Real(0.5);
  const Vec3 h = box.max * Real(0.5) - box.min * Real(0.5);
  return Obb{pose.apply(c), pose.rotation_matrix(), glm::max(h, Vec3(Real(0)))};
}

Vec3 Obb::support(const Vec3& direction) const {
  Vec3 p = center;
  for (int i = 0; i < 3; ++i)
    p += (glm::dot(direction, axes[i]) >= Real(0) ? half_extents[i] : -half_extents[i]) * axes[i];
  return p;
}

std::array<Vec3, 8> Obb::corners() const {
  std::array<Vec3, 8> c;
  for (int k = 0; k < 8; ++k) {
    Vec3 p = center;
    for (int i = 0; i < 3; ++i) p += ((k >> i) & 1 ? half_extents[i] : -half_extents[i]) * axes[i];
    c[static_cast<std::size_t>(k)] = p;
  }
  return c;
}

Aabb Obb::aabb() const {
  Vec3 e;
  for (int r = 0; r < 3; ++r) {
    e[r] = std::abs(axes[0][r]) * half_extents.x + std::abs(axes[1][r]) * half_extents.y +
           std::abs(axes[2][r]) * half_extents.z;
  }
  return {center - e, center + e};
}

Result<BoundingCapsule> BoundingCapsule::create(const Vec3& p0, const Vec3& p1, Real radius) {
  if (auto e = validate::finite(p0, "p0")) return *e;
  if (auto e = validate::finite(p1, "p1")) return *e;
  if (auto e = validate::non_negative(radius, "radius")) return *e;
  return BoundingCapsule{p0, p1, radius};
}

Real BoundingCapsule::distance_squared_to_core(const Vec3& point) const {
  const Vec3 ab = p1 - p0;
  const Vec3 ap = point - p0;
  const Real len2 = glm::dot(ab, ab);
  Real t = Real(0);
  if (len2 > Real(0)) t = std::clamp(glm::dot(ap, ab) / len2, Real(0), Real(1));
  const Vec3 d = ap - t * ab;
  return glm::dot(d, d);
}

Vec3 BoundingCapsule::support(const Vec3& direction) const {
  const Vec3 end = glm::dot(direction, p1 - p0) > Real(0) ? p1 : p0;
  return BoundingSphere{end, radius}.support(direction);
}

}  // namespace proxima
