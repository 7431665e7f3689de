// Triangle-triangle intersection test and closest points.
//
// Intersection (after Moller, "A Fast Triangle-Triangle Intersection Test", JGT 1997):
//  1. Huge or tiny coordinates are rescaled by a power of two; the touching tolerance is
//     tol = kRelativeTolerance * (largest |coordinate|).
//  2. A triangle thinner than tol (or thin in the sense of detail::is_thin_triangle) is its
//     longest edge: the test becomes segment-triangle or segment-segment distance <= tol.
//  3. Signed distances of A's vertices to B's plane (unit normal), those within tol snapped
//     to 0; all of one strict sign: no intersection. The same for B against A's plane.
//  4. All of one triangle's distances 0: coplanar, tested in 2-D (the projection dropping
//     the dominant axis of the normal): an edge pair crossing (strict orientation signs)
//     or an end point within tol of the other edge, or one triangle's vertex inside the
//     other.
//  5. Otherwise each triangle meets the other's plane in an interval of the line
//     L where the two planes meet: the points where its edges cross that plane and its vertices
//     on it, measured along D = nA x nB. The triangles meet iff the intervals overlap (closed,
//     with tol). Collecting the crossing points replaces Moller's case table by one loop
//     and handles snapped vertices without special cases.
//
// Closest points (Ericson, Real-Time Collision Detection, 5.1.10; Eberly, "Distance
// Between Two Triangles in 3D"):
//  1. Rescale as above.
//  2. An edge of one triangle crossing the other (detail::common_point_segment_triangle,
//     the crossing confirmed by its distance to the triangle): the triangles intersect,
//     distance 0 at the crossing point; an unconfirmed crossing joins the candidates. For
//     non-coplanar triangles the intersection segment ends on such crossings, so every
//     intersection is found here or in step 3 (coplanar overlaps have touching edges or a
//     vertex inside, at distance 0).
//  3. Otherwise the nearest of the 15 candidate pairs: each vertex against the other
//     triangle (6) and each edge pair (9). For disjoint triangles a closest pair always
//     involves a vertex or two edges: two interior points would need parallel planes, and
//     sliding in them reaches a boundary.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

#include <array>

namespace proxima::geometry {

namespace {

using Tri = std::array<Vec3, 3>;

// Largest |coordinate| of the six vertices (infinity for non-finite input).
Real max_abs(const Tri& a, const Tri& b) { return detail::magnitude({a[0], a[1], a[2], b[0], b[1], b[2]}); }

// The two end points of the longest edge of a thin triangle.
std::array<Vec3, 2> longest_edge(const Tri& t) {
  const Real l01 = length_squared(t[1] - t[0]);
  const Real l12 = length_squared(t[2] - t[1]);
  const Real l20 = length_squared(t[0] - t[2]);
  if (l01 >= l12 && l01 >= l20) return {t[0], t[1]};
  if (l12 >= l20) return {t[1], t[2]};
  return {t[2], t[0]};
}

// Height of the triangle over its longest edge below tol, or thin: treat as a segment.
bool acts_as_segment(const Vec3& n, const Tri& t, Real tol) {
  if (detail::is_thin_triangle(n, t[0], t[1], t[2])) return true;
  const Real l2 = std::max({length_squared(t[1] - t[0]), length_squared(t[2] - t[1]), length_squared(t[0] - t[2])});
  return length_squared(n) <= tol * tol * l2;
}

Real orient_2d(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
}

Real distance_squared_point_segment_2d(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const Real num = glm::dot(p - a, ab);
  if (num <= Real(0)) return glm::dot(p - a, p - a);
  const Real den = glm::dot(ab, ab);
  if (num >= den) return glm::dot(p - b, p - b);
  const Vec2 d = p - (a + (num / den) * ab);
  return glm::dot(d, d);
}

bool opposite(Real x, Real y) { return (x > Real(0) && y < Real(0)) || (x < Real(0) && y > Real(0)); }

// Closed 2-D segments p0p1 and q0q1 meet (within tol).
bool segments_meet_2d(const Vec2& p0, const Vec2& p1, const Vec2& q0, const Vec2& q1, Real tol) {
  if (opposite(orient_2d(p0, p1, q0), orient_2d(p0, p1, q1)) &&
      opposite(orient_2d(q0, q1, p0), orient_2d(q0, q1, p1))) {
    return true;
  }
  const Real tol2 = tol * tol;
  return distance_squared_point_segment_2d(p0, q0, q1) <= tol2 ||
         distance_squared_point_segment_2d(p1, q0, q1) <= tol2 ||
         distance_squared_point_segment_2d(q0, p0, p1) <= tol2 || distance_squared_point_segment_2d(q1, p0, p1) <= tol2;
}

// p inside the closed 2-D triangle t (either orientation).
bool inside_2d(const Vec2& p, const std::array<Vec2, 3>& t) {
  const Real o0 = orient_2d(t[0], t[1], p);
  const Real o1 = orient_2d(t[1], t[2], p);
  const Real o2 = orient_2d(t[2], t[0], p);
  return (o0 >= Real(0) && o1 >= Real(0) && o2 >= Real(0)) || (o0 <= Real(0) && o1 <= Real(0) && o2 <= Real(0));
}

// Step 4: coplanar triangles, projected along the dominant axis of `normal`.
bool coplanar_intersect(const Tri& a, const Tri& b, const Vec3& normal, Real tol) {
  const Vec3 an = glm::abs(normal);
  const int drop = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
  const int i = drop == 0 ? 1 : 0;
  const int j = drop == 2 ? 1 : 2;
  const Vec3 origin = a[0];
  std::array<Vec2, 3> a2;
  std::array<Vec2, 3> b2;
  for (int k = 0; k < 3; ++k) {
    const Vec3 ra = a[k] - origin;
    const Vec3 rb = b[k] - origin;
    a2[k] = Vec2(ra[i], ra[j]);
    b2[k] = Vec2(rb[i], rb[j]);
  }
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      if (segments_meet_2d(a2[k], a2[(k + 1) % 3], b2[l], b2[(l + 1) % 3], tol)) return true;
    }
  }
  return inside_2d(a2[0], b2) || inside_2d(b2[0], a2);
}

