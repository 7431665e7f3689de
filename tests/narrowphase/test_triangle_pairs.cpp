// Triangle-box and triangle-triangle pairs: depth against a brute-force minimum of the
// support overlap over a dense set of directions refined by pattern search (long double)
// and a long double SAT over every face normal, in-plane edge normal and edge-pair cross
// product; gap against an exhaustive vertex-face / edge-edge search; witnesses on both
// surfaces with point_b = point_a + signed_distance * normal (edge-edge and in-plane axes
// included); manifold invariants; flat contacts with analytic areas.
#include <gtest/gtest.h>

#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "narrowphase/pairs_polyhedral.hpp"
#include "polytope_reference.hpp"
#include "support/random.hpp"

namespace proxima::test {
namespace test_triangle_pairs {

constexpr bool kFloat = sizeof(Real) == 4;

Triangle random_triangle(Random& rng, Real size) {
  for (;;) {
    const Vec3 c = rng.vec3(-size, size);
    const Vec3 b = rng.vec3(-size, size);
    auto t = Triangle::create(rng.vec3(-size, size), b, c);
    if (t && t.value().area() > Real(0.05) * size * size) return t.value();
  }
}

std::array<Vec3, 3> tri_world(const Triangle& t, const Transform& p) {
  return {p.apply(t.a()), p.apply(t.b()), p.apply(t.c())};
}

// Smallest overlap of the projections over a Fibonacci sphere of directions (long double):
// a brute-force upper bound of the penetration depth (every direction's overlap bounds it).
LD dense_depth_bound(const LPolytope& a, const LPolytope& b) {
  constexpr int kDirections = 2000;
  const LD golden = 3.14159265358979323846L * (3 - std::sqrt(5.0L));
  LD best = std::numeric_limits<LD>::infinity();
  for (int i = 0; i < kDirections; ++i) {
    const LD z = 1 - (2 * (i + 0.5L)) / kDirections;
    const LD r = std::sqrt(1 - z * z);
    best = std::min(best, overlap_on(a, b, PolyVec{r * std::cos(golden * i), r * std::sin(golden * i), z}));
  }
  return best;
}

// Exact penetration depth by exhaustive search over the Minkowski difference's vertices
// (long double): every plane through three of them with all the others on one side is a
// face plane; the depth is the smallest distance from the origin to a face plane (0 for a
// flat difference through the origin). Independent of the SAT's choice of axes.
LD hull_depth(const LPolytope& a, const LPolytope& b) {
  std::vector<PolyVec> m;
  LD scale = 0;
  for (const PolyVec& va : a.vertices) {
    for (const PolyVec& vb : b.vertices) {
      m.push_back(va - vb);
      scale = std::max(scale, norm(m.back()));
    }
  }
  const LD eps = 1e-12L * scale;
  LD best = std::numeric_limits<LD>::infinity();
  const std::size_t n = m.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      for (std::size_t k = j + 1; k < n; ++k) {
        PolyVec nn = cross(m[j] - m[i], m[k] - m[i]);
        const LD len = norm(nn);
        if (!(len > 1e-9L * scale * scale)) continue;
        nn = {nn.x / len, nn.y / len, nn.z / len};
        const LD off = dot(nn, m[i]);
        bool below = true;
        bool above = true;
        for (const PolyVec& v : m) {
          const LD d = dot(nn, v) - off;
          below = below && d <= eps;
          above = above && d >= -eps;
        }
        if (below) best = std::min(best, off);  // origin inside: off >= 0 is its distance
        if (above) best = std::min(best, -off);
      }
    }
  }
  return std::max(best, LD(0));
}

Real brute_tri_tri(const std::array<Vec3, 3>& a, const std::array<Vec3, 3>& b) {
  Real best = std::numeric_limits<Real>::infinity();
  for (int i = 0; i < 3; ++i) {
    best = std::min(best, glm::length(a[i] - geometry::closest_point_triangle(a[i], b[0], b[1], b[2]).point));
    best = std::min(best, glm::length(b[i] - geometry::closest_point_triangle(b[i], a[0], a[1], a[2]).point));
    for (int j = 0; j < 3; ++j) {
      const auto sp = geometry::closest_points_segment_segment(a[i], a[(i + 1) % 3], b[j], b[(j + 1) % 3]);
      best = std::min(best, std::sqrt(sp.distance_squared));
    }
  }
  return best;
}

