// Tests of the half-space pair routines: seeded sweeps of every shape against random
// half-spaces checked against a long double reference (minus the support function of the
// shape, written from its definition, in the direction -n, minus the plane offset), the sign
// convention, witnesses on the surfaces, the flip of intersect across the plane, manifold
// counts against a brute-force count of the candidate features below the plane, the generic
// routine's default steps against the closed forms that replace them, named resting cases
// (box, cylinder, cone, capsule, hull) and half-space against half-space.
#include <gtest/gtest.h>

#include <proxima/narrowphase/contact.hpp>

#include <string>
#include <type_traits>
#include <vector>

#include "narrowphase/generic_halfspace.hpp"
#include "narrowphase/pair_reference.hpp"
#include "narrowphase/pairs_halfspace.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_pairs_halfspace {

using narrow::pair_collide;
using narrow::pair_distance;
using narrow::pair_intersect;
using test::LD;
using test::LVec;

Transform at(const Vec3& p, const Quat& q = kIdentityQuat) { return Transform{p, q}; }
Quat about(const Vec3& axis, Real angle) { return glm::angleAxis(angle, glm::normalize(axis)); }
HalfSpace floor_at(Real height) { return *HalfSpace::create(Vec3(0, 0, 1), height); }
constexpr Real kHalfPi = Real(1.5707963267948966);

Real tol_for(const Transform& pa, const Transform& pb, Real size) {
  return Real(256) * kEpsilon *
         std::max(Real(1), std::max(max_abs_component(pa.position), max_abs_component(pb.position)) + size);
}

// Exact signed distance of shape A to the half-space, in long double.
template <class A>
LD reference_distance(const A& a, const Transform& pa, const HalfSpace& b, const Transform& pb) {
  const test::LPose lb(pb);
  const LVec n = lb.rot.apply(test::ld(b.normal()));
  const LD offset = LD(b.offset()) + glm::dot(n, lb.p);
  return -test::support_world(a, pa, -n) - offset;
}

// Every invariant of one (A, HalfSpace) query; returns the manifold for count checks.
template <class A>
ContactManifold check_halfspace(const A& a, const Transform& pa, const HalfSpace& b, const Transform& pb, Real tol,
                                const PairRequest& request, const std::string& ctx) {
  const DistanceResult d = pair_distance(a, pa, b, pb, request, nullptr);
  EXPECT_TRUE(std::isfinite(d.signed_distance)) << ctx;
  EXPECT_NEAR(double(d.signed_distance), double(reference_distance(a, pa, b, pb)), double(tol)) << ctx;
  EXPECT_NEAR(glm::length(d.normal), Real(1), Real(1e-5)) << ctx;
  EXPECT_LE(glm::length(d.normal + pb.apply_vector(b.normal())), Real(1e-5)) << ctx;
  EXPECT_LE(glm::length(d.point_b - (d.point_a + d.signed_distance * d.normal)), tol) << ctx;
  EXPECT_LE(std::abs(a.closest_point(pa.inverse_apply(d.point_a)).signed_distance), tol) << ctx;
  EXPECT_LE(std::abs(b.closest_point(pb.inverse_apply(d.point_b)).signed_distance), tol) << ctx;
  // The touching rule (contact.hpp): within max(contact distance, the pair's tolerance).
  EXPECT_EQ(pair_intersect(a, pa, b, pb, request, nullptr), in_contact(d, request)) << ctx;
  const Real eps = Real(8) * tol;
  Transform apart = pb;
  apart.position += (-d.signed_distance + eps) * d.normal;
  Transform into = pb;
  into.position += (-d.signed_distance - eps) * d.normal;
  EXPECT_FALSE(pair_intersect(a, pa, b, apart, {}, nullptr)) << ctx;
  EXPECT_TRUE(pair_intersect(a, pa, b, into, {}, nullptr)) << ctx;
  const ContactManifold m = pair_collide(a, pa, b, pb, request, nullptr);
  EXPECT_EQ(m.count > 0, in_contact(d, request)) << ctx;
  EXPECT_LE(m.count, request.max_contacts) << ctx;
  for (int i = 0; i < m.count; ++i) {
    const ContactPoint& c = m.points[static_cast<std::size_t>(i)];
    const std::string pc = ctx + " point " + std::to_string(i);
    EXPECT_EQ(c.normal, d.normal) << pc;
    EXPECT_LE(glm::length(c.point_b - (c.point_a - c.depth * c.normal)), tol) << pc;
    // On A's surface; a capsule's second core end pushed by the radius may lie inside it.
    const Real on_a = a.closest_point(pa.inverse_apply(c.point_a)).signed_distance;
    EXPECT_LE(i == 0 ? std::abs(on_a) : on_a, tol) << pc;
    EXPECT_LE(std::abs(b.closest_point(pb.inverse_apply(c.point_b)).signed_distance), tol) << pc;
    EXPECT_GE(c.depth, -(request.contact_distance + Real(2) * tol)) << pc;
    EXPECT_LE(c.depth, -d.signed_distance + tol) << pc;
    for (int j = 0; j < i; ++j) EXPECT_NE(c.feature_id, m.points[static_cast<std::size_t>(j)].feature_id) << pc;
  }
  if (m.count > 0) {
    EXPECT_NEAR(m.points[0].depth, -d.signed_distance, tol) << ctx;
  }
  return m;
}

