// The dispatch table over every ShapeType (the convex shapes, the half-space, the mesh and the
// compound): every cell filled, mirrored cells flagged exactly where the routine is written
// for the other order, every query on (B, A) equal to the mirrored query on (A, B), and every
// cell answering intersect, distance, collide and collide_all, including a compound whose
// children are a convex shape, a mesh and a nested compound.
#include <gtest/gtest.h>

#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>

#include <cmath>
#include <limits>
#include <vector>

#include "narrowphase/dispatch.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_dispatch {

std::vector<Shape> one_of_each() {
  std::vector<Shape> s;
  s.emplace_back(Point::create().value());
  s.emplace_back(Segment::create(Vec3(-0.5, 0, 0), Vec3(0.5, 0.1, 0)).value());
  s.emplace_back(Triangle::create(Vec3(-0.5, -0.4, 0), Vec3(0.6, -0.3, 0.05), Vec3(0, 0.6, 0)).value());
  s.emplace_back(Sphere::create(Real(0.5)).value());
  s.emplace_back(Capsule::create(Real(0.3), Real(0.4)).value());
  s.emplace_back(Box::create(Vec3(0.4, 0.3, 0.5)).value());
  s.emplace_back(Cylinder::create(Real(0.4), Real(0.5)).value());
  s.emplace_back(Cone::create(Real(0.4), Real(0.5)).value());
  s.emplace_back(Ellipsoid::create(Vec3(0.5, 0.3, 0.4)).value());
  std::vector<Vec3> pts{{-0.5, -0.4, -0.3}, {0.5, -0.4, -0.2}, {0, 0.5, -0.3}, {0.1, 0, 0.6}, {0.3, 0.3, 0.3}};
  s.emplace_back(ConvexHull::create(pts).value());
  s.emplace_back(HalfSpace::create(Vec3(0, 0, 1), Real(0)).value());
  // A closed tetrahedron mesh.
  IndexedMesh tetra;
  tetra.vertices = {{-0.5, -0.4, -0.3}, {0.5, -0.4, -0.2}, {0, 0.5, -0.3}, {0.1, 0, 0.6}};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  const TriangleMesh mesh = TriangleMesh::create(tetra).value();
  s.emplace_back(mesh);
  // A compound of a box, the mesh and a nested compound holding a sphere.
  std::vector<CompoundChild> inner;
  inner.push_back({Sphere::create(Real(0.2)).value(), Transform{Vec3(0, 0, 0.3), Quat(1, 0, 0, 0)}});
  std::vector<CompoundChild> kids;
  kids.push_back({Box::create(Vec3(0.2, 0.3, 0.2)).value(), Transform{Vec3(-0.3, 0, 0), Quat(1, 0, 0, 0)}});
  kids.push_back({mesh, Transform{Vec3(0.3, 0, 0), Quat(1, 0, 0, 0)}});
  kids.push_back({Compound::create(std::move(inner)).value(), Transform{}});
  s.emplace_back(Compound::create(std::move(kids)).value());
  return s;
}

bool is_composite(int type) { return !is_convex(static_cast<ShapeType>(type)); }

// Where the cell runs the (B, A) routine: convex pairs when A comes after B; composite pairs
// when A is the lower kind (the compound's routine takes the compound as A, the mesh's
// routine the mesh as A).
bool expect_mirrored(int i, int j) { return is_composite(i) || is_composite(j) ? i < j : i > j; }

TEST(Dispatch, EveryCellFilledAndMirroredFlagged) {
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      const narrow::PairFunctions& f = narrow::pair_functions(static_cast<ShapeType>(i), static_cast<ShapeType>(j));
      EXPECT_NE(f.intersect, nullptr);
      EXPECT_NE(f.distance, nullptr);
      EXPECT_NE(f.collide, nullptr);
      EXPECT_NE(f.collide_all, nullptr);
      EXPECT_EQ(f.mirrored, expect_mirrored(i, j)) << i << " " << j;
      EXPECT_EQ(f.analytic, narrow::pair_functions(static_cast<ShapeType>(j), static_cast<ShapeType>(i)).analytic);
      if (is_composite(i) || is_composite(j)) {
        EXPECT_FALSE(f.analytic);
      }
    }
  }
}

