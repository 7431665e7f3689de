// Shape casts: a geometry translated along a vector against a still one.
//
// Steps:
//  1. Validate, then recentre on B's position (tolerances follow the pair's size, not its
//     distance from the world origin).
//  2. Convex against convex: GJK ray casting on the cores with margin = radii + target
//     (van den Bergen 2004, gjk_raycast.hpp). A hit at t = 0 is classified by the narrow
//     phase's distance: overlap (depth, push-out normal), touching and moving in (hit at
//     0: the gap measured a short step along the path has shrunk), or touching and not
//     moving in (no hit). A hit's distance is the cast's |v| less the radii (its witnesses
//     along the advancing normal can miss a graze's gap).
//  3. Convex against a half-space: closed form on the deepest support point along the
//     plane's normal.
//  4. Against a mesh or a compound (in B's frame): nearest-first walk of its hierarchy,
//     where a node's key is the first t at which A's swept box reaches it (slab test on the
//     node box grown by A's box); each triangle (its support mapping) or child is cast as
//     in 2 and 3, and the least validated t bounds the walk.
//  5. A mesh or compound moving against a convex shape: B cast along -translation against
//     A, the answer mirrored. Two non-convex geometries: time_of_impact with translations.

#include <proxima/ccd/shape_cast.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/geometry/gjk_raycast.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <string_view>
#include <type_traits>

#include "ccd/toi_unchecked.hpp"