// Counts the points (world) within contact_distance + tol of the plane (gap in long double).
int count_below(const std::vector<Vec3>& world_points, Real radius, const HalfSpace& b, const Transform& pb,
                Real limit) {
  const test::LPose lb(pb);
  const LVec n = lb.rot.apply(test::ld(b.normal()));
  const LD offset = LD(b.offset()) + glm::dot(n, lb.p);
  int count = 0;
  for (const Vec3& p : world_points) count += glm::dot(n, test::ld(p)) - offset - radius <= limit ? 1 : 0;
  return count;
}

template <class MakeShape, class Features>
void sweep(std::uint64_t seed, const char* name, MakeShape make, Features features, Real radius, Real size) {
  test::Random rng(seed);
  for (int i = 0; i < 1500; ++i) {
    const auto a = make(rng);
    const Vec3 centre = i % 3 == 2 ? Vec3(Real(400), Real(-300), Real(200)) : Vec3(Real(0));
    Transform pa = rng.pose(Real(1.5));
    pa.position += centre;
    Transform pb = rng.pose(Real(1.5));
    pb.position += centre;
    const Real offset = rng.uniform(Real(-1), Real(1));
    const HalfSpace b = *HalfSpace::create(rng.unit_vector(), offset);
    PairRequest request;
    request.contact_distance = i % 2 == 0 ? Real(0) : rng.uniform(Real(0), Real(0.5));
    request.max_contacts = rng.integer(1, 4);
    const Real tol = tol_for(pa, pb, size);
    const std::string ctx = std::string(name) + " " + std::to_string(i);
    const ContactManifold m = check_halfspace(a, pa, b, pb, tol, request, ctx);
    // Feature count: the candidates within the contact distance (ties near the limit skipped).
    const std::vector<Vec3> pts = features(a, pa);
    if (!pts.empty() && m.count > 0) {
      const int lo = count_below(pts, radius, b, pb, request.contact_distance - tol);
      const int hi = count_below(pts, radius, b, pb, request.contact_distance + Real(3) * tol);
      if (lo == hi) {
        EXPECT_EQ(m.count, std::min({lo, 4, request.max_contacts})) << ctx;
      }
    }
  }
}

TEST(PairsHalfSpace, PointSweep) {
  sweep(
      201, "point", [](test::Random&) { return *Point::create(); },
      [](const Point&, const Transform& p) { return std::vector<Vec3>{p.position}; }, Real(0), Real(0));
}

TEST(PairsHalfSpace, SegmentSweep) {
  sweep(
      202, "segment",
      [](test::Random& r) {
        const Vec3 b = r.vec3(Real(-1), Real(1));
        return *Segment::create(r.vec3(Real(-1), Real(1)), b);
      },
      [](const Segment& s, const Transform& p) {
        return std::vector<Vec3>{p.apply(s.a()), p.apply(s.b())};
      },
      Real(0), Real(2));
}

TEST(PairsHalfSpace, TriangleSweep) {
  sweep(
      203, "triangle",
      [](test::Random& r) {
        for (;;) {
          const Vec3 c = r.vec3(Real(-1), Real(1));
          const Vec3 b = r.vec3(Real(-1), Real(1));
          auto t = Triangle::create(r.vec3(Real(-1), Real(1)), b, c);
          if (t && t->area() > Real(0.05)) return *t;
        }
      },
      [](const Triangle& t, const Transform& p) {
        return std::vector<Vec3>{p.apply(t.a()), p.apply(t.b()), p.apply(t.c())};
      },
      Real(0), Real(2));
}

