// k-DOP: directions, validation, vertices, volume and emptiness.
//
// Steps: the polytope queries shift the slabs to a local origin (the centre of the axis
// slabs) and work in double precision, then enumerate vertices as intersections of three
// slab planes (bounds/slab_polytope.cpp). Tolerances are relative to the magnitude of the
// bounds, i.e. to the precision the bounds were stored in.
// Source: Ericson, Real-Time Collision Detection, 4.6; Klosowski, Held, Mitchell, Sowizral,
// Zikan, "Efficient Collision Detection Using Bounding Volume Hierarchies of k-DOPs", IEEE
// TVCG 4(1), 1998.
#include <proxima/bounds/kdop.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>

#include <algorithm>
#include <string>

#include "bounds/kdop_internal.hpp"
#include "bounds/slab_polytope.hpp"

namespace proxima {

namespace detail {

template <int K>
KdopPolytope make_kdop_polytope(const std::array<Real, K / 2>& lo, const std::array<Real, K / 2>& hi) {
  KdopPolytope p;
  constexpr int kSlabs = K / 2;
  // Local origin: centre of the axis slabs (only when they are consistent and finite).
  glm::dvec3 origin(0.0);
  double magnitude = 0.0;
  for (int i = 0; i < kSlabs; ++i) magnitude = std::max({magnitude, std::abs(double(lo[i])), std::abs(double(hi[i]))});
  for (int a = 0; a < 3; ++a) {
    if (lo[a] <= hi[a]) origin[a] = 0.5 * double(lo[a]) + 0.5 * double(hi[a]);
  }
  p.origin = origin;
  double extent = 0.0;
  for (int i = 0; i < kSlabs; ++i) {
    const Vec3 d = Kdop<K>::direction(i);
    p.dirs[i] = glm::dvec3(d);
    const double shift = glm::dot(p.dirs[i], origin);
    p.lo[i] = double(lo[i]) - shift;
    p.hi[i] = double(hi[i]) - shift;
    extent = std::max({extent, std::abs(p.lo[i]), std::abs(p.hi[i])});
  }
  p.count = kSlabs;
  // The bounds carry the rounding of Real at their own magnitude; geometry derived from
  // them is trusted to a few ulps of that plus a relative part of the local extent.
  p.slack = 16.0 * double(kEpsilon) * magnitude + 1e-12 * extent + 1e-300;
  return p;
}

template KdopPolytope make_kdop_polytope<6>(const std::array<Real, 3>&, const std::array<Real, 3>&);
template KdopPolytope make_kdop_polytope<14>(const std::array<Real, 7>&, const std::array<Real, 7>&);
template KdopPolytope make_kdop_polytope<18>(const std::array<Real, 9>&, const std::array<Real, 9>&);
template KdopPolytope make_kdop_polytope<26>(const std::array<Real, 13>&, const std::array<Real, 13>&);

std::vector<glm::dvec3> KdopPolytope::local_vertices(bool stop_at_first) const {
  for (int i = 0; i < count; ++i) {
    if (!(lo[i] <= hi[i] + slack)) return {};
  }
  const auto c = static_cast<std::size_t>(count);
  return slab_polytope_vertices(std::span<const glm::dvec3>(dirs.data(), c), std::span<const double>(lo.data(), c),
                                std::span<const double>(hi.data(), c), slack, 2.0 * slack, stop_at_first);
}

}  // namespace detail

template <int K>
Result<Kdop<K>> Kdop<K>::create(const std::array<Real, K / 2>& min_bounds, const std::array<Real, K / 2>& max_bounds) {
  for (int i = 0; i < kSlabCount; ++i) {
    if (auto e = validate::finite(min_bounds[i], "min[" + std::to_string(i) + "]")) return *e;
  }
  for (int i = 0; i < kSlabCount; ++i) {
    if (auto e = validate::finite(max_bounds[i], "max[" + std::to_string(i) + "]")) return *e;
  }
  for (int i = 0; i < kSlabCount; ++i) {
    if (!(min_bounds[i] <= max_bounds[i])) {
      return make_error(ErrorCode::InvalidArgument, "max[" + std::to_string(i) + "]",
                        "must not be less than min[" + std::to_string(i) + "]");
    }
  }
  Kdop k;
  k.min = min_bounds;
  k.max = max_bounds;
  if (k.is_empty()) {
    return make_error(ErrorCode::Degenerate, "max", "the slabs have no common point (empty k-DOP)");
  }
  return k;
}

template <int K>
bool Kdop<K>::is_empty() const {
  return detail::make_kdop_polytope<K>(min, max).local_vertices(true).empty();
}

template <int K>
std::vector<Vec3> Kdop<K>::vertices() const {
  const detail::KdopPolytope p = detail::make_kdop_polytope<K>(min, max);
  std::vector<Vec3> out;
  for (const glm::dvec3& v : p.local_vertices(false)) out.push_back(Vec3(v + p.origin));
  return out;
}

template <int K>
Real Kdop<K>::volume() const {
  const detail::KdopPolytope p = detail::make_kdop_polytope<K>(min, max);
  const std::vector<glm::dvec3> v = p.local_vertices(false);
  const auto c = static_cast<std::size_t>(p.count);
  return Real(detail::slab_polytope_volume(std::span<const glm::dvec3>(p.dirs.data(), c),
                                           std::span<const double>(p.lo.data(), c),
                                           std::span<const double>(p.hi.data(), c), v, 2.0 * p.slack));
}

template struct Kdop<6>;
template struct Kdop<14>;
template struct Kdop<18>;
template struct Kdop<26>;

}  // namespace proxima
