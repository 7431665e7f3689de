// Tessellations checked against the shapes' own definitions: round shapes' vertices lie on
// the analytic surface, the inscribed area and volume approach the closed forms (4 pi r^2,
// 4/3 pi r^3, ...) as the segment count grows, every triangle of a convex solid faces away
// from its inside, a box's vertices are support points, a hull's faces close its volume.
#include <gtest/gtest.h>

#include <proxima/debug/tessellate.hpp>
#include <proxima/shapes/shape.hpp>

#include <cmath>
#include <numbers>
#include <support/solid_test_meshes.hpp>

namespace proxima::test_tessellate {

using debug::DrawMesh;
using debug::tessellate;
using debug::TessellationOptions;

Vec3 corner(const DrawMesh& m, std::size_t t, int k) { return m.positions[m.indices[3 * t + std::size_t(k)]]; }

double area(const DrawMesh& m) {
  double sum = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    sum += 0.5 * double(glm::length(glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0))));
  }
  return sum;
}

/// Signed volume by the divergence theorem: positive for a closed, outward-facing mesh.
double volume(const DrawMesh& m) {
  double sum = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    sum += double(glm::dot(corner(m, t, 0), glm::cross(corner(m, t, 1), corner(m, t, 2)))) / 6.0;
  }
  return sum;
}

/// Every non-degenerate triangle's outward normal points away from `inside`.
void expect_outward(const DrawMesh& m, const Vec3& inside) {
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3 n = glm::cross(corner(m, t, 1) - corner(m, t, 0), corner(m, t, 2) - corner(m, t, 0));
    if (glm::length(n) < Real(1e-6)) continue;
    const Vec3 centroid = (corner(m, t, 0) + corner(m, t, 1) + corner(m, t, 2)) / Real(3);
    EXPECT_GT(glm::dot(n, centroid - inside), Real(0)) << "triangle " << t;
  }
}

void expect_valid_indices(const DrawMesh& m) {
  ASSERT_EQ(m.indices.size() % 3, 0u);
  for (std::uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
}

TEST(Tessellate, SphereVerticesOnSurfaceAreaAndVolumeConverge) {
  const Real r = Real(1.5);
  const Sphere sphere = Sphere::create(r).value();
  const DrawMesh coarse = tessellate(sphere, {.segments = 12});
  const DrawMesh fine = tessellate(sphere, {.segments = 96});
  expect_valid_indices(fine);
  for (const Vec3& p : fine.positions) EXPECT_NEAR(glm::length(p), r, 1e-5 * r);
  const double exact_area = 4 * std::numbers::pi * r * r;
  EXPECT_LT(area(coarse), area(fine));  // inscribed: grows towards the sphere's area
  EXPECT_LT(area(fine), exact_area);
  EXPECT_NEAR(area(fine), exact_area, 0.002 * exact_area);
  EXPECT_NEAR(volume(fine), 4.0 / 3.0 * std::numbers::pi * r * r * r, 0.003 * 4.0 / 3.0 * std::numbers::pi * r * r * r);
  expect_outward(fine, Vec3(0));
}

TEST(Tessellate, CapsuleVerticesAtRadiusFromCore) {
  const Capsule capsule = Capsule::create(Real(0.5), Real(2)).value();
  const DrawMesh m = tessellate(capsule, {.segments = 64});
  expect_valid_indices(m);
  for (const Vec3& p : m.positions) {
    const Vec3 core(0, 0, std::clamp(p.z, Real(-2), Real(2)));
    EXPECT_NEAR(glm::length(p - core), 0.5, 1e-5);
  }
  const double exact = std::numbers::pi * 0.25 * 4.0 + 4.0 / 3.0 * std::numbers::pi * 0.125;
  EXPECT_NEAR(volume(m), exact, 0.005 * exact);
  EXPECT_NEAR(area(m), 2 * std::numbers::pi * 0.5 * 4.0 + 4 * std::numbers::pi * 0.25,
              0.005 * (4 * std::numbers::pi + std::numbers::pi));
  expect_outward(m, Vec3(0));
}

TEST(Tessellate, CylinderAndConeVerticesOnRimsAndAxis) {
  const DrawMesh cylinder = tessellate(Cylinder::create(Real(1), Real(0.5)).value(), {.segments = 128});
  for (const Vec3& p : cylinder.positions) {
    EXPECT_NEAR(std::abs(p.z), 0.5, 1e-6);
    const Real rho = std::hypot(p.x, p.y);
    EXPECT_TRUE(rho < Real(1e-6) || std::abs(rho - 1) < Real(1e-5)) << rho;
  }
  EXPECT_NEAR(volume(cylinder), std::numbers::pi * 1.0, 0.002 * std::numbers::pi);
  expect_outward(cylinder, Vec3(0));
  const DrawMesh cone = tessellate(Cone::create(Real(1), Real(1)).value(), {.segments = 128});
  EXPECT_NEAR(volume(cone), std::numbers::pi * 2.0 / 3.0, 0.002 * std::numbers::pi);
  expect_outward(cone, Vec3(0, 0, -0.5));
}

TEST(Tessellate, EllipsoidVerticesOnItsSurface) {
  const Vec3 radii(1, 2, 0.5);
  const DrawMesh m = tessellate(Ellipsoid::create(radii).value(), {.segments = 96});
  for (const Vec3& p : m.positions) EXPECT_NEAR(glm::length(p / radii), 1.0, 1e-5);
  EXPECT_NEAR(volume(m), 4.0 / 3.0 * std::numbers::pi, 0.004 * 4.0 / 3.0 * std::numbers::pi);
  expect_outward(m, Vec3(0));
}

TEST(Tessellate, BoxVerticesAreSupportPoints) {
  const Box box = Box::create(Vec3(1, 2, 3)).value();
  const DrawMesh m = tessellate(box);
  EXPECT_EQ(m.positions.size(), 8u);
  EXPECT_EQ(m.triangle_count(), 12u);
  for (const Vec3& p : m.positions) {
    const Vec3 direction(p.x > 0 ? 1 : -1, p.y > 0 ? 1 : -1, p.z > 0 ? 1 : -1);
    EXPECT_EQ(box.support(direction), p);
  }
  EXPECT_NEAR(volume(m), 48.0, 1e-4);
  EXPECT_NEAR(area(m), 2 * (2 * 4 + 2 * 6 + 4 * 6), 1e-4);
  expect_outward(m, Vec3(0));
}

TEST(Tessellate, HullFacesCloseItsVolume) {
  const std::vector<Vec3> points = {Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(0, 2, 0),
                                    Vec3(0, 0, 2), Vec3(2, 2, 2), Vec3(1, 1, 0.5)};
  const ConvexHull hull = ConvexHull::create(points).value();
  const DrawMesh m = tessellate(hull);
  expect_valid_indices(m);
  EXPECT_EQ(m.positions.size(), hull.vertices().size());
  EXPECT_NEAR(volume(m), double(hull.mass_properties().volume), 1e-4);
  Vec3 centroid(0);
  for (const Vec3& p : m.positions) centroid += p / Real(m.positions.size());
  expect_outward(m, centroid);
}

TEST(Tessellate, SurfacesHaveBothSides) {
  const Triangle triangle = Triangle::create(Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0)).value();
  const DrawMesh t = tessellate(triangle);
  EXPECT_EQ(t.triangle_count(), 2u);
  EXPECT_NEAR(area(t), 2 * 0.5, 1e-6);
  EXPECT_NEAR(volume(t), 0.0, 1e-9);
  const HalfSpace ground = HalfSpace::create(Vec3(0, 0, 1), Real(-1)).value();
  const DrawMesh g = tessellate(ground, {.halfspace_extent = Real(10)});
  EXPECT_EQ(g.triangle_count(), 4u);
  for (const Vec3& p : g.positions) EXPECT_NEAR(p.z, -1, 1e-6);
  const Vec3 front = glm::cross(corner(g, 0, 1) - corner(g, 0, 0), corner(g, 0, 2) - corner(g, 0, 0));
  EXPECT_GT(front.z, 0);  // the first winding faces out of the solid (+normal)
  EXPECT_NEAR(area(g), 2 * 20.0 * 20.0, 1e-2);
}