TEST(PairsHalfSpace, SphereSweep) {
  sweep(
      204, "sphere", [](test::Random& r) { return *Sphere::create(r.uniform(Real(0.1), Real(1.5))); },
      [](const Sphere&, const Transform&) { return std::vector<Vec3>{}; }, Real(0), Real(2));
}

TEST(PairsHalfSpace, CapsuleSweep) {
  sweep(
      205, "capsule",
      [](test::Random& r) {
        const Real h = r.uniform(Real(0), Real(1.5));
        return *Capsule::create(r.uniform(Real(0.1), Real(1)), h);
      },
      [](const Capsule&, const Transform&) { return std::vector<Vec3>{}; }, Real(0), Real(3));
}

TEST(PairsHalfSpace, BoxSweep) {
  sweep(
      206, "box", [](test::Random& r) { return *Box::create(r.vec3(Real(0.1), Real(1.5))); },
      [](const Box& b, const Transform& p) {
        std::vector<Vec3> v;
        const Vec3& h = b.half_extents();
        for (int i = 0; i < 8; ++i)
          v.push_back(p.apply(Vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z)));
        return v;
      },
      Real(0), Real(3));
}

TEST(PairsHalfSpace, CylinderSweep) {
  sweep(
      207, "cylinder",
      [](test::Random& r) {
        const Real h = r.uniform(Real(0.1), Real(1.5));
        return *Cylinder::create(r.uniform(Real(0.1), Real(1.5)), h);
      },
      [](const Cylinder&, const Transform&) { return std::vector<Vec3>{}; }, Real(0), Real(3));
}

TEST(PairsHalfSpace, ConeSweep) {
  sweep(
      208, "cone",
      [](test::Random& r) {
        const Real h = r.uniform(Real(0.1), Real(1.5));
        return *Cone::create(r.uniform(Real(0.1), Real(1.5)), h);
      },
      [](const Cone&, const Transform&) { return std::vector<Vec3>{}; }, Real(0), Real(3));
}

TEST(PairsHalfSpace, EllipsoidSweep) {
  sweep(
      209, "ellipsoid", [](test::Random& r) { return *Ellipsoid::create(r.vec3(Real(0.1), Real(1.5))); },
      [](const Ellipsoid&, const Transform&) { return std::vector<Vec3>{}; }, Real(0), Real(3));
}

TEST(PairsHalfSpace, ConvexHullSweep) {
  sweep(
      210, "hull",
      [](test::Random& r) {
        std::vector<Vec3> pts;
        for (int i = 0; i < 14; ++i) pts.push_back(r.in_ball(Real(1.2)));
        return *ConvexHull::create(pts);
      },
      [](const ConvexHull&, const Transform&) { return std::vector<Vec3>{}; }, Real(0), Real(3));
}

// ---------------------------------------------------------------------------------------------
// The generic routine's default steps (generic_halfspace.hpp) against the closed forms.

// The size from the local box equals each closed-form size (the hull keeps its own measure).
TEST(PairsHalfSpace, GenericSizeMatchesTheClosedForms) {
  test::Random rng(211);
  for (int i = 0; i < 200; ++i) {
    const auto same = [&](const auto& shape) {
      using S = std::decay_t<decltype(shape)>;
      EXPECT_EQ(narrow::detail::halfspace_size<S>(shape), narrow::detail::halfspace_size(shape)) << i;
    };
    same(*Point::create());
    const Vec3 s1 = rng.vec3(Real(-2), Real(2));
    same(*Segment::create(rng.vec3(Real(-2), Real(2)), s1));
    const Vec3 t2 = rng.vec3(Real(-2), Real(-0.5));
    same(*Triangle::create(Vec3(0), rng.vec3(Real(0.5), Real(2)), t2));
    same(*Sphere::create(rng.uniform(Real(0.1), Real(2))));
    const Real capsule_h = i % 4 == 0 ? Real(0) : rng.uniform(Real(0), Real(2));
    same(*Capsule::create(rng.uniform(Real(0.1), Real(2)), capsule_h));
    same(*Box::create(rng.vec3(Real(0.1), Real(2))));
    const Real cylinder_h = rng.uniform(Real(0.1), Real(2));
    same(*Cylinder::create(rng.uniform(Real(0.1), Real(2)), cylinder_h));
    const Real cone_h = rng.uniform(Real(0.1), Real(2));
    same(*Cone::create(rng.uniform(Real(0.1), Real(2)), cone_h));
    same(*Ellipsoid::create(rng.vec3(Real(0.1), Real(2))));
  }
}