TEST(Dispatch, MirroringHoldsForEveryPair) {
  const std::vector<Shape> shapes = one_of_each();
  ASSERT_EQ(static_cast<int>(shapes.size()), kShapeTypeCount);
  // Convex pairs draw from their own sequence (the poses they had before the composite
  // kinds joined the table); composite pairs from another.
  test::Random convex_rng(20261121);
  test::Random composite_rng(20261126);
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      test::Random& rng = is_composite(i) || is_composite(j) ? composite_rng : convex_rng;
      for (int trial = 0; trial < 12; ++trial) {
        const Transform pa = rng.pose(Real(0.8));
        const Transform pb = rng.pose(Real(0.8));
        const ShapeRef a(shapes[std::size_t(i)]);
        const ShapeRef b(shapes[std::size_t(j)]);
        const DistanceResult ab = distance(a, pa, b, pb);
        const DistanceResult ba = distance(b, pb, a, pa);
        ASSERT_TRUE(std::isfinite(ab.signed_distance)) << i << " " << j;
        // Same routine up to the swap when one of the two cells is the mirror of the other;
        // for A == B both are direct calls with swapped arguments, equal within tolerance.
        const Real tol = i == j ? Real(1e-3) : Real(0);
        EXPECT_NEAR(ab.signed_distance, ba.signed_distance, tol)
            << i << " " << j << " status " << int(ab.status) << "/" << int(ba.status) << " method " << int(ab.method)
            << "/" << int(ba.method);
        if (i != j) {
          EXPECT_EQ(ab.point_a, ba.point_b);
          EXPECT_EQ(ab.point_b, ba.point_a);
          EXPECT_EQ(ab.normal, -ba.normal);
          EXPECT_EQ(ab.status, ba.status);
          EXPECT_EQ(ab.method, ba.method);
        }
        EXPECT_EQ(intersect(a, pa, b, pb), intersect(b, pb, a, pa)) << i << " " << j;
        const ContactManifold mab = collide(a, pa, b, pb);
        const ContactManifold mba = collide(b, pb, a, pa);
        // A composite pair's manifold is reduced from A's witness points, so the mirrored
        // reduction may keep a different number of points; both find contact or neither.
        if (is_composite(i) || is_composite(j)) {
          EXPECT_EQ(mab.count > 0, mba.count > 0) << i << " " << j;
        } else {
          EXPECT_EQ(mab.count, mba.count);
        }
        if (i != j && !is_composite(i) && !is_composite(j)) {
          EXPECT_EQ(mab.normal, -mba.normal);
          for (int k = 0; k < mab.count && k < mba.count; ++k) {
            EXPECT_EQ(mab.points[std::size_t(k)].point_a, mba.points[std::size_t(k)].point_b);
            EXPECT_EQ(mab.points[std::size_t(k)].feature_id, mirror_feature_id(mba.points[std::size_t(k)].feature_id));
          }
        }
      }
    }
  }
}

TEST(Dispatch, NonFinitePoseGivesInvalidInputEverywhere) {
  const std::vector<Shape> shapes = one_of_each();
  Transform bad;
  {
    test::ScopedNoFpTraps no_traps;
    bad.position.x = std::numeric_limits<Real>::quiet_NaN();
  }
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      const ShapeRef a(shapes[std::size_t(i)]);
      const ShapeRef b(shapes[std::size_t(j)]);
      const DistanceResult d = distance(a, bad, b, Transform{});
      EXPECT_EQ(d.status, PairStatus::InvalidInput) << i << " " << j;
      EXPECT_FALSE(intersect(a, Transform{}, b, bad)) << i << " " << j;
      const ContactManifold m = collide(a, bad, b, Transform{});
      EXPECT_EQ(m.count, 0);
      EXPECT_EQ(m.status, PairStatus::InvalidInput);
    }
  }
}

TEST(Dispatch, SeparatedAndOverlappingSpheresThroughEveryEntryPoint) {
  const Sphere s = Sphere::create(Real(1)).value();
  const Box box = Box::create(Vec3(1)).value();
  Transform far;
  far.position = Vec3(5, 0, 0);
  EXPECT_FALSE(intersect(s, Transform{}, box, far));
  const DistanceResult d = distance(s, Transform{}, box, far);
  EXPECT_NEAR(d.signed_distance, 3, 1e-4);
  EXPECT_NEAR(d.normal.x, 1, 1e-4);
  Transform near;
  near.position = Vec3(1.5, 0, 0);
  EXPECT_TRUE(intersect(s, Transform{}, box, near));
  EXPECT_NEAR(distance(box, near, s, Transform{}).signed_distance, -0.5, 1e-4);
  EXPECT_EQ(collide(s, Transform{}, box, near).count >= 1, true);
}

}  // namespace test_dispatch
}  // namespace proxima

