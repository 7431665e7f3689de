#pragma once
// The convention checks of contact.hpp applied to one placed pair, shared by the invariant
// sweep and the degenerate-case suite. Every check compares the narrow phase with something
// it did not compute: the shapes' own closest_point (surfaces), the same query after a rigid
// move of B along the reported normal (the signed distance must change by exactly the move),
// the query with A and B swapped, and the boolean and manifold queries.
#include "narrowphase_test_util.hpp"

namespace proxima::test {

/// Collects the failed checks of many cases and reports the first few in full.
class PairChecker {
 public:
  /// Checks one case; `label` names it in messages (pair, seed, index).
  void check(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
             const std::string& label);

  /// Cases checked, cases with at least one failed check.
  int cases() const { return cases_; }
  int failed_cases() const { return failed_cases_; }
  /// The first failures, described (one line each, with a reproducer).
  const std::vector<std::string>& messages() const { return messages_; }
  /// Distinct names of the checks that failed, with their counts.
  std::string summary() const {
    std::string s;
    for (const auto& [name, count] : counts_) s += name + "=" + std::to_string(count) + " ";
    return s;
  }
  /// Extra relative slack for degenerate inputs (multiplies the tolerance).
  Real slack = Real(1);

 private:
  void fail(const std::string& check, const std::string& detail);
  int cases_ = 0;
  int failed_cases_ = 0;
  bool current_failed_ = false;
  std::string current_;
  std::vector<std::string> messages_;
  std::vector<std::pair<std::string, int>> counts_;
};

inline void PairChecker::fail(const std::string& check, const std::string& detail) {
  if (!current_failed_) ++failed_cases_;
  current_failed_ = true;
  bool found = false;
  for (auto& [name, count] : counts_) {
    if (name == check) {
      ++count;
      found = true;
    }
  }
  if (!found) counts_.emplace_back(check, 1);
  if (messages_.size() < 6) messages_.push_back(check + ": " + detail + "\n    " + current_);
}

inline std::string fmt3(const Vec3& v) {
  std::ostringstream o;
  o.precision(9);
  o << "(" << v.x << "," << v.y << "," << v.z << ")";
  return o.str();
}

inline void PairChecker::check(const Shape& a, const Transform& pose_a, const Shape& b, const Transform& pose_b,
                               const std::string& label) {
  ++cases_;
  current_failed_ = false;
  current_ = label + " A=" + describe(a, pose_a) + " B=" + describe(b, pose_b);
  const ShapeType ta = shape_type(a);
  const ShapeType tb = shape_type(b);
  // Tolerance: the checks' relative accuracy at the shapes' size (at least four times the
  // library's own linear_tolerance there), plus the rounding of coordinates far from the
  // origin.
  const Real size = std::max({shape_scale(a), shape_scale(b), Real(1e-30)});
  const Real far = std::max(max_abs_component(pose_a.position), max_abs_component(pose_b.position));
  const Real tol =
      slack * std::max(narrow_tolerance(size), Real(4) * linear_tolerance(size)) + Real(256) * kEpsilon * far;
  const PairRequest request{};

  const DistanceResult d = distance(a, pose_a, b, pose_b, request);
  const bool hit = intersect(a, pose_a, b, pose_b, request);
  const ContactManifold m = collide(a, pose_a, b, pose_b, request);
  std::ostringstream got;
  got.precision(9);
  got << "sd=" << d.signed_distance << " pa=" << fmt3(d.point_a) << " pb=" << fmt3(d.point_b) << " n=" << fmt3(d.normal)
      << " status=" << status_name(d.status) << " method=" << int(d.method) << " hit=" << hit << " count=" << m.count;
  const std::string g = got.str();

  if (d.status == PairStatus::InvalidInput) fail("status_invalid", g);
  if (!std::isfinite(d.signed_distance) || !finite3(d.point_a) || !finite3(d.point_b) || !finite3(d.normal)) {
    fail("non_finite", g);
    return;
  }
  if (std::abs(glm::length(d.normal) - Real(1)) > Real(100) * kEpsilon) fail("normal_not_unit", g);

  // Two half-spaces: only the boolean answer is meaningful (they overlap unless their
  // normals are opposite and the planes apart).
  if (ta == ShapeType::HalfSpace && tb == ShapeType::HalfSpace) {
    const HalfSpace& ha = std::get<HalfSpace>(a);
    const HalfSpace& hb = std::get<HalfSpace>(b);
    const Vec3 na = pose_a.apply_vector(ha.normal());
    const Vec3 nb = pose_b.apply_vector(hb.normal());
    if (glm::dot(na, nb) > Real(-0.999) && !hit) fail("halfspaces_not_overlapping", g);
    return;
  }

  const Real sd = d.signed_distance;
  // Boolean, distance and manifold agree away from the boundary.
  if (sd > tol && hit) fail("intersect_true_but_apart", g);
  if (sd < -tol && !hit) fail("intersect_false_but_overlap", g);
  if (sd > tol && m.count > 0) fail("collide_points_but_apart", g);
  if (sd < -tol && m.count == 0) fail("collide_empty_but_overlap", g);

  // Witnesses: point_b = point_a + sd * normal, each on its own surface.
  if (glm::length(d.point_a + sd * d.normal - d.point_b) > tol) fail("witness_relation", g);
  const Real on_a = surface_distance(a, pose_a, d.point_a);
  const Real on_b = surface_distance(b, pose_b, d.point_b);
  if (std::abs(on_a) > tol) fail("point_a_off_surface", g + " surface_distance=" + std::to_string(on_a));
  if (std::abs(on_b) > tol) fail("point_b_off_surface", g + " surface_distance=" + std::to_string(on_b));

  // Rigid moves of B along the normal: by -sd they touch, by -sd + eps they are apart by
  // eps, by -sd - eps they are at most eps apart.
  const Real eps = Real(4) * tol;
  auto moved = [&](Real t) {
    Transform p = pose_b;
    p.position += t * d.normal;
    return p;
  };
  const Transform touch = moved(-sd);
  const DistanceResult dt = distance(a, pose_a, b, touch, request);
  if (std::abs(dt.signed_distance) > Real(2) * tol) {
    fail("move_to_touch", g + " after move sd=" + std::to_string(dt.signed_distance));
  }
  const Transform apart = moved(-sd + eps);
  if (intersect(a, pose_a, b, apart, request)) fail("move_apart_still_intersects", g);
  const DistanceResult da = distance(a, pose_a, b, apart, request);
  if (da.signed_distance < eps - Real(2) * tol) {
    fail("move_apart_distance", g + " after move sd=" + std::to_string(da.signed_distance));
  }
  // Moved eps past touching, the Minkowski difference holds the point -eps * normal, so
  // they are at most eps apart (overlapping when both are thick there).
  const Transform closer = moved(-sd - eps);
  PairRequest near_request;
  near_request.contact_distance = eps + tol;
  if (!intersect(a, pose_a, b, closer, near_request)) fail("move_closer_not_touching", g);

  // Swapped order: same distance, opposite normal.
  const DistanceResult s = distance(b, pose_b, a, pose_a, request);
  if (std::abs(s.signed_distance - sd) > tol) {
    fail("swap_distance", g + " swapped sd=" + std::to_string(s.signed_distance));
  }
  // (Apart only: an overlap may have several directions of least depth.)
  if (sd > tol && glm::dot(s.normal, -d.normal) < Real(0.99)) {
    fail("swap_normal", g + " swapped n=" + fmt3(s.normal));
  }

  // Manifold: unit shared normal, depth no larger than the pair's, witnesses related.
  if (m.count > 0) {
    if (std::abs(glm::length(m.normal) - Real(1)) > Real(100) * kEpsilon) fail("manifold_normal_not_unit", g);
    Real deepest = -kRealMax;
    for (int i = 0; i < m.count; ++i) {
      const ContactPoint& c = m.points[static_cast<std::size_t>(i)];
      if (!finite3(c.point_a) || !finite3(c.point_b) || !std::isfinite(c.depth)) {
        fail("manifold_non_finite", g);
        continue;
      }
      deepest = std::max(deepest, c.depth);
      if (c.depth > -sd + tol) {
        fail("manifold_depth_exceeds_pair",
             g + " point depth=" + std::to_string(c.depth) + " manifold n=" + fmt3(m.normal));
      }
      if (glm::length(c.normal - m.normal) > Real(1e-3)) fail("manifold_point_normal", g);
      if (glm::length(c.point_a - c.depth * c.normal - c.point_b) > tol) fail("manifold_witness_relation", g);
    }
    // The deepest point carries the pair's penetration (whatever normal a tie picked).
    if (sd < -tol && deepest < -sd - tol) {
      fail("manifold_shallower_than_pair", g + " deepest=" + std::to_string(deepest) + " manifold n=" + fmt3(m.normal));
    }
  }
}

}  // namespace proxima::test