// Step 5: the interval of L covered by triangle t, whose vertices have snapped signed
// distances d to the other plane (not all of one strict sign, not all 0), measured as
// D.(x - origin).
void interval_on_line(const Tri& t, const std::array<Real, 3>& d, const Vec3& dir, const Vec3& origin, Real& lo,
                      Real& hi) {
  lo = kRealMax;
  hi = -kRealMax;
  std::array<Real, 3> x;
  for (int k = 0; k < 3; ++k) x[k] = glm::dot(dir, t[k] - origin);
  for (int k = 0; k < 3; ++k) {
    if (d[k] == Real(0)) {
      lo = std::min(lo, x[k]);
      hi = std::max(hi, x[k]);
    }
    const int l = (k + 1) % 3;
    if (opposite(d[k], d[l])) {
      const Real v = x[k] + (x[l] - x[k]) * (d[k] / (d[k] - d[l]));
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
}

// Snapped signed distances of t's vertices to the plane through `on` with unit normal u;
// returns false when all are of one strict sign (t on one side).
bool straddles(const Tri& t, const Vec3& u, const Vec3& on, Real tol, std::array<Real, 3>& d) {
  int positive = 0;
  int negative = 0;
  for (int k = 0; k < 3; ++k) {
    d[k] = glm::dot(u, t[k] - on);
    if (std::abs(d[k]) <= tol) d[k] = Real(0);
    positive += d[k] > Real(0) ? 1 : 0;
    negative += d[k] < Real(0) ? 1 : 0;
  }
  return positive < 3 && negative < 3;
}

bool triangles_intersect_unscaled(const Tri& a, const Tri& b, Real tol) {
  const Vec3 na = glm::cross(a[1] - a[0], a[2] - a[0]);
  const Vec3 nb = glm::cross(b[1] - b[0], b[2] - b[0]);
  const bool seg_a = acts_as_segment(na, a, tol);
  const bool seg_b = acts_as_segment(nb, b, tol);
  const Real tol2 = tol * tol;
  if (seg_a && seg_b) {
    const auto ea = longest_edge(a);
    const auto eb = longest_edge(b);
    return detail::closest_points_segment_segment_unscaled(ea[0], ea[1], eb[0], eb[1]).distance_squared <= tol2;
  }
  if (seg_a) {
    const auto ea = longest_edge(a);
    return detail::closest_points_segment_triangle_unscaled(ea[0], ea[1], b[0], b[1], b[2]).distance_squared <= tol2;
  }
  if (seg_b) {
    const auto eb = longest_edge(b);
    return detail::closest_points_segment_triangle_unscaled(eb[0], eb[1], a[0], a[1], a[2]).distance_squared <= tol2;
  }

  const Vec3 ua = na / std::sqrt(length_squared(na));
  const Vec3 ub = nb / std::sqrt(length_squared(nb));
  std::array<Real, 3> da;
  std::array<Real, 3> db;
  if (!straddles(a, ub, b[0], tol, da)) return false;
  if (!straddles(b, ua, a[0], tol, db)) return false;
  const bool flat_a = da[0] == Real(0) && da[1] == Real(0) && da[2] == Real(0);
  const bool flat_b = db[0] == Real(0) && db[1] == Real(0) && db[2] == Real(0);
  if (flat_a || flat_b) return coplanar_intersect(a, b, ua, tol);

  const Vec3 dir = glm::cross(ua, ub);
  Real lo_a;
  Real hi_a;
  Real lo_b;
  Real hi_b;
  interval_on_line(a, da, dir, a[0], lo_a, hi_a);
  interval_on_line(b, db, dir, a[0], lo_b, hi_b);
  const Real slack = tol * std::sqrt(length_squared(dir));
  return lo_a <= hi_b + slack && lo_b <= hi_a + slack;
}

ClosestPair triangle_triangle_unscaled(const Tri& a, const Tri& b) {
  // 2. Crossings of an edge through the other triangle.
  const Vec3 na = glm::cross(a[1] - a[0], a[2] - a[0]);
  const Vec3 nb = glm::cross(b[1] - b[0], b[2] - b[0]);
  const Real accept = detail::crossing_acceptance(max_abs(a, b));
  ClosestPair best{a[0], b[0], kRealMax};
  ClosestPair crossing;
  if (!detail::is_thin_triangle(nb, b[0], b[1], b[2])) {
    for (int k = 0; k < 3; ++k) {
      switch (detail::common_point_segment_triangle(a[k], a[(k + 1) % 3], b[0], b[1], b[2], nb, accept, crossing)) {
        case detail::Crossing::Common: return crossing;
        case detail::Crossing::Candidate:
          if (crossing.distance_squared < best.distance_squared) best = crossing;
          break;
        case detail::Crossing::None: break;
      }
    }
  }
  if (!detail::is_thin_triangle(na, a[0], a[1], a[2])) {
    for (int k = 0; k < 3; ++k) {
      switch (detail::common_point_segment_triangle(b[k], b[(k + 1) % 3], a[0], a[1], a[2], na, accept, crossing)) {
        case detail::Crossing::Common: return {crossing.on_b, crossing.on_a, Real(0)};
        case detail::Crossing::Candidate:
          if (crossing.distance_squared < best.distance_squared)
            best = {crossing.on_b, crossing.on_a, crossing.distance_squared};
          break;
        case detail::Crossing::None: break;
      }
    }
  }

  // 3. Vertex-triangle and edge-edge candidates.
  for (int k = 0; k < 3; ++k) {
    const Vec3 on_b = detail::closest_point_triangle_unscaled(a[k], b[0], b[1], b[2]).point;
    const Real d2 = length_squared(a[k] - on_b);
    if (d2 < best.distance_squared) best = {a[k], on_b, d2};
  }
  for (int k = 0; k < 3; ++k) {
    const Vec3 on_a = detail::closest_point_triangle_unscaled(b[k], a[0], a[1], a[2]).point;
    const Real d2 = length_squared(b[k] - on_a);
    if (d2 < best.distance_squared) best = {on_a, b[k], d2};
  }
  for (int k = 0; k < 3; ++k) {
    for (int l = 0; l < 3; ++l) {
      const SegmentPair s = detail::closest_points_segment_segment_unscaled(a[k], a[(k + 1) % 3], b[l], b[(l + 1) % 3]);
      if (s.distance_squared < best.distance_squared) best = {s.on_a, s.on_b, s.distance_squared};
    }
  }
  return best;
}

Tri scaled(const Tri& t, int e) { return {detail::scaled(t[0], e), detail::scaled(t[1], e), detail::scaled(t[2], e)}; }

}  // namespace

bool triangles_intersect(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0, const Vec3& b1,
                         const Vec3& b2) {
  const Tri a{a0, a1, a2};
  const Tri b{b0, b1, b2};
  const Real m = max_abs(a, b);
  if (!std::isfinite(m)) return false;
  const int e = detail::rescale_exponent(m);
  if (e == 0) return triangles_intersect_unscaled(a, b, kRelativeTolerance * m);
  return triangles_intersect_unscaled(scaled(a, -e), scaled(b, -e), kRelativeTolerance * std::ldexp(m, -e));
}

ClosestPair closest_points_triangle_triangle(const Vec3& a0, const Vec3& a1, const Vec3& a2, const Vec3& b0,
                                             const Vec3& b1, const Vec3& b2) {
  const Tri a{a0, a1, a2};
  const Tri b{b0, b1, b2};
  const Real m = max_abs(a, b);
  if (!std::isfinite(m)) return {Vec3(detail::kNaN), Vec3(detail::kNaN), detail::kNaN};
  const int e = detail::rescale_exponent(m);
  if (e == 0) return triangle_triangle_unscaled(a, b);
  ClosestPair r = triangle_triangle_unscaled(scaled(a, -e), scaled(b, -e));
  r.on_a = detail::scaled(r.on_a, e);
  r.on_b = detail::scaled(r.on_b, e);
  r.distance_squared = std::ldexp(r.distance_squared, 2 * e);
  return r;
}

}  // namespace proxima::geometry