void expect_same_manifold(const ContactManifold& a, const ContactManifold& b, const std::string& ctx) {
  ASSERT_EQ(a.count, b.count) << ctx;
  EXPECT_EQ(a.normal, b.normal) << ctx;
  EXPECT_EQ(a.status, b.status) << ctx;
  for (std::size_t i = 0; i < static_cast<std::size_t>(a.count); ++i) {
    EXPECT_EQ(a.points[i].point_a, b.points[i].point_a) << ctx << " point " << i;
    EXPECT_EQ(a.points[i].point_b, b.points[i].point_b) << ctx << " point " << i;
    EXPECT_EQ(a.points[i].depth, b.points[i].depth) << ctx << " point " << i;
    EXPECT_EQ(a.points[i].feature_id, b.points[i].feature_id) << ctx << " point " << i;
  }
}

// The supporting feature (the default third step) gives the same manifold as the closed-form
// candidates of a segment, of a capsule with a core segment, and of a triangle whose front
// faces the plane; the closed forms stay for their cost (and a triangle's back, a capsule of
// half length 0).
TEST(PairsHalfSpace, SupportingFeatureStepMatchesTheClosedForms) {
  test::Random rng(212);
  int compared = 0;
  for (int i = 0; i < 3000; ++i) {
    const Transform pa = rng.pose(Real(1.5));
    const Transform pb = rng.pose(Real(1.5));
    const Real offset = rng.uniform(Real(-1), Real(1));
    const HalfSpace b = *HalfSpace::create(rng.unit_vector(), offset);
    PairRequest request;
    request.contact_distance = i % 2 == 0 ? Real(0) : rng.uniform(Real(0), Real(0.5));
    request.max_contacts = rng.integer(1, 4);
    const auto compare = [&](const auto& a, const char* name) {
      using S = std::decay_t<decltype(a)>;
      const narrow::detail::PlaneQuery q = narrow::detail::plane_query(a, pa, b, pb, request);
      if (!(q.distance.signed_distance <= request.contact_distance)) return;
      ++compared;
      expect_same_manifold(narrow::detail::plane_contacts<S>(a, pa, q, request),
                           narrow::detail::plane_contacts(a, pa, q, request), name + std::to_string(i));
    };
    const Vec3 s1 = rng.vec3(Real(-1), Real(1));
    compare(*Segment::create(rng.vec3(Real(-1), Real(1)), s1), "segment ");
    const Real capsule_h = rng.uniform(Real(0.01), Real(1.5));
    compare(*Capsule::create(rng.uniform(Real(0.1), Real(1)), capsule_h), "capsule ");
    const Vec3 t2 = rng.vec3(Real(-1), Real(-0.5));
    const Triangle t = *Triangle::create(Vec3(0), rng.vec3(Real(0.5), Real(1)), t2);
    const Vec3 down = pa.inverse_apply_vector(-pb.apply_vector(b.normal()));
    if (glm::dot(t.normal(), down) >= Real(0)) compare(t, "triangle ");
  }
  EXPECT_GT(compared, 1000);
}

// Where the supporting feature would change the answer: a triangle on its back turns to a, c, b
// (with equal gaps, the order of the points), a capsule of half length 0 is one point.
TEST(PairsHalfSpace, SupportingFeatureStepDiffersWhereClosedFormsStay) {
  using narrow::detail::plane_contacts;
  const auto vertex = [](std::uint32_t i) { return make_feature_id(FeatureKind::Vertex, i, FeatureKind::Face, 0); };
  const HalfSpace f = floor_at(0);
  const Triangle t = *Triangle::create(Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0));  // normal +z, away from the floor
  const Transform pt = at({0, 0, Real(-0.01)});
  const narrow::detail::PlaneQuery qt = narrow::detail::plane_query(t, pt, f, at({}), {});
  const ContactManifold closed = plane_contacts(t, pt, qt, {});
  const ContactManifold generic = plane_contacts<Triangle>(t, pt, qt, {});
  ASSERT_EQ(closed.count, 3);
  ASSERT_EQ(generic.count, 3);
  EXPECT_EQ(closed.points[1].feature_id, vertex(1));
  EXPECT_EQ(generic.points[1].feature_id, vertex(2));
  const Capsule c = *Capsule::create(Real(0.5), Real(0));
  const Transform pc = at({0, 0, Real(0.49)});
  const narrow::detail::PlaneQuery qc = narrow::detail::plane_query(c, pc, f, at({}), {});
  EXPECT_EQ(plane_contacts(c, pc, qc, {}).count, 2);
  EXPECT_EQ(plane_contacts<Capsule>(c, pc, qc, {}).count, 1);
}

