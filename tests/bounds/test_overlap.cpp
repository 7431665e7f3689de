// Overlap tests of every pair of bounding-volume types (Aabb, sphere, Obb, capsule, k-DOP
// of each K, hull), checked against independent certificates: a common point (found by
// sampling both volumes, by vertex enumeration of the shrunk half-space intersection, or
// as a Frank-Wolfe pair of core points closer than the radii) proves overlap; a
// Frank-Wolfe separating direction whose gap exceeds the radii proves separation. Cases
// within a margin of touching are counted as ambiguous and must stay rare. Plus named
// cases: touching, parallel edges, the k-DOP pair that the slab test gets wrong, far from
// the origin, tiny and huge scales.
#include <gtest/gtest.h>

#include <proxima/bounds/fit_kdop.hpp>
#include <proxima/bounds/overlap.hpp>
#include <proxima/core/tolerance.hpp>

#include <cstdio>
#include <variant>
#include <vector>

#include "bounds/test_bounds_reference.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_overlap {

using test::D3;
using test::VolumeType;

enum class Truth { Overlap, Separate, Ambiguous };

Truth reference_truth(const test::VolumeRef& a, const test::VolumeRef& b, double delta, test::Random& rng) {
  const double rsum = a.radius + b.radius;
  const test::DistanceBounds fw = test::frank_wolfe_distance(a.core, b.core, 4000, 0.1 * delta);
  bool overlap = fw.upper <= rsum - delta;
  const bool separate = fw.lower >= rsum + delta;
  if (!overlap && !separate && !a.planes.empty() && !b.planes.empty()) {
    // Both polytopes: is the intersection of the two shrunk polytopes non-empty?
    std::vector<test::HalfSpaceRef> h;
    for (const auto& p : a.planes) h.push_back({p.n, p.d - delta * glm::length(p.n)});
    for (const auto& p : b.planes) h.push_back({p.n, p.d - delta * glm::length(p.n)});
    overlap = !test::halfspace_vertices(h, 0.0, true).empty();
  }
  if (!overlap && !separate) {
    // Sampling in the intersection of the two boxes.
    const D3 lo = glm::max(a.lo, b.lo), hi = glm::min(a.hi, b.hi);
    if (lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z) {
      for (int i = 0; i < 2000 && !overlap; ++i) {
        const double uz = double(rng.uniform(0, 1));
        const double uy = double(rng.uniform(0, 1));
        const double ux = double(rng.uniform(0, 1));
        const D3 p(lo.x + (hi.x - lo.x) * ux, lo.y + (hi.y - lo.y) * uy, lo.z + (hi.z - lo.z) * uz);
        overlap = test::ref_contains(a, p, -delta) && test::ref_contains(b, p, -delta);
      }
    }
  }
  EXPECT_FALSE(overlap && separate) << "inconsistent reference";
  if (overlap) return Truth::Overlap;
  if (separate) return Truth::Separate;
  return Truth::Ambiguous;
}

struct PairStats {
  int overlap = 0, separate = 0, ambiguous = 0;
};

template <int K>
PairStats run_pair(VolumeType ta, VolumeType tb, int cases, std::uint64_t seed) {
  test::Random rng(seed);
  PairStats stats;
  for (int i = 0; i < cases; ++i) {
    // Variants: unit scale, tiny, huge, far from the origin.
    const int variant = i % 4;
    const Real scale = variant == 1 ? Real(1e-4) : (variant == 2 ? Real(1e4) : Real(1));
    const Vec3 offset = variant == 3 ? Vec3(Real(1e4), Real(-1e4), Real(0.5e4)) : Vec3(0);
    const double magnitude = double(scale) * 4 + double(glm::length(offset));
    const double delta = 1e-3 * double(scale) + 64.0 * double(kEpsilon) * magnitude;
    const auto a = test::make_volume<K>(rng, ta, scale, offset);
    const auto b = test::make_volume<K>(rng, tb, scale, offset);
    const bool ab = std::visit([](const auto& x, const auto& y) { return overlaps(x, y); }, a.volume, b.volume);
    const bool ba = std::visit([](const auto& x, const auto& y) { return overlaps(x, y); }, b.volume, a.volume);
    EXPECT_EQ(ab, ba) << test::volume_name(ta) << "-" << test::volume_name(tb) << " case " << i;
    const Truth truth = reference_truth(a.ref, b.ref, delta, rng);
    switch (truth) {
      case Truth::Overlap:
        ++stats.overlap;
        EXPECT_TRUE(ab) << test::volume_name(ta) << "-" << test::volume_name(tb) << " K=" << K << " case " << i;
        break;
      case Truth::Separate:
        ++stats.separate;
        EXPECT_FALSE(ab) << test::volume_name(ta) << "-" << test::volume_name(tb) << " K=" << K << " case " << i;
        break;
      case Truth::Ambiguous: ++stats.ambiguous; break;
    }
  }
  return stats;
}