Real brute_tri_box(const std::array<Vec3, 3>& t, const Box& box, const Transform& pb) {
  Real best = std::numeric_limits<Real>::infinity();
  const auto c = box_corners(box, pb);
  for (const Vec3& v : c)
    best = std::min(best, glm::length(v - geometry::closest_point_triangle(v, t[0], t[1], t[2]).point));
  for (const Vec3& v : t) {
    best = std::min(
        best, glm::length(v - geometry::closest_point_obb(v, pb.position, pb.rotation_matrix(), box.half_extents())));
  }
  for (const auto& e : box_edges()) {
    for (int j = 0; j < 3; ++j) {
      const auto sp = geometry::closest_points_segment_segment(c[e[0]], c[e[1]], t[j], t[(j + 1) % 3]);
      best = std::min(best, std::sqrt(sp.distance_squared));
    }
  }
  return best;
}

template <class B>
void check_manifold(const Triangle& a, const Transform& pa, const B& b, const Transform& pb, const DistanceResult& d,
                    Real tol) {
  PairRequest req;
  req.contact_distance = Real(0.05);
  const ContactManifold m = narrow::pair_collide(a, pa, b, pb, req, nullptr);
  if (d.signed_distance > req.contact_distance + tol) {
    EXPECT_EQ(m.count, 0);
    return;
  }
  if (d.signed_distance < req.contact_distance - tol) {
    ASSERT_GE(m.count, 1);
  }
  for (int i = 0; i < m.count; ++i) {
    const ContactPoint& c = m.points[i];
    EXPECT_LE(std::abs(a.closest_point(pa.inverse_apply(c.point_a)).signed_distance), tol) << i;
    EXPECT_LE(std::abs(b.closest_point(pb.inverse_apply(c.point_b)).signed_distance), tol) << i;
    EXPECT_LE(c.depth, -d.signed_distance + tol);
    EXPECT_LE(max_abs_component(c.point_a - c.depth * c.normal - c.point_b), tol);
  }
}

TEST(TrianglePairs, TriangleBoxSweep) {
  Random rng(404);
  const Real tol = kFloat ? Real(5e-4) : Real(1e-9);
  int dense_checked = 0;
  for (int n = 0; n < 2000; ++n) {
    const Triangle a = random_triangle(rng, Real(1.5));
    const Box b = Box::create(rng.vec3(Real(0.1), Real(1.2))).value();
    const Transform pa = rng.pose(Real(1));
    const Transform pb = rng.pose(Real(1));
    SCOPED_TRACE(n);
    const DistanceResult d = narrow::pair_distance(a, pa, b, pb, {}, nullptr);
    const LPolytope LA = triangle_polytope(a, pa);
    const LPolytope LB = box_polytope(b, pb);
    const LD ov = sat_overlap(LA, LB);
    if (ov >= 0) {
      EXPECT_NEAR(d.signed_distance, -static_cast<Real>(ov), tol);
      if (n % 4 == 0) {
        ++dense_checked;
        // Every direction's overlap bounds the depth from above (tight); the refined search
        // reaches it up to its own convergence (looser in double).
        EXPECT_GE(d.signed_distance, -static_cast<Real>(dense_depth_bound(LA, LB)) - tol) << "dense depth bound";
        EXPECT_NEAR(d.signed_distance, -static_cast<Real>(hull_depth(LA, LB)), tol) << "exhaustive depth";
      }
    } else {
      EXPECT_NEAR(d.signed_distance, brute_tri_box(tri_world(a, pa), b, pb), tol);
    }
    EXPECT_LE(max_abs_component(d.point_a + d.signed_distance * d.normal - d.point_b), tol);
    EXPECT_LE(std::abs(a.closest_point(pa.inverse_apply(d.point_a)).signed_distance), tol);
    EXPECT_LE(std::abs(b.closest_point(pb.inverse_apply(d.point_b)).signed_distance), tol);
    check_manifold(a, pa, b, pb, d, tol);
  }
  EXPECT_GT(dense_checked, 50);
}

