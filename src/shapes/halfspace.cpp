// HalfSpace: the unbounded solid n . x <= d.
//
// Steps:
//  - construction: the normal is divided by its largest component, then by its length, and
//    the offset by the same factors, so that neither tiny nor huge normals under- or
//    overflow;
//  - support: a linear programme, max direction . x over the half-space clipped to the cube
//    |x|_inf <= E. Start from the cube's support corner E sign(direction); while it lies
//    outside the plane, slide coordinates back across the cube, cheapest first (least loss
//    of direction . x per unit of n . x regained, |direction_i| / |n_i|), stopping exactly on
//    the plane: the greedy solution of this fractional knapsack is optimal (Dantzig 1957);
//  - bounds: unbounded (+-kRealMax) except along an axis that the normal matches exactly;
//    the world box is derived from the world normal and offset, never by transforming an
//    unbounded box;
//  - contains / closest point: the signed plane distance n . p - d and the projection;
//  - ray cast: geometry::ray_halfspace.
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/halfspace.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace proxima {
namespace {

// Box of {x : n . x <= d} when n (unit, world or local) matches an axis exactly, else the
// unbounded box.
Aabb plane_box(const Vec3& n, Real d) {
  Aabb box{Vec3(-kRealMax), Vec3(kRealMax)};
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const int k = (i + 2) % 3;
    if (n[j] != Real(0) || n[k] != Real(0) || n[i] == Real(0)) continue;
    const Real bound = std::clamp(d / n[i], -kRealMax, kRealMax);
    if (n[i] > Real(0)) {
      box.max[i] = bound;
    } else {
      box.min[i] = bound;
    }
  }
  return box;
}

}  // namespace

Result<HalfSpace> HalfSpace::create(const Vec3& normal, Real offset) {
  if (auto e = validate::finite(normal, "normal")) return *e;
  const Real m = max_abs_component(normal);
  if (!(m > Real(0))) return make_error(ErrorCode::Degenerate, "normal", "must not be the zero vector");
  if (auto e = validate::finite(offset, "offset")) return *e;
  const Vec3 w = normal / m;
  const Real l = glm::length(w);
  const Real d = (offset / m) / l;
  if (!is_finite(d) || std::abs(d) > kMaxCoordinate) {
    return make_error(ErrorCode::OutOfRange, "offset",
                      "divided by the length of the normal, exceeds the supported range");
  }
  return HalfSpace(w / l, d);
}

Vec3 HalfSpace::support(const Vec3& direction_in) const {
  const Vec3 direction = is_finite(direction_in) ? direction_in : Vec3(Real(0));
  const Real extent = std::max(kSupportExtent, std::abs(offset_));
  Vec3 x;
  for (int i = 0; i < 3; ++i) x[i] = direction[i] >= Real(0) ? extent : -extent;
  Real excess = glm::dot(normal_, x) - offset_;
  if (excess <= Real(0)) return x;
  // Axes that can bring n . x down (n_i x_i > 0), cheapest ratio |d_i| / |n_i| first.
  std::array<int, 3> order{};
  int count = 0;
  for (int i = 0; i < 3; ++i) {
    if (normal_[i] * x[i] > Real(0)) order[static_cast<std::size_t>(count++)] = i;
  }
  std::sort(order.begin(), order.begin() + count, [&](int a, int b) {
    return std::abs(direction[a]) * std::abs(normal_[b]) < std::abs(direction[b]) * std::abs(normal_[a]);
  });
  for (int k = 0; k < count && excess > Real(0); ++k) {
    const int i = order[static_cast<std::size_t>(k)];
    const Real n_abs = std::abs(normal_[i]);
    const Real capacity = Real(2) * extent * n_abs;
    const Real sign = x[i] > Real(0) ? Real(1) : Real(-1);
    if (capacity >= excess) {
      x[i] = std::clamp(x[i] - sign * (excess / n_abs), -extent, extent);
      excess = Real(0);
    } else {
      x[i] = -x[i];
      excess -= capacity;
    }
  }
  return x;
}

Aabb HalfSpace::local_aabb() const { return plane_box(normal_, offset_); }

Aabb HalfSpace::world_aabb(const Transform& pose) const {
  const Vec3 n = pose.apply_vector(normal_);
  return plane_box(n, offset_ + glm::dot(n, pose.position));
}

std::optional<RayHit> HalfSpace::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0)) || !is_finite(ray.origin) || !is_finite(ray.direction)) return std::nullopt;
  return geometry::ray_halfspace(ray, max_t, normal_, offset_);
}

bool HalfSpace::contains(const Vec3& point) const { return is_finite(point) && glm::dot(normal_, point) <= offset_; }

SurfacePoint HalfSpace::closest_point(const Vec3& point) const {
  if (!is_finite(point)) return SurfacePoint{offset_ * normal_, normal_, std::numeric_limits<Real>::infinity()};
  const Real s = glm::dot(normal_, point) - offset_;
  SurfacePoint r;
  r.point = point - s * normal_;
  r.normal = normal_;
  r.signed_distance = s;
  return r;
}

}  // namespace proxima