// ---------------------------------------------------------------------------------------------
// Resting cases.

TEST(PairsHalfSpace, BoxRestingAndTilted) {
  const Box b = *Box::create({1, 2, Real(0.5)});
  const HalfSpace f = floor_at(0);
  // Flat, sunk by 0.01: four corners, depth 0.01.
  const ContactManifold m = pair_collide(b, at({0, 0, Real(0.49)}), f, at({}), {}, nullptr);
  ASSERT_EQ(m.count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[static_cast<std::size_t>(i)].depth, Real(0.01), Real(1e-5));
  EXPECT_EQ(m.normal, Vec3(0, 0, -1));
  // Lifted by 0.01 with contact distance 0.02: four speculative points, depth -0.01.
  PairRequest spec;
  spec.contact_distance = Real(0.02);
  const ContactManifold s = pair_collide(b, at({0, 0, Real(0.51)}), f, at({}), spec, nullptr);
  ASSERT_EQ(s.count, 4);
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(s.points[static_cast<std::size_t>(i)].depth, Real(-0.01), Real(1e-5));
  EXPECT_TRUE(pair_intersect(b, at({0, 0, Real(0.51)}), f, at({}), spec, nullptr));
  EXPECT_FALSE(pair_intersect(b, at({0, 0, Real(0.51)}), f, at({}), {}, nullptr));
  // Feature ids stable under a small slide.
  const ContactManifold m2 = pair_collide(b, at({Real(0.05), 0, Real(0.49)}), f, at({}), {}, nullptr);
  ASSERT_EQ(m2.count, 4);
  for (int i = 0; i < 4; ++i)
    EXPECT_EQ(m2.points[static_cast<std::size_t>(i)].feature_id, m.points[static_cast<std::size_t>(i)].feature_id);
  // Tilted about y (edges along y lowest), sunk by 0.001: two points; about a generic axis (a
  // corner lowest): one.
  const auto resting = [&](const Quat& q) {
    Real low = std::numeric_limits<Real>::infinity();
    for (int i = 0; i < 8; ++i) {
      const Vec3& h = b.half_extents();
      low = std::min(low, (q * Vec3(i & 1 ? h.x : -h.x, i & 2 ? h.y : -h.y, i & 4 ? h.z : -h.z)).z);
    }
    return at({0, 0, -low - Real(0.001)}, q);
  };
  EXPECT_EQ(pair_collide(b, resting(about({0, 1, 0}, Real(0.3))), f, at({}), {}, nullptr).count, 2);
  EXPECT_EQ(pair_collide(b, resting(about({1, 1, 0}, Real(0.3))), f, at({}), {}, nullptr).count, 1);
  // max_contacts = 2 keeps two corners, the deepest first, and a far one.
  PairRequest two;
  two.max_contacts = 2;
  const ContactManifold t = pair_collide(b, at({0, 0, Real(0.49)}), f, at({}), two, nullptr);
  ASSERT_EQ(t.count, 2);
  EXPECT_NEAR(glm::length(t.points[0].point_a - t.points[1].point_a), std::sqrt(Real(20)), Real(1e-4));
}

TEST(PairsHalfSpace, CylinderStandingLyingTilted) {
  const Cylinder c = *Cylinder::create(Real(0.5), 1);
  const HalfSpace f = floor_at(0);
  const ContactManifold stand = pair_collide(c, at({0, 0, Real(0.99)}), f, at({}), {}, nullptr);
  ASSERT_EQ(stand.count, 4);
  for (int i = 0; i < 4; ++i) {
    const ContactPoint& p = stand.points[static_cast<std::size_t>(i)];
    EXPECT_NEAR(p.depth, Real(0.01), Real(1e-5));
    EXPECT_NEAR(std::hypot(p.point_a.x, p.point_a.y), Real(0.5), Real(1e-5));
  }
  const ContactManifold lie =
      pair_collide(c, at({0, 0, Real(0.49)}, about({1, 0, 0}, kHalfPi)), f, at({}), {}, nullptr);
  ASSERT_EQ(lie.count, 2);
  EXPECT_NEAR(std::abs(lie.points[0].point_a.y - lie.points[1].point_a.y), Real(2), Real(1e-5));
  const ContactManifold tilt =
      pair_collide(c, at({0, 0, Real(1)}, about({1, 0, 0}, Real(0.2))), f, at({}), {}, nullptr);
  EXPECT_EQ(tilt.count, 1);
}

