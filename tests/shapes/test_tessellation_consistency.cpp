// Tessellation consistency: a sphere, capsule, cylinder and box tessellated into closed
// meshes answer ray casts, distances and contact depths against convex shapes like the
// primitives, within the tessellation error.
//
// Reference: the tessellations have their vertices on the primitive's surface, so for the
// convex primitives mesh ⊂ primitive ("outer"); the same primitive shrunk to the mesh's
// inradius (computed from the face planes) lies inside the mesh ("inner"). Every answer
// on the mesh is then bracketed by the narrow phase's (or the shape's ray cast's) answers on
// the inner and outer primitives: ray t_outer <= t_mesh <= t_inner; distance
// d_outer <= d_mesh <= d_inner; for shallow penetrations the bounds stated at that test.
// The box tessellation is exact (inner = outer). Seeded random poses, thousands of cases per primitive.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "narrowphase/narrowphase_test_util.hpp"
#include "shapes/shape_visit.hpp"
#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_tessellation_consistency {

// Narrow-phase accuracy on curved shapes (EPA, GJK) bounds the agreement; float needs more.
const Real kTol = sizeof(Real) == 4 ? Real(2e-3) : Real(1e-6);

struct Case {
  const char* name;
  Shape outer;
  Shape inner;
  TriangleMesh mesh;
};

/// Inradius-shrunk primitive: the largest one of the same kind inside the mesh.
Case make_case(const char* name, const Shape& outer, IndexedMesh indexed) {
  auto mesh = TriangleMesh::create(std::move(indexed));
  EXPECT_TRUE(mesh.ok()) << name;
  const TriangleMesh& m = mesh.value();
  Real r_in = std::numeric_limits<Real>::infinity();
  for (std::uint32_t t = 0; t < m.triangle_count(); ++t) {
    const auto v = m.triangle(t);
    const Vec3 n = glm::normalize(glm::cross(v[1] - v[0], v[2] - v[0]));
    const Real d = glm::dot(n, v[0]);
    if (std::holds_alternative<Sphere>(outer)) r_in = std::min(r_in, d);
    if (const auto* c = std::get_if<Capsule>(&outer)) r_in = std::min(r_in, d - c->half_length() * std::abs(n.z));
    if (std::holds_alternative<Cylinder>(outer) && std::abs(n.z) < Real(0.5)) r_in = std::min(r_in, d);
  }
  Shape inner = outer;
  if (std::holds_alternative<Sphere>(outer)) inner = Sphere::create(r_in).value();
  if (const auto* c = std::get_if<Capsule>(&outer)) inner = Capsule::create(r_in, c->half_length()).value();
  if (const auto* c = std::get_if<Cylinder>(&outer)) inner = Cylinder::create(r_in, c->half_length()).value();
  return {name, outer, inner, m};
}

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back(make_case("sphere", Sphere::create(Real(1)).value(), test::tessellate_sphere(Real(1), 48, 24)));
  c.push_back(make_case("capsule", Capsule::create(Real(0.6), Real(0.7)).value(),
                        test::tessellate_capsule(Real(0.6), Real(0.7), 40, 20)));
  c.push_back(make_case("cylinder", Cylinder::create(Real(0.8), Real(0.6)).value(),
                        test::tessellate_cylinder(Real(0.8), Real(0.6), 48)));
  c.push_back(make_case("box", Box::create(Vec3(0.9, 0.6, 0.5)).value(), test::tessellate_box(Vec3(0.9, 0.6, 0.5), 3)));
  return c;
}

/// A small convex probe of random kind.
Shape random_probe(test::Random& rng) {
  switch (rng.integer(0, 3)) {
    case 0: return Sphere::create(rng.uniform(Real(0.1), Real(0.4))).value();
    case 1: return Box::create(rng.vec3(Real(0.1), Real(0.35))).value();
    case 2: {
      const Real h = rng.uniform(Real(0.05), Real(0.3));
      return Capsule::create(rng.uniform(Real(0.1), Real(0.25)), h).value();
    }
    default: {
      const Real h = rng.uniform(Real(0.1), Real(0.3));
      return Cylinder::create(rng.uniform(Real(0.1), Real(0.3)), h).value();
    }
  }
}

