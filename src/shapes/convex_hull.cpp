// ConvexHull queries (the hull itself is built in convex_hull_build.cpp).
//
//  - support_index: linear scan for hulls up to kLinearScanMaxVertices (in float with SSE2,
//    four vertices per step over blocks stored x x x x y y y y z z z z: every dot product
//    and the running maximum in one pass, then the first vertex reaching the maximum, so
//    the answer is the first vertex of largest dot product, as the scalar scan gives);
//    otherwise hill-climbing (a local maximum
//    of a linear function over the vertex graph of a convex polytope is global; moves
//    only on a strictly larger dot product, so no cycle) — the "hill climbing" of van den
//    Bergen, Collision Detection in Interactive 3D Environments, 2004, sec. 4.3.4, and
//    Cameron's "enhanced GJK" (1997). Moves go to any vertex sharing a face, so faces
//    merged within the input's rounding (planar only to that accuracy) cannot hide a
//    better vertex behind a bend.
//  - raycast: Cyrus–Beck clipping of the ray's parameter interval against every face
//    half-space (Cyrus and Beck 1978; Ericson, Real-Time Collision Detection, 5.3.8).
//  - contains: every face plane test; a point within tolerance() in front of some planes
//    is decided by its exact distance (shifted planes would bulge out at sharp edges).
//  - closest_point (Ericson 5.1): inside, the nearest face plane (for a convex solid the
//    depth is the smallest plane distance and the projection lies on that face); outside,
//    the nearest of the projections that fall inside their face polygon and the closest
//    points on every edge; its normal the offset's direction, or, within the coordinates'
//    rounding of the surface, the normal of the face whose plane is farthest in front.
//  - world_aabb: box of the transformed vertices; above 512 vertices, six hill-climbing
//    support queries along the world axes seen in the local frame.
// Every query works relative to the centre of the hull's box (shifted vertices and plane
// offsets precomputed in double): for a hull far from its local origin the differences
// are exact, so dot products and plane tests keep the hull's own resolution.

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "geometry/raycast_detail.hpp"
#include "shapes/convex_hull_data.hpp"

#if defined(__SSE2__) && !PROXIMA_DOUBLE
#include <emmintrin.h>
#define PROXIMA_HULL_SCAN_SSE2 1
#else
#define PROXIMA_HULL_SCAN_SSE2 0
#endif

