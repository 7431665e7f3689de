// Certified time of impact by conservative advancement.
//
// Steps (Mirtich, "Impulse-based dynamic simulation of rigid body systems", PhD thesis 1996,
// ch. 3; the directional bound of Zhang, Redon, Lee, Kim, ACM TOG 2007):
//  1. Recentre: every position is taken relative to B's start position, so the tolerances
//     and the rounding follow the size of the pair and its motion, not its distance from
//     the world origin.
//  2. At the current time t, the narrow phase gives the distance d (an upper bound: the
//     distance of two surface points) and the normal n from A to B.
//  3. Lower bounds of the distance after t, both proved in motion.hpp:
//     - directional (bounded convex shapes): g = min over B of n.x - max over A of n.x,
//       from one support call per shape, is <= the distance at every time, and it
//       decreases at most at mu = n.(v_a - v_b) + |n x w_a| r_a + |n x w_b| r_b, where r
//       is the radius of the shape's core about its rotation axis through its origin (the
//       axis is fixed in the body's frame; a rounding ball does not move under rotation
//       about its centre);
//     - Lipschitz (any geometry): the distance itself, less the narrow phase's error,
//       decreases at most at L = |v_a - v_b| + |w_a| R_a + |w_b| R_b (R the full radius;
//       for a half-space, the largest distance from its origin to the other shape).
//     Each proves the gap above the target on [t, t + (lower - target) / rate]; the step
//     is the longer of the two.
//  4. Stop with Hit when d <= target + tolerance, with Separated when the step passes 1 or
//     no bound can close the gap, with MaxIterations at the cap.
//  5. Two convex shapes whose cores do not turn move by a relative translation: that case
//     is answered by GJK ray casting (shape_cast.hpp), whose advances are certified the same
//     way (a separating plane kept at the target), in one GJK run instead of several.
//  6. t = 0 contract: penetration deeper than the tolerance is InitiallyOverlapping (depth
//     and normal from the narrow phase's EPA or closed form); a touching pair whose
//     certified closing speed is <= 0 is Separated.

#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "ccd/shape_radii.hpp"
#include "ccd/toi_unchecked.hpp"

namespace proxima {

namespace {}  // namespace

std::optional<Error> validate_toi_options(const ToiOptions& o) {
  const auto fine = [](Real x) { return std::isfinite(x) && x >= Real(0) && x <= kMaxCoordinate; };
  if (fine(o.target_distance) && fine(o.tolerance) && o.max_iterations >= 1) return std::nullopt;
  if (auto e = validate::non_negative(o.target_distance, "options.target_distance")) return e;
  if (auto e = validate::non_negative(o.tolerance, "options.tolerance")) return e;
  if (o.max_iterations < 1) {
    return make_error(ErrorCode::OutOfRange, "options.max_iterations", "must be at least 1");
  }
  return std::nullopt;
}

namespace {

Motion shifted(const Motion& m, const Vec3& origin) {
  return {{m.start.position - origin, m.start.rotation}, {m.end.position - origin, m.end.rotation}};
}

// Placements along a motion from its angular velocity, computed once: one sine and cosine
// per placement instead of a slerp's inverse cosine and three sines. The same rotation as
// slerp (the shortest-arc rotation from start to end, scaled by t, applied on the left).
struct Placements {
  Vec3 p0{Real(0)}, v{Real(0)}, axis{Real(0)};
  Quat q0 = kIdentityQuat;
  Real angle = Real(0);

