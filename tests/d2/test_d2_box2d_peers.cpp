// Cross-validation of the 2D narrow phase on the 20,000 W9 pairs (polygons2d_pairs.txt)
// against Box2D 2.4.1 and an exact reference of this file:
//   reference  the signed distance of two rounded convex shapes in long double: the cores'
//              Minkowski difference is the convex hull of every vertex difference b_j - a_i;
//              the cores' signed distance is the distance from the origin to that hull's
//              boundary (negative inside), and both radii are subtracted;
//   b2Distance proxies with the shapes' exact radii (a capsule: two vertices and its
//              radius), useRadii = true; Box2D reports 0 for overlapping shapes;
//   b2Collide* b2CollideCircles, b2CollidePolygonAndCircle, b2CollidePolygons,
//              b2CollideEdgeAndCircle and b2CollideEdgeAndPolygon (segments and capsules as
//              two-sided edges), on shapes built as Box2D builds them: every polygon and
//              edge carries the b2_polygonRadius skin on top of its own radius, so Box2D
//              reports the points whose gap is at most the skins; Proxima's collide gets
//              that sum as its contact distance, and Box2D's separations are measured with
//              the exact radii (b2WorldManifold::Initialize), so both sides answer the same
//              question.
// Proxima must agree with the reference on every pair (signed distance, the overlap verdict,
// witness points on the surfaces, the deepest manifold point); Box2D's disagreements with
// the reference are counted by kind and printed ("[box2d-tally]" lines, docs/validation.md).
#include <gtest/gtest.h>

#include <proxima/d2/narrowphase.hpp>

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "d2/d2_reference.hpp"
#include "support/polygons2d_workloads.hpp"
#include "support/workloads.hpp"

#if PROXIMA_HAVE_BOX2D
#include "support/box2d_peers.hpp"
#endif