namespace proxima {
namespace test_dispatch {

// Every cell answers every query on a touching, an overlapping and a separated placement:
// intersect agrees with the distance's sign, collide_all's contacts are within the contact
// distance and name the parts of the mesh and compound sides, collide's manifold is empty
// exactly when collide_all found nothing, and every number is finite.
TEST(Dispatch, EveryCellAnswersEveryQuery) {
  const std::vector<Shape> shapes = one_of_each();
  for (int i = 0; i < kShapeTypeCount; ++i) {
    for (int j = 0; j < kShapeTypeCount; ++j) {
      const ShapeRef a(shapes[std::size_t(i)]);
      const ShapeRef b(shapes[std::size_t(j)]);
      for (const Real x : {Real(0.1), Real(0.6), Real(3)}) {
        const Transform pa{};
        const Transform pb{Vec3(x, Real(0.05), Real(0.02)), Quat(1, 0, 0, 0)};
        PairRequest request;
        request.contact_distance = Real(0.01);
        const DistanceResult d = distance(a, pa, b, pb, request);
        ASSERT_TRUE(std::isfinite(d.signed_distance)) << i << " " << j << " x=" << x;
        EXPECT_TRUE(std::isfinite(d.point_a.x) && std::isfinite(d.point_b.x) && std::isfinite(d.normal.x));
        const bool hit = intersect(a, pa, b, pb, request);
        // Meshes are surfaces: a shape inside a closed mesh touches nothing, while the
        // distance of two crossing surfaces is 0; so only a clear gap must agree.
        if (d.signed_distance > Real(0.05)) {
          EXPECT_FALSE(hit) << i << " " << j << " x=" << x;
        }
        if (d.signed_distance < Real(0) && !is_composite(i) && !is_composite(j)) {
          EXPECT_TRUE(hit);
        }
        ContactVector all;
        collide_all(a, pa, b, pb, request, all);
        for (const ContactPoint& c : all.contacts) {
          EXPECT_TRUE(std::isfinite(c.depth)) << i << " " << j;
          EXPECT_GE(c.depth, -request.contact_distance - Real(1e-3)) << i << " " << j;
          if (shape_type(shapes[std::size_t(i)]) == ShapeType::TriangleMesh) {
            EXPECT_NE(c.sub_a.triangle, kNoIndex);
          }
          if (shape_type(shapes[std::size_t(j)]) == ShapeType::TriangleMesh) {
            EXPECT_NE(c.sub_b.triangle, kNoIndex);
          }
          if (shape_type(shapes[std::size_t(i)]) == ShapeType::Compound) {
            EXPECT_LT(c.sub_a.child, 3u);
          }
          if (shape_type(shapes[std::size_t(j)]) == ShapeType::Compound) {
            EXPECT_LT(c.sub_b.child, 3u);
          }
        }
        EXPECT_EQ(hit, !all.contacts.empty()) << i << " " << j << " x=" << x;
        const ContactManifold m = collide(a, pa, b, pb, request);
        EXPECT_EQ(m.count > 0, !all.contacts.empty()) << i << " " << j << " x=" << x;
        FirstContact first;
        collide_all(a, pa, b, pb, request, first);
        EXPECT_EQ(first.first.has_value(), !all.contacts.empty());
        if (first.first) {
          EXPECT_EQ(first.first->point_a, all.contacts.front().point_a) << i << " " << j << " x=" << x;
        }
      }
    }
  }
}

// The owning Shape and the view: a Shape of every kind converts to a ShapeRef of its type,
// and a compound child's shape is the same owning type.
TEST(Dispatch, ShapeRefViewsEveryKind) {
  const std::vector<Shape> shapes = one_of_each();
  ASSERT_EQ(shapes.size(), std::size_t(kShapeTypeCount));
  for (int i = 0; i < kShapeTypeCount; ++i) {
    const ShapeRef r(shapes[std::size_t(i)]);
    EXPECT_EQ(r.type(), static_cast<ShapeType>(i));
    EXPECT_EQ(is_convex(r.type()), i < kConvexShapeTypeCount);
  }
  const Compound& c = std::get<Compound>(shapes.back());
  EXPECT_EQ(shape_type(c.children()[1].shape), ShapeType::TriangleMesh);
  EXPECT_EQ(ShapeRef(c.children()[2].shape).type(), ShapeType::Compound);
}

}  // namespace test_dispatch
}  // namespace proxima