TEST(TessellationConsistency, RayHitsBracketedByInnerAndOuterPrimitives) {
  test::Random rng(501);
  for (const Case& c : cases()) {
    int hits = 0;
    for (int k = 0; k < 1500; ++k) {
      const Transform pose = rng.pose(Real(2));
      const Vec3 origin = pose.position + Real(4) * rng.unit_vector();
      const Vec3 target = pose.position + rng.in_ball(Real(1.2));
      const Ray ray{origin, target - origin};
      const Real max_t = Real(2);
      const auto mesh_hit = raycast(ShapeRef(c.mesh), pose, ray, max_t);
      const auto outer_hit = raycast(ShapeRef(c.outer), pose, ray, max_t);
      const auto inner_hit = raycast(ShapeRef(c.inner), pose, ray, max_t);
      const Real len = glm::length(ray.direction);
      const Real tol_t = kTol / len;
      if (mesh_hit) {
        ++hits;
        ASSERT_TRUE(outer_hit) << c.name << " case " << k;
        EXPECT_GE(mesh_hit->t, outer_hit->t - tol_t) << c.name << " case " << k;
        EXPECT_EQ(mesh_hit->sub.child, kNoIndex);
        EXPECT_LT(mesh_hit->sub.triangle, c.mesh.triangle_count());
      }
      if (inner_hit) {
        ASSERT_TRUE(mesh_hit) << c.name << " case " << k;
        EXPECT_LE(mesh_hit->t, inner_hit->t + tol_t) << c.name << " case " << k;
      }
    }
    EXPECT_GT(hits, 300) << c.name;
  }
}

TEST(TessellationConsistency, DistancesBracketedWhenSeparated) {
  test::Random rng(502);
  for (const Case& c : cases()) {
    int checked = 0;
    for (int k = 0; k < test::sweep_size(1500); ++k) {
      const Transform pose = rng.pose(Real(1));
      const Shape probe = random_probe(rng);
      const Vec3 towards = rng.unit_vector();
      const Real apart = rng.uniform(Real(1), Real(2.5));
      const Transform pp{pose.position + apart * towards, rng.rotation()};
      const DistanceResult outer = distance(ShapeRef(c.outer), pose, ShapeRef(probe), pp);
      if (outer.signed_distance <= Real(0.01)) continue;
      const DistanceResult inner = distance(ShapeRef(c.inner), pose, ShapeRef(probe), pp);
      const DistanceResult mesh = distance(ShapeRef(c.mesh), pose, ShapeRef(probe), pp);
      ++checked;
      EXPECT_GE(mesh.signed_distance, outer.signed_distance - kTol) << c.name << " case " << k;
      EXPECT_LE(mesh.signed_distance, inner.signed_distance + kTol) << c.name << " case " << k;
      ASSERT_LT(mesh.sub_a.triangle, c.mesh.triangle_count());
      // Witnesses realise the distance and lie on the named triangle.
      EXPECT_NEAR(glm::length(mesh.point_b - mesh.point_a), mesh.signed_distance, kTol);
      const auto v = c.mesh.triangle(mesh.sub_a.triangle);
      const auto tri = Triangle::create(v[0], v[1], v[2]).value();
      EXPECT_LE(tri.closest_point(pose.inverse_apply(mesh.point_a)).signed_distance, kTol) << c.name << " case " << k;
      // The same from the other side.
      const DistanceResult back = distance(ShapeRef(probe), pp, ShapeRef(c.mesh), pose);
      EXPECT_NEAR(back.signed_distance, mesh.signed_distance, kTol);
      EXPECT_EQ(back.sub_b.triangle, mesh.sub_a.triangle);
    }
    EXPECT_GT(checked, test::sweep_share(800)) << c.name;
  }
}

/// Height of the support point of `s` (at `pose`) along the world direction `n`.
Real support_height(const Shape& s, const Transform& pose, const Vec3& n) {
  return detail::visit_convex(
      s, [&](const auto& x) { return glm::dot(pose.apply(x.support(pose.inverse_apply_vector(n))), n); });
}

