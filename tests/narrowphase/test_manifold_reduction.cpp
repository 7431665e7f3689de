// Tests of the contact reduction (select_contacts / reduce_contacts): each step checked
// against an exhaustive search over the candidates (farthest point, largest triangle,
// largest added area), the deepest point always kept, early stops on coincident and collinear
// points, bounds on k, and a streamed candidate filter.
#include <gtest/gtest.h>

#include <proxima/narrowphase/contact.hpp>

#include <vector>

#include "narrowphase/manifold_reduction.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_manifold_reduction {

using narrow::reduce_contacts;
using narrow::select_contacts;

ContactPoint contact(const Vec3& p, Real depth) {
  ContactPoint c;
  c.point_a = p;
  c.point_b = p - depth * c.normal;
  c.depth = depth;
  return c;
}

Vec3 mid(const ContactPoint& c) { return (c.point_a + c.point_b) * Real(0.5); }

// Projected (z) triangle area, doubled.
Real area2(const Vec3& a, const Vec3& b, const Vec3& c) { return std::abs(glm::cross(b - a, c - a).z); }

TEST(ManifoldReduction, FewerThanKKeepsAllDeepestFirst) {
  std::vector<ContactPoint> in = {contact({0, 0, 0}, Real(0.1)), contact({1, 0, 0}, Real(0.3)),
                                  contact({0, 1, 0}, Real(0.2))};
  std::array<ContactPoint, kMaxContactPoints> out{};
  ASSERT_EQ(reduce_contacts(in, Vec3(0, 0, 1), 4, out), 3);
  EXPECT_EQ(out[0].depth, Real(0.3));
}

TEST(ManifoldReduction, BoundsOnK) {
  std::vector<ContactPoint> in;
  for (int i = 0; i < 8; ++i) in.push_back(contact({Real(i), Real(i * i % 5), 0}, Real(i) * Real(0.01)));
  std::array<ContactPoint, kMaxContactPoints> out{};
  EXPECT_EQ(reduce_contacts(in, Vec3(0, 0, 1), 0, out), 0);
  EXPECT_EQ(reduce_contacts(in, Vec3(0, 0, 1), -3, out), 0);
  EXPECT_EQ(reduce_contacts(in, Vec3(0, 0, 1), 9, out), 4);
  EXPECT_EQ(reduce_contacts({}, Vec3(0, 0, 1), 4, out), 0);
}

TEST(ManifoldReduction, CoincidentAndCollinear) {
  std::vector<ContactPoint> same(6, contact({1, 2, 3}, Real(0.5)));
  std::array<ContactPoint, kMaxContactPoints> out{};
  EXPECT_EQ(reduce_contacts(same, Vec3(0, 0, 1), 4, out), 1);
  std::vector<ContactPoint> line;
  for (int i = 0; i < 7; ++i) line.push_back(contact({Real(i), 0, 0}, Real(0.1) + Real(i == 3) * Real(0.1)));
  ASSERT_EQ(reduce_contacts(line, Vec3(0, 0, 1), 4, out), 2);
  EXPECT_EQ(out[0].point_a.x, Real(3));
  EXPECT_EQ(out[1].point_a.x, Real(0));  // farthest from x = 3 (tie with 6: the first)
}

