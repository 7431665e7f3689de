// Closest point of a triangle to a point.
//
// Steps (Ericson, Real-Time Collision Detection, 5.1.5, Voronoi regions):
//  1. Huge or tiny coordinates are rescaled by a power of two.
//  2. Thin triangles (collinear vertices, coincident vertices, slivers whose height is a
//     few ulps of their longest edge; detail::is_thin_triangle) have no usable plane: the
//     answer is the nearest of the three edges (exact clamped projections).
//  3. Vertex regions: p is behind a vertex with respect to both of its edges.
//  4. Edge regions: p projects inside an edge and lies outside the triangle's side of it.
//     The outside test uses the signed area n.(edge x (p - vertex)), n = ab x ac, which is
//     Ericson's difference of dot-product products rewritten with the Binet-Cauchy identity
//     so that it does not cancel; the edge parameter is a ratio of two dot products with
//     the edge, clamped into [0, 1].
//  5. Face region: barycentric coordinates from the three signed areas, clamped to be
//     non-negative and normalised, so the point always lies in the triangle.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>

namespace proxima::geometry {

namespace {

// The nearest point of one edge and its squared distance to p (fallback of step 2).
struct EdgeCandidate {
  SegmentPoint point;
  Real distance_squared;
};

EdgeCandidate edge_candidate(const Vec3& p, const Vec3& from, const Vec3& to) {
  const SegmentPoint c = detail::closest_point_segment_unscaled(p, from, to);
  return {c, length_squared(p - c.point)};
}

TrianglePoint on_vertex(const Vec3& point, int vertex) {
  TrianglePoint r;
  r.point = point;
  r.barycentric = Vec3(Real(0));
  r.barycentric[vertex] = Real(1);
  r.feature = vertex == 0   ? TriangleFeature::VertexA
              : vertex == 1 ? TriangleFeature::VertexB
                            : TriangleFeature::VertexC;
  return r;
}

// The point from + t (to - from) of edge (from, to) = vertices (i, j), as a TrianglePoint.
TrianglePoint on_edge(const SegmentPoint& c, int i, int j, TriangleFeature edge) {
  if (c.t <= Real(0)) return on_vertex(c.point, i);
  if (c.t >= Real(1)) return on_vertex(c.point, j);
  TrianglePoint r;
  r.point = c.point;
  r.barycentric = Vec3(Real(0));
  r.barycentric[i] = Real(1) - c.t;
  r.barycentric[j] = c.t;
  r.feature = edge;
  return r;
}

// Step 2: nearest of the three edges.
TrianglePoint nearest_edge(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const EdgeCandidate ab = edge_candidate(p, a, b);
  const EdgeCandidate bc = edge_candidate(p, b, c);
  const EdgeCandidate ca = edge_candidate(p, c, a);
  if (ab.distance_squared <= bc.distance_squared && ab.distance_squared <= ca.distance_squared) {
    return on_edge(ab.point, 0, 1, TriangleFeature::EdgeAB);
  }
  if (bc.distance_squared <= ca.distance_squared) return on_edge(bc.point, 1, 2, TriangleFeature::EdgeBC);
  return on_edge(ca.point, 2, 0, TriangleFeature::EdgeCA);
}

// A point of edge (from, to) at parameter num / (num - num_end), where num = edge.(p - from)
// >= 0 and num_end = edge.(p - to) <= 0.
TrianglePoint edge_point(const Vec3& from, const Vec3& to, Real num, Real num_end, int i, int j, TriangleFeature edge) {
  const Real den = num - num_end;
  const Real t = den > Real(0) ? std::min(Real(1), num / den) : Real(0);
  return on_edge({from + t * (to - from), t}, i, j, edge);
}

}  // namespace

namespace detail {

TrianglePoint closest_point_triangle_unscaled(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a;
  const Vec3 ac = c - a;
  const Vec3 bc = c - b;
  const Vec3 n = glm::cross(ab, ac);
  if (is_thin_triangle(n, a, b, c)) return nearest_edge(p, a, b, c);

  // 3. Vertex regions.
  const Vec3 ap = p - a;
  const Real ab_ap = glm::dot(ab, ap);
  const Real ac_ap = glm::dot(ac, ap);
  if (ab_ap <= Real(0) && ac_ap <= Real(0)) return on_vertex(a, 0);
  const Vec3 bp = p - b;
  const Real ab_bp = glm::dot(ab, bp);
  const Real bc_bp = glm::dot(bc, bp);
  if (ab_bp >= Real(0) && bc_bp <= Real(0)) return on_vertex(b, 1);
  const Vec3 cp = p - c;
  const Real ac_cp = glm::dot(ac, cp);
  const Real bc_cp = glm::dot(bc, cp);
  if (ac_cp >= Real(0) && bc_cp >= Real(0)) return on_vertex(c, 2);

  // 4. Edge regions: the signed areas (times |n|) of the sub-triangles opposite each vertex.
  const Real area_c = glm::dot(n, glm::cross(ab, ap));  // p, a, b: weight of c
  if (area_c <= Real(0) && ab_ap >= Real(0) && ab_bp <= Real(0)) {
    return edge_point(a, b, ab_ap, ab_bp, 0, 1, TriangleFeature::EdgeAB);
  }
  const Real area_b = glm::dot(n, glm::cross(ap, ac));  // p, c, a: weight of b
  if (area_b <= Real(0) && ac_ap >= Real(0) && ac_cp <= Real(0)) {
    return edge_point(a, c, ac_ap, ac_cp, 0, 2, TriangleFeature::EdgeCA);
  }
  const Real area_a = glm::dot(n, glm::cross(bp, cp));  // p, b, c: weight of a
  if (area_a <= Real(0) && bc_bp >= Real(0) && bc_cp <= Real(0)) {
    return edge_point(b, c, bc_bp, bc_cp, 1, 2, TriangleFeature::EdgeBC);
  }

  // 5. Face region.
  const Real u = std::max(Real(0), area_a);
  const Real v = std::max(Real(0), area_b);
  const Real w = std::max(Real(0), area_c);
  const Real sum = u + v + w;
  if (!(sum > Real(0))) return nearest_edge(p, a, b, c);
  TrianglePoint r;
  r.barycentric = Vec3(u / sum, v / sum, w / sum);
  r.point = a + r.barycentric.y * ab + r.barycentric.z * ac;
  r.feature = TriangleFeature::Face;
  return r;
}

}  // namespace detail

TrianglePoint closest_point_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Real m = detail::magnitude({p, a, b, c});
  if (!std::isfinite(m)) return {Vec3(detail::kNaN), Vec3(detail::kNaN), TriangleFeature::Face};
  const int e = detail::rescale_exponent(m);
  if (e == 0) return detail::closest_point_triangle_unscaled(p, a, b, c);
  TrianglePoint r = detail::closest_point_triangle_unscaled(detail::scaled(p, -e), detail::scaled(a, -e),
                                                            detail::scaled(b, -e), detail::scaled(c, -e));
  // Vertices come back exactly; other points through the (exact) inverse scaling.
  switch (r.feature) {
    case TriangleFeature::VertexA: r.point = a; break;
    case TriangleFeature::VertexB: r.point = b; break;
    case TriangleFeature::VertexC: r.point = c; break;
    default: r.point = detail::scaled(r.point, e); break;
  }
  return r;
}

}  // namespace proxima::geometry
