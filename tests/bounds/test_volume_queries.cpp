// Ray, segment and plane queries on every bounding volume, against references written
// without the library's bounds code: rays are marched on an independent point-in-volume
// predicate (with a margin that sorts out grazing cases), planes are checked against the
// projection range of the volume's reference core.
#include <gtest/gtest.h>

#include <proxima/bounds/fit_kdop.hpp>
#include <proxima/bounds/volume_queries.hpp>
#include <proxima/core/tolerance.hpp>

#include <cstdio>
#include <variant>
#include <vector>

#include "bounds/test_bounds_reference.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_volume_queries {

using test::D3;
using test::VolumeType;

struct RayStats {
  int hits = 0, misses = 0, ambiguous = 0;
};

template <int K>
RayStats check_rays(VolumeType type, int cases, std::uint64_t seed, bool segments) {
  test::Random rng(seed);
  RayStats stats;
  for (int i = 0; i < cases; ++i) {
    const auto v = test::make_volume<K>(rng, type, Real(1), Vec3(0), Real(0.3));
    const Vec3 origin = rng.vec3(Real(-4), Real(4));
    const Vec3 target = rng.vec3(Real(-0.8), Real(0.8));
    Ray ray{origin, target - origin};
    if (i % 5 == 0) ray.direction *= Real(0.3);  // not normalised
    const Real max_t = segments ? Real(1) : rng.uniform(Real(0), Real(3));
    const std::optional<Real> t =
        segments ? (std::visit([&](const auto& x) { return intersects_segment(x, origin, origin + ray.direction); },
                               v.volume)
                        ? std::optional<Real>(Real(0))
                        : std::nullopt)
                 : std::visit([&](const auto& x) { return ray_entry(x, ray, max_t); }, v.volume);
    // Reference: march the ray in fine steps on the reference predicate.
    constexpr int kSteps = 3000;
    const double len = double(glm::length(ray.direction));
    const double delta = 1e-4;
    const double step_t = double(max_t) / kSteps;
    const double coarse = len * step_t + delta;
    double first_shrunk = -1, first_grown = -1;
    bool any_coarse = false;
    for (int k = 0; k <= kSteps; ++k) {
      const double tk = step_t * k;
      const D3 p = D3(ray.origin) + tk * D3(ray.direction);
      if (first_shrunk < 0 && test::ref_contains(v.ref, p, -delta)) first_shrunk = tk;
      if (first_grown < 0 && test::ref_contains(v.ref, p, delta)) first_grown = tk;
      any_coarse = any_coarse || test::ref_contains(v.ref, p, coarse);
    }
    const char* name = test::volume_name(type);
    if (first_shrunk >= 0) {
      ++stats.hits;
      EXPECT_TRUE(t.has_value()) << name << " K=" << K << " case " << i;
      if (!segments && t.has_value()) {
        EXPECT_GE(*t, Real(0));
        EXPECT_LE(*t, max_t);
        // The entry is no later than a point surely inside, and not before the volume
        // (grown by the margin) is reached.
        EXPECT_LE(double(*t), first_shrunk + 1e-6) << name << " case " << i;
        EXPECT_GE(double(*t), first_grown - step_t - 1e-6) << name << " case " << i;
        const D3 p = D3(ray.origin) + double(*t) * D3(ray.direction);
        EXPECT_TRUE(test::ref_contains(v.ref, p, 1e-4 + 1e-5 * len)) << name << " case " << i;
      }
    } else if (!any_coarse) {
      ++stats.misses;
      EXPECT_FALSE(t.has_value()) << name << " K=" << K << " case " << i;
    } else {
      ++stats.ambiguous;
    }
  }
  return stats;
}

template <int K>
void check_all_rays(std::uint64_t seed, bool kdop_only) {
  for (int a = 0; a < test::kVolumeTypeCount; ++a) {
    const auto type = static_cast<VolumeType>(a);
    if (kdop_only && type != VolumeType::Kdop) continue;
    for (bool segments : {false, true}) {
      const RayStats s = check_rays<K>(type, 400, seed + std::uint64_t(a) * 7 + segments, segments);
      EXPECT_GT(s.hits, 50) << test::volume_name(type);
      EXPECT_GT(s.misses, 50) << test::volume_name(type);
      EXPECT_LT(s.ambiguous, 40) << test::volume_name(type);
    }
  }
}