TEST(PairsHalfSpace, ConeOnBaseAndSide) {
  const Cone c = *Cone::create(Real(0.5), 1);
  const HalfSpace f = floor_at(0);
  EXPECT_EQ(pair_collide(c, at({0, 0, Real(0.99)}), f, at({}), {}, nullptr).count, 4);
  // Lying on its slant side: the plane through the apex (0, 0, 1) and the rim point (0.5, 0, -1).
  const Vec3 out = glm::normalize(Vec3(2, 0, Real(0.5)));  // outward normal of the slant line
  const HalfSpace side = *HalfSpace::create(-out, -glm::dot(out, Vec3(0, 0, 1)) + Real(0.01));
  const ContactManifold m = pair_collide(c, at({}), side, at({}), {}, nullptr);
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.points[0].depth, Real(0.01), Real(1e-5));
  EXPECT_NEAR(m.points[1].depth, Real(0.01), Real(1e-5));
  // Apex down: one point.
  EXPECT_EQ(pair_collide(c, at({0, 0, Real(0.99)}, about({1, 0, 0}, Real(3.14159265))), f, at({}), {}, nullptr).count,
            1);
}

TEST(PairsHalfSpace, CapsuleFlatAndUpright) {
  const Capsule c = *Capsule::create(Real(0.5), 1);
  const HalfSpace f = floor_at(0);
  const ContactManifold flat =
      pair_collide(c, at({0, 0, Real(0.49)}, about({0, 1, 0}, kHalfPi)), f, at({}), {}, nullptr);
  ASSERT_EQ(flat.count, 2);
  EXPECT_NE(flat.points[0].feature_id, flat.points[1].feature_id);
  EXPECT_EQ(pair_collide(c, at({0, 0, Real(1.49)}), f, at({}), {}, nullptr).count, 1);
  const DistanceResult d = pair_distance(c, at({0, 0, Real(1.49)}), f, at({}), {}, nullptr);
  EXPECT_NEAR(d.signed_distance, Real(-0.01), Real(1e-5));
}

TEST(PairsHalfSpace, HullManyVerticesOnTheFloor) {
  // A 32-gon prism lying on its polygon face: four points spanning a large area.
  std::vector<Vec3> pts;
  for (int i = 0; i < 32; ++i) {
    const Real t = Real(2) * kPi * Real(i) / Real(32);
    pts.emplace_back(std::cos(t), std::sin(t), 0);
    pts.emplace_back(std::cos(t), std::sin(t), 1);
  }
  const ConvexHull h = *ConvexHull::create(pts);
  const ContactManifold m = pair_collide(h, at({0, 0, Real(-0.01)}), floor_at(0), at({}), {}, nullptr);
  ASSERT_EQ(m.count, 4);
  const auto area = [](const Vec3& a, const Vec3& b, const Vec3& c) {
    return Real(0.5) * std::abs(glm::cross(b - a, c - a).z);
  };
  // Area of the quadrilateral (convex, in some order): the larger of the two diagonal splits.
  const Vec3 p[4] = {m.points[0].point_a, m.points[1].point_a, m.points[2].point_a, m.points[3].point_a};
  const Real quad =
      std::max({area(p[0], p[1], p[2]) + area(p[0], p[2], p[3]), area(p[0], p[1], p[3]) + area(p[1], p[2], p[3]),
                area(p[0], p[2], p[1]) + area(p[0], p[1], p[3])});
  EXPECT_GE(quad, Real(1.9));  // the largest inscribed quadrilateral (a square) has area 2
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(m.points[static_cast<std::size_t>(i)].depth, Real(0.01), Real(1e-5));
}