TEST(Tessellate, PointAndSegmentMarkers) {
  const DrawMesh p = tessellate(Point::create().value(), {.marker_radius = Real(0.1)});
  for (const Vec3& v : p.positions) EXPECT_NEAR(glm::length(v), 0.1, 1e-6);
  EXPECT_GT(volume(p), 0);
  const Segment segment = Segment::create(Vec3(1, 1, 1), Vec3(3, 2, 1)).value();
  const DrawMesh s = tessellate(segment, {.marker_radius = Real(0.05)});
  expect_valid_indices(s);
  for (const Vec3& v : s.positions) {
    const Vec3 ab = segment.b() - segment.a();
    const Real t = std::clamp(glm::dot(v - segment.a(), ab) / glm::dot(ab, ab), Real(0), Real(1));
    const Real d = glm::length(v - (segment.a() + t * ab));
    EXPECT_TRUE(d < Real(1e-5) || std::abs(d - Real(0.05)) < Real(1e-5)) << d;
  }
  EXPECT_GT(volume(s), 0);
}

TEST(Tessellate, MeshAndCompoundKeepTheirTriangles) {
  const TriangleMesh mesh = TriangleMesh::create(test::box_mesh(Vec3(-1), Vec3(1))).value();
  const DrawMesh m = tessellate(mesh);
  EXPECT_EQ(m.triangle_count(), mesh.triangle_count());
  EXPECT_NEAR(volume(m), 8.0, 1e-4);
  const Box box = Box::create(Vec3(0.5)).value();
  const Transform shift{Vec3(3, 0, 0), kIdentityQuat};
  std::vector<CompoundChild> children = {{Shape(box), Transform{}}, {Shape(mesh), shift}};
  const Compound compound = Compound::create(std::move(children)).value();
  const DrawMesh c = tessellate(compound);
  EXPECT_EQ(c.triangle_count(), 12u + mesh.triangle_count());
  EXPECT_NEAR(volume(c), 1.0 + 8.0, 1e-4);
  for (std::size_t i = 8; i < c.positions.size(); ++i) EXPECT_GE(c.positions[i].x, Real(2) - Real(1e-6));
}

}  // namespace proxima::test_tessellate
