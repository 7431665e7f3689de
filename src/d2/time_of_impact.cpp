/// @file time_of_impact.cpp
/// Certified time of impact of two moving 2D shapes.
///
/// Steps (conservative advancement: Mirtich, "Impulse-based dynamic simulation of rigid body
/// systems", 1996, ch. 3; the same certificate as ccd/time_of_impact.cpp):
///   1. validate the motions and options; the tolerance is raised to the pair's precision
///      floor, 64 epsilon times the scale of the shapes and their motions;
///   2. for each pair of parts (a convex shape is one part, a chain one part per segment,
///      skipped when the other shape's vertex centroid starts behind it), from t = 0:
///      measure the signed distance d and normal n (core_distance); the separation along the
///      fixed n can shrink no faster than mu = (v_a - v_b) . n + |w_a| R_a + |w_b| R_b (R: the
///      part's reach from its shape's origin), so it stays above the target until
///      t + (d - target) / mu; advance there; stop within the tolerance (Hit), when mu <= 0
///      (Separated for all time), or past the best time found so far;
///   3. the earliest part pair wins; t = 0 follows the contract of time_of_impact.hpp.

#include <proxima/core/tolerance.hpp>
#include <proxima/d2/narrowphase.hpp>
#include <proxima/d2/time_of_impact.hpp>

#include <cmath>
#include <string>
#include <vector>