template <int K>
void run_all_pairs(int cases, std::uint64_t seed, bool kdop_only) {
  int total = 0, ambiguous = 0;
  for (int a = 0; a < test::kVolumeTypeCount; ++a) {
    for (int b = a; b < test::kVolumeTypeCount; ++b) {
      const auto ta = static_cast<VolumeType>(a), tb = static_cast<VolumeType>(b);
      if (kdop_only && ta != VolumeType::Kdop && tb != VolumeType::Kdop) continue;
      const PairStats s = run_pair<K>(ta, tb, cases, seed + std::uint64_t(a * 10 + b));
      total += s.overlap + s.separate + s.ambiguous;
      ambiguous += s.ambiguous;
      // Both outcomes must be well represented, and ambiguous cases rare.
      EXPECT_GT(s.overlap, cases / 20) << test::volume_name(ta) << "-" << test::volume_name(tb);
      EXPECT_GT(s.separate, cases / 20) << test::volume_name(ta) << "-" << test::volume_name(tb);
      EXPECT_LT(s.ambiguous, cases / 10) << test::volume_name(ta) << "-" << test::volume_name(tb);
    }
  }
  std::printf("K=%d: %d pair cases, %d ambiguous (%.2f%%)\n", K, total, ambiguous, 100.0 * ambiguous / total);
}

TEST(Overlap, AllPairsWithKdop14AgainstReference) { run_all_pairs<14>(300, 1000, false); }
TEST(Overlap, KdopPairsWithKdop6AgainstReference) { run_all_pairs<6>(150, 2000, true); }
TEST(Overlap, KdopPairsWithKdop18AgainstReference) { run_all_pairs<18>(150, 3000, true); }
TEST(Overlap, KdopPairsWithKdop26AgainstReference) { run_all_pairs<26>(150, 4000, true); }

TEST(Overlap, TouchingVolumesOverlap) {
  // Exactly touching closed volumes share their boundary point.
  const Aabb a{Vec3(0), Vec3(1)};
  const Aabb b{Vec3(1, 0, 0), Vec3(2, 1, 1)};
  EXPECT_TRUE(overlaps(a, b));
  const BoundingSphere s{Vec3(2, Real(0.5), Real(0.5)), Real(1)};
  EXPECT_TRUE(overlaps(a, s));
  EXPECT_TRUE(overlaps(s, BoundingSphere{Vec3(4, Real(0.5), Real(0.5)), Real(1)}));
  const Obb o{Vec3(Real(1.5), Real(0.5), Real(0.5)), Mat3(Real(1)), Vec3(Real(0.5))};
  EXPECT_TRUE(overlaps(a, o));
  const BoundingCapsule c{Vec3(-1, 2, 0), Vec3(-1, 5, 0), Real(1)};  // touches a's edge x = 0, y = 1?
  EXPECT_FALSE(overlaps(a, c));  // the corner (0, 1, 0) is at distance sqrt(2) from the core
  const BoundingCapsule c2{Vec3(-1, Real(0.5), Real(0.5)), Vec3(-1, 3, Real(0.5)), Real(1)};
  EXPECT_TRUE(overlaps(a, c2));  // touches the face x = 0
  Kdop14 k = *fit_kdop<14>(std::vector<Vec3>{Vec3(1, 0, 0), Vec3(2, 1, 1), Vec3(2, 0, 1)});
  EXPECT_TRUE(overlaps(a, k));
  EXPECT_TRUE(overlaps(k, *fit_kdop<14>(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 1, 1)})));
}

