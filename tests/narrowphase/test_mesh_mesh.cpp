// Mesh against mesh (src/midphase/mesh_mesh.cpp) checked against brute force over every
// triangle pair in the world frame, and against analytic answers for boxes.
//
// Meshes: tessellated spheres (subdivided icosahedra), subdivided boxes and tori of 80 to
// 320 triangles, at seeded random poses placed so that about half of the cases overlap.
// Checked per case: the boolean equals "some pair intersects" (brute force with
// geometry::triangles_intersect on world-frame triangles); the distance equals the minimum of
// geometry::closest_points_triangle_triangle over all pairs, its witnesses lie on the
// triangles it names; collide_all reports exactly the intersecting triangle pairs.
// Disagreements are allowed only for pairs whose exact distance is within rounding of zero.
// The default (oriented-node) descent is checked against brute force; the axis-aligned
// reference path must give the same boolean, the same distance (within rounding) and the
// same contact pairs, here and on larger meshes over random poses (OrientedMatchesAabb).
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "narrowphase/mesh_mesh.hpp"
#include "narrowphase/narrowphase_test_util.hpp"
#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_mesh_mesh {

// ---- test meshes ------------------------------------------------------------------------

// Shared builders (solid_test_meshes.hpp): geodesic sphere, box with n x n quads per face,
// torus.
IndexedMesh icosphere(int levels, Real radius) { return test::icosphere_mesh(levels, radius); }
IndexedMesh box_mesh(const Vec3& h, int n) { return test::tessellate_box(h, n); }
IndexedMesh torus(Real major, Real minor, int segments, int sides) {
  return test::torus_mesh(major, minor, segments, sides);
}

TriangleMesh make(IndexedMesh m) {
  Result<TriangleMesh> r = TriangleMesh::create(std::move(m));
  EXPECT_TRUE(r.ok());
  return std::move(r).value();
}

// ---- brute force ------------------------------------------------------------------------

using Tri = std::array<Vec3, 3>;

std::vector<Tri> world_triangles(const TriangleMesh& mesh, const Transform& pose) {
  std::vector<Tri> out;
  for (std::uint32_t i = 0; i < mesh.triangle_count(); ++i) {
    const Tri t = mesh.triangle(i);
    out.push_back({pose.apply(t[0]), pose.apply(t[1]), pose.apply(t[2])});
  }
  return out;
}

struct Brute {
  std::set<std::pair<std::uint32_t, std::uint32_t>> intersecting;  ///< triangles_intersect
  std::vector<Real> distances;                                     ///< exact distance of pair (i, j) at i * count_b + j
  std::uint32_t count_b = 0;
  Real min_distance = std::numeric_limits<Real>::infinity();
  Real scale = Real(0);  ///< largest |world coordinate|
  Real distance(const std::pair<std::uint32_t, std::uint32_t>& p) const {
    return distances[p.first * count_b + p.second];
  }
  /// Distance below which a pair may be called touching or not (the triangle test's own
  /// tolerance in world coordinates, doubled).
  Real touch() const { return Real(2) * kRelativeTolerance * std::max(Real(1), scale); }
};

Brute brute_force(const std::vector<Tri>& ta, const std::vector<Tri>& tb) {
  Brute b;
  b.count_b = static_cast<std::uint32_t>(tb.size());
  b.distances.resize(ta.size() * tb.size());
  for (const Tri& t : ta) {
    for (const Vec3& v : t) b.scale = std::max(b.scale, geometry::detail::max_abs(v));
  }
  for (const Tri& t : tb) {
    for (const Vec3& v : t) b.scale = std::max(b.scale, geometry::detail::max_abs(v));
  }
  for (std::uint32_t i = 0; i < ta.size(); ++i) {
    for (std::uint32_t j = 0; j < tb.size(); ++j) {
      const Tri& x = ta[i];
      const Tri& y = tb[j];
      if (geometry::triangles_intersect(x[0], x[1], x[2], y[0], y[1], y[2])) b.intersecting.insert({i, j});
      const Real d =
          std::sqrt(geometry::closest_points_triangle_triangle(x[0], x[1], x[2], y[0], y[1], y[2]).distance_squared);
      b.distances[i * b.count_b + j] = d;
      b.min_distance = std::min(b.min_distance, d);
    }
  }
  return b;
}