// The exact directional signed distance of a box from a triangle (the ghost-contact
// correction of a mesh against a box) against the pair's exact distance: at the answer's
// translation the two touch; a little farther along they are apart (and, for a separated
// pair, halfway there too); with no answer, every sampled translation leaves them apart.
TEST(TrianglePairs, TriangleBoxDirectionalSignedDistance) {
  Random rng(406);
  const Real tol = kFloat ? Real(2e-4) : Real(1e-9);
  int overlapping = 0, separated = 0, never = 0;
  for (int k = 0; k < 2000; ++k) {
    const Triangle a = random_triangle(rng, Real(1.5));
    const Box b = Box::create(rng.vec3(Real(0.1), Real(1.2))).value();
    const Transform pa = rng.pose(Real(1));
    const Transform pb = rng.pose(Real(1));
    const Vec3 n = glm::normalize(rng.vec3(Real(-1), Real(1)));
    SCOPED_TRACE(k);
    const auto moved = [&](Real t) { return Transform{pb.position + t * n, pb.rotation}; };
    const auto sd_at = [&](Real t) { return narrow::pair_distance(a, pa, b, moved(t), {}, nullptr).signed_distance; };
    const Real r = narrow::triangle_box_directional_signed_distance(a, pa, b, pb, n);
    if (!std::isfinite(r)) {
      ++never;
      for (int i = 0; i <= 40; ++i) EXPECT_GT(sd_at(-Real(i) * Real(0.25)), Real(0)) << "t = " << -i * 0.25;
      continue;
    }
    (r <= Real(0) ? overlapping : separated)++;
    EXPECT_NEAR(sd_at(-r), Real(0), tol) << "touching at the answer";
    EXPECT_GT(sd_at(-r + Real(0.01)), Real(0)) << "apart beyond it";
    if (r > Real(0)) {
      EXPECT_GT(sd_at(Real(-0.5) * r), Real(0)) << "apart on the way";
    }
    if (r < Real(-0.02)) {
      EXPECT_LT(sd_at(-r - Real(0.01)), Real(0)) << "overlapping before it";
    }
  }
  EXPECT_GT(overlapping, 100);
  EXPECT_GT(separated, 100);
  EXPECT_GT(never, 100);
}

TEST(TrianglePairs, TriangleTriangleSweep) {
  Random rng(405);
  const Real tol = kFloat ? Real(5e-4) : Real(1e-9);
  int dense_checked = 0;
  for (int n = 0; n < 2000; ++n) {
    const Triangle a = random_triangle(rng, Real(1.5));
    const Triangle b = random_triangle(rng, Real(1.5));
    const Transform pa = rng.pose(Real(1));
    const Transform pb = rng.pose(Real(1));
    SCOPED_TRACE(n);
    const DistanceResult d = narrow::pair_distance(a, pa, b, pb, {}, nullptr);
    const LPolytope LA = triangle_polytope(a, pa);
    const LPolytope LB = triangle_polytope(b, pb);
    const LD ov = sat_overlap(LA, LB);
    if (ov >= 0) {
      EXPECT_NEAR(d.signed_distance, -static_cast<Real>(ov), tol);
      if (n % 4 == 0) {
        ++dense_checked;
        // Every direction's overlap bounds the depth from above (tight); the refined search
        // reaches it up to its own convergence (looser in double).
        EXPECT_GE(d.signed_distance, -static_cast<Real>(dense_depth_bound(LA, LB)) - tol) << "dense depth bound";
        EXPECT_NEAR(d.signed_distance, -static_cast<Real>(hull_depth(LA, LB)), tol) << "exhaustive depth";
      }
    } else {
      EXPECT_NEAR(d.signed_distance, brute_tri_tri(tri_world(a, pa), tri_world(b, pb)), tol);
    }
    EXPECT_LE(max_abs_component(d.point_a + d.signed_distance * d.normal - d.point_b), tol);
    EXPECT_LE(std::abs(a.closest_point(pa.inverse_apply(d.point_a)).signed_distance), tol);
    EXPECT_LE(std::abs(b.closest_point(pb.inverse_apply(d.point_b)).signed_distance), tol);
    check_manifold(a, pa, b, pb, d, tol);
  }
  EXPECT_GT(dense_checked, 50);
}

TEST(TrianglePairs, FlatContacts) {
  // A triangle lying on a box's top face: three points, the triangle's area.
  const Box box = Box::create(Vec3(2, 2, 1)).value();
  const Triangle tri = Triangle::create(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)).value();
  Transform pt;
  pt.position = Vec3(Real(-0.3), Real(0.2), Real(0.99));
  const ContactManifold m = narrow::pair_collide(tri, pt, box, {}, {}, nullptr);
  ASSERT_EQ(m.count, 3);
  EXPECT_NEAR(manifold_area(m), Real(0.5), Real(1e-5));
  EXPECT_NEAR(m.normal.z, -1, Real(1e-5));
  // Two parallel triangles 0.01 apart with a contact distance of 0.05.
  Transform p2;
  p2.position = Vec3(Real(0.2), Real(0.1), Real(0.01));
  PairRequest req;
  req.contact_distance = Real(0.05);
  const ContactManifold t = narrow::pair_collide(tri, {}, tri, p2, req, nullptr);
  ASSERT_GE(t.count, 3);
  for (int i = 0; i < t.count; ++i) EXPECT_NEAR(t.points[i].depth, Real(-0.01), Real(1e-5));
}

}  // namespace test_triangle_pairs
}  // namespace proxima::test
