// The stated numeric range (core/tolerance.hpp, kMaxCoordinate: 1e7 in float, 1e50 in
// double) at its edges: every convex pair with shapes as large as accepted, placed as far
// out as accepted, agrees with the independent reference of reference_distance.hpp (exact
// for two polytopes, the support-function search otherwise, a half-space's closed form) and
// passes the convention checks of pair_checker.hpp; mass properties of the largest accepted
// shapes are finite and agree with the closed forms; past the range, inputs are refused
// naming the field, poses answer InvalidInput, and overflowing mass properties are never NaN.
#include <gtest/gtest.h>

#include <proxima/shapes/compound.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <cmath>
#include <numbers>
#include <string>

#include "narrowphase/pair_checker.hpp"
#include "narrowphase/reference_distance.hpp"

namespace proxima::test {
namespace {

/// The reference signed distance of a placed pair: a half-space's closed form (the other
/// shape's support along the plane's normal), else decide_signed_distance; `seed` (the
/// contestant's normal) is only evaluated by the support functions, never trusted.
double reference_distance(const Shape& a, const Transform& pa, const Shape& b, const Transform& pb, D3v seed) {
  if (const HalfSpace* h = std::get_if<HalfSpace>(&a)) {
    const Vec3 n = pa.apply_vector(h->normal());
    const double plane = double(h->offset()) + dot(d3v(n), d3v(pa.position));
    return dot(reference_support(b, pb, -1.0 * d3v(n)), d3v(n)) - plane;
  }
  if (std::holds_alternative<HalfSpace>(b)) return reference_distance(b, pb, a, pa, -1.0 * seed);
  if (world_polytope(a, pa) && world_polytope(b, pb)) return decide_signed_distance(a, pa, b, pb);
  return reference_signed_distance(a, pa, b, pb, 1500, 8, {seed}).signed_distance;
}

/// Where the shapes of one sweep are placed: their size and the offset of the pair.
struct Placement {
  const char* name;
  Real size;    ///< random_shape's size: extents reach 3.75 times it
  Real offset;  ///< both poses are moved by (offset, -offset, offset)
};

/// Every ordered convex pair, `per_pair` seeded cases at `placement`: the reference and the
/// convention checks. Returns the failures' descriptions (empty when all pass).
std::vector<std::string> sweep(const Placement& placement, int per_pair) {
  std::vector<std::string> failures;
  PairChecker checker;
  for (ShapeType ta : all_shape_types()) {
    for (ShapeType tb : all_shape_types()) {
      Random rng(7100 + 31 * int(ta) + int(tb));
      for (int i = 0; i < per_pair; ++i) {
        const Shape a = random_shape(rng, ta, placement.size);
        const Shape b = random_shape(rng, tb, placement.size);
        const Vec3 offset(placement.offset, -placement.offset, placement.offset);
        const Transform pa{rng.in_ball(Real(1.5) * placement.size) + offset, rng.rotation()};
        const Transform pb{rng.in_ball(Real(1.5) * placement.size) + offset, rng.rotation()};
        const std::string label =
            std::string(placement.name) + " " + to_string(ta) + "-" + to_string(tb) + " case " + std::to_string(i);
        checker.check(a, pa, b, pb, label);
        if (ta == ShapeType::HalfSpace && tb == ShapeType::HalfSpace) continue;  // boolean only
        const DistanceResult d = distance(a, pa, b, pb, PairRequest{});
        // The reference sees the pair moved back by the offset (exact for unit shapes, whose
        // positions lie within a factor two of it; else off by an ulp of the offset, inside
        // the tolerance's allowance for it), where its double arithmetic keeps the shapes'
        // features apart.
        const Transform ra{pa.position - offset, pa.rotation};
        const Transform rb{pb.position - offset, pb.rotation};
        const double ref = reference_distance(a, ra, b, rb, d3v(d.normal));
        const Real size = std::max({shape_scale(a), shape_scale(b), Real(1e-30)});
        const Real far = std::max(max_abs_component(pa.position), max_abs_component(pb.position));
        const double tol =
            double(std::max(narrow_tolerance(size), Real(4) * linear_tolerance(size)) + Real(256) * kEpsilon * far);
        if (!(std::abs(double(d.signed_distance) - ref) <= tol)) {
          failures.push_back(label + ": distance " + std::to_string(d.signed_distance) + " status " +
                             status_name(d.status) + ", reference " + std::to_string(ref) + " (tolerance " +
                             std::to_string(tol) + ")\n    A=" + describe(a, pa) + "\n    B=" + describe(b, pb));
        }
      }
    }
  }
  for (const std::string& m : checker.messages()) failures.push_back(m);
  return failures;
}

void expect_no_failures(const std::vector<std::string>& failures) {
  EXPECT_TRUE(failures.empty()) << failures.size() << " failures; the first:\n"
                                << (failures.empty() ? std::string() : failures.front());
  for (std::size_t i = 1; i < std::min<std::size_t>(failures.size(), 4); ++i) ADD_FAILURE() << failures[i];
}

// Extents up to 3.75 x kMax/4 (just under kMaxCoordinate), positions up to 0.875 kMax.
TEST(NumericRange, EveryPairAtTheLargestAcceptedSizeAndOffsetMatchesTheReference) {
  expect_no_failures(sweep({"largest, far", kMaxCoordinate / 4, kMaxCoordinate / 2}, 3));
}

TEST(NumericRange, EveryPairAtTheLargestAcceptedSizeAtTheOriginMatchesTheReference) {
  expect_no_failures(sweep({"largest, origin", kMaxCoordinate / 4, Real(0)}, 3));
}

// Unit shapes at the edge of the range: the answer is right to the rounding of the poses
// there (256 epsilon times the offset), and finite.
TEST(NumericRange, EveryPairOfUnitShapesAtTheLargestAcceptedOffsetMatchesTheReference) {
  expect_no_failures(sweep({"unit, far", Real(1), kMaxCoordinate * Real(0.9)}, 1));
}

TEST(NumericRange, SizesPastTheRangeAreRefusedNamingTheField) {
  const Real past = Real(2) * kMaxCoordinate;
  const Result<Sphere> sphere = Sphere::create(past);
  ASSERT_FALSE(sphere.ok());
  EXPECT_EQ(sphere.error().field, "radius");
  const Result<Box> box = Box::create(Vec3(1, past, 1));
  ASSERT_FALSE(box.ok());
  EXPECT_EQ(box.error().field, "half_extents.y");
  const std::vector<Vec3> cloud{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, past}};
  const Result<ConvexHull> hull = ConvexHull::create(cloud);
  ASSERT_FALSE(hull.ok());
  EXPECT_EQ(hull.error().field, "points[3].z");
  // At the edge itself they are accepted.
  EXPECT_TRUE(Sphere::create(kMaxCoordinate).ok());
  EXPECT_TRUE(Box::create(Vec3(kMaxCoordinate)).ok());
}

TEST(NumericRange, PosesPastTheRangeAnswerInvalidInput) {
  const Shape a = Sphere::create(Real(1)).value();
  const Shape b = Box::create(Vec3(1)).value();
  const Transform near;
  const Transform past{Vec3(0, Real(5) * kMaxCoordinate, 0), Quat(1, 0, 0, 0)};
  const DistanceResult d = distance(a, near, b, past, PairRequest{});
  EXPECT_EQ(d.status, PairStatus::InvalidInput);
  EXPECT_EQ(d.signed_distance, std::numeric_limits<Real>::infinity());
  EXPECT_FALSE(intersect(a, past, b, near, PairRequest{}));
  EXPECT_EQ(collide(a, near, b, past, PairRequest{}).count, 0);
  // Composed placements up to kMaxPlacedCoordinate are in range (answered, overlapping).
  const Transform composed{Vec3(0, Real(2.5) * kMaxCoordinate, 0), Quat(1, 0, 0, 0)};
  const DistanceResult inside = distance(a, composed, b, composed, PairRequest{});
  EXPECT_NE(inside.status, PairStatus::InvalidInput);
  EXPECT_LE(inside.signed_distance, Real(0));
}

/// Relative agreement of a mass property with its closed form.
void expect_relative(double got, double want, const char* what) {
  EXPECT_NEAR(got / want, 1.0, kFloatBuild ? 1e-5 : 1e-12) << what << ": " << got << " against " << want;
}

// The largest accepted shapes at the largest density the range promises (100 in float, 1e50
// in double): finite, and equal to the closed forms.
TEST(NumericRange, MassPropertiesOfTheLargestShapesAreFiniteAndMatchTheClosedForms) {
  const double s = double(kMaxCoordinate);
  const Real density = kFloatBuild ? Real(100) : Real(1e50);
  const double rho = double(density);
  const double pi = std::numbers::pi;
  {
    const MassProperties m = Sphere::create(kMaxCoordinate).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    expect_relative(m.volume, 4.0 / 3.0 * pi * s * s * s, "sphere volume");
    expect_relative(m.inertia[0][0], 0.4 * rho * 4.0 / 3.0 * pi * s * s * s * s * s, "sphere inertia");
  }
  const double box_mass = rho * 8 * s * s * s;
  const double box_inertia = box_mass * (s * s + s * s) / 3.0;
  {
    const MassProperties m = Box::create(Vec3(kMaxCoordinate)).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    expect_relative(m.mass, box_mass, "box mass");
    expect_relative(m.inertia[1][1], box_inertia, "box inertia");
  }
  {
    const MassProperties m = Cylinder::create(kMaxCoordinate, kMaxCoordinate).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    const double mass = rho * pi * s * s * 2 * s;
    expect_relative(m.inertia[2][2], mass * s * s / 2, "cylinder axial inertia");
    expect_relative(m.inertia[0][0], mass * (3 * s * s + 4 * s * s) / 12, "cylinder transverse inertia");
  }
  {
    const MassProperties m = Cone::create(kMaxCoordinate, kMaxCoordinate).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    const double mass = rho * pi * s * s * 2 * s / 3;
    expect_relative(m.inertia[2][2], 0.3 * mass * s * s, "cone axial inertia");
    expect_relative(m.inertia[0][0], mass * (3.0 / 20.0 * s * s + 3.0 / 80.0 * 4 * s * s), "cone transverse inertia");
  }
  {
    const MassProperties m = Ellipsoid::create(Vec3(kMaxCoordinate)).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    expect_relative(m.inertia[0][0], 0.4 * rho * 4.0 / 3.0 * pi * s * s * s * s * s, "ellipsoid inertia");
  }
  EXPECT_TRUE(is_finite(Capsule::create(kMaxCoordinate, kMaxCoordinate).value().mass_properties(density)));
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) {
    corners.emplace_back(i & 1 ? kMaxCoordinate : -kMaxCoordinate, i & 2 ? kMaxCoordinate : -kMaxCoordinate,
                         i & 4 ? kMaxCoordinate : -kMaxCoordinate);
  }
  {
    const MassProperties m = ConvexHull::create(corners).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    expect_relative(m.mass, box_mass, "hull mass");
    expect_relative(m.inertia[0][0], box_inertia, "hull inertia");
    EXPECT_LE(std::abs(m.inertia[0][1]), 1e-6 * box_inertia);
  }
  {
    const std::vector<TriangleIndices> faces{{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                                             {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    const MassProperties m = TriangleMesh::create(IndexedMesh{corners, faces}).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    expect_relative(m.mass, box_mass, "mesh mass");
    expect_relative(m.inertia[2][2], box_inertia, "mesh inertia");
  }
  {
    // Two boxes of half extents kMax/2 side by side along x: one box 2 kMax x kMax x kMax.
    const Real h = kMaxCoordinate / 2;
    const Shape half = Box::create(Vec3(h)).value();
    const std::vector<CompoundChild> kids{{half, Transform{Vec3(-h, 0, 0), Quat(1, 0, 0, 0)}},
                                          {half, Transform{Vec3(h, 0, 0), Quat(1, 0, 0, 0)}}};
    const MassProperties m = Compound::create(kids).value().mass_properties(density);
    ASSERT_TRUE(is_finite(m));
    const double mass = rho * 2 * s * s * s;
    expect_relative(m.inertia[0][0], mass * (s * s + s * s) / 12, "compound inertia about x");
    expect_relative(m.inertia[1][1], mass * (4 * s * s + s * s) / 12, "compound inertia about y");
  }
}

// Past Real's range (a density far above the promise) the overflowing components are
// infinite, never NaN, and is_finite says so; a compound's inertia is +infinity throughout.
TEST(NumericRange, MassPropertiesPastTheNumberRangeAreInfiniteNeverNaN) {
  const Real density = std::numeric_limits<Real>::max() / Real(1e6);
  const auto no_nan = [](const MassProperties& m) {
    bool ok = !std::isnan(m.volume) && !std::isnan(m.mass);
    for (int c = 0; c < 3; ++c) {
      ok = ok && !std::isnan(m.centroid[c]);
      for (int r = 0; r < 3; ++r) ok = ok && !std::isnan(m.inertia[c][r]);
    }
    return ok;
  };
  Random rng(77);
  for (ShapeType t : all_shape_types()) {
    if (t == ShapeType::HalfSpace) continue;
    const Shape shape = random_shape(rng, t, kMaxCoordinate / 4);
    const MassProperties m = std::visit(
        [&](const auto& s) {
          if constexpr (requires { s.mass_properties(density); }) {
            return s.mass_properties(density);
          } else {
            return MassProperties{};
          }
        },
        shape);
    EXPECT_TRUE(no_nan(m)) << to_string(t);
    if (m.volume > Real(0)) {
      EXPECT_FALSE(is_finite(m)) << to_string(t);
    }
  }
  const Shape ball = Sphere::create(kMaxCoordinate).value();
  const Transform turned{Vec3(kMaxCoordinate, 0, 0), glm::angleAxis(Real(0.7), glm::normalize(Vec3(1, 2, 3)))};
  const std::vector<CompoundChild> kids{{ball, turned}, {ball, Transform{}}};
  const MassProperties m = Compound::create(kids).value().mass_properties(density);
  EXPECT_TRUE(no_nan(m));
  EXPECT_FALSE(is_finite(m));
  EXPECT_EQ(m.inertia[0][1], std::numeric_limits<Real>::infinity());
}

}  // namespace
}  // namespace proxima::test