Real point_triangle_distance(const Vec3& p, const Tri& t) {
  return glm::length(p - geometry::closest_point_triangle(p, t[0], t[1], t[2]).point);
}

/// Tolerance on distances (length units, scene of size ~3).
Real distance_tolerance() { return sizeof(Real) == 4 ? Real(5e-5) : Real(1e-11); }

struct Stats {
  int cases = 0;
  int hits = 0;
  int ambiguous_pairs = 0;
};

/// Triangle pairs of collide_all with node kind `nodes`.
std::set<std::pair<std::uint32_t, std::uint32_t>> contact_pairs(const TriangleMesh& a, const Transform& pose_a,
                                                                const TriangleMesh& b, const Transform& pose_b,
                                                                const PairRequest& request,
                                                                narrow::MeshMeshNodes nodes) {
  std::vector<ContactPoint> contacts;
  test::mesh_mesh_contacts(a, pose_a, b, pose_b, request, contacts, nodes);
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const ContactPoint& c : contacts) pairs.insert({c.sub_a.triangle, c.sub_b.triangle});
  return pairs;
}

/// The oriented-node descent against the axis-aligned one: same boolean, same contact
/// pairs, same distance within rounding. Returns the boolean.
bool expect_paths_agree(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b, const Transform& pose_b,
                        const PairRequest& request) {
  using narrow::MeshMeshNodes;
  const bool hit = narrow::mesh_mesh_intersect(a, pose_a, b, pose_b, request, MeshMeshNodes::Oriented);
  EXPECT_EQ(hit, narrow::mesh_mesh_intersect(a, pose_a, b, pose_b, request, MeshMeshNodes::Aabb));
  EXPECT_EQ(contact_pairs(a, pose_a, b, pose_b, request, MeshMeshNodes::Oriented),
            contact_pairs(a, pose_a, b, pose_b, request, MeshMeshNodes::Aabb));
  const DistanceResult d = narrow::mesh_mesh_distance(a, pose_a, b, pose_b, request, MeshMeshNodes::Oriented);
  const DistanceResult r = narrow::mesh_mesh_distance(a, pose_a, b, pose_b, request, MeshMeshNodes::Aabb);
  EXPECT_NEAR(d.signed_distance, r.signed_distance, distance_tolerance());
  return hit;
}