namespace proxima {

namespace {

// Closest point to p on segment ab (a == b allowed).
Vec3 closest_on_segment(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Real len2 = glm::dot(ab, ab);
  if (!(len2 > Real(0))) return a;
  const Real t = std::clamp(glm::dot(p - a, ab) / len2, Real(0), Real(1));
  return a + t * ab;
}

// Index of the first vertex of largest dot product with d (0 when no dot product is larger
// than -infinity, e.g. for a NaN direction). v holds n >= 1 tightly packed vertices. The
// reference path: the vectorised scan below must return the same index.
std::uint32_t scan_support(const Vec3* v, std::uint32_t n, const Vec3& d) {
  std::uint32_t best = 0;
  Real best_dot = -std::numeric_limits<Real>::infinity();
  for (std::uint32_t i = 0; i < n; ++i) {
    const Real dot = glm::dot(v[i], d);
    if (dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  return best;
}

#if PROXIMA_HULL_SCAN_SSE2
// Dot products of one block of four vertices with (dx, dy, dz): (x dx + y dy) + z dz, the
// operations of glm::dot in its order, so every product equals the scalar one.
inline __m128 block_dots(const float* p, __m128 dx, __m128 dy, __m128 dz) {
  const __m128 x = _mm_loadu_ps(p);
  const __m128 y = _mm_loadu_ps(p + 4);
  const __m128 z = _mm_loadu_ps(p + 8);
  return _mm_add_ps(_mm_add_ps(_mm_mul_ps(x, dx), _mm_mul_ps(y, dy)), _mm_mul_ps(z, dz));
}

// The same answer from the blocks of four (detail::HullData::scan_blocks): pass 1 keeps the
// lane-wise maximum of the products (maxps drops NaN products), pass 2 recomputes them
// block by block and returns the first vertex whose product equals the maximum. Padding
// repeats vertex 0, so it can only tie behind it.
std::uint32_t scan_support_blocks(const float* blocks, std::uint32_t n, const Vec3& d) {
  const std::uint32_t nb = (n + 3) / 4;
  const __m128 dx = _mm_set1_ps(d.x);
  const __m128 dy = _mm_set1_ps(d.y);
  const __m128 dz = _mm_set1_ps(d.z);
  // Two running maxima break the dependency chain of the max.
  __m128 best0 = _mm_set1_ps(-std::numeric_limits<float>::infinity());
  __m128 best1 = best0;
  std::uint32_t b = 0;
  for (; b + 2 <= nb; b += 2) {
    best0 = _mm_max_ps(block_dots(blocks + 12 * b, dx, dy, dz), best0);  // NaN product: keeps best
    best1 = _mm_max_ps(block_dots(blocks + 12 * b + 12, dx, dy, dz), best1);
  }
  if (b < nb) best0 = _mm_max_ps(block_dots(blocks + 12 * b, dx, dy, dz), best0);
  __m128 best = _mm_max_ps(best0, best1);
  best = _mm_max_ps(best, _mm_shuffle_ps(best, best, _MM_SHUFFLE(2, 3, 0, 1)));
  best = _mm_max_ps(best, _mm_shuffle_ps(best, best, _MM_SHUFFLE(1, 0, 3, 2)));
  for (b = 0; b < nb; ++b) {
    const int mask = _mm_movemask_ps(_mm_cmpeq_ps(block_dots(blocks + 12 * b, dx, dy, dz), best));
    if (mask != 0) return 4 * b + static_cast<std::uint32_t>(std::countr_zero(static_cast<unsigned>(mask)));
  }
  return 0;  // every product NaN
}
#endif

}  // namespace

std::uint32_t ConvexHull::support_index(const Vec3& direction, std::uint32_t start_vertex) const {
  if (data().shifted_vertices.size() <= kLinearScanMaxVertices) return scan_support_index(direction);
  return climb_support_index(direction, start_vertex);
}

std::uint32_t ConvexHull::scan_support_index(const Vec3& direction) const {
#if PROXIMA_HULL_SCAN_SSE2
  return scan_support_blocks(data().scan_blocks.data(), static_cast<std::uint32_t>(data().shifted_vertices.size()),
                             direction);
#else
  return scan_support(data().shifted_vertices.data(), static_cast<std::uint32_t>(data().shifted_vertices.size()),
                      direction);
#endif
}

std::uint32_t ConvexHull::scalar_support_index(const Vec3& direction) const {
  return scan_support(data().shifted_vertices.data(), static_cast<std::uint32_t>(data().shifted_vertices.size()),
                      direction);
}

std::uint32_t ConvexHull::climb_support_index(const Vec3& direction, std::uint32_t start_vertex) const {
  // Relative to the box centre: for a hull far from the origin the differences are exact
  // and the dot products keep the hull's own resolution.
  const std::vector<Vec3>& v = data().shifted_vertices;
  const auto n = static_cast<std::uint32_t>(v.size());
  std::uint32_t current = start_vertex < n ? start_vertex : 0;
  Real current_dot = glm::dot(v[current], direction);
  // Steepest ascent: each pass moves to the best strictly better neighbour. The dot
  // product strictly increases, so a vertex is never revisited and the loop ends.
  for (;;) {
    std::uint32_t next = current;
    Real next_dot = current_dot;
    const std::uint32_t* nb_begin = data().climb_neighbors.data() + data().climb_offsets[current];
    const std::uint32_t* nb_end = data().climb_neighbors.data() + data().climb_offsets[current + 1];
    for (const std::uint32_t* it = nb_begin; it != nb_end; ++it) {
      const std::uint32_t nb = *it;
      const Real d = glm::dot(v[nb], direction);
      if (d > next_dot) {
        next_dot = d;
        next = nb;
      }
    }
    if (next == current) return current;
    current = next;
    current_dot = next_dot;
  }
}

Aabb ConvexHull::world_aabb(const Transform& pose) const {
  const Mat3 r = pose.rotation_matrix();
  const std::vector<Vec3>& v = data().shifted_vertices;
  Aabb box = Aabb::empty();
  // Measured (bench/RESULTS.md): the streaming scan costs about 2 ns per vertex, six
  // hill-climbs cost more than that up to about 500 vertices.
  constexpr std::size_t kScanMaxVertices = 512;
  if (v.size() <= kScanMaxVertices) {
    for (const Vec3& p : v) box.grow(r * p);
  } else {
    // World axis i seen in the local frame is row i of R: one hill-climb per face of the
    // box, each warm-started from the previous answer.
    std::uint32_t hint = 0;
    for (int i = 0; i < 3; ++i) {
      const Vec3 row(r[0][i], r[1][i], r[2][i]);
      hint = support_index(row, hint);
      box.max[i] = glm::dot(row, v[hint]);
      hint = support_index(-row, hint);
      box.min[i] = glm::dot(row, v[hint]);
    }
  }
  const Vec3 c = pose.apply(data().reference);
  box.min += c;
  box.max += c;
  return box;
}

// Signed distance of the shifted point q in front of face i's plane.
static inline Real plane_distance(const detail::HullData& d, std::size_t i, const Vec3& q) {
  return glm::dot(d.faces[i].normal, q) - d.shifted_offsets[i];
}

bool ConvexHull::contains(const Vec3& point) const {
  const Real tol = data().tolerance;
  const Vec3 q = point - data().reference;
  Real worst = -kRealMax;
  for (std::size_t i = 0; i < data().faces.size(); ++i) {
    const Real d = plane_distance(data(), i, q);
    if (d > tol) return false;
    worst = std::max(worst, d);
  }
  if (worst <= Real(0)) return true;
  // Within tolerance of some face planes: the planes shifted out by tol would meet far
  // beyond a sharp edge of a thin hull, so decide by the true distance to the hull.
  return closest_point(point).signed_distance <= tol;
}

std::optional<RayHit> ConvexHull::raycast(const Ray& ray, Real max_t) const {
  if (!(max_t >= Real(0))) return std::nullopt;
  const Vec3 origin = ray.origin - data().reference;
  Real t_enter = Real(0);
  Real t_exit = max_t;
  std::size_t enter_face = data().faces.size();
  const Real tol = data().tolerance;
  for (std::size_t i = 0; i < data().faces.size(); ++i) {
    // Inside the face's half-space: t * denom <= dist.
    const Vec3& n = data().faces[i].normal;
    const Real denom = glm::dot(n, ray.direction);
    const Real dist = -plane_distance(data(), i, origin);
    if (denom == Real(0)) {
      if (dist < -tol) return std::nullopt;  // parallel and outside
      continue;
    }
    const Real t = dist / denom;
    if (denom < Real(0)) {
      if (t > t_enter) {
        t_enter = t;
        enter_face = i;
      }
    } else if (t < t_exit) {
      t_exit = t;
    }
    if (t_enter > t_exit) return std::nullopt;
  }
  RayHit hit;
  if (enter_face == data().faces.size()) {
    // The origin is inside (or on) the hull.
    hit.t = Real(0);
    hit.point = ray.origin;
    // -direction / |direction| from the direction scaled by its largest component: the
    // squared length of a tiny direction (1e-30 in float) underflows to 0.
    Real length;
    Vec3 unit;
    hit.normal =
        geometry::detail::length_and_direction(ray.direction, length, unit) ? -unit : closest_point(ray.origin).normal;
    return hit;
  }
  hit.t = t_enter;
  hit.point = ray.at(t_enter);
  hit.normal = data().faces[enter_face].normal;
  return hit;
}

SurfacePoint ConvexHull::closest_point(const Vec3& point) const {
  const std::vector<HullFace>& faces = data().faces;
  const std::vector<Vec3>& v = data().shifted_vertices;
  const Vec3& ref = data().reference;
  const Vec3 p = point - ref;
  // The face whose plane is farthest in front of (or least behind) the point.
  std::size_t best_face = 0;
  Real best_plane = -kRealMax;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const Real d = plane_distance(data(), i, p);
    if (d > best_plane) {
      best_plane = d;
      best_face = i;
    }
  }
  SurfacePoint r;
  if (best_plane <= Real(0)) {
    // Inside or on the surface: the nearest face plane.
    r.normal = faces[best_face].normal;
    r.point = point - best_plane * r.normal;
    r.signed_distance = best_plane;
    return r;
  }
  // Outside: the nearest point over every face polygon.
  Real best_d2 = kRealMax;
  Vec3 best_point = p;
  for (std::size_t i = 0; i < faces.size(); ++i) {
    const HullFace& f = faces[i];
    const Real d = plane_distance(data(), i, p);
    if (d <= Real(0) || d * d >= best_d2) continue;
    const Vec3 q = p - d * f.normal;
    bool inside = true;
    for (std::uint32_t k = 0; k < f.index_count && inside; ++k) {
      const Vec3& a = v[data().face_indices[f.first_index + k]];
      const Vec3& b = v[data().face_indices[f.first_index + (k + 1) % f.index_count]];
      inside = glm::dot(glm::cross(b - a, q - a), f.normal) >= Real(0);
    }
    if (inside) {
      best_d2 = d * d;
      best_point = q;
    }
  }
  for (const HullEdge& e : data().edges) {
    const Vec3 q = closest_on_segment(p, v[e.v0], v[e.v1]);
    const Vec3 pq = p - q;
    const Real d2 = glm::dot(pq, pq);
    if (d2 < best_d2) {
      best_d2 = d2;
      best_point = q;
    }
  }
  const Real dist = std::sqrt(best_d2);
  r.point = best_point + ref;
  r.signed_distance = dist;
  // Normal from the offset when it is beyond the rounding of the coordinates, else the
  // normal of the face whose plane is farthest in front, one of the nearest feature's faces
  // (a point on a vertex was 1 ulp off it in z, and its normal was +z, outside the vertex's
  // normal cone).
  const Real rounding = Real(64) * kEpsilon * std::max(max_abs_component(point), max_abs_component(p));
  if (dist > rounding && dist > std::numeric_limits<Real>::min() * Real(1e6)) {
    const Vec3 n = (p - best_point) / dist;
    const Real nl = glm::length(n);
    r.normal = (nl > Real(0.5) && nl < Real(1.5)) ? n / nl : faces[best_face].normal;
  } else {
    r.normal = faces[best_face].normal;
  }
  return r;
}

MassProperties ConvexHull::mass_properties(Real density) const {
  MassProperties m;
  m.volume = data().volume;
  m.mass = density * data().volume;
  m.centroid = data().centroid;
  m.inertia = data().unit_inertia * density;
  return m;
}

}  // namespace proxima