TEST(PairsHalfSpace, SegmentAndTriangleVertices) {
  const HalfSpace f = floor_at(0);
  const Segment s = *Segment::create({-1, 0, Real(-0.1)}, {1, 0, Real(-0.2)});
  EXPECT_EQ(pair_collide(s, at({}), f, at({}), {}, nullptr).count, 2);
  const Segment up = *Segment::create({-1, 0, Real(-0.1)}, {1, 0, Real(0.2)});
  EXPECT_EQ(pair_collide(up, at({}), f, at({}), {}, nullptr).count, 1);
  const Triangle t = *Triangle::create({0, 0, Real(-0.1)}, {1, 0, Real(-0.1)}, {0, 1, Real(0.3)});
  const ContactManifold m = pair_collide(t, at({}), f, at({}), {}, nullptr);
  ASSERT_EQ(m.count, 2);
  EXPECT_NEAR(m.points[0].depth, Real(0.1), Real(1e-6));
}

TEST(PairsHalfSpace, HalfSpaceHalfSpace) {
  const HalfSpace up = floor_at(0);                                     // z <= 0
  const HalfSpace down = *HalfSpace::create(Vec3(0, 0, -1), Real(-2));  // z >= 2
  const DistanceResult gap = pair_distance(up, at({}), down, at({}), {}, nullptr);
  EXPECT_NEAR(gap.signed_distance, Real(2), Real(1e-6));
  EXPECT_EQ(gap.status, PairStatus::Separated);
  EXPECT_EQ(gap.normal, Vec3(0, 0, 1));
  EXPECT_LE(glm::length(gap.point_b - (gap.point_a + gap.signed_distance * gap.normal)), Real(1e-6));
  EXPECT_NEAR(gap.point_b.z, Real(2), Real(1e-6));
  EXPECT_FALSE(pair_intersect(up, at({}), down, at({}), {}, nullptr));
  // Moved down by 3: overlapping slab of thickness 1.
  const DistanceResult over = pair_distance(up, at({}), down, at({0, 0, -3}), {}, nullptr);
  EXPECT_NEAR(over.signed_distance, Real(-1), Real(1e-6));
  EXPECT_EQ(over.status, PairStatus::Penetrating);
  const ContactManifold m = pair_collide(up, at({}), down, at({0, 0, -3}), {}, nullptr);
  ASSERT_EQ(m.count, 1);
  EXPECT_NEAR(m.points[0].depth, Real(1), Real(1e-6));
  // Not anti-parallel: unbounded overlap, a finite documented depth.
  for (const Vec3& n : {Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, Real(0.6), Real(-0.8))}) {
    const HalfSpace other = *HalfSpace::create(n, Real(5));
    const DistanceResult d = pair_distance(up, at({1, 2, 3}), other, at({}, about({1, 1, 0}, Real(0.1))), {}, nullptr);
    EXPECT_EQ(d.signed_distance, -narrow::kHalfSpacePairDepth);
    EXPECT_EQ(d.status, PairStatus::Penetrating);
    EXPECT_TRUE(is_finite(d.point_a) && is_finite(d.point_b) && is_finite(d.normal));
    EXPECT_TRUE(pair_intersect(up, at({1, 2, 3}), other, at({}), {}, nullptr));
  }
  // Far planes: finite answers.
  const HalfSpace far = *HalfSpace::create(Vec3(0, 0, -1), -kMaxCoordinate);
  const DistanceResult f = pair_distance(up, at({}), far, at({}), {}, nullptr);
  EXPECT_TRUE(std::isfinite(f.signed_distance));
  EXPECT_GT(f.signed_distance, Real(0));
}

TEST(PairsHalfSpace, NonFinitePoses) {
  const Real nan = std::numeric_limits<Real>::quiet_NaN();
  const Transform bad{Vec3(0, nan, 0), kIdentityQuat};
  const HalfSpace f = floor_at(0);
  const Box b = *Box::create({1, 1, 1});
  EXPECT_EQ(pair_distance(b, bad, f, at({}), {}, nullptr).status, PairStatus::InvalidInput);
  EXPECT_EQ(pair_distance(f, at({}), f, bad, {}, nullptr).status, PairStatus::InvalidInput);
  EXPECT_FALSE(pair_intersect(b, at({}), f, bad, {}, nullptr));
  const ContactManifold m = pair_collide(*Cylinder::create(1, 1), bad, f, at({}), {}, nullptr);
  EXPECT_EQ(m.count, 0);
  EXPECT_EQ(m.status, PairStatus::InvalidInput);
}

}  // namespace test_pairs_halfspace
}  // namespace proxima