void check_case(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b, const Transform& pose_b,
                Stats& stats) {
  const std::vector<Tri> ta = world_triangles(a, pose_a);
  const std::vector<Tri> tb = world_triangles(b, pose_b);
  const Brute ref = brute_force(ta, tb);
  const PairRequest request;
  ++stats.cases;

  // Boolean.
  const bool hit = narrow::mesh_mesh_intersect(a, pose_a, b, pose_b, request);
  const bool ref_hit = !ref.intersecting.empty();
  if (hit != ref_hit) {
    EXPECT_LE(ref.min_distance, ref.touch()) << "boolean " << hit << " vs brute force " << ref_hit;
  }
  stats.hits += ref_hit ? 1 : 0;

  // Distance.
  const DistanceResult d = narrow::mesh_mesh_distance(a, pose_a, b, pose_b, request);
  ASSERT_TRUE(std::isfinite(d.signed_distance));
  EXPECT_NEAR(d.signed_distance, ref.min_distance, distance_tolerance());
  if (ref_hit) {
    EXPECT_LE(d.signed_distance, ref.touch());
  }
  ASSERT_LT(d.sub_a.triangle, a.triangle_count());
  ASSERT_LT(d.sub_b.triangle, b.triangle_count());
  EXPECT_LE(point_triangle_distance(d.point_a, ta[d.sub_a.triangle]), distance_tolerance());
  EXPECT_LE(point_triangle_distance(d.point_b, tb[d.sub_b.triangle]), distance_tolerance());
  EXPECT_NEAR(glm::length(d.point_b - d.point_a), d.signed_distance, distance_tolerance());
  EXPECT_NEAR(glm::length(d.normal), Real(1), Real(1e-4));
  EXPECT_NEAR(ref.distance({d.sub_a.triangle, d.sub_b.triangle}), d.signed_distance, distance_tolerance());
  if (d.signed_distance > Real(1e-3)) {
    // point_b = point_a + signed_distance * normal.
    const Vec3 expected = d.point_a + d.signed_distance * d.normal;
    EXPECT_LE(glm::length(expected - d.point_b), distance_tolerance());
  }

  // All contacts: the set of triangle pairs.
  std::vector<ContactPoint> contacts;
  test::mesh_mesh_contacts(a, pose_a, b, pose_b, request, contacts);
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  expect_paths_agree(a, pose_a, b, pose_b, request);
  for (const ContactPoint& c : contacts) {
    ASSERT_LT(c.sub_a.triangle, a.triangle_count());
    ASSERT_LT(c.sub_b.triangle, b.triangle_count());
    pairs.insert({c.sub_a.triangle, c.sub_b.triangle});
    EXPECT_TRUE(is_finite(c.point_a) && is_finite(c.point_b) && is_finite(c.normal));
    EXPECT_NEAR(glm::length(c.normal), Real(1), Real(1e-3));
    // The contact lies near both triangles it names.
    EXPECT_LE(point_triangle_distance(c.point_a, ta[c.sub_a.triangle]), Real(1e-3));
    EXPECT_LE(point_triangle_distance(c.point_b, tb[c.sub_b.triangle]), Real(1e-3));
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> only_mine;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> only_ref;
  std::set_difference(pairs.begin(), pairs.end(), ref.intersecting.begin(), ref.intersecting.end(),
                      std::back_inserter(only_mine));
  std::set_difference(ref.intersecting.begin(), ref.intersecting.end(), pairs.begin(), pairs.end(),
                      std::back_inserter(only_ref));
  for (const auto& p : only_mine) {
    ++stats.ambiguous_pairs;
    EXPECT_LE(ref.distance(p), ref.touch()) << "extra pair " << p.first << "," << p.second;
  }
  for (const auto& p : only_ref) {
    ++stats.ambiguous_pairs;
    EXPECT_LE(ref.distance(p), ref.touch()) << "missed pair " << p.first << "," << p.second;
  }
}

// ---- tests ------------------------------------------------------------------------------

struct Scene {
  TriangleMesh a;
  TriangleMesh b;
  Real reach;  ///< B's centre is placed within this distance of A's
};

void sweep(const Scene& s, std::uint64_t seed, int full_cases) {
  const int cases = test::sweep_size(full_cases);
  test::Random rng(seed);
  Stats stats;
  for (int k = 0; k < cases; ++k) {
    const Transform pose_a = rng.pose(Real(2));
    const Transform pose_b{pose_a.position + rng.in_ball(s.reach), rng.rotation()};
    SCOPED_TRACE(k);
    check_case(s.a, pose_a, s.b, pose_b, stats);
    if (::testing::Test::HasFatalFailure()) return;
  }
  // The sweep covers both outcomes.
  EXPECT_GT(stats.hits, cases / 10);
  EXPECT_LT(stats.hits, cases - cases / 10);
  EXPECT_LE(stats.ambiguous_pairs, cases / 20 + 2);
}

TEST(MeshMesh, SphereTorusBruteForce) {
  sweep({make(icosphere(1, Real(0.6))), make(torus(Real(0.8), Real(0.25), 12, 6)), Real(1.6)}, 11, 80);
}

TEST(MeshMesh, BoxSphereBruteForce) {
  sweep({make(box_mesh(Vec3(0.5, 0.3, 0.7), 2)), make(icosphere(2, Real(0.5))), Real(1.2)}, 12, 40);
}

TEST(MeshMesh, TorusTorusBruteForce) {
  sweep({make(torus(Real(0.7), Real(0.2), 16, 8)), make(torus(Real(0.6), Real(0.25), 12, 8)), Real(1.5)}, 13, 20);
}

TEST(MeshMesh, BoxBoxBruteForce) {
  sweep({make(box_mesh(Vec3(0.4, 0.4, 0.4), 3)), make(box_mesh(Vec3(0.6, 0.2, 0.3), 2)), Real(1.4)}, 14, 100);
}

// Axis-aligned boxes (common rotation) apart by a gap g along x: distance g exactly, witnesses
// on the facing faces, no contact; touching (g = 0): boolean true, distance 0.
TEST(MeshMesh, OrientedMatchesAabb) {
  // Larger meshes than the brute-force sweeps (1,280 and 1,536 triangles), 200 poses with
  // B's centre within reach of A's, half of them with a contact distance.
  const TriangleMesh a = make(icosphere(3, Real(0.6)));
  const TriangleMesh b = make(torus(Real(0.8), Real(0.2), 48, 16));
  test::Random rng(21);
  int hits = 0;
  const int cases = test::sweep_size(200);
  for (int k = 0; k < cases; ++k) {
    SCOPED_TRACE(k);
    const Transform pose_a = rng.pose(Real(2));
    const Transform pose_b{pose_a.position + rng.in_ball(Real(1.5)), rng.rotation()};
    PairRequest request;
    if (k % 2 == 1) request.contact_distance = Real(0.02);
    hits += expect_paths_agree(a, pose_a, b, pose_b, request) ? 1 : 0;
  }
  EXPECT_GT(hits, cases / 10);
  EXPECT_LT(hits, cases - cases / 10);
}

TEST(MeshMesh, BoxGapAnalytic) {
  const TriangleMesh a = make(box_mesh(Vec3(0.5, 0.5, 0.5), 3));
  const TriangleMesh b = make(box_mesh(Vec3(0.3, 0.2, 0.4), 2));
  test::Random rng(15);
  for (int k = 0; k < test::sweep_size(200); ++k) {
    const Quat q = rng.rotation();
    const Vec3 origin = rng.vec3(Real(-3), Real(3));
    const Real gap = k < 20 ? Real(0) : rng.uniform(Real(1e-3), Real(1));
    const Real offset_z = rng.uniform(Real(-0.5), Real(0.5));
    const Real offset_y = rng.uniform(Real(-0.5), Real(0.5));
    const Vec3 offset(Real(0.8) + gap, offset_y, offset_z);
    const Transform pa{origin, q};
    const Transform pb{origin + q * offset, q};
    const DistanceResult d = narrow::mesh_mesh_distance(a, pa, b, pb, {});
    EXPECT_NEAR(d.signed_distance, gap, Real(20) * distance_tolerance()) << k;
    const Vec3 n_local = glm::conjugate(q) * d.normal;
    if (gap > Real(1e-2)) {
      EXPECT_NEAR(n_local.x, Real(1), Real(1e-3)) << k;
    }
    EXPECT_EQ(narrow::mesh_mesh_intersect(a, pa, b, pb, {}), gap == Real(0)) << k;
    std::vector<ContactPoint> contacts;
    test::mesh_mesh_contacts(a, pa, b, pb, {}, contacts);
    EXPECT_EQ(contacts.empty(), gap != Real(0)) << k;
    // Within a contact distance above the gap: boolean true, contacts with depth -gap.
    PairRequest speculative;
    speculative.contact_distance = gap + Real(1e-2);
    EXPECT_TRUE(narrow::mesh_mesh_intersect(a, pa, b, pb, speculative)) << k;
    contacts.clear();
    test::mesh_mesh_contacts(a, pa, b, pb, speculative, contacts);
    ASSERT_FALSE(contacts.empty()) << k;
    Real deepest = -std::numeric_limits<Real>::infinity();
    for (const ContactPoint& c : contacts) deepest = std::max(deepest, c.depth);
    EXPECT_NEAR(deepest, -gap, Real(20) * distance_tolerance()) << k;
  }
}

// The contact distance: boolean true exactly when the brute-force distance is within it.
TEST(MeshMesh, ContactDistanceBruteForce) {
  const TriangleMesh a = make(icosphere(1, Real(0.5)));
  const TriangleMesh b = make(torus(Real(0.6), Real(0.2), 12, 6));
  test::Random rng(16);
  int within = 0;
  for (int k = 0; k < test::sweep_size(60); ++k) {
    const Transform pa = rng.pose(Real(2));
    const Transform pb{pa.position + rng.in_ball(Real(2)), rng.rotation()};
    const Brute ref = brute_force(world_triangles(a, pa), world_triangles(b, pb));
    PairRequest request;
    request.contact_distance = Real(0.1);
    if (std::abs(ref.min_distance - request.contact_distance) < Real(1e-4)) continue;
    const bool expected = ref.min_distance <= request.contact_distance;
    within += expected ? 1 : 0;
    EXPECT_EQ(narrow::mesh_mesh_intersect(a, pa, b, pb, request), expected) << k;
    std::vector<ContactPoint> contacts;
    test::mesh_mesh_contacts(a, pa, b, pb, request, contacts);
    std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
    for (const ContactPoint& c : contacts) pairs.insert({c.sub_a.triangle, c.sub_b.triangle});
    std::size_t expected_pairs = 0;
    for (std::uint32_t i = 0; i < a.triangle_count(); ++i) {
      for (std::uint32_t j = 0; j < b.triangle_count(); ++j) {
        const std::pair<std::uint32_t, std::uint32_t> p{i, j};
        const Real dist = ref.distance(p);
        if (std::abs(dist - request.contact_distance) < Real(1e-4)) continue;
        if (dist <= request.contact_distance) {
          ++expected_pairs;
          EXPECT_TRUE(pairs.count(p)) << k << " missed " << p.first << "," << p.second;
        } else {
          EXPECT_FALSE(pairs.count(p)) << k << " extra " << p.first << "," << p.second;
        }
      }
    }
    EXPECT_GE(pairs.size(), expected_pairs);
  }
  EXPECT_GT(within, test::sweep_share(6));
}

// The same mesh at the same pose: every triangle touches its neighbours and itself.
TEST(MeshMesh, IdenticalPlacement) {
  const TriangleMesh a = make(box_mesh(Vec3(0.5, 0.5, 0.5), 2));
  const Transform pose{Vec3(1, 2, 3), glm::normalize(Quat(Real(0.9), Real(0.1), Real(0.3), Real(-0.2)))};
  EXPECT_TRUE(narrow::mesh_mesh_intersect(a, pose, a, pose, {}));
  const DistanceResult d = narrow::mesh_mesh_distance(a, pose, a, pose, {});
  EXPECT_EQ(d.signed_distance, Real(0));
  std::vector<ContactPoint> contacts;
  test::mesh_mesh_contacts(a, pose, a, pose, {}, contacts);
  std::set<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (const ContactPoint& c : contacts) pairs.insert({c.sub_a.triangle, c.sub_b.triangle});
  for (std::uint32_t i = 0; i < a.triangle_count(); ++i) EXPECT_TRUE(pairs.count({i, i})) << i;
}

// Far apart: spheres of radius r1, r2 whose centres are D apart; the tessellated spheres are
// inscribed, so the distance lies in [D - r1 - r2, D - r1 cos - r2 cos] for the level's
// largest face-centre depth.
TEST(MeshMesh, FarSpheresBracket) {
  const TriangleMesh a = make(icosphere(2, Real(1)));
  const TriangleMesh b = make(icosphere(2, Real(0.5)));
  test::Random rng(17);
  for (int k = 0; k < 100; ++k) {
    const Transform pa{rng.vec3(Real(-10), Real(10)), rng.rotation()};
    const Real dist = rng.uniform(Real(2), Real(20));
    const Transform pb{pa.position + rng.unit_vector() * dist, rng.rotation()};
    const DistanceResult d = narrow::mesh_mesh_distance(a, pa, b, pb, {});
    EXPECT_LE(d.signed_distance, dist - Real(1.5) * Real(0.95) + Real(1e-4)) << k;
    EXPECT_GE(d.signed_distance, dist - Real(1.5) - Real(1e-4)) << k;
    EXPECT_FALSE(narrow::mesh_mesh_intersect(a, pa, b, pb, {}));
  }
}

}  // namespace test_mesh_mesh
}  // namespace proxima
