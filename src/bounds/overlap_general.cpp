// Overlap tests without a closed form, by GJK on the volumes' cores, and the exact k-DOP
// tests.
//
// Steps:
//  - Every bounding volume is core (+) ball: Aabb and Obb = their 8 corners, k-DOP = its
//    vertices, hull = its vertices (radius 0); sphere = its centre, capsule = its segment
//    (plus the radius). Two volumes overlap when the GJK distance between the cores'
//    convex hulls is at most the sum of the radii (bounds/convex_distance.cpp).
//  - k-DOP vs k-DOP (same K) and vs Aabb: the intersection of the slabs is itself a slab
//    polytope (lower bound = max of the lower bounds, upper = min of the upper bounds; the
//    box narrows slabs 0-2). A slab whose interval is empty separates at once; otherwise
//    the intersection is non-empty iff it has a vertex (vertex enumeration, stop at the
//    first). This is exact, where the per-slab interval test is only conservative.
// Sources: Gilbert, Johnson, Keerthi 1988; van den Bergen 1999; Ericson, Real-Time
// Collision Detection, 4.6 and 9.5; Klosowski et al. 1998 for the k-DOP slab test.
#include <proxima/bounds/convex_distance.hpp>
#include <proxima/bounds/overlap.hpp>

#include <array>
#include <span>

#include "bounds/kdop_internal.hpp"

namespace proxima {
namespace {

std::array<Vec3, 8> corners(const Aabb& box) {
  std::array<Vec3, 8> c;
  for (int k = 0; k < 8; ++k) {
    c[static_cast<std::size_t>(k)] =
        Vec3((k & 1) ? box.max.x : box.min.x, (k & 2) ? box.max.y : box.min.y, (k & 4) ? box.max.z : box.min.z);
  }
  return c;
}

bool cores(std::span<const Vec3> a, Real ra, std::span<const Vec3> b, Real rb) {
  if (a.empty() || b.empty()) return false;
  return convex_cores_overlap(a, ra, b, rb);
}

template <int K>
bool kdop_nonempty(const std::array<Real, K / 2>& lo, const std::array<Real, K / 2>& hi) {
  const detail::KdopPolytope p = detail::make_kdop_polytope<K>(lo, hi);
  return !p.local_vertices(true).empty();
}

}  // namespace

bool overlaps(const Aabb& a, const BoundingCapsule& b) {
  if (!a.is_valid()) return false;
  const auto c = corners(a);
  const std::array<Vec3, 2> s{b.p0, b.p1};
  return cores(c, Real(0), s, b.radius);
}

bool overlaps(const Aabb& a, const ConvexHull& b) {
  if (!a.is_valid()) return false;
  const auto c = corners(a);
  return cores(c, Real(0), b.vertices(), Real(0));
}

bool overlaps(const BoundingSphere& a, const ConvexHull& b) {
  const std::array<Vec3, 1> c{a.center};
  return cores(c, a.radius, b.vertices(), Real(0));
}

bool overlaps(const Obb& a, const BoundingCapsule& b) {
  const auto c = a.corners();
  const std::array<Vec3, 2> s{b.p0, b.p1};
  return cores(c, Real(0), s, b.radius);
}

bool overlaps(const Obb& a, const ConvexHull& b) {
  const auto c = a.corners();
  return cores(c, Real(0), b.vertices(), Real(0));
}

bool overlaps(const BoundingCapsule& a, const BoundingCapsule& b) {
  const std::array<Vec3, 2> s{a.p0, a.p1};
  const std::array<Vec3, 2> t{b.p0, b.p1};
  return cores(s, a.radius, t, b.radius);
}

bool overlaps(const BoundingCapsule& a, const ConvexHull& b) {
  const std::array<Vec3, 2> s{a.p0, a.p1};
  return cores(s, a.radius, b.vertices(), Real(0));
}

bool overlaps(const ConvexHull& a, const ConvexHull& b) { return cores(a.vertices(), Real(0), b.vertices(), Real(0)); }

template <int K>
bool overlaps(const Aabb& a, const Kdop<K>& b) {
  if (!a.is_valid()) return false;
  std::array<Real, K / 2> lo = b.min;
  std::array<Real, K / 2> hi = b.max;
  for (int i = 0; i < 3; ++i) {
    lo[i] = std::max(lo[i], a.min[i]);
    hi[i] = std::min(hi[i], a.max[i]);
  }
  return kdop_nonempty<K>(lo, hi);
}

template <int K>
bool overlaps(const BoundingSphere& a, const Kdop<K>& b) {
  const std::vector<Vec3> v = b.vertices();
  const std::array<Vec3, 1> c{a.center};
  return cores(c, a.radius, v, Real(0));
}

template <int K>
bool overlaps(const Obb& a, const Kdop<K>& b) {
  const std::vector<Vec3> v = b.vertices();
  const auto c = a.corners();
  return cores(c, Real(0), v, Real(0));
}

template <int K>
bool overlaps(const BoundingCapsule& a, const Kdop<K>& b) {
  const std::vector<Vec3> v = b.vertices();
  const std::array<Vec3, 2> s{a.p0, a.p1};
  return cores(s, a.radius, v, Real(0));
}

template <int K>
bool overlaps(const Kdop<K>& a, const Kdop<K>& b) {
  std::array<Real, K / 2> lo;
  std::array<Real, K / 2> hi;
  for (int i = 0; i < K / 2; ++i) {
    lo[i] = std::max(a.min[i], b.min[i]);
    hi[i] = std::min(a.max[i], b.max[i]);
  }
  return kdop_nonempty<K>(lo, hi);
}

template <int K>
bool overlaps(const Kdop<K>& a, const ConvexHull& b) {
  const std::vector<Vec3> v = a.vertices();
  return cores(v, Real(0), b.vertices(), Real(0));
}

#define PROXIMA_INSTANTIATE_KDOP_OVERLAPS(K)                         \
  template bool overlaps<K>(const Aabb&, const Kdop<K>&);            \
  template bool overlaps<K>(const BoundingSphere&, const Kdop<K>&);  \
  template bool overlaps<K>(const Obb&, const Kdop<K>&);             \
  template bool overlaps<K>(const BoundingCapsule&, const Kdop<K>&); \
  template bool overlaps<K>(const Kdop<K>&, const Kdop<K>&);         \
  template bool overlaps<K>(const Kdop<K>&, const ConvexHull&);

PROXIMA_INSTANTIATE_KDOP_OVERLAPS(6)
PROXIMA_INSTANTIATE_KDOP_OVERLAPS(14)
PROXIMA_INSTANTIATE_KDOP_OVERLAPS(18)
PROXIMA_INSTANTIATE_KDOP_OVERLAPS(26)
#undef PROXIMA_INSTANTIATE_KDOP_OVERLAPS

}  // namespace proxima