namespace proxima {

namespace {

enum class Kind { Convex, HalfSpace, Mesh, Compound };

Kind kind_of(ShapeRef s) {
  switch (s.type()) {
    case ShapeType::HalfSpace: return Kind::HalfSpace;
    case ShapeType::TriangleMesh: return Kind::Mesh;
    case ShapeType::Compound: return Kind::Compound;
    default: return Kind::Convex;
  }
}

// The cast's fixed inputs, in the recentred world frame.
struct Cast {
  ShapeRef a;
  Transform pose_a;
  Vec3 s;  // translation
  Real target = Real(0);
  Real tolerance = Real(0);
  int max_iterations = 64;
  bool cull = false;
};

CastResult no_hit() { return CastResult{}; }

// An answer at t = 0 from the narrow phase's distance there.
CastResult at_start(const DistanceResult& d, CcdStatus status) {
  CastResult r;
  r.status = status;
  r.t = Real(0);
  r.distance = d.signed_distance;
  if (status == CcdStatus::InitiallyOverlapping) r.depth = -d.signed_distance;
  r.point_a = d.point_a;
  r.point_b = d.point_b;
  r.point = (d.point_a + d.point_b) * Real(0.5);
  r.normal = d.normal;
  r.sub_a = d.sub_a;
  r.sub_b = d.sub_b;
  return r;
}

// Whether the translation moves touching shapes into each other: the contact normal says so
// (the motion closes the gap along it by more than the tolerance; a slide along the contact
// plane, rounding included, does not), and the gap measured along the path shrinks by more
// than the distance's rounding (an eighth of a tolerance) at one of the steps where the
// normal predicts a closing of 1, 16, 256, ... tolerances, up to the path's end. The normal
// alone cannot say: where the contact is a vertex of the Minkowski difference (a cone's apex
// on a cylinder's rim) every direction of its normal cone is a valid answer, and a motion can
// close along one while the shapes part along another, or close ten times slower than the
// normal predicts (a box's corner on another's edge). The first step sees a closing that
// curvature soon undoes (a sphere pressed on a ridge while rolling off it), the longer ones
// a slow closing, or one that the distance's own error hides at the first. The signed
// distance of two convex shapes is convex in the translation's t: a gap that shrank at any
// step is a motion moving in, and one that shrank at none is the start's deepest point.
bool moves_in(const Cast& c, ShapeRef b, const Transform& pose_b, const DistanceResult& start) {
  const Real closing = glm::dot(start.normal, c.s);
  if (!(closing > c.tolerance)) return false;
  for (Real predicted = c.tolerance;; predicted *= Real(16)) {
    const Real step = std::min(Real(1), predicted / closing);
    const Transform ahead{c.pose_a.position + step * c.s, c.pose_a.rotation};
    if (distance(c.a, ahead, b, pose_b).signed_distance < start.signed_distance - Real(0.125) * c.tolerance) {
      return true;
    }
    if (step == Real(1)) return false;
  }
}

// A candidate within target + tolerance at t = 0: overlap, hit at 0 when moving in, else none.
CastResult classify_start(const Cast& c, ShapeRef b, const Transform& pose_b) {
  const DistanceResult d = distance(c.a, c.pose_a, b, pose_b);
  if (d.signed_distance < -c.tolerance) return at_start(d, CcdStatus::InitiallyOverlapping);
  if (d.signed_distance > c.target + c.tolerance || !moves_in(c, b, pose_b, d)) return no_hit();
  return at_start(d, CcdStatus::Hit);
}

// Conservative advancement on the narrow phase's distance for the translation of A (two
// non-convex geometries, or a convex pair whose GJK cast could not decide).
CastResult cast_by_advancement(const Cast& c, ShapeRef b, const Transform& pose_b) {
  ToiOptions o;
  o.target_distance = c.target;
  o.tolerance = c.tolerance;
  o.max_iterations = c.max_iterations;
  const Motion ma{c.pose_a, {c.pose_a.position + c.s, c.pose_a.rotation}};
  const ToiResult toi = detail::time_of_impact_unchecked(c.a, ma, b, Motion::stationary(pose_b), o, false);
  CastResult r;
  r.status = toi.status;
  r.t = toi.toi;
  r.distance = toi.distance;
  r.depth = toi.depth;
  r.point = toi.point;
  r.point_a = toi.point_a;
  r.point_b = toi.point_b;
  r.normal = toi.normal;
  r.iterations = toi.iterations;
  r.sub_a = toi.sub_a;
  r.sub_b = toi.sub_b;
  return r;
}

// A's core support and radius in the recentred world frame.
template <class F>
decltype(auto) with_core(ShapeRef shape, const Transform& pose, F&& f) {
  return visit_shape(shape, [&](const auto& s) {
    using S = std::decay_t<decltype(s)>;
    if constexpr (ConvexShape<S> && !std::is_same_v<S, HalfSpace>) {
      const auto core = [&](const Vec3& d) { return pose.apply(s.core_support(pose.inverse_apply_vector(d))); };
      return f(core, s.core_radius());
    } else {
      const auto none = [&](const Vec3&) { return pose.position; };
      return f(none, Real(0));
    }
  });
}

// GJK cast of A's core against a core given by `support_b` (radius rb), B still.
// `classify` answers a pair within reach at t = 0; `fallback` answers by conservative
// advancement when the GJK cast cannot decide (iteration cap, or stalled by rounding).
template <class SupportB>
CastResult cast_cores(const Cast& c, SupportB& support_b, Real rb, const auto& classify, const auto& fallback) {
  return with_core(c.a, c.pose_a, [&](auto& support_a, Real ra) {
    const Real margin = ra + rb + c.target;
    const gjk::CastOutcome o = gjk::cast(support_a, support_b, c.s, margin, c.tolerance, c.max_iterations);
    if (o.capped || o.stalled) {
      CastResult r = fallback();
      r.iterations += o.iterations;
      return r;
    }
    if (!o.hit) {
      CastResult r = no_hit();
      r.iterations = o.iterations;
      return r;
    }
    if (!o.advanced) {
      CastResult r = classify();
      r.iterations += o.iterations;
      return r;
    }
    CastResult r;
    r.status = CcdStatus::Hit;
    r.t = o.lambda;
    r.normal = o.normal;
    r.point_a = o.point_a + ra * o.normal;
    r.point_b = o.point_b - rb * o.normal;
    r.point = (r.point_a + r.point_b) * Real(0.5);
    // |v|, the cores' distance at the hit, less the radii: the simplex's witnesses projected on
    // the advancing plane's normal said about 0 along a graze whose gap stays within the
    // tolerance (parallel faces sliding past each other).
    r.distance = o.distance - ra - rb;
    r.iterations = o.iterations;
    return r;
  });
}

CastResult cast_convex(const Cast& c, ShapeRef b, const Transform& pose_b) {
  return with_core(b, pose_b, [&](auto& support_b, Real rb) {
    return cast_cores(
        c, support_b, rb, [&] { return classify_start(c, b, pose_b); },
        [&] { return cast_by_advancement(c, b, pose_b); });
  });
}

// Convex A against a half-space B: the deepest point of A along the plane's normal m moves
// by t (m . s); the hit is where its signed height reaches the target.
CastResult cast_halfspace(const Cast& c, const HalfSpace& h, const Transform& pose_b) {
  const Vec3 m = pose_b.apply_vector(h.normal());
  const Real offset = h.offset() + glm::dot(m, pose_b.position);
  const Vec3 deepest = visit_shape(c.a, [&](const auto& s) -> Vec3 {
    using S = std::decay_t<decltype(s)>;
    if constexpr (ConvexShape<S> && !std::is_same_v<S, HalfSpace>) {
      return support(s, c.pose_a, -m);
    } else {
      return c.pose_a.position;
    }
  });
  const Real height = glm::dot(m, deepest) - offset;  // signed distance of A to the plane
  if (height <= c.target + c.tolerance) return classify_start(c, h, pose_b);
  const Real closing = -glm::dot(m, c.s);
  if (!(closing > Real(0))) return no_hit();
  const Real t = (height - c.target) / closing;
  if (!(t <= Real(1))) return no_hit();
  CastResult r;
  r.status = CcdStatus::Hit;
  r.t = t;
  r.normal = -m;
  r.point_a = deepest + t * c.s;
  r.point_b = r.point_a - c.target * m;
  r.point = (r.point_a + r.point_b) * Real(0.5);
  r.distance = c.target;
  return r;
}

// First t in [0, 1] at which the box `moving` translated by t s overlaps `node` (a lower
// bound for anything inside the node); +infinity when it never does.
Real entry_time(const Aabb& moving, const Vec3& s, const Aabb& node) {
  Real t0 = Real(0), t1 = Real(1);
  for (int i = 0; i < 3; ++i) {
    const Real lo = node.min[i] - moving.max[i];  // the translation must reach [lo, hi]
    const Real hi = node.max[i] - moving.min[i];
    if (s[i] == Real(0)) {
      if (lo > Real(0) || hi < Real(0)) return kRealInfinity;
      continue;
    }
    Real a = lo / s[i], b = hi / s[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return kRealInfinity;
  }
  return t0;
}

// Keeps the better of two answers: an overlap first, then the least t among hits.
void keep_best(CastResult& best, const CastResult& r, SubShapeId sub) {
  const auto rank = [](const CastResult& x) {
    return x.status == CcdStatus::InitiallyOverlapping ? 0 : x.status == CcdStatus::Hit ? 1 : 2;
  };
  const int iterations = best.iterations + r.iterations;
  if (rank(r) < rank(best) || (rank(r) == 1 && rank(best) == 1 && r.t < best.t)) {
    best = r;
    if (sub.child != kNoIndex) best.sub_b.child = sub.child;
    if (sub.triangle != kNoIndex) best.sub_b.triangle = sub.triangle;
  } else if (r.status == CcdStatus::MaxIterations && best.status == CcdStatus::Separated) {
    best.status = CcdStatus::MaxIterations;
  }
  best.iterations = iterations;
}

CastResult cast_any(const Cast& c, ShapeRef b, const Transform& pose_b);

// An overlap found on one part stands for the whole geometry: the narrow phase's distance
// over all parts gives the deepest penetration and its normal, as distance and collide do.
CastResult deepest_overlap(const Cast& c, const CastResult& found, ShapeRef b, const Transform& pose_b) {
  if (found.status != CcdStatus::InitiallyOverlapping) return found;
  const DistanceResult d = distance(c.a, c.pose_a, b, pose_b);
  if (!(d.signed_distance < Real(0))) return found;
  CastResult r = at_start(d, CcdStatus::InitiallyOverlapping);
  r.iterations = found.iterations;
  return r;
}

// Distance from p to the segment [a, b].
Real segment_distance(const Vec3& p, const Vec3& a, const Vec3& b) {
  const Vec3 ab = b - a;
  const Real len2 = glm::dot(ab, ab);
  const Real u = len2 > Real(0) ? std::clamp(glm::dot(p - a, ab) / len2, Real(0), Real(1)) : Real(0);
  return glm::length(p - (a + u * ab));
}

// True when edge e of triangle t is shared with a coplanar triangle (a seam of a flat
// region; `face` is t's unit normal, either orientation).
bool flat_edge(const TriangleMesh& mesh, std::uint32_t t, int e, const Vec3& face) {
  const std::uint32_t other = mesh.neighbors(t)[static_cast<std::size_t>(e)];
  if (other == kNoIndex) return false;
  const std::array<Vec3, 3> w = mesh.triangle(other);
  const Vec3 n = glm::cross(w[1] - w[0], w[2] - w[0]);
  const Real len = glm::length(n);
  return len > Real(0) && std::abs(glm::dot(n / len, face)) >= Real(1) - Real(1e-4);
}

// A hit on triangle t (mesh frame: contact point `p`, normal `n` from A to the mesh) is a
// ghost when the motion does not close it along n by more than the tolerance (a graze), or
// when it lies on a flat seam (an inactive edge shared with a coplanar triangle), or on a
// corner whose edges in t are such seams, while A does not move into the triangle's plane: a shape sliding over a
// flat mesh reaches the seams between its triangles edge-on, and those are not walls (the
// narrow phase's internal-edge rule, mesh_convex.cpp, applied to casts).
bool ghost_contact(const Cast& c, const TriangleMesh& mesh, std::uint32_t t, const std::array<Vec3, 3>& v,
                   const Vec3& p, const Vec3& n, const Vec3& s_local) {
  Vec3 face = glm::cross(v[1] - v[0], v[2] - v[0]);
  const Real area2 = glm::length(face);
  if (!(area2 > Real(0))) return false;
  face /= area2;
  if (glm::dot(face, n) > Real(0)) face = -face;  // now from the triangle towards A
  // A graze: the motion does not close the contact (a shape sliding along the mesh touches
  // the next triangle at the seam, with the floor's normal).
  if (!(glm::dot(n, s_local) > c.tolerance)) return true;
  const Real reach = std::max(c.tolerance, Real(1e-3) * std::sqrt(area2));
  const std::uint8_t active = mesh.active_edges(t);
  int near = 0;
  bool real = false;
  for (int e = 0; e < 3; ++e) {
    if (segment_distance(p, v[e], v[(e + 1) % 3]) <= reach) {
      ++near;
      real = real || ((active >> e) & 1u) || !flat_edge(mesh, t, e, face);
    }
  }
  if (near == 0 || real) return false;  // inside the face, or on an active or concave edge
  // Moving into the plane along the face normal (A to B is -face) by more than the
  // tolerance: the triangle is really in the way.
  return !(glm::dot(-face, s_local) > c.tolerance);
}

CastResult cast_mesh(const Cast& c, const TriangleMesh& mesh, const Transform& pose_b) {
  const Transform to_b = pose_b.inverse();
  const Aabb moving = world_aabb(c.a, to_b * c.pose_a).inflated(c.target + c.tolerance);
  const Vec3 s_local = to_b.apply_vector(c.s);
  CastResult best = no_hit();
  Real bound = Real(1);
  const auto gap = [&](const Aabb& node) { return entry_time(moving, s_local, node); };
  mesh.bvh().traverse_nearest(gap, bound, [&](std::uint32_t t) {
    const std::array<Vec3, 3> v = mesh.triangle(t);
    const Vec3 normal = glm::cross(v[1] - v[0], v[2] - v[0]);
    if (c.cull && glm::dot(normal, s_local) > Real(0)) return;
    const std::array<Vec3, 3> w{pose_b.apply(v[0]), pose_b.apply(v[1]), pose_b.apply(v[2])};
    const auto support_b = [&](const Vec3& d) {
      const Real d0 = glm::dot(d, w[0]), d1 = glm::dot(d, w[1]), d2 = glm::dot(d, w[2]);
      return d0 >= d1 ? (d0 >= d2 ? w[0] : w[2]) : (d1 >= d2 ? w[1] : w[2]);
    };
    const auto classify = [&]() {
      const auto tri = Triangle::create(v[0], v[1], v[2]);
      return tri ? classify_start(c, *tri, pose_b) : no_hit();
    };
    const auto fallback = [&]() {
      const auto tri = Triangle::create(v[0], v[1], v[2]);
      return tri ? cast_by_advancement(c, *tri, pose_b) : no_hit();
    };
    CastResult r = cast_cores(c, support_b, Real(0), classify, fallback);
    if (r.status == CcdStatus::Hit &&
        ghost_contact(c, mesh, t, v, to_b.apply(r.point_b), to_b.apply_vector(r.normal), s_local)) {
      r = no_hit();
    }
    keep_best(best, r, SubShapeId{kNoIndex, t});
    if (best.status == CcdStatus::Hit) bound = best.t;
    if (best.status == CcdStatus::InitiallyOverlapping) bound = Real(-1);
  });
  return deepest_overlap(c, best, mesh, pose_b);
}

CastResult cast_compound(const Cast& c, const Compound& compound, const Transform& pose_b) {
  const Transform to_b = pose_b.inverse();
  const Aabb moving = world_aabb(c.a, to_b * c.pose_a).inflated(c.target + c.tolerance);
  const Vec3 s_local = to_b.apply_vector(c.s);
  const auto kids = compound.children();
  CastResult best = no_hit();
  Real bound = Real(1);
  const auto gap = [&](const Aabb& node) { return entry_time(moving, s_local, node); };
  compound.bvh().traverse_nearest(gap, bound, [&](std::uint32_t k) {
    const CastResult r = cast_any(c, kids[k].shape, pose_b * kids[k].pose);
    keep_best(best, r, SubShapeId{k, kNoIndex});
    if (best.status == CcdStatus::Hit) bound = best.t;
    if (best.status == CcdStatus::InitiallyOverlapping) bound = Real(-1);
  });
  return deepest_overlap(c, best, compound, pose_b);
}

CastResult mirrored(const CastResult& r) {
  CastResult m = r;
  m.point_a = r.point_b;
  m.point_b = r.point_a;
  m.normal = -r.normal;
  m.sub_a = r.sub_b;
  m.sub_b = r.sub_a;
  return m;
}

CastResult cast_any(const Cast& c, ShapeRef b, const Transform& pose_b) {
  const Kind ka = kind_of(c.a), kb = kind_of(b);
  if (ka == Kind::Convex) {
    switch (kb) {
      case Kind::Convex: return cast_convex(c, b, pose_b);
      case Kind::HalfSpace: return cast_halfspace(c, b.as<HalfSpace>(), pose_b);
      case Kind::Mesh: return cast_mesh(c, b.as<TriangleMesh>(), pose_b);
      default: return cast_compound(c, b.as<Compound>(), pose_b);
    }
  }
  if (kb == Kind::Convex) {
    Cast back = c;
    back.a = b;
    back.pose_a = pose_b;
    back.s = -c.s;
    // The answer has B moved back by t s with A still; moving both by t s puts A where it
    // is at t and B where it stays.
    CastResult r = mirrored(cast_any(back, c.a, c.pose_a));
    const Vec3 shift = r.t * c.s;
    if (r.status == CcdStatus::Hit) {
      r.point += shift;
      r.point_a += shift;
      r.point_b += shift;
    }
    return r;
  }
  if (ka == Kind::Compound) {
    // Each child of a moving compound against B (B is not convex here).
    const auto kids = c.a.as<Compound>().children();
    CastResult best = no_hit();
    for (std::uint32_t k = 0; k < kids.size(); ++k) {
      Cast child = c;
      child.a = kids[k].shape;
      child.pose_a = c.pose_a * kids[k].pose;
      CastResult r = cast_any(child, b, pose_b);
      r.sub_a.child = k;
      keep_best(best, r, SubShapeId{});
    }
    return best;
  }
  return cast_by_advancement(c, b, pose_b);
}

std::optional<Error> validate_pose(const Transform& pose, std::string_view name) {
  if (validate::is_acceptable(pose.position) && validate::is_unit(pose.rotation)) return std::nullopt;
  const std::string n(name);
  if (auto e = validate::finite(pose.position, n + ".position")) return e;
  return validate::unit_quaternion(pose.rotation, n + ".rotation");
}

}  // namespace

std::optional<Error> validate_cast_options(const CastOptions& o) {
  const auto fine = [](Real x) { return std::isfinite(x) && x >= Real(0) && x <= kMaxCoordinate; };
  if (fine(o.target_distance) && fine(o.tolerance) && o.max_iterations >= 1) return std::nullopt;
  if (auto e = validate::non_negative(o.target_distance, "options.target_distance")) return e;
  if (auto e = validate::non_negative(o.tolerance, "options.tolerance")) return e;
  if (o.max_iterations < 1) return make_error(ErrorCode::OutOfRange, "options.max_iterations", "must be at least 1");
  return std::nullopt;
}

Result<CastResult> shape_cast(ShapeRef a, const Transform& pose_a, const Vec3& translation, ShapeRef b,
                              const Transform& pose_b, const CastOptions& options) {
  if (auto e = validate_pose(pose_a, "pose_a")) return *e;
  if (auto e = validate::finite(translation, "translation")) return *e;
  if (auto e = validate_pose(pose_b, "pose_b")) return *e;
  const auto fine = [](Real x) { return std::isfinite(x) && x >= Real(0); };  // no field name built when valid
  if (!fine(options.target_distance) || !fine(options.tolerance)) {
    if (auto e = validate::non_negative(options.target_distance, "options.target_distance")) return *e;
    if (auto e = validate::non_negative(options.tolerance, "options.tolerance")) return *e;
  }
  if (options.max_iterations < 1)
    return make_error(ErrorCode::OutOfRange, "options.max_iterations", "must be at least 1");

  const Vec3 origin = pose_b.position;
  Cast c{a, {pose_a.position - origin, pose_a.rotation}, translation};
  const Transform local_b{Vec3(Real(0)), pose_b.rotation};
  const Real reach = glm::length(c.pose_a.position) + glm::length(translation);
  const Vec3 extents = world_aabb(a, Transform::identity()).extents();
  const Real size = a.type() == ShapeType::HalfSpace ? Real(0) : std::max({extents.x, extents.y, extents.z});
  c.target = options.target_distance;
  c.tolerance = std::max(options.tolerance, Real(64) * kEpsilon * std::max(Real(1), reach + size));
  c.max_iterations = options.max_iterations;
  c.cull = options.cull_back_faces;
  CastResult r = cast_any(c, b, local_b);
  r.point += origin;
  r.point_a += origin;
  r.point_b += origin;
  return r;
}

}  // namespace proxima