TEST(ManifoldReduction, EachStepMatchesExhaustiveSearch) {
  test::Random rng(301);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = rng.integer(1, 24);
    std::vector<ContactPoint> in;
    for (int i = 0; i < n; ++i) {
      const Real z = rng.uniform(Real(-0.01), Real(0.01));
      const Real y = rng.uniform(-2, 2);
      const Real x = rng.uniform(-2, 2);
      const Vec3 p(x, y, z);
      in.push_back(contact(p, rng.uniform(Real(-0.1), Real(0.1))));
    }
    const int k = rng.integer(1, 4);
    std::array<ContactPoint, kMaxContactPoints> out{};
    const int count = reduce_contacts(in, Vec3(0, 0, 1), k, out);
    // Random points: no ties, no collinear triples; the fourth step stops when every point
    // lies inside the triangle (checked below).
    ASSERT_GE(count, std::min({n, k, 3})) << trial;
    ASSERT_LE(count, std::min(n, k)) << trial;
    Real deepest = -1;
    for (const ContactPoint& c : in) deepest = std::max(deepest, c.depth);
    EXPECT_EQ(out[0].depth, deepest) << trial;
    const Real eps = Real(1e-5);
    if (count >= 2) {
      Real far = 0;
      for (const ContactPoint& c : in) far = std::max(far, glm::length(mid(c) - mid(out[0])));
      EXPECT_NEAR(glm::length(mid(out[1]) - mid(out[0])), far, eps) << trial;
    }
    if (count >= 3) {
      Real best = 0;
      for (const ContactPoint& c : in) best = std::max(best, area2(mid(out[0]), mid(out[1]), mid(c)));
      EXPECT_NEAR(area2(mid(out[0]), mid(out[1]), mid(out[2])), best, eps) << trial;
    }
    if (count >= 3 && k == 4) {
      // The fourth point adds the most area outside the triangle: the largest of the three
      // quadrilaterals made by attaching it to an edge.
      const Vec3 a = mid(out[0]), b = mid(out[1]), c = mid(out[2]);
      const Real base = area2(a, b, c);
      const auto added = [&](const Vec3& p) {
        // Area added by p outside the triangle (0 inside): hull area minus triangle area.
        const Vec3 e[3][2] = {{a, b}, {b, c}, {c, a}};
        const Real s = glm::cross(b - a, c - a).z > 0 ? Real(1) : Real(-1);
        Real best_edge = 0;
        for (const auto& ed : e) best_edge = std::max(best_edge, -s * glm::cross(ed[1] - ed[0], p - ed[0]).z);
        return best_edge;
      };
      Real best = 0;
      for (const ContactPoint& cp : in) best = std::max(best, added(mid(cp)));
      if (count == 4) {
        EXPECT_NEAR(added(mid(out[3])), best, eps) << trial;
      } else {
        EXPECT_LE(best, eps) << trial;  // nothing outside the triangle
      }
      EXPECT_GT(base, 0);
    }
  }
}

TEST(ManifoldReduction, SquareKeepsCornersAndDeepest) {
  // A 5 x 5 grid with the deepest point at the centre: the centre, then three corners.
  std::vector<ContactPoint> in;
  for (int i = 0; i < 5; ++i) {
    for (int j = 0; j < 5; ++j)
      in.push_back(contact({Real(i), Real(j), 0}, (i == 2 && j == 2) ? Real(0.2) : Real(0.1)));
  }
  std::array<ContactPoint, kMaxContactPoints> out{};
  ASSERT_EQ(reduce_contacts(in, Vec3(0, 0, 1), 4, out), 4);
  EXPECT_EQ(out[0].point_a, Vec3(2, 2, 0));
  for (int i = 1; i < 4; ++i) {
    const Vec3& p = out[static_cast<std::size_t>(i)].point_a;
    EXPECT_TRUE((p.x == 0 || p.x == 4) && (p.y == 0 || p.y == 4)) << i;
  }
}

TEST(ManifoldReduction, StreamedFilter) {
  // select_contacts over a filtered stream: only the used candidates are chosen.
  std::vector<Vec3> pts;
  for (int i = 0; i < 16; ++i) pts.emplace_back(std::cos(Real(i)), std::sin(Real(i)), Real(i % 2));
  std::array<int, 4> chosen{};
  const int count = select_contacts(
      16, [&](int i) { return pts[static_cast<std::size_t>(i)]; },
      [&](int i) { return -pts[static_cast<std::size_t>(i)].z; }, [&](int i) { return i % 2 == 0; }, Vec3(0, 0, 1), 4,
      chosen);
  ASSERT_EQ(count, 4);
  for (int i = 0; i < count; ++i) EXPECT_EQ(chosen[static_cast<std::size_t>(i)] % 2, 0);
}

}  // namespace test_manifold_reduction
}  // namespace proxima
