// Tests of Bvh: structure invariants checked exhaustively (every primitive in exactly one
// leaf, every node box the exact union of what is below it, children after parents, depth
// bound), box queries against brute force over all primitives, refit, adversarial inputs.

#include <gtest/gtest.h>

#include <proxima/spatial/bvh.hpp>

#include <algorithm>
#include <cmath>
#include <vector>

#include "support/random.hpp"

namespace proxima {
namespace test_bvh {

std::vector<Vec3> centers_of(const std::vector<Aabb>& boxes) {
  std::vector<Vec3> c(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) c[i] = boxes[i].center();
  return c;
}

bool same_box(const Vec3& lo, const Vec3& hi, const BvhNode& n) { return lo == n.min && hi == n.max; }

/// Checks every structural invariant of `bvh` built over `boxes`.
void check_structure(const Bvh& bvh, const std::vector<Aabb>& boxes, std::uint32_t max_leaf) {
  const auto nodes = bvh.nodes();
  const auto prims = bvh.primitives();
  if (boxes.empty()) {
    EXPECT_TRUE(bvh.empty());
    EXPECT_TRUE(prims.empty());
    return;
  }
  ASSERT_EQ(prims.size(), boxes.size());
  // primitives() is a permutation.
  std::vector<int> seen(boxes.size(), 0);
  for (std::uint32_t p : prims) {
    ASSERT_LT(p, boxes.size());
    ++seen[p];
  }
  for (int s : seen) ASSERT_EQ(s, 1);
  // Walk from the root: every node reached once, leaves cover each slot exactly once.
  std::vector<int> reached(nodes.size(), 0);
  std::vector<int> slot_used(prims.size(), 0);
  std::uint32_t leaves = 0, max_depth = 0;
  struct Item {
    std::uint32_t node, depth;
  };
  std::vector<Item> stack{{0, 1}};
  while (!stack.empty()) {
    const Item it = stack.back();
    stack.pop_back();
    ASSERT_LT(it.node, nodes.size());
    ++reached[it.node];
    max_depth = std::max(max_depth, it.depth);
    const BvhNode& n = nodes[it.node];
    Vec3 lo(kRealMax), hi(-kRealMax);
    if (n.is_leaf()) {
      ++leaves;
      EXPECT_LE(n.count, max_leaf);
      ASSERT_LE(std::size_t(n.first) + n.count, prims.size());
      for (std::uint32_t i = n.first; i != n.first + n.count; ++i) {
        ++slot_used[i];
        lo = glm::min(lo, boxes[prims[i]].min);
        hi = glm::max(hi, boxes[prims[i]].max);
      }
    } else {
      ASSERT_GT(n.first, it.node) << "children must come after their parent";
      ASSERT_LT(n.first + 1, nodes.size());
      for (std::uint32_t c = n.first; c != n.first + 2; ++c) {
        lo = glm::min(lo, nodes[c].min);
        hi = glm::max(hi, nodes[c].max);
        stack.push_back({c, it.depth + 1});
      }
    }
    EXPECT_TRUE(same_box(lo, hi, n)) << "node " << it.node << " box is not the union of its contents";
  }
  for (int r : reached) EXPECT_EQ(r, 1);
  for (int s : slot_used) EXPECT_EQ(s, 1);
  EXPECT_LE(max_depth, Bvh::kMaxDepth);
  const BvhStats st = bvh.stats();
  EXPECT_EQ(st.node_count, nodes.size());
  EXPECT_EQ(st.leaf_count, leaves);
  EXPECT_EQ(st.depth, max_depth);
  EXPECT_EQ(st.node_count, 2 * st.leaf_count - 1);
  EXPECT_GE(st.sah_cost, Real(1));
}

/// Primitives whose box overlaps `q`, by the tree and by brute force, compared as sets.
void check_query(const Bvh& bvh, const std::vector<Aabb>& boxes, const Aabb& q) {
  std::vector<std::uint32_t> got, want;
  bvh.traverse([&](const BvhNode& n) { return n.bounds().overlaps(q); },
               [&](std::uint32_t p) {
                 if (boxes[p].overlaps(q)) got.push_back(p);
                 return true;
               });
  for (std::uint32_t i = 0; i < boxes.size(); ++i)
    if (boxes[i].overlaps(q)) want.push_back(i);
  std::sort(got.begin(), got.end());
  ASSERT_EQ(got, want);
}

std::vector<Aabb> random_boxes(test::Random& rng, std::size_t n, Real extent, Real max_size) {
  std::vector<Aabb> boxes(n);
  for (Aabb& b : boxes) {
    const Vec3 c = rng.vec3(-extent, extent);
    const Vec3 h = rng.in_box(Vec3(0), Vec3(max_size));
    b = Aabb::from_center_half_extents(c, h);
  }
  return boxes;
}

TEST(Bvh, EmptyInput) {
  const Bvh bvh = Bvh::build({}, {});
  EXPECT_TRUE(bvh.empty());
  EXPECT_FALSE(bvh.bounds().is_valid());
  EXPECT_EQ(bvh.stats().node_count, 0u);
  EXPECT_EQ(bvh.stats().depth, 0u);
  int visits = 0;
  EXPECT_TRUE(bvh.traverse([&](const BvhNode&) { return ++visits, true; }, [&](std::uint32_t) { return true; }));
  EXPECT_EQ(visits, 0);
  Bvh copy = bvh;
  copy.refit({});
  EXPECT_TRUE(copy.empty());
}

TEST(Bvh, SinglePrimitive) {
  const std::vector<Aabb> boxes{{Vec3(1, 2, 3), Vec3(4, 5, 6)}};
  Bvh bvh = Bvh::build(boxes, centers_of(boxes));
  ASSERT_EQ(bvh.nodes().size(), 1u);
  EXPECT_TRUE(bvh.nodes()[0].is_leaf());
  EXPECT_EQ(bvh.primitives()[0], 0u);
  EXPECT_EQ(bvh.bounds().min, Vec3(1, 2, 3));
  EXPECT_EQ(bvh.bounds().max, Vec3(4, 5, 6));
  const BvhStats s = bvh.stats();
  EXPECT_EQ(s.leaf_count, 1u);
  EXPECT_EQ(s.depth, 1u);
  const std::vector<Aabb> moved{{Vec3(-1), Vec3(0)}};
  bvh.refit(moved);
  EXPECT_EQ(bvh.bounds().min, Vec3(-1));
  EXPECT_EQ(bvh.bounds().max, Vec3(0));
}

TEST(Bvh, RandomBoxesStructureAndQueriesMatchBruteForce) {
  test::Random rng(101);
  struct Config {
    std::size_t n;
    std::uint32_t leaf, bins;
  };
  for (const Config cfg : {Config{1000, 4, 16}, Config{2000, 1, 2}, Config{777, 16, 64}, Config{3, 4, 16},
                           Config{5, 1, 16}, Config{1500, 255, 8}}) {
    SCOPED_TRACE(cfg.n);
    const std::vector<Aabb> boxes = random_boxes(rng, cfg.n, Real(10), Real(0.8));
    BvhBuildOptions opt;
    opt.max_leaf_size = cfg.leaf;
    opt.bin_count = cfg.bins;
    const Bvh bvh = Bvh::build(boxes, centers_of(boxes), opt);
    check_structure(bvh, boxes, cfg.leaf);
    for (int q = 0; q < 500; ++q) {
      const Real half = rng.uniform(0, 3);
      const Aabb query = Aabb::from_center_half_extents(rng.vec3(-11, 11), Vec3(half));
      check_query(bvh, boxes, query);
    }
  }
}

TEST(Bvh, RefitKeepsExactBoxesAndQueries) {
  test::Random rng(202);
  std::vector<Aabb> boxes = random_boxes(rng, 3000, Real(20), Real(1));
  Bvh bvh = Bvh::build(boxes, centers_of(boxes));
  const std::vector<BvhNode> before(bvh.nodes().begin(), bvh.nodes().end());
  for (int round = 0; round < 3; ++round) {
    for (Aabb& b : boxes) {  // move and resize every box
      const Vec3 d = rng.vec3(-3, 3);
      b = Aabb::from_center_half_extents(b.center() + d, Vec3(rng.uniform(0, 2)));
    }
    bvh.refit(boxes);
    check_structure(bvh, boxes, 4);
    for (int q = 0; q < 700; ++q) {
      const Real half = rng.uniform(0, 4);
      const Aabb query = Aabb::from_center_half_extents(rng.vec3(-25, 25), Vec3(half));
      check_query(bvh, boxes, query);
    }
  }
  // Topology unchanged.
  ASSERT_EQ(bvh.nodes().size(), before.size());
  for (std::size_t i = 0; i < before.size(); ++i) {
    EXPECT_EQ(bvh.nodes()[i].first, before[i].first);
    EXPECT_EQ(bvh.nodes()[i].count, before[i].count);
  }
}

TEST(Bvh, TraversalStopsWhenLeafSaysSo) {
  test::Random rng(7);
  const std::vector<Aabb> boxes = random_boxes(rng, 500, Real(5), Real(1));
  const Bvh bvh = Bvh::build(boxes, centers_of(boxes));
  int calls = 0;
  EXPECT_FALSE(bvh.traverse([](const BvhNode&) { return true; }, [&](std::uint32_t) { return ++calls < 10; }));
  EXPECT_EQ(calls, 10);
}

TEST(Bvh, AllCentresEqual) {
  // Same centre, different sizes: SAH has nothing to bin; median splits by position.
  test::Random rng(3);
  std::vector<Aabb> boxes(5000);
  for (Aabb& b : boxes) b = Aabb::from_center_half_extents(Vec3(1, -2, 3), Vec3(rng.uniform(0, 1)));
  const Bvh bvh = Bvh::build(boxes, centers_of(boxes));
  check_structure(bvh, boxes, 4);
  EXPECT_LE(bvh.stats().depth, 15u);  // balanced: ceil(log2(5000 / 4)) + 1
  // Identical boxes too.
  const std::vector<Aabb> same(1000, Aabb{Vec3(0), Vec3(1)});
  check_structure(Bvh::build(same, centers_of(same)), same, 4);
  for (int q = 0; q < 50; ++q) check_query(bvh, boxes, Aabb::from_center_half_extents(rng.vec3(-2, 3), Vec3(0.5)));
}

TEST(Bvh, PointsOnALine) {
  std::vector<Aabb> boxes;
  for (int i = 0; i < 4000; ++i) boxes.push_back(Aabb::from_point(Vec3(Real(i) * Real(0.25), 0, 0)));
  const Bvh bvh = Bvh::build(boxes, centers_of(boxes));
  check_structure(bvh, boxes, 4);
  test::Random rng(4);
  for (int q = 0; q < 300; ++q) {
    const Aabb query{Vec3(rng.uniform(-10, 1010), -1, -1), Vec3(0)};
    const Aabb qq{query.min, Vec3(query.min.x + rng.uniform(0, 5), 1, 1)};
    check_query(bvh, boxes, qq);
  }
}

TEST(Bvh, ExponentialSpacingNeverExceedsMaxDepth) {
  // Centres at 1.2^i on a line: every SAH plane peels off the largest few, which would give
  // a depth near n; the builder must fall back to median splits before kMaxDepth.
  for (const std::size_t n : {std::size_t(150), std::size_t(220)}) {
    std::vector<Aabb> boxes;
    Real x = 1;
    for (std::size_t i = 0; i < n; ++i, x *= Real(1.2))
      boxes.push_back(Aabb::from_center_half_extents(Vec3(x, 0, 0), Vec3(x * Real(0.01))));
    for (const std::uint32_t leaf : {1u, 4u}) {
      BvhBuildOptions opt;
      opt.max_leaf_size = leaf;
      const Bvh bvh = Bvh::build(boxes, centers_of(boxes), opt);
      check_structure(bvh, boxes, leaf);
      EXPECT_LE(bvh.stats().depth, Bvh::kMaxDepth);
      for (std::size_t i = 0; i < n; i += 7) check_query(bvh, boxes, boxes[i]);
    }
  }
}

TEST(Bvh, MillionScaleSpread) {
  // Tiny and huge boxes mixed, positions spread over 1e6.
  test::Random rng(5);
  std::vector<Aabb> boxes(3000);
  for (Aabb& b : boxes) {
    const Real scale = std::pow(Real(10), rng.uniform(-3, 3));
    const Real spread = std::pow(Real(10), rng.uniform(-6, 0));
    b = Aabb::from_center_half_extents(rng.vec3(-1, 1) * Real(1e6) * spread, Vec3(scale));
  }
  const Bvh bvh = Bvh::build(boxes, centers_of(boxes));
  check_structure(bvh, boxes, 4);
  for (int q = 0; q < 500; ++q) {
    const Real s = std::pow(Real(10), rng.uniform(-3, 5));
    check_query(bvh, boxes, Aabb::from_center_half_extents(rng.vec3(-1, 1) * s, Vec3(s * Real(0.1))));
  }
}

TEST(Bvh, FlatAndDegenerateBoxes) {
  // Boxes flat on z (a terrain) and zero-size points: area zero everywhere.
  test::Random rng(6);
  std::vector<Aabb> boxes(2000);
  for (Aabb& b : boxes) {
    const Real cy = rng.uniform(-5, 5);
    const Real cx = rng.uniform(-5, 5);
    const Vec3 c(cx, cy, 0);
    b = {c, c + Vec3(rng.uniform(0, Real(0.1)), 0, 0)};
  }
  const Bvh bvh = Bvh::build(boxes, centers_of(boxes));
  check_structure(bvh, boxes, 4);
  for (int q = 0; q < 300; ++q) {
    const Real half = rng.uniform(0, 1);
    const Real cy = rng.uniform(-5, 5);
    const Real cx = rng.uniform(-5, 5);
    check_query(bvh, boxes, Aabb::from_center_half_extents(Vec3(cx, cy, 0), Vec3(half)));
  }
}

}  // namespace test_bvh
}  // namespace proxima