namespace proxima::d2 {
namespace test_box2d_peers {

namespace pb = proxima::bench;
using LD = long double;

// ---------------------------------------------------------------------------------------
// The exact reference (long double, from the file's numbers)

// Points, hulls and the origin's signed distance to a hull come from d2_reference.hpp.
using d2::test::P;

/// A core (vertices, world frame) and its radius.
struct RefShape {
  std::vector<P> vertices;
  LD radius = 0;
};

/// The core's vertices in the shape's local frame (a circle: its centre; a box: 4 corners).
std::vector<P> local_vertices(const pb::Polygons2dShape& s) {
  if (s.kind == pb::Polygons2dKind::Circle) return {P{}};
  if (s.kind == pb::Polygons2dKind::Box) {
    const LD x = s.half_x, y = s.half_y;
    return {{-x, -y}, {x, -y}, {x, y}, {-x, y}};
  }
  std::vector<P> v;
  for (int i = 0; i < s.count; ++i) v.push_back({s.vertices[std::size_t(i)][0], s.vertices[std::size_t(i)][1]});
  return v;
}

/// The shape's core placed in the world, in long double.
RefShape ref_shape(const pb::Polygons2dShape& s, const pb::Polygons2dPose& pose) {
  const LD c = std::cos(LD(pose.angle)), sn = std::sin(LD(pose.angle));
  RefShape r;
  r.radius = s.radius;
  for (const P& l : local_vertices(s)) r.vertices.push_back({c * l.x - sn * l.y + pose.x, sn * l.x + c * l.y + pose.y});
  return r;
}

/// The exact signed distance of two rounded convex shapes (> 0 apart, < 0 overlapping).
LD ref_signed_distance(const RefShape& a, const RefShape& b) {
  std::vector<P> diff;
  for (const P& pa : a.vertices)
    for (const P& pbv : b.vertices) diff.push_back(pbv - pa);
  return d2::test::point_polygon_signed_distance(P{}, d2::test::hull(diff)) - a.radius - b.radius;
}

/// Signed distance from a world point to the shape's surface (< 0 inside).
LD ref_point_distance(const RefShape& s, const Vec2& p) { return ref_signed_distance(s, RefShape{{P{p.x, p.y}}, 0}); }

// ---------------------------------------------------------------------------------------
// The workload, with Proxima's answers and the reference's

/// One W9 pair as read, its reference shapes and exact signed distance.
struct Pair {
  pb::Polygons2dPair raw;
  RefShape ref_a, ref_b;
  LD reference = 0;  // exact signed distance
  LD scale = 1;      // largest coordinate of the pair (>= 1): the tolerances' scale
};

/// Every pair, and the pairs as the 2D module's shapes (same order).
struct Workload {
  std::vector<Pair> pairs;
  std::vector<pb::Polygons2dShapePair> shapes;
};

/// The pair's largest coordinate plus radius, at least 1.
LD pair_scale(const Pair& p) {
  LD s = 1;
  for (const RefShape* r : {&p.ref_a, &p.ref_b})
    for (const P& v : r->vertices) s = std::max({s, std::abs(v.x) + r->radius, std::abs(v.y) + r->radius});
  return s;
}

/// The W9 pairs file in the shared data folder.
std::string pairs_path() { return pb::workload_path(pb::workload_dir(), "polygons2d_pairs.txt"); }

/// The workload, read and decided once, or the reader's error (a file that is present but
/// cannot be read fails the tests; only an absent file skips them).
const std::variant<Workload, std::string>& load() {
  static const std::variant<Workload, std::string> workload = []() -> std::variant<Workload, std::string> {
    auto raw = pb::read_polygons2d_pairs(pairs_path());
    if (!raw) return raw.error().what();
    auto shapes = pb::to_d2_pairs(*raw);
    if (!shapes) return shapes.error().what();
    Workload w;
    w.shapes = std::move(*shapes);
    for (const pb::Polygons2dPair& r : *raw) {
      Pair p{r, ref_shape(r.a, r.pose_a), ref_shape(r.b, r.pose_b)};
      p.reference = ref_signed_distance(p.ref_a, p.ref_b);
      p.scale = pair_scale(p);
      w.pairs.push_back(std::move(p));
    }
    return w;
  }();
  return workload;
}

/// Loads the workload into `w`: skips the test when the shared file is absent, fails it when
/// the file is present but cannot be read.
#define PROXIMA_W9_LOAD(w)                                                                \
  if (!std::filesystem::exists(pairs_path())) {                                           \
    GTEST_SKIP() << "no W9 workload (polygons2d_pairs.txt) in " << pb::workload_dir();    \
  }                                                                                       \
  ASSERT_TRUE(std::holds_alternative<Workload>(load())) << std::get<std::string>(load()); \
  const Workload* w = &std::get<Workload>(load())

/// Proxima's accuracy at a pair's scale: a few hundred ulps of Real.
LD proxima_tolerance(const Pair& p) { return LD(500) * LD(std::numeric_limits<Real>::epsilon()) * p.scale; }

/// "pair k (line k + 2)": where a pair is in polygons2d_pairs.txt.
std::string describe(std::size_t k) { return "pair " + std::to_string(k) + " (line " + std::to_string(k + 2) + ")"; }

// ---------------------------------------------------------------------------------------
// Proxima against the reference

TEST(D2Box2dPeers, WorkloadMatchesItsManifest) {
  PROXIMA_W9_LOAD(w);
  ASSERT_EQ(w->pairs.size(), 20000u);
  int kinds[5] = {};
  int overlapping = 0;
  for (const Pair& p : w->pairs) {
    ++kinds[int(p.raw.a.kind)], ++kinds[int(p.raw.b.kind)];
    overlapping += p.reference <= 0;
  }
  // MANIFEST.txt: polygon 10003, box2d 8027, circle 7934, capsule2d 7986, segment2d 6050;
  // 9546 pairs overlapping by the generator's exact test.
  EXPECT_EQ(kinds[int(pb::Polygons2dKind::Polygon)], 10003);
  EXPECT_EQ(kinds[int(pb::Polygons2dKind::Box)], 8027);
  EXPECT_EQ(kinds[int(pb::Polygons2dKind::Circle)], 7934);
  EXPECT_EQ(kinds[int(pb::Polygons2dKind::Capsule)], 7986);
  EXPECT_EQ(kinds[int(pb::Polygons2dKind::Segment)], 6050);
  EXPECT_EQ(overlapping, 9546);
}

TEST(D2Box2dPeers, DistanceAndIntersectMatchTheReference) {
  PROXIMA_W9_LOAD(w);
  int overlapping = 0, wrong_distance = 0, wrong_verdict = 0, wrong_witness = 0;
  LD worst = 0;
  for (std::size_t k = 0; k < w->pairs.size(); ++k) {
    const Pair& p = w->pairs[k];
    const pb::Polygons2dShapePair& s = w->shapes[k];
    const DistanceResult r = distance(s.a, s.pose_a, s.b, s.pose_b);
    const bool hit = intersect(s.a, s.pose_a, s.b, s.pose_b);
    const LD tol = proxima_tolerance(p);
    const LD error = std::abs(LD(r.signed_distance) - p.reference);
    worst = std::max(worst, error / p.scale);
    overlapping += hit;
    if (error > tol)
      ++wrong_distance,
          ADD_FAILURE() << describe(k) << ": distance " << r.signed_distance << ", reference " << double(p.reference);
    if (hit != (p.reference <= 0) && std::abs(p.reference) > tol) {
      ++wrong_verdict, ADD_FAILURE() << describe(k) << ": intersect " << hit << ", reference " << double(p.reference);
    }
    // Witnesses on the surfaces, point_b = point_a + signed_distance * normal.
    const LD on_a = ref_point_distance(p.ref_a, r.point_a), on_b = ref_point_distance(p.ref_b, r.point_b);
    const Vec2 gap = r.point_b - (r.point_a + r.signed_distance * r.normal);
    if (std::abs(on_a) > tol || std::abs(on_b) > tol || LD(glm::length(gap)) > tol) {
      ++wrong_witness, ADD_FAILURE() << describe(k) << ": witnesses off the surfaces by " << double(on_a) << ", "
                                     << double(on_b) << ", gap " << glm::length(gap);
    }
  }
  std::cout << "[proxima] W9 distance: worst error " << double(worst) << " x scale; intersect " << overlapping
            << " overlapping; wrong distance " << wrong_distance << ", verdict " << wrong_verdict << ", witness "
            << wrong_witness << "\n";
}

// ---------------------------------------------------------------------------------------
// Regressions found by this comparison

// W9 pair 2345 (a pentagon against a circle): make_core_pair rotated the unset normal of
// the circle's 1-vertex core; an indeterminate value there could raise the invalid-operation
// trap. A signalling NaN in that unused slot must now never be computed with.
TEST(D2Box2dPeers, OneVertexCoreNormalIsNeverRead) {
  const Polygon pentagon = Polygon::create(std::vector<Vec2>{{Real(0.43), Real(0.774)},
                                                             {Real(-0.063), Real(0.625)},
                                                             {Real(-0.725), Real(-0.677)},
                                                             {Real(0.798), Real(0.209)},
                                                             {Real(0.797), Real(0.578)}})
                               .value();
  ConvexCore circle;
  circle.count = 1;
  circle.vertices[0] = Vec2(Real(0));
  circle.radius = Real(0.965);
  circle.normals.fill(Vec2(std::numeric_limits<Real>::signaling_NaN()));
  const Pose pose_a = Pose::from({Real(-1.105), Real(-0.792)}, Real(0.8807));
  const Pose pose_b = Pose::from({Real(-0.264), Real(-1.333)}, Real(2.6444));
  const DistanceResult d = core_distance(pentagon.core(), pose_a, circle, pose_b);
  const DistanceResult m = mirrored(core_distance(circle, pose_b, pentagon.core(), pose_a));
  EXPECT_LT(d.signed_distance, Real(0));
  EXPECT_NEAR(d.signed_distance, m.signed_distance, Real(1e-5));
  EXPECT_EQ(core_manifold(pentagon.core(), pose_a, circle, pose_b).count, 1);
}

#if PROXIMA_HAVE_BOX2D
// ---------------------------------------------------------------------------------------
// Box2D: b2Distance and b2Collide* on the shapes of support/box2d_peers.hpp

using B2Side = pb::Box2dShape;

/// b2Distance on a pair with a fresh simplex cache.
b2DistanceOutput b2_distance(const B2Side& a, const B2Side& b) {
  const b2DistanceInput input = pb::box2d_distance_input(a, b);
  b2SimplexCache cache;
  cache.count = 0;
  b2DistanceOutput output;
  b2Distance(&output, &cache, &input);
  return output;
}

/// Box2D's manifold of a pair in A-to-B terms: point count, normal, deepest separation
/// (measured with the exact radii).
struct B2Contact {
  int count = 0;
  Vec2 normal{Real(1), Real(0)};
  float deepest = 0;
};

/// Box2D's manifold of (a, b), calling b2Collide* with the sides swapped where Box2D takes
/// them in the other order; nothing for edge against edge.
std::optional<B2Contact> b2_collide(const B2Side& a, const B2Side& b) {
  b2Manifold m;
  bool swapped = false;
  if (!pb::box2d_collide_ordered(a, b, m)) {
    if (!pb::box2d_collide_ordered(b, a, m)) return std::nullopt;
    swapped = true;
  }
  const B2Side& first = swapped ? b : a;
  const B2Side& second = swapped ? a : b;
  B2Contact c;
  c.count = m.pointCount;
  if (c.count == 0) return c;
  b2WorldManifold world;
  world.Initialize(&m, first.xf, first.radius, second.xf, second.radius);
  c.normal = Vec2(Real(world.normal.x), Real(world.normal.y)) * Real(swapped ? -1 : 1);
  c.deepest = *std::min_element(world.separations, world.separations + c.count);
  return c;
}

/// Box2D's accuracy at a pair's scale (single precision).
LD box2d_tolerance(const Pair& p) { return LD(500) * LD(FLT_EPSILON) * p.scale; }

/// Counts of the outcomes of one comparison, with the first pair of each outcome.
struct Tally {
  std::string name;
  std::vector<std::pair<std::string, std::pair<int, std::size_t>>> outcomes;
  void add(const std::string& outcome, std::size_t pair) {
    for (auto& o : outcomes) {
      if (o.first == outcome) return void(++o.second.first);
    }
    outcomes.push_back({outcome, {1, pair}});
  }
  void print() const {
    for (const auto& o : outcomes) {
      std::cout << "[box2d-tally] " << name << ": " << o.first << " " << o.second.first << " (first: pair "
                << o.second.second << ")\n";
    }
  }
};

// ---------------------------------------------------------------------------------------
// b2Distance

/// Tallies b2Distance's answer on pair k against the reference and Proxima's witnesses.
void compare_distance(const Pair& p, const pb::Polygons2dShapePair& s, std::size_t k, Tally& t) {
  const B2Side a = pb::make_box2d_shape(p.raw.a, p.raw.pose_a), b = pb::make_box2d_shape(p.raw.b, p.raw.pose_b);
  const b2DistanceOutput out = b2_distance(a, b);
  const LD tol = box2d_tolerance(p);
  const bool b2_overlap = out.distance < 10.0f * b2_epsilon;  // b2TestOverlap's rule
  if (b2_overlap != (p.reference <= 0)) {
    t.add(std::abs(p.reference) <= tol ? "overlap verdict differs within tolerance" : "overlap verdict wrong", k);
  }
  if (p.reference <= tol) return t.add("overlapping (Box2D reports 0)", k);
  const LD error = std::abs(LD(out.distance) - p.reference);
  t.add(error <= tol ? "distance agrees" : "distance wrong", k);
  const DistanceResult r = distance(s.a, s.pose_a, s.b, s.pose_b);
  const LD apart = std::max(glm::length(r.point_a - Vec2(Real(out.pointA.x), Real(out.pointA.y))),
                            glm::length(r.point_b - Vec2(Real(out.pointB.x), Real(out.pointB.y))));
  if (apart <= tol) return t.add("witnesses agree", k);
  const Vec2 wa(Real(out.pointA.x), Real(out.pointA.y)), wb(Real(out.pointB.x), Real(out.pointB.y));
  const bool valid = std::abs(ref_point_distance(p.ref_a, wa)) <= tol &&
                     std::abs(ref_point_distance(p.ref_b, wb)) <= tol &&
                     std::abs(LD(glm::length(wb - wa)) - p.reference) <= tol;
  t.add(valid ? "witnesses differ, both exact (not unique)" : "Box2D witnesses off the surfaces", k);
}

TEST(D2Box2dPeers, B2DistanceAgainstTheReference) {
  PROXIMA_W9_LOAD(w);
  Tally t{"b2Distance", {}};
  for (std::size_t k = 0; k < w->pairs.size(); ++k) compare_distance(w->pairs[k], w->shapes[k], k, t);
  t.print();
}

// ---------------------------------------------------------------------------------------
// b2Collide*

/// True when the pair is rounded and its cores are apart: a clipped manifold point may then
/// be shallower than the shapes' penetration (the rounded end nearest the other core lies
/// past the reference edge's side line and is clipped away).
bool rounded_apart(const Pair& p) { return p.reference + p.ref_a.radius + p.ref_b.radius > 0; }

/// Box2D's axis hysteresis: b2CollideEdgeAndPolygon keeps the edge's axis unless the
/// polygon's separates more by 2 % plus 0.001; b2CollidePolygons keeps A's face unless B's
/// separates more by 0.1 b2_linearSlop.
LD box2d_hysteresis(const Pair& p) { return LD(0.02) * std::abs(p.reference) + LD(0.001); }

/// Our deepest point against the reference: exact, or (rounded cores apart) never deeper.
void judge_our_deepest(const Pair& p, LD ours, LD tol, std::size_t k, Tally& t) {
  if (std::abs(ours - p.reference) <= tol) return t.add("Proxima deepest exact", k);
  if (rounded_apart(p) && ours > p.reference) return t.add("Proxima deepest shallower (clipped rounded end)", k);
  t.add("Proxima deepest wrong", k);
  ADD_FAILURE() << describe(k) << ": deepest manifold separation " << double(ours) << ", reference "
                << double(p.reference);
}

/// Box2D's deepest point against the reference: exact, shallower on rounded cores apart,
/// deeper within its axis hysteresis, or wrong.
void judge_their_deepest(const Pair& p, LD theirs, LD tol, std::size_t k, Tally& t) {
  if (std::abs(theirs - p.reference) <= tol) return t.add("Box2D deepest exact", k);
  if (rounded_apart(p) && theirs > p.reference) return t.add("Box2D deepest shallower (clipped rounded end)", k);
  if (theirs < p.reference && p.reference - theirs <= box2d_hysteresis(p) + tol) {
    return t.add("Box2D deepest deeper within its axis hysteresis", k);
  }
  t.add("Box2D deepest wrong", k);
}

/// The contact verdicts: a point is due when the exact gap is at most the skins.
void judge_verdicts(const Pair& p, int ours, int theirs, LD reach, LD tol, std::size_t k, Tally& t) {
  if (std::abs(p.reference - reach) <= tol) return;
  const bool due = p.reference <= reach;
  if ((theirs > 0) != due) t.add(due ? "Box2D misses a due contact" : "Box2D reports a contact beyond reach", k);
  if ((ours > 0) != due) {
    t.add("Proxima contact verdict wrong", k);
    ADD_FAILURE() << describe(k) << ": " << ours << " manifold points, reference " << double(p.reference);
  }
}

/// Tallies both manifolds of pair k against the reference.
void compare_manifold(const Pair& p, const pb::Polygons2dShapePair& s, std::size_t k, Tally& t) {
  const B2Side a = pb::make_box2d_shape(p.raw.a, p.raw.pose_a), b = pb::make_box2d_shape(p.raw.b, p.raw.pose_b);
  const std::optional<B2Contact> theirs = b2_collide(a, b);
  if (!theirs) return t.add("pairs Box2D has no function for (edge-edge)", k);
  const Real reach = Real(a.skin + b.skin);
  const Manifold ours = collide(s.a, s.pose_a, s.b, s.pose_b, reach);
  const LD tol = std::max(box2d_tolerance(p), proxima_tolerance(p));
  judge_verdicts(p, ours.count, theirs->count, LD(reach), tol, k, t);
  if (ours.count == 0 || theirs->count == 0) return;
  Real depth = ours.points[0].depth;
  for (int i = 1; i < ours.count; ++i) depth = std::max(depth, ours.points[i].depth);
  judge_our_deepest(p, -LD(depth), tol, k, t);
  judge_their_deepest(p, LD(theirs->deepest), tol, k, t);
  const bool same_normal = glm::dot(ours.normal, theirs->normal) >= Real(1 - 1e-5);
  t.add(same_normal ? "normals agree" : "normals differ", k);
  if (same_normal && ours.count != theirs->count) t.add("same normal, point count differs (side lines)", k);
}

TEST(D2Box2dPeers, B2CollideAgainstTheReference) {
  PROXIMA_W9_LOAD(w);
  Tally t{"b2Collide", {}};
  for (std::size_t k = 0; k < w->pairs.size(); ++k) compare_manifold(w->pairs[k], w->shapes[k], k, t);
  t.print();
}
#endif

}  // namespace test_box2d_peers
}  // namespace proxima::d2