TEST(VolumeQueries, RaysAndSegmentsAgainstMarching) { check_all_rays<14>(600, false); }
TEST(VolumeQueries, RaysAndSegmentsAgainstMarchingKdop6) { check_all_rays<6>(610, true); }
TEST(VolumeQueries, RaysAndSegmentsAgainstMarchingKdop18) { check_all_rays<18>(620, true); }
TEST(VolumeQueries, RaysAndSegmentsAgainstMarchingKdop26) { check_all_rays<26>(630, true); }

TEST(VolumeQueries, RayConventions) {
  const Aabb box{Vec3(-1), Vec3(1)};
  const BoundingSphere sphere{Vec3(0), Real(1)};
  const Obb obb{Vec3(0), Mat3(Real(1)), Vec3(1)};
  const BoundingCapsule capsule{Vec3(0, 0, -1), Vec3(0, 0, 1), Real(1)};
  std::vector<Vec3> cube;
  for (int k = 0; k < 8; ++k) cube.push_back(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
  const Kdop26 kdop = *fit_kdop<26>(cube);
  auto check = [](const auto& v, const char* name) {
    // Inside origin: t = 0, whatever the direction (zero included) or max_t.
    EXPECT_EQ(ray_entry(v, Ray{Vec3(0), Vec3(1, 0, 0)}, Real(5)), Real(0)) << name;
    EXPECT_EQ(ray_entry(v, Ray{Vec3(0), Vec3(0)}, Real(5)), Real(0)) << name;
    EXPECT_EQ(ray_entry(v, Ray{Vec3(0), Vec3(0, 1, 0)}, Real(0)), Real(0)) << name;
    // Zero direction outside: miss.
    EXPECT_FALSE(ray_entry(v, Ray{Vec3(5, 0, 0), Vec3(0)}, Real(5)).has_value()) << name;
    // t in units of |direction|: hits the face x = 1 at distance 2 -> t = 1 for |d| = 2.
    const auto t = ray_entry(v, Ray{Vec3(3, 0, 0), Vec3(-2, 0, 0)}, Real(10));
    ASSERT_TRUE(t.has_value()) << name;
    EXPECT_NEAR(*t, Real(1), Real(1e-5)) << name;
    // max_t too short, and pointing away.
    EXPECT_FALSE(ray_entry(v, Ray{Vec3(3, 0, 0), Vec3(-2, 0, 0)}, Real(0.9)).has_value()) << name;
    EXPECT_FALSE(ray_entry(v, Ray{Vec3(3, 0, 0), Vec3(2, 0, 0)}, Real(100)).has_value()) << name;
    // Segments.
    EXPECT_TRUE(intersects_segment(v, Vec3(3, 0, 0), Vec3(-3, 0, 0))) << name;
    EXPECT_FALSE(intersects_segment(v, Vec3(3, 0, 0), Vec3(2, 0, 0))) << name;
    EXPECT_TRUE(intersects_segment(v, Vec3(Real(0.5), 0, 0), Vec3(Real(0.5), 0, 0))) << name;
  };
  check(box, "aabb");
  check(sphere, "sphere");
  check(obb, "obb");
  check(capsule, "capsule");
  check(kdop, "kdop");
  // A ray lying in a face plane of a slab volume hits (closed volumes).
  EXPECT_TRUE(ray_entry(box, Ray{Vec3(-5, 1, 0), Vec3(1, 0, 0)}, Real(10)).has_value());
  EXPECT_TRUE(ray_entry(obb, Ray{Vec3(-5, 1, 0), Vec3(1, 0, 0)}, Real(10)).has_value());
  EXPECT_TRUE(ray_entry(kdop, Ray{Vec3(-5, 1, 0), Vec3(1, 0, 0)}, Real(10)).has_value());
  EXPECT_FALSE(ray_entry(box, Ray{Vec3(-5, Real(1.001), 0), Vec3(1, 0, 0)}, Real(10)).has_value());
  // Along the capsule's axis from outside: enters at the cap.
  const auto ta = ray_entry(capsule, Ray{Vec3(0, 0, 5), Vec3(0, 0, -1)}, Real(10));
  ASSERT_TRUE(ta.has_value());
  EXPECT_NEAR(*ta, Real(3), Real(1e-5));
  // Radius-0 volumes: a segment-capsule is hit by a ray crossing it only on a set of
  // measure zero; a point sphere on the ray is hit.
  EXPECT_TRUE(ray_entry(BoundingSphere{Vec3(2, 0, 0), Real(0)}, Ray{Vec3(0), Vec3(1, 0, 0)}, Real(5)).has_value());
  // Empty volumes are never hit.
  EXPECT_FALSE(ray_entry(Aabb(), Ray{Vec3(0), Vec3(1, 0, 0)}, Real(5)).has_value());
  EXPECT_FALSE(ray_entry(Kdop14(), Ray{Vec3(0), Vec3(1, 0, 0)}, Real(5)).has_value());
  // Far from the origin and huge/tiny scales.
  const Vec3 far(Real(1e4), Real(-1e4), Real(1e4));
  EXPECT_NEAR(*ray_entry(BoundingSphere{far, Real(1)}, Ray{far + Vec3(10, 0, 0), Vec3(-1, 0, 0)}, Real(100)), Real(9),
              Real(1e-2));
  EXPECT_NEAR(
      *ray_entry(Aabb{Vec3(Real(-1e-4)), Vec3(Real(1e-4))}, Ray{Vec3(Real(1e-3), 0, 0), Vec3(-1, 0, 0)}, Real(1)),
      Real(9e-4), Real(1e-8));
}

template <int K>
void check_planes(std::uint64_t seed) {
  test::Random rng(seed);
  int decided = 0;
  for (int a = 0; a < test::kVolumeTypeCount; ++a) {
    const auto type = static_cast<VolumeType>(a);
    for (int i = 0; i < 500; ++i) {
      const auto v = test::make_volume<K>(rng, type, Real(1), Vec3(0), Real(0.5));
      const Real n_length = rng.uniform(Real(0.2), Real(3));
      Vec3 n = rng.unit_vector() * n_length;
      if (i % 50 == 0) n = Vec3(0);
      const Real d = rng.uniform(Real(-4), Real(4));
      const PlaneSide side = std::visit([&](const auto& x) { return classify_plane(x, n, d); }, v.volume);
      double lo = 1e300, hi = -1e300;
      for (const D3& p : v.ref.core) {
        lo = std::min(lo, glm::dot(p, D3(n)));
        hi = std::max(hi, glm::dot(p, D3(n)));
      }
      lo -= v.ref.radius * glm::length(D3(n));
      hi += v.ref.radius * glm::length(D3(n));
      const double margin = 1e-4 * (1 + glm::length(D3(n)));
      if (lo > double(d) + margin) {
        EXPECT_EQ(side, PlaneSide::Front) << test::volume_name(type);
        ++decided;
      } else if (hi < double(d) - margin) {
        EXPECT_EQ(side, PlaneSide::Back) << test::volume_name(type);
        ++decided;
      } else if (lo < double(d) - margin && hi > double(d) + margin) {
        EXPECT_EQ(side, PlaneSide::Straddling) << test::volume_name(type);
        ++decided;
      }
    }
  }
  EXPECT_GT(decided, 2900);
}

TEST(VolumeQueries, PlaneSidesAgainstReferenceRanges) {
  check_planes<6>(640);
  check_planes<14>(641);
  check_planes<18>(642);
  check_planes<26>(643);
}

TEST(VolumeQueries, PlaneNamedCases) {
  const Aabb box{Vec3(0), Vec3(1)};
  EXPECT_EQ(classify_plane(box, Vec3(1, 0, 0), Real(1)), PlaneSide::Straddling);  // touching
  EXPECT_EQ(classify_plane(box, Vec3(1, 0, 0), Real(-0.001)), PlaneSide::Front);
  EXPECT_EQ(classify_plane(box, Vec3(1, 0, 0), Real(1.001)), PlaneSide::Back);
  EXPECT_EQ(classify_plane(box, Vec3(0), Real(-1)), PlaneSide::Front);
  EXPECT_EQ(classify_plane(box, Vec3(0), Real(1)), PlaneSide::Back);
  EXPECT_EQ(classify_plane(box, Vec3(0), Real(0)), PlaneSide::Straddling);
  const BoundingSphere s{Vec3(0), Real(1)};
  EXPECT_EQ(classify_plane(s, Vec3(0, 2, 0), Real(2)), PlaneSide::Straddling);  // n.x = 2 at y = 1
  EXPECT_EQ(classify_plane(s, Vec3(0, 2, 0), Real(2.01)), PlaneSide::Back);
}

}  // namespace test_volume_queries
}  // namespace proxima