TEST(Overlap, ParallelObbEdgesDoNotFalselySeparate) {
  // Boxes with parallel axes (cross products vanish) that overlap.
  const Mat3 r = glm::mat3_cast(glm::angleAxis(Real(0.3), glm::normalize(Vec3(1, 2, 3))));
  const Obb a{Vec3(0), r, Vec3(1, 2, 3)};
  for (int i = 0; i < 100; ++i) {
    const Vec3 shift =
        r * Vec3(Real(1.9) * Real(i % 3 == 0), Real(3.9) * Real(i % 3 == 1), Real(5.9) * Real(i % 3 == 2));
    EXPECT_TRUE(overlaps(a, Obb{shift, r, Vec3(1, 2, 3)}));
    EXPECT_FALSE(overlaps(a, Obb{shift * Real(1.1), r, Vec3(1, 2, 3)}));
  }
}

TEST(Overlap, KdopIsExactWhereTheSlabTestIsConservative) {
  // Two 14-DOPs (tetrahedra-like corners) whose slab intervals all overlap but which are
  // disjoint: separated by an axis that is a cross product of edge directions.
  const std::vector<Vec3> a_pts{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  Kdop14 a = *fit_kdop<14>(a_pts);
  int conservative_only = 0;
  test::Random rng(77);
  for (int i = 0; i < 4000; ++i) {
    std::vector<Vec3> b_pts;
    const Vec3 c = rng.vec3(Real(-0.3), Real(1));
    for (int k = 0; k < 3; ++k) b_pts.push_back(c + rng.vec3(Real(-0.4), Real(0.4)));
    const Kdop14 b = *fit_kdop<14>(b_pts);
    if (!kdop_slabs_overlap(a, b)) {
      EXPECT_FALSE(overlaps(a, b));
      continue;
    }
    const test::VolumeRef ra = test::ref_of(a), rb = test::ref_of(b);
    const test::DistanceBounds fw = test::frank_wolfe_distance(ra.core, rb.core, 1000, 1e-4);
    if (fw.lower > 1e-3) {
      ++conservative_only;
      EXPECT_FALSE(overlaps(a, b));
    }
  }
  EXPECT_GT(conservative_only, 5);
}

TEST(Overlap, EmptyAndDegenerateVolumes) {
  const Aabb empty;
  const Aabb unit{Vec3(0), Vec3(1)};
  EXPECT_FALSE(overlaps(empty, unit));
  EXPECT_FALSE(overlaps(empty, BoundingSphere{Vec3(0), Real(10)}));
  EXPECT_FALSE(overlaps(empty, Obb{Vec3(0), Mat3(Real(1)), Vec3(10)}));
  EXPECT_FALSE(overlaps(empty, BoundingCapsule{Vec3(0), Vec3(1), Real(10)}));
  EXPECT_FALSE(overlaps(empty, *fit_kdop<26>(std::vector<Vec3>{Vec3(0), Vec3(1)})));
  EXPECT_FALSE(overlaps(Kdop26(), *fit_kdop<26>(std::vector<Vec3>{Vec3(0), Vec3(1)})));
  EXPECT_FALSE(overlaps(Kdop26(), BoundingSphere{Vec3(0), Real(10)}));
  // Points and segments as volumes of radius 0.
  const BoundingSphere point{Vec3(Real(0.5)), Real(0)};
  EXPECT_TRUE(overlaps(unit, point));
  EXPECT_TRUE(overlaps(point, BoundingCapsule{Vec3(0), Vec3(1), Real(0)}));
  EXPECT_FALSE(overlaps(BoundingSphere{Vec3(Real(0.5), 0, 0), Real(0)}, BoundingCapsule{Vec3(0), Vec3(1), Real(0)}));
  // Flat k-DOPs and boxes.
  const Kdop18 flat = *fit_kdop<18>(std::vector<Vec3>{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)});
  EXPECT_TRUE(overlaps(unit, flat));
  EXPECT_TRUE(overlaps(flat, BoundingSphere{Vec3(Real(0.2), Real(0.2), Real(-0.5)), Real(0.5)}));
  EXPECT_FALSE(overlaps(flat, BoundingSphere{Vec3(Real(0.2), Real(0.2), Real(-0.5)), Real(0.49)}));
}

}  // namespace test_overlap
}  // namespace proxima