// Shallow penetrations. What holds for every contact of a mesh whose triangles lie inside the
// outer primitive O: moving the probe P by its depth along the contact normal n separates it
// from the contact's triangle, and that takes at most h_O(n) + h_P(-n) (the translation that
// clears O's support plane), so depth <= h_O(n) + h_P(-n) (support functions only). Contacts
// with the narrow phase's own normal are also bounded by O's penetration depth (a subset of O
// cannot need a longer minimum translation); the reduced manifold's depth is the deepest
// contact's. Distance is the deepest triangle pair's (geometry_queries.hpp), checked against
// the brute-force minimum over all triangles, and bounded by O's signed distance. Inner-primitive
// lower bounds are not laws for a surface mesh (near a convex edge each triangle can be escaped
// sideways by less than the solid's depth), so they are only counted and printed.
TEST(TessellationConsistency, ShallowContactDepthsBracketed) {
  test::Random rng(503);
  PairRequest request;
  for (const Case& c : cases()) {
    int checked = 0, below_inner = 0;
    for (int k = 0; k < test::sweep_size(600); ++k) {
      const Transform pose = rng.pose(Real(1));
      const Shape probe = random_probe(rng);
      // Probe placed on a random ray from the centre, just touching the outer primitive,
      // then pushed in by a depth well below the probe's size.
      const Vec3 dir = rng.unit_vector();
      Transform pp{pose.position + Real(3) * dir, rng.rotation()};
      const DistanceResult gap = distance(ShapeRef(c.outer), pose, ShapeRef(probe), pp);
      const Real depth = rng.uniform(Real(0.01), Real(0.05));
      pp.position -= (gap.signed_distance + depth) * gap.normal;
      const DistanceResult outer = distance(ShapeRef(c.outer), pose, ShapeRef(probe), pp);
      const DistanceResult inner = distance(ShapeRef(c.inner), pose, ShapeRef(probe), pp);
      if (inner.signed_distance > -Real(0.002)) continue;  // the tessellation error ate the overlap
      std::vector<ContactPoint> contacts;
      test::collect_contacts(ShapeRef(c.mesh), pose, ShapeRef(probe), pp, request, contacts);
      ASSERT_FALSE(contacts.empty()) << c.name << " case " << k;
      // Brute force over every triangle, narrow phase per triangle.
      const Aabb probe_box = std::visit([&](const auto& x) { return x.world_aabb(pp); }, probe);
      Real brute = std::numeric_limits<Real>::infinity();
      for (std::uint32_t t = 0; t < c.mesh.triangle_count(); ++t) {
        const auto v = c.mesh.triangle(t);
        const auto tri = Triangle::create(v[0], v[1], v[2]);
        if (!tri || !tri->world_aabb(pose).overlaps(probe_box)) continue;  // apart: not the minimum
        brute = std::min(brute, distance(ShapeRef(*tri), pose, ShapeRef(probe), pp).signed_distance);
      }
      Real deepest = -std::numeric_limits<Real>::infinity();
      for (const ContactPoint& gc : contacts) {
        deepest = std::max(deepest, gc.depth);
        const Vec3 n = gc.normal;
        EXPECT_NEAR(glm::length(n), Real(1), kTol);
        EXPECT_LT(gc.sub_a.triangle, c.mesh.triangle_count());
        EXPECT_LE(gc.depth, support_height(c.outer, pose, n) + support_height(probe, pp, -n) + kTol)
            << c.name << " case " << k;
        const auto v = c.mesh.triangle(gc.sub_a.triangle);
        const auto tri = Triangle::create(v[0], v[1], v[2]).value();
        const ContactManifold raw = collide(ShapeRef(tri), pose, ShapeRef(probe), pp, request);
        if (raw.count > 0 && glm::dot(raw.normal, n) > Real(1) - Real(1e-6)) {
          EXPECT_LE(gc.depth, -outer.signed_distance + kTol) << c.name << " case " << k;
        }
      }
      ++checked;
      below_inner += deepest < -inner.signed_distance - kTol;
      EXPECT_GE(deepest, -brute - kTol) << c.name << " case " << k;
      const DistanceResult d = distance(ShapeRef(c.mesh), pose, ShapeRef(probe), pp);
      EXPECT_NEAR(d.signed_distance, brute, kTol) << c.name << " case " << k;
      EXPECT_LE(d.signed_distance, kTol) << c.name << " case " << k;
      EXPECT_GE(d.signed_distance, outer.signed_distance - kTol) << c.name << " case " << k;
      EXPECT_TRUE(intersect(ShapeRef(c.mesh), pose, ShapeRef(probe), pp));
      const ContactManifold m = collide(ShapeRef(c.mesh), pose, ShapeRef(probe), pp);
      ASSERT_GT(m.count, 0);
      EXPECT_NEAR(m.points[0].depth, deepest, kTol);
    }
    EXPECT_GT(checked, test::sweep_share(300)) << c.name;
    std::printf("%s: %d of %d cases with the deepest contact below the inner primitive's depth\n", c.name, below_inner,
                checked);
    RecordProperty(std::string(c.name) + "_below_inner", below_inner);
  }
}

}  // namespace test_tessellation_consistency
}  // namespace proxima
