// Axis-aligned box and k-DOP fitting: one pass over the points keeping the minimum and
// maximum of each slab's projection (Ericson, Real-Time Collision Detection, 4.2 and 4.6).
// The bounds are the projections themselves, so containment is exact.
#include <proxima/bounds/fit_aabb.hpp>
#include <proxima/bounds/fit_kdop.hpp>

#include "bounds/fit_util.hpp"

namespace proxima {

Result<Aabb> fit_aabb(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  Aabb box = Aabb::from_point(points[0]);
  for (const Vec3& p : points) box.grow(p);
  return box;
}

template <int K>
Result<Kdop<K>> fit_kdop(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  Kdop<K> k;
  for (const Vec3& p : points) k.grow(p);
  return k;
}

template Result<Kdop<6>> fit_kdop<6>(std::span<const Vec3>);
template Result<Kdop<14>> fit_kdop<14>(std::span<const Vec3>);
template Result<Kdop<18>> fit_kdop<18>(std::span<const Vec3>);
template Result<Kdop<26>> fit_kdop<26>(std::span<const Vec3>);

}  // namespace proxima