namespace proxima::d2 {
namespace {

/// A moving part: its core, its motion and its reach from the shape's origin.
struct MovingPart {
  ConvexCore core;
  const Motion* motion = nullptr;
  Real reach = Real(0);
  PartIndex part = -1;
};

Real core_reach(const ConvexCore& core) {
  Real r = Real(0);
  for (int i = 0; i < core.count; ++i) r = std::max(r, glm::length(core.vertices[i]));
  return r + core.radius;
}

std::optional<Error> check_motion(const Motion& m, const std::string& name) {
  const Rotation& q = m.start.rotation;
  if (!is_finite(m.start.position) || max_abs_component(m.start.position) > kMaxCoordinate || !std::isfinite(q.c) ||
      !std::isfinite(q.s) || std::abs(q.c * q.c + q.s * q.s - Real(1)) > Real(1e-3)) {
    return Error{ErrorCode::NotFinite, name + ".start", "must be a finite pose with a unit rotation"};
  }
  if (!is_finite(m.translation) || max_abs_component(m.translation) > kMaxCoordinate) {
    return Error{ErrorCode::NotFinite, name + ".translation", "must be finite"};
  }
  if (!std::isfinite(m.rotation)) return Error{ErrorCode::NotFinite, name + ".rotation", "must be finite"};
  return std::nullopt;
}

struct Advance {
  Real tolerance = Real(0);
  Real target = Real(0);
  int max_iterations = 0;
};

/// The closing-speed bound along n (A to B) of the two parts, per unit time.
Real closing_speed(const MovingPart& a, const MovingPart& b, const Vec2& n) {
  return glm::dot(a.motion->translation - b.motion->translation, n) + std::abs(a.motion->rotation) * a.reach +
         std::abs(b.motion->rotation) * b.reach;
}

ToiResult fill(ToiResult r, const DistanceResult& d, const MovingPart& a, const MovingPart& b) {
  r.distance = d.signed_distance;
  r.point_a = d.point_a;
  r.point_b = d.point_b;
  r.point = (d.point_a + d.point_b) * Real(0.5);
  r.normal = d.normal;
  r.part_a = a.part;
  r.part_b = b.part;
  return r;
}

/// Conservative advancement of one part pair over [0, t_max].
ToiResult advance(const MovingPart& a, const MovingPart& b, const Advance& opt, Real t_max, int& iterations) {
  ToiResult r;
  Real t = Real(0), certified = Real(0);
  for (int step = 0;; ++step) {
    const DistanceResult d = core_distance(a.core, a.motion->at(t), b.core, b.motion->at(t));
    ++iterations;
    const Real mu = closing_speed(a, b, d.normal);
    if (step == 0 && d.signed_distance < -opt.tolerance) {
      r = fill(r, d, a, b);
      r.status = CcdStatus::InitiallyOverlapping;
      r.toi = r.t_lower = r.t_upper = Real(0);
      r.depth = -d.signed_distance;
      return r;
    }
    const Real gap = d.signed_distance - opt.target;
    if (gap <= opt.tolerance) {
      if (step == 0 && mu <= opt.tolerance) return r;  // touching but not approaching
      r = fill(r, d, a, b);
      r.status = CcdStatus::Hit;
      r.toi = r.t_upper = t;
      r.t_lower = gap > Real(0) ? t : certified;
      return r;
    }
    certified = t;
    if (!(mu > Real(0))) break;  // the separation along n never shrinks
    t += gap / mu;
    if (t > t_max) break;
    if (step + 1 >= opt.max_iterations) {
      r.status = CcdStatus::MaxIterations;
      r.toi = r.t_lower = certified;
      r.t_upper = Real(1);
      return r;
    }
  }
  r.status = CcdStatus::Separated;
  r.toi = r.t_lower = r.t_upper = Real(1);
  return r;
}

/// The parts of a shape: the shape itself, or one per chain segment.
std::vector<MovingPart> parts_of(const Shape& shape, const Motion& motion) {
  std::vector<MovingPart> parts;
  if (shape.is_convex()) {
    MovingPart p{shape.core(), &motion, Real(0), -1};
    p.reach = core_reach(p.core);
    parts.push_back(p);
    return parts;
  }
  const Chain& chain = shape.chain();
  Real reach = Real(0);
  for (const Vec2& q : chain.points()) reach = std::max(reach, glm::length(q));
  for (int i = 0; i < chain.segment_count(); ++i) parts.push_back({chain.segment(i).core(), &motion, reach, i});
  return parts;
}

/// True when `other`'s vertex centroid starts behind the one-sided chain segment `segment`.
bool behind(const MovingPart& segment, const MovingPart& other) {
  Vec2 c(Real(0));
  for (int i = 0; i < other.core.count; ++i) c += other.motion->start.apply(other.core.vertices[i]);
  c /= static_cast<Real>(other.core.count);
  const Vec2 local = segment.motion->start.inverse_apply(c);
  return glm::dot(segment.core.normals[0], local - segment.core.vertices[0]) < Real(0);
}

Real motion_scale(const std::vector<MovingPart>& pa, const Motion& ma, const std::vector<MovingPart>& pb,
                  const Motion& mb) {
  Real reach = Real(0);
  for (const MovingPart& p : pa) reach = std::max(reach, p.reach);
  for (const MovingPart& p : pb) reach = std::max(reach, p.reach);
  return reach + glm::length(mb.start.position - ma.start.position) + glm::length(ma.translation) +
         glm::length(mb.translation);
}

}  // namespace

Result<ToiResult> time_of_impact(const Shape& a, const Motion& motion_a, const Shape& b, const Motion& motion_b,
                                 const ToiOptions& options) {
  if (auto e = check_motion(motion_a, "motion_a")) return *e;
  if (auto e = check_motion(motion_b, "motion_b")) return *e;
  if (auto e = validate_toi_options(options)) return *e;
  const std::vector<MovingPart> parts_a = parts_of(a, motion_a), parts_b = parts_of(b, motion_b);
  const Real floor = Real(64) * kEpsilon * motion_scale(parts_a, motion_a, parts_b, motion_b);
  const Advance opt{std::max(options.tolerance, floor), options.target_distance, options.max_iterations};
  ToiResult best;
  int iterations = 0;
  for (const MovingPart& pa : parts_a) {
    for (const MovingPart& pb : parts_b) {
      if ((pa.part >= 0 && behind(pa, pb)) || (pb.part >= 0 && behind(pb, pa))) continue;
      const ToiResult r = advance(pa, pb, opt, best.toi, iterations);
      const bool earlier = r.status != CcdStatus::Separated &&
                           (best.status == CcdStatus::Separated || r.toi < best.toi ||
                            (r.toi == best.toi && r.status == CcdStatus::InitiallyOverlapping && r.depth > best.depth));
      if (earlier) best = r;
    }
  }
  best.iterations = iterations;
  return best;
}

Result<ToiResult> shape_cast(const Shape& a, const Pose& pose_a, const Vec2& translation, const Shape& b,
                             const Pose& pose_b, const ToiOptions& options) {
  return time_of_impact(a, Motion::translating(pose_a, translation), b, Motion::translating(pose_b, Vec2(Real(0))),
                        options);
}

}  // namespace proxima::d2