  Placements(const Motion& m, const Vec3& w) : p0(m.start.position), v(m.displacement()), q0(m.start.rotation) {
    angle = glm::length(w);
    if (angle > Real(0)) axis = w / angle;
  }
  Transform at(Real t) const {
    Transform r{p0 + t * v, q0};
    if (angle > Real(0)) {
      const Real h = Real(0.5) * angle * t;
      const Real s = std::sin(h);
      r.rotation = glm::normalize(Quat(std::cos(h), axis.x * s, axis.y * s, axis.z * s) * q0);
    }
    return r;
  }
};

// The pair's fixed data over the whole query.
struct Pair {
  Pair(ShapeRef shape_a, ShapeRef shape_b) : a(shape_a), b(shape_b) {}
  ShapeRef a, b;
  Motion ma, mb;  // recentred motions
  Vec3 va{Real(0)}, vb{Real(0)}, wa{Real(0)}, wb{Real(0)};
  detail::ShapeRadii ra, rb;
  Real lip_a = Real(0), lip_b = Real(0);  // rotational radii of the Lipschitz bound
  Real scale = Real(1);
  Real target = Real(0);
  Real tolerance = Real(0);
};

// Rotational radius of the Lipschitz bound for `self`: its full radius, or, for a
// half-space, the largest distance from its origin to any point of `other` over the step
// (the distance between the two linear origin paths is convex in t: largest at an end).
Real lipschitz_radius(const detail::ShapeRadii& self, const detail::ShapeRadii& other, const Motion& ms,
                      const Motion& mo) {
  if (!self.halfspace) return self.full;
  const Real ends =
      std::max(glm::length(mo.start.position - ms.start.position), glm::length(mo.end.position - ms.end.position));
  return ends + other.full;
}

// Radii of a geometry for its motion: about its rotation axis (fixed in the body's frame,
// since the body turns about it) when it rotates.
detail::ShapeRadii radii_for(ShapeRef shape, const Motion& m, const Vec3& w) {
  const Real speed = glm::length(w);
  if (!(speed > Real(0))) return detail::shape_radii(shape);
  return detail::shape_radii_about_axis(shape, m.start.inverse_apply_vector(w / speed));
}

Real rotational(const Vec3& w, Real radius) {
  const Real speed = glm::length(w);
  return speed > Real(0) ? speed * radius : Real(0);
}

// Closing speed bound along n at the contact (<= 0: the pair cannot approach along n).
Real closing_speed(const Pair& p, const Vec3& n) {
  if (p.ra.halfspace || p.rb.halfspace) {
    // A half-space's normal turns with it: only its translation is directional.
    if (glm::length(p.wa) > Real(0) || glm::length(p.wb) > Real(0)) return kRealInfinity;
    return glm::dot(n, p.va - p.vb);
  }
  return directional_speed_bound(n, p.va - p.vb, p.wa, p.ra.core) + glm::length(glm::cross(n, p.wb)) * p.rb.core;
}

// How far past t the gap is proved to stay above the target (0: no progress proved).
Real certified_step(const Pair& p, const DistanceResult& d, const Transform& pa, const Transform& pb) {
  const Vec3 n = d.normal;
  Real step = Real(0);
  // Lipschitz bound on the narrow phase's distance, less its error.
  const Real error = Real(16) * kEpsilon * p.scale + Real(8) * kEpsilon * std::abs(d.signed_distance);
  const Real lower = d.signed_distance - error;
  const Real lip = glm::length(p.va - p.vb) + rotational(p.wa, p.lip_a) + rotational(p.wb, p.lip_b);
  if (lower > p.target) step = lip > Real(0) ? (lower - p.target) / lip : kRealInfinity;
  // Directional bound (two bounded convex shapes).
  if (p.ra.convex && p.rb.convex) {
    const Real g = glm::dot(n, detail::world_support(p.b, pb, -n)) - glm::dot(n, detail::world_support(p.a, pa, n));
    const Real mu = closing_speed(p, n);
    if (g > p.target) step = std::max(step, mu > Real(0) ? (g - p.target) / mu : kRealInfinity);
  }
  return step;
}

void fill_contact(ToiResult& r, const DistanceResult& d, const Vec3& origin) {
  r.point_a = d.point_a + origin;
  r.point_b = d.point_b + origin;
  r.point = (r.point_a + r.point_b) * Real(0.5);
  r.normal = d.normal;
  r.distance = d.signed_distance;
  r.sub_a = d.sub_a;
  r.sub_b = d.sub_b;
}

ToiResult& separated(ToiResult& r) {
  r.status = CcdStatus::Separated;
  r.toi = r.t_lower = r.t_upper = Real(1);
  return r;
}

// MaxIterations: apart by more than the target on [0, t]; nothing known after it.
ToiResult& bracket(ToiResult& r, Real t) {
  r.status = CcdStatus::MaxIterations;
  r.toi = r.t_lower = t;
  r.t_upper = Real(1);
  return r;
}

// Two bounded convex shapes whose cores do not turn (no rotation, or a core that rotation
// leaves in place: a sphere or a point): the relative motion is a translation.
bool translating_pair(const Pair& p) {
  const auto still = [](const Vec3& w, const detail::ShapeRadii& r) {
    return (r.convex && r.core == Real(0)) || !(glm::length(w) > Real(0));
  };
  return still(p.wa, p.ra) && still(p.wb, p.rb);
}

// A translating pair: the shape cast of A along its motion relative to B (GJK ray casting
// for convex parts, each mesh triangle or compound child in nearest-first order). Each
// advance of the cast keeps a separating plane at the target, so [0, t] is certified as in
// conservative advancement.
ToiResult by_cast(const Pair& p, const ToiOptions& options, const Vec3& origin) {
  CastOptions co;
  co.target_distance = options.target_distance;
  co.tolerance = p.tolerance;
  co.max_iterations = options.max_iterations;
  const auto c = shape_cast(p.a, p.ma.start, p.va - p.vb, p.b, p.mb.start, co);
  ToiResult r;
  if (!c) {
    r.status = CcdStatus::Failed;
    r.t_lower = Real(0);
    return r;
  }
  r.iterations = c->iterations;
  switch (c->status) {
    case CcdStatus::Separated: return separated(r);
    case CcdStatus::MaxIterations: return bracket(r, Real(0));
    default: break;
  }
  r.status = c->status;
  r.toi = r.t_lower = r.t_upper = c->t;
  r.distance = c->distance;
  r.depth = c->depth;
  const Vec3 moved = c->t * p.vb + origin;  // B's travel up to t, back to world
  r.point_a = c->point_a + moved;
  r.point_b = c->point_b + moved;
  r.point = c->point + moved;
  r.normal = c->normal;
  r.sub_a = c->sub_a;
  r.sub_b = c->sub_b;
  return r;
}

}  // namespace

const char* to_string(CcdStatus status) {
  switch (status) {
    case CcdStatus::Hit: return "hit";
    case CcdStatus::Separated: return "separated";
    case CcdStatus::InitiallyOverlapping: return "initially_overlapping";
    case CcdStatus::MaxIterations: return "max_iterations";
    default: return "failed";
  }
}

Result<ToiResult> time_of_impact(ShapeRef a, const Motion& motion_a, ShapeRef b, const Motion& motion_b,
                                 const ToiOptions& options) {
  if (auto e = validate_motion(motion_a, "motion_a")) return *e;
  if (auto e = validate_motion(motion_b, "motion_b")) return *e;
  if (auto e = validate_toi_options(options)) return *e;
  return detail::time_of_impact_unchecked(a, motion_a, b, motion_b, options, true);
}

namespace detail {

ToiResult time_of_impact_unchecked(ShapeRef a, const Motion& motion_a, ShapeRef b, const Motion& motion_b,
                                   const ToiOptions& options, bool allow_cast) {
  Pair p(a, b);
  const Vec3 origin = motion_b.start.position;
  p.ma = shifted(motion_a, origin);
  p.mb = shifted(motion_b, origin);
  p.va = p.ma.displacement();
  p.vb = p.mb.displacement();
  p.wa = p.ma.angular_velocity();
  p.wb = p.mb.angular_velocity();
  p.ra = radii_for(a, p.ma, p.wa);
  p.rb = radii_for(b, p.mb, p.wb);
  p.lip_a = lipschitz_radius(p.ra, p.rb, p.ma, p.mb);
  p.lip_b = lipschitz_radius(p.rb, p.ra, p.mb, p.ma);
  const Real reach =
      std::max({glm::length(p.ma.start.position), glm::length(p.ma.end.position), glm::length(p.mb.end.position)});
  const Real size_a = p.ra.halfspace ? Real(0) : p.ra.full;
  const Real size_b = p.rb.halfspace ? Real(0) : p.rb.full;
  p.scale = std::max(Real(1), reach + size_a + size_b);
  p.target = options.target_distance;
  p.tolerance = std::max(options.tolerance, Real(64) * kEpsilon * p.scale);

  const Placements place_a(p.ma, p.wa), place_b(p.mb, p.wb);
  if (allow_cast && translating_pair(p)) {
    // A hit is measured by the narrow phase at its time (the answer's distance and points).
    // The cast raises the tolerance to its own precision floor (its scale holds the whole
    // translation), so a hit farther than this pair's target + tolerance is not certified
    // here: the advancement below measures it again.
    ToiResult cast = by_cast(p, options, origin);
    if (cast.status != CcdStatus::Hit) return cast;
    // A convex pair's cast distance is its GJK |v| at the hit.
    if (p.ra.convex && p.rb.convex) {
      if (cast.distance <= p.target + p.tolerance) return cast;
    } else {
      const DistanceResult d = distance(a, place_a.at(cast.toi), b, place_b.at(cast.toi));
      if (std::isfinite(d.signed_distance) && d.signed_distance <= p.target + p.tolerance) {
        cast.distance = d.signed_distance;
        cast.point_a = d.point_a + origin;
        cast.point_b = d.point_b + origin;
        cast.point = (cast.point_a + cast.point_b) * Real(0.5);
        return cast;
      }
    }
  }

  ToiResult r;
  PairCache cache;
  Real t = Real(0);
  for (int k = 0; k < options.max_iterations; ++k) {
    const Transform pa = place_a.at(t);
    const Transform pb = place_b.at(t);
    const DistanceResult d = distance(a, pa, b, pb, {}, &cache);
    r.iterations = k + 1;
    if (d.status == PairStatus::InvalidInput || !std::isfinite(d.signed_distance)) {
      r.status = CcdStatus::Failed;
      r.t_lower = t;
      return r;
    }
    if (k == 0 && d.signed_distance < -p.tolerance) {
      r.status = CcdStatus::InitiallyOverlapping;
      r.toi = r.t_lower = r.t_upper = Real(0);
      r.depth = -d.signed_distance;
      fill_contact(r, d, origin);
      return r;
    }
    if (d.signed_distance <= p.target + p.tolerance) {
      if (k == 0 && closing_speed(p, d.normal) <= p.tolerance) return separated(r);  // touching, moving apart
      r.status = CcdStatus::Hit;
      r.toi = r.t_lower = r.t_upper = t;
      fill_contact(r, d, origin);
      return r;
    }
    const Real step = certified_step(p, d, pa, pb);
    // No bound proves progress when the tolerance is below what the geometry can resolve:
    // report the bracket reached.
    if (!(step > Real(0))) return bracket(r, t);
    if (t + step >= Real(1)) return separated(r);
    t += step;
  }
  return bracket(r, t);
}

}  // namespace detail

}  // namespace proxima
