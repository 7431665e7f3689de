// Shape casts (src/ccd/shape_cast.cpp) against closed forms, an independent algorithm and
// brute force.
//
// Closed forms, computed here in double: sphere against sphere (a quadratic), sphere against
// box (the centre's ray against the box rounded by the radius: three slabs, twelve edge
// cylinders, eight corner balls), a point against any convex shape and a sphere against a
// sphere, capsule or box (the centre's ray against the other shape inflated, by raycast),
// capsule against half-space (its lower end along the plane's normal). A cast with tolerance
// tol must land in the window where the gap is within [target, target + tol], that is
// t in [t(target + tol), t(target)] of the closed form, up to rounding.
//
// The independent reference: time_of_impact with the same translation (conservative
// advancement on the narrow phase's distance, not GJK ray casting) on seeded sweeps over
// every convex kind against every convex kind and a half-space. Both must classify each
// case alike (overlap, hit, miss) except inside the tolerance band, and their hit times
// agree within (tolerance + rounding) / closing speed. Every hit is also checked on the
// narrow phase's distance at the reported t (within target + tolerance, not deeper than the
// target); every miss by the least distance along the path (golden-section search: the
// gap of two translated convex sets is convex in t).
//
// Meshes (a torus, an open terrain) and compounds: against brute force over the parts (each
// triangle cast as a Triangle shape, each child cast at its composed pose), with and without
// back-face culling, both ways round (the part moving or still), and the grazing case of a
// box sliding along a mesh face or edge it touches at t = 0 that must report the wall ahead.
//
// Also: the t = 0 contract (overlap, touching and moving apart, sliding, moving in, zero
// translation), accuracy independent of the size (5, 50, 500 units) and of the distance
// from the origin (1e4; 1e6 in double), every error field, and finite answers throughout.
#include <gtest/gtest.h>

#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "ccd/case_text.hpp"
#include "narrowphase/reference_distance.hpp"
#include "support/random.hpp"
#include "support/solid_test_meshes.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_shape_cast {

using test::num;
using test::text;

constexpr bool kFloat = sizeof(Real) == 4;
constexpr double kInf = std::numeric_limits<double>::infinity();
using D3 = glm::dvec3;

D3 dv(const Vec3& v) { return D3(double(v.x), double(v.y), double(v.z)); }

// ---------------------------------------------------------------------------------------
// Shapes and placements

constexpr std::array<ShapeType, 10> kConvexKinds{
    ShapeType::Sphere,    ShapeType::Capsule,    ShapeType::Box,      ShapeType::Cylinder, ShapeType::Cone,
    ShapeType::Ellipsoid, ShapeType::ConvexHull, ShapeType::Triangle, ShapeType::Segment,  ShapeType::Point};

ConvexHull random_hull(test::Random& rng, Real size) {
  std::vector<Vec3> points;
  for (int i = 0; i < 12; ++i) points.push_back(rng.in_ball(size));
  for (int i = 0; i < 4; ++i) points.push_back(rng.unit_vector() * size);
  return ConvexHull::create(points).value();
}

// A convex shape of `kind` about `size` across (half sizes in [0.2, 1] x size).
Shape random_convex(test::Random& rng, ShapeType kind, Real size) {
  const auto r = [&](Real lo, Real hi) { return size * rng.uniform(lo, hi); };
  switch (kind) {
    case ShapeType::Sphere: return Sphere::create(r(Real(0.3), Real(1))).value();
    case ShapeType::Capsule: return Capsule::create(r(Real(0.2), Real(0.6)), r(Real(0.2), Real(1))).value();
    case ShapeType::Box: return Box::create(size * rng.vec3(Real(0.2), Real(1))).value();
    case ShapeType::Cylinder: return Cylinder::create(r(Real(0.2), Real(1)), r(Real(0.2), Real(1))).value();
    case ShapeType::Cone: return Cone::create(r(Real(0.2), Real(1)), r(Real(0.2), Real(1))).value();
    case ShapeType::Ellipsoid: return Ellipsoid::create(size * rng.vec3(Real(0.2), Real(1))).value();
    case ShapeType::ConvexHull: return random_hull(rng, size);
    case ShapeType::Triangle:
      for (;;) {
        auto t = Triangle::create(rng.in_ball(size), rng.in_ball(size), rng.in_ball(size));
        if (t && t->area() > Real(0.05) * size * size) return *t;
      }
    case ShapeType::Segment:
      for (;;) {
        auto s = Segment::create(rng.in_ball(size), rng.in_ball(size));
        if (s && s->length() > Real(0.2) * size) return *s;
      }
    default: return Point::create().value();
  }
}

std::string text(const Transform& t) {
  const Quat& q = t.rotation;
  return "{" + text(t.position) + ", q(w " + num(q.w) + ", x " + num(q.x) + ", y " + num(q.y) + ", z " + num(q.z) +
         ")}";
}

// The shape's kind and parameters, to reproduce a failing case.
std::string text(ShapeRef shape) {
  std::string out = to_string(shape.type());
  switch (shape.type()) {
    case ShapeType::Sphere: out += " r " + num(shape.as<Sphere>().radius()); break;
    case ShapeType::Capsule:
      out += " r " + num(shape.as<Capsule>().radius()) + " h " + num(shape.as<Capsule>().half_length());
      break;
    case ShapeType::Cylinder:
      out += " r " + num(shape.as<Cylinder>().radius()) + " h " + num(shape.as<Cylinder>().half_length());
      break;
    case ShapeType::Cone:
      out += " r " + num(shape.as<Cone>().radius()) + " h " + num(shape.as<Cone>().half_length());
      break;
    case ShapeType::Box: out += " " + text(shape.as<Box>().half_extents()); break;
    case ShapeType::Ellipsoid: out += " " + text(shape.as<Ellipsoid>().radii()); break;
    case ShapeType::Segment: out += " " + text(shape.as<Segment>().a()) + " " + text(shape.as<Segment>().b()); break;
    case ShapeType::Triangle: {
      const Triangle& t = shape.as<Triangle>();
      out += " " + text(t.a()) + " " + text(t.b()) + " " + text(t.c());
      break;
    }
    case ShapeType::HalfSpace:
      out += " n " + text(shape.as<HalfSpace>().normal()) + " d " + num(shape.as<HalfSpace>().offset());
      break;
    case ShapeType::ConvexHull:
      out += " vertices";
      for (const Vec3& v : shape.as<ConvexHull>().vertices()) out += " " + text(v);
      break;
    default: break;
  }
  return out;
}

// A case in full: A, its pose and translation, B and its pose.
std::string text(ShapeRef a, const Transform& pa, const Vec3& s, ShapeRef b, const Transform& pb) {
  std::string out = "A ";
  for (const std::string& part : {text(a), std::string(" at "), text(pa), std::string(" along "), text(s),
                                  std::string("; B "), text(b), std::string(" at "), text(pb)}) {
    out += part;
  }
  return out;
}

Transform moved(const Transform& pose, const Vec3& s, Real t) { return {pose.position + t * s, pose.rotation}; }

// Signed distance of A placed at pose_a + t s to B (the narrow phase: an independent answer).
Real gap_at(ShapeRef a, const Transform& pose_a, const Vec3& s, Real t, ShapeRef b, const Transform& pose_b) {
  return distance(a, moved(pose_a, s, t), b, pose_b).signed_distance;
}

// Least distance along the whole path (golden-section search on the convex gap of two
// translated convex sets), and the ends.
Real least_gap(ShapeRef a, const Transform& pose_a, const Vec3& s, ShapeRef b, const Transform& pose_b) {
  const auto f = [&](Real t) { return gap_at(a, pose_a, s, t, b, pose_b); };
  Real lo = Real(0), hi = Real(1);
  const Real phi = Real(0.6180339887498949);
  Real x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
  Real f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < 40; ++k) {
    if (f1 < f2) {
      hi = x2, x2 = x1, f2 = f1;
      x1 = hi - phi * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1, x1 = x2, f1 = f2;
      x2 = lo + phi * (hi - lo);
      f2 = f(x2);
    }
  }
  return std::min({f1, f2, f(Real(0)), f(Real(1))});
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Every field finite, t in [0, 1], a unit normal: whatever the status. Empty when so, else
// what is wrong.
std::string malformed(const CastResult& r) {
  if (!(std::isfinite(r.t) && std::isfinite(r.distance) && std::isfinite(r.depth))) return "non-finite t or distance";
  if (!(finite(r.point) && finite(r.point_a) && finite(r.point_b) && finite(r.normal))) return "non-finite point";
  if (!(r.t >= Real(0) && r.t <= Real(1))) return "t outside [0, 1]";
  const bool contact = r.status == CcdStatus::Hit || r.status == CcdStatus::InitiallyOverlapping;
  if (contact && std::abs(glm::length(r.normal) - Real(1)) > Real(1e-3)) {
    return "normal of length " + std::to_string(glm::length(r.normal));
  }
  if (r.status == CcdStatus::Separated && r.t != Real(1)) return "separated with t < 1";
  if (r.status == CcdStatus::InitiallyOverlapping && !(r.t == Real(0) && r.depth > Real(0))) {
    return "overlap with t > 0 or depth <= 0";
  }
  return {};
}

// Largest tolerance a cast may use (shape_cast.hpp, time_of_impact.hpp): the requested one
// raised to the documented floor 8 linear_tolerance(scale), the scale being the shapes' size
// plus their distance (here: the boxes' diagonals, the distance of the origins and |s|).
Real cast_tolerance(ShapeRef a, const Transform& pa, const Vec3& s, ShapeRef b, const Transform& pb, Real requested) {
  const auto size = [](ShapeRef x) {
    if (x.type() == ShapeType::HalfSpace) return Real(0);
    return glm::length(world_aabb(x, Transform{}).extents());
  };
  const Real scale = size(a) + size(b) + glm::length(pa.position - pb.position) + glm::length(s);
  return std::max(requested, Real(8) * linear_tolerance(scale));
}

// Malformed answers seen by cast() (the contract of every status, whatever the pair):
// counted, the first few described; the fixture expects none.
struct Audit {
  int malformed = 0;
  std::string examples;
};
Audit& audit() {
  static Audit a;
  return a;
}

class ShapeCast : public ::testing::Test {
 protected:
  void SetUp() override { audit() = Audit{}; }
  void TearDown() override { EXPECT_EQ(audit().malformed, 0) << "malformed answers:" << audit().examples; }
};

CastResult cast(ShapeRef a, const Transform& pa, const Vec3& s, ShapeRef b, const Transform& pb,
                const CastOptions& options = {}) {
  const Result<CastResult> r = shape_cast(a, pa, s, b, pb, options);
  EXPECT_TRUE(r.ok()) << (r.ok() ? "" : r.error().what());
  if (!r.ok()) return CastResult{};
  const std::string wrong = malformed(*r);
  if (!wrong.empty() && ++audit().malformed <= 3) {
    audit().examples += "\n  " + wrong + " (" + to_string(r->status) + ", t " + std::to_string(r->t) + "): ";
    audit().examples += text(a, pa, s, b, pb);
  }
  return *r;
}

// ---------------------------------------------------------------------------------------
// Closed forms (double)

// Least t >= 0 with |p + t s| = radius (p outside), +infinity when never.
double ray_ball(const D3& p, const D3& s, double radius) {
  const double a = glm::dot(s, s), b = glm::dot(p, s), c = glm::dot(p, p) - radius * radius;
  if (c <= 0) return 0;
  if (b >= 0 || a == 0) return kInf;
  const double disc = b * b - a * c;
  if (disc < 0) return kInf;
  return c / (-b + std::sqrt(disc));  // the smaller root, without cancellation
}

// Least t >= 0 at which p + t s enters the box |x_i| <= h_i (slab test), +infinity when never.
double ray_slab_box(const D3& p, const D3& s, const D3& h) {
  double t0 = 0, t1 = kInf;
  for (int i = 0; i < 3; ++i) {
    if (s[i] == 0) {
      if (std::abs(p[i]) > h[i]) return kInf;
      continue;
    }
    double a = (-h[i] - p[i]) / s[i], b = (h[i] - p[i]) / s[i];
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
  }
  return t0 <= t1 ? t0 : kInf;
}

// Least t >= 0 at which p + t s comes within `radius` of the segment {c + u e_axis, |u| <= h}.
double ray_edge_cylinder(const D3& p, const D3& s, const D3& c, int axis, double h, double radius) {
  D3 q = p - c, d = s;
  q[axis] = 0;
  d[axis] = 0;
  const double t = ray_ball(q, d, radius);  // the infinite cylinder, in the plane across the axis
  if (!(t < kInf)) return kInf;
  const double u = p[axis] + t * s[axis] - c[axis];
  return std::abs(u) <= h ? t : kInf;
}

// Least t >= 0 at which the point p + t s (box frame) comes within `radius` of the box of
// half extents h: the ray against the rounded box, the union of three slabs grown along one
// axis each, twelve edge cylinders and eight corner balls (first entry = least entry).
double ray_rounded_box(const D3& p, const D3& s, const D3& h, double radius) {
  double t = kInf;
  for (int i = 0; i < 3; ++i) {
    D3 grown = h;
    grown[i] += radius;
    t = std::min(t, ray_slab_box(p, s, grown));
    for (int sj = -1; sj <= 1; sj += 2) {
      for (int sk = -1; sk <= 1; sk += 2) {
        D3 c(0);
        c[(i + 1) % 3] = sj * h[(i + 1) % 3];
        c[(i + 2) % 3] = sk * h[(i + 2) % 3];
        t = std::min(t, ray_edge_cylinder(p, s, c, i, h[i], radius));
      }
    }
  }
  for (int k = 0; k < 8; ++k) {
    const D3 corner((k & 1) ? h.x : -h.x, (k & 2) ? h.y : -h.y, (k & 4) ? h.z : -h.z);
    t = std::min(t, ray_ball(p - corner, s, radius));
  }
  return t;
}

// Accuracy of the narrow phase's distance at the sweep's length scale (~10; GJK on curved
// cores converges linearly).
const Real kGapAccuracy = kFloat ? Real(5e-5) : Real(1e-9);
// Accuracy of a penetration depth (EPA at the sweep's scale; the cast measures it in a frame
// recentred on B, the test in the world frame).
const Real kDepthAccuracy = kFloat ? Real(5e-5) : Real(1e-7);

// Wrong answers of a sweep: counted, the first few described in full (shapes, poses,
// translation) so that each reproduces on its own.
struct Failures {
  int count = 0;
  std::string examples;
  void add(const std::string& what) {
    if (++count <= 4) examples += "\n  " + what;
  }
};

std::string fmt(const char* format, double x, double y = 0, double z = 0) {
  char buffer[200];
  std::snprintf(buffer, sizeof(buffer), format, x, y, z);
  return buffer;
}

// The window of a closed form: early = first t at which the gap reaches target + tolerance,
// late = first t at which it reaches the target. A correct cast lands in [early, late].
struct Window {
  double early = kInf;
  double late = kInf;
};

// Empty when the cast fits the window up to `slack` (fraction of s), else what is wrong.
std::string check_window(const CastResult& r, const Window& w, double slack) {
  const std::string got = std::string(to_string(r.status)) + fmt(" t %.9g", double(r.t));
  const std::string window = fmt(" (window [%.9g, %.9g], slack %.3g)", w.early, w.late, slack);
  if (w.late <= 1) {
    if (r.status != CcdStatus::Hit) return "expected a hit, got " + got + window;
    if (double(r.t) < w.early - slack || double(r.t) > w.late + slack) return "t out of the window: " + got + window;
  } else if (w.early <= 1) {
    // Passing within the tolerance band: either answer, but a hit not before the window.
    if (r.status == CcdStatus::Hit && double(r.t) < w.early - slack) return "early hit: " + got + window;
  } else if (r.status != CcdStatus::Separated) {
    return "expected no hit, got " + got + window;
  }
  return {};
}

// Slack in t of a window check: the rounding of float inputs and of the cast itself at
// length scale `scale`, over the closing speed along the normal (|s| per unit t).
double window_slack(double scale, double closing) {
  const double rounding = (kFloat ? 4e-6 : 1e-12) * std::max(1.0, scale);
  return rounding / std::max(closing, 1e-3 * scale);
}

TEST_F(ShapeCast, SphereAgainstSphereQuadratic) {
  test::Random rng(1101);
  int hits = 0;
  Failures wrong;
  const int n = test::sweep_size(3000);
  for (int i = 0; i < n; ++i) {
    const Sphere a = Sphere::create(rng.uniform(Real(0.1), Real(1.5))).value();
    const Sphere b = Sphere::create(rng.uniform(Real(0.1), Real(1.5))).value();
    const Transform pa = rng.pose(Real(4)), pb = rng.pose(Real(4));
    const Vec3 s = (pb.position - pa.position + rng.in_ball(Real(2))) * rng.uniform(Real(0.2), Real(1.6));
    CastOptions o;
    o.target_distance = i % 3 == 0 ? rng.uniform(Real(0), Real(0.3)) : Real(0);
    o.tolerance = i % 2 == 0 ? Real(1e-4) : Real(3e-3);
    const D3 p = dv(pa.position) - dv(pb.position);
    const Real tol = cast_tolerance(a, pa, s, b, pb, o.tolerance);
    if (glm::length(p) <= double(a.radius() + b.radius() + o.target_distance + tol) + 1e-3) continue;
    const CastResult r = cast(a, pa, s, b, pb, o);
    const double rr = double(a.radius()) + double(b.radius()) + double(o.target_distance);
    const Window w{ray_ball(p, dv(s), rr + double(tol)), ray_ball(p, dv(s), rr)};
    const double closing = w.late <= 1 ? -glm::dot(glm::normalize(p + w.late * dv(s)), dv(s)) : 0;
    const std::string problem = check_window(r, w, window_slack(10, closing));
    if (!problem.empty()) wrong.add(problem + ": " + text(a, pa, s, b, pb));
    if (r.status == CcdStatus::Hit) {
      ++hits;
      // The normal joins the centres at t, from A to B.
      const D3 centres = dv(pb.position) - (dv(pa.position) + double(r.t) * dv(s));
      EXPECT_GT(glm::dot(dv(r.normal), glm::normalize(centres)), 0.999) << "case " << i;
    }
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(hits, test::sweep_share(800));
}

TEST_F(ShapeCast, SphereAgainstBoxIsTheRayAgainstTheRoundedBox) {
  test::Random rng(1102);
  int hits = 0;
  Failures wrong;
  const int n = test::sweep_size(3000);
  for (int i = 0; i < n; ++i) {
    const Sphere a = Sphere::create(rng.uniform(Real(0.05), Real(1))).value();
    const Box b = Box::create(rng.vec3(Real(0.1), Real(1.5))).value();
    const Transform pa = rng.pose(Real(4)), pb = rng.pose(Real(4));
    // Aim at a corner, an edge or a face of the box (the rounded parts as often as the flat).
    const Vec3 aim = pb.apply(b.half_extents() * rng.vec3(Real(-1.2), Real(1.2)));
    const Vec3 s = (aim - pa.position) * rng.uniform(Real(0.3), Real(1.6));
    CastOptions o;
    o.target_distance = i % 3 == 0 ? rng.uniform(Real(0), Real(0.3)) : Real(0);
    // The centre's ray in the box frame.
    const D3 p = dv(pb.inverse_apply(pa.position));
    const D3 d = dv(pb.inverse_apply_vector(s));
    const double rr = double(a.radius()) + double(o.target_distance);
    const Real tol = cast_tolerance(a, pa, s, b, pb, o.tolerance);
    if (ray_rounded_box(p, D3(0), dv(b.half_extents()), rr + double(tol) + 1e-3) == 0) continue;
    const CastResult r = cast(a, pa, s, b, pb, o);
    const Window w{ray_rounded_box(p, d, dv(b.half_extents()), rr + double(tol)),
                   ray_rounded_box(p, d, dv(b.half_extents()), rr)};
    const double closing = r.status == CcdStatus::Hit ? double(glm::dot(r.normal, s)) : 0;
    const std::string problem = check_window(r, w, window_slack(10, closing));
    if (!problem.empty()) wrong.add(problem + ": " + text(a, pa, s, b, pb));
    hits += r.status == CcdStatus::Hit;
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(hits, test::sweep_share(1000));
}

// Compares a cast of a point or a sphere with the ray of its centre against B (inflated by
// the sphere's radius): the cast stops within the tolerance before the surface the ray
// meets; a cast that hits where the ray misses passes within the tolerance.
std::string check_against_ray(const CastResult& r, const std::optional<RayHit>& ray, const Vec3& s, Real tol,
                              const std::function<Real(Real)>& gap) {
  const std::string got = std::string(to_string(r.status)) + fmt(" t %.9g", double(r.t));
  if (ray) {
    const double closing = -double(glm::dot(ray->normal, s));
    const double slack = window_slack(6, closing);
    const double early = double(ray->t) - double(tol) / std::max(closing, 1e-3) - slack;
    if (r.status != CcdStatus::Hit || double(r.t) > double(ray->t) + slack || double(r.t) < early) {
      return got + fmt(", the ray hits at %.9g (closing speed %.3g)", double(ray->t), closing);
    }
    // The normal (A to B) faces the surface's outward normal where the ray meets it; the
    // cast stops up to the tolerance short of it, so near an edge it may lean within the
    // edge's normal cone, never against the surface.
    const double facing = -double(glm::dot(r.normal, ray->normal));
    if (!(facing > 0.5)) return got + fmt(": normal . -surface normal = %.9g", facing);
  } else if (r.status == CcdStatus::Hit) {
    const Real g = gap(r.t);
    if (g > tol + kGapAccuracy || g < -kGapAccuracy) return got + fmt(" where the ray misses; gap there %.9g", g);
  }
  return {};
}

TEST_F(ShapeCast, PointCastIsTheRaycast) {
  test::Random rng(1103);
  const Point point = Point::create().value();
  int hits = 0;
  Failures wrong;
  const int n = test::sweep_size(2100);
  for (int i = 0; i < n; ++i) {
    const ShapeType kind = kConvexKinds[std::size_t(i % 7)];  // the solids: sphere .. hull
    const Shape b = random_convex(rng, kind, Real(1));
    const Transform pa = rng.pose(Real(3)), pb = rng.pose(Real(3));
    const Vec3 s = (pb.position - pa.position + rng.in_ball(Real(1))) * rng.uniform(Real(0.3), Real(1.6));
    if (gap_at(point, pa, s, Real(0), b, pb) <= Real(2e-3)) continue;
    const CastResult r = cast(point, pa, s, b, pb);
    const Real tol = cast_tolerance(point, pa, s, b, pb, CastOptions{}.tolerance);
    const std::optional<RayHit> ray = raycast(b, pb, Ray{pa.position, s}, Real(1));
    const std::string problem =
        check_against_ray(r, ray, s, tol, [&](Real t) { return gap_at(point, pa, s, t, b, pb); });
    if (!problem.empty()) wrong.add(problem + ": " + text(point, pa, s, b, pb));
    hits += ray.has_value();
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(hits, test::sweep_share(600));
}

TEST_F(ShapeCast, SphereCastIsTheRayAgainstTheInflatedShape) {
  test::Random rng(1104);
  int hits = 0;
  Failures wrong;
  const int n = test::sweep_size(2000);
  for (int i = 0; i < n; ++i) {
    const Real ra = rng.uniform(Real(0.05), Real(0.8));
    const Sphere a = Sphere::create(ra).value();
    const Transform pa = rng.pose(Real(3)), pb = rng.pose(Real(3));
    const Vec3 s = (pb.position - pa.position + rng.in_ball(Real(1))) * rng.uniform(Real(0.3), Real(1.6));
    const Ray ray{pa.position, s};
    Shape b = Point::create().value(), inflated = b;
    std::optional<RayHit> hit;
    bool start_inside = false;
    switch (i % 3) {
      case 0: {
        const Real rb = rng.uniform(Real(0.1), Real(1));
        b = Sphere::create(rb).value();
        inflated = Sphere::create(rb + ra).value();
        break;
      }
      case 1: {
        const Real rb = rng.uniform(Real(0.1), Real(0.6)), h = rng.uniform(Real(0.1), Real(1));
        b = Capsule::create(rb, h).value();
        inflated = Capsule::create(rb + ra, h).value();
        break;
      }
      default: {
        // The rounded box has no shape of its own: the closed form above.
        const Box box = Box::create(rng.vec3(Real(0.1), Real(1))).value();
        b = box;
        const D3 p = dv(pb.inverse_apply(pa.position)), d = dv(pb.inverse_apply_vector(s));
        start_inside = ray_rounded_box(p, D3(0), dv(box.half_extents()), double(ra)) == 0;
        const double t = ray_rounded_box(p, d, dv(box.half_extents()), double(ra));
        if (!start_inside && t <= 1) {
          // Its normal: from the nearest box point to the centre at t.
          const D3 c = p + t * d;
          const D3 nearest = glm::clamp(c, -dv(box.half_extents()), dv(box.half_extents()));
          hit = RayHit{Real(t), ray.at(Real(t)), pb.apply_vector(Vec3(glm::normalize(c - nearest)))};
        }
      }
    }
    if (i % 3 != 2) {
      start_inside = raycast(inflated, pb, Ray{pa.position, Vec3(0)}, Real(0)).has_value();
      hit = raycast(inflated, pb, ray, Real(1));
    }
    if (start_inside || gap_at(a, pa, s, Real(0), b, pb) <= Real(2e-3)) continue;
    const CastResult r = cast(a, pa, s, b, pb);
    const Real tol = cast_tolerance(a, pa, s, b, pb, CastOptions{}.tolerance);
    const std::string problem = check_against_ray(r, hit, s, tol, [&](Real t) { return gap_at(a, pa, s, t, b, pb); });
    if (!problem.empty()) wrong.add(problem + ": " + text(a, pa, s, b, pb));
    hits += hit.has_value();
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(hits, test::sweep_share(600));
}

TEST_F(ShapeCast, CapsuleAgainstHalfSpaceClosedForm) {
  test::Random rng(1105);
  int hits = 0, misses = 0;
  Failures wrong;
  const int n = test::sweep_size(2000);
  for (int i = 0; i < n; ++i) {
    const Capsule a = Capsule::create(rng.uniform(Real(0.05), Real(0.8)), rng.uniform(Real(0.1), Real(1.5))).value();
    const HalfSpace h = HalfSpace::create(rng.unit_vector(), rng.uniform(Real(-2), Real(2))).value();
    const Transform pb = rng.pose(Real(2));
    // World plane m . x = offset; A starts above it, moving at random (half towards it).
    const D3 m = dv(pb.apply_vector(h.normal()));
    const double offset = double(h.offset()) + glm::dot(m, dv(pb.position));
    Transform pa = rng.pose(Real(4));
    pa.position =
        pb.position + Vec3(m * (double(h.offset()) + double(rng.uniform(Real(0), Real(4))))) + rng.in_ball(Real(3));
    const Vec3 s = rng.vector_of_length(Real(0.5), Real(8)) - (i % 2 == 0 ? Vec3(m) * Real(4) : Vec3(0));
    CastOptions o;
    o.target_distance = i % 3 == 0 ? rng.uniform(Real(0), Real(0.3)) : Real(0);
    // The capsule's lower end along m.
    const D3 top = dv(pa.apply(a.top())), bottom = dv(pa.apply(a.bottom()));
    const double height = std::min(glm::dot(m, top), glm::dot(m, bottom)) - offset - double(a.radius());
    const double closing = -glm::dot(m, dv(s));
    const Real tol = cast_tolerance(a, pa, s, h, pb, o.tolerance);
    if (height <= double(o.target_distance + tol) + 1e-3) continue;
    const CastResult r = cast(a, pa, s, h, pb, o);
    const double late = closing > 0 ? (height - double(o.target_distance)) / closing : kInf;
    const double early = closing > 0 ? (height - double(o.target_distance + tol)) / closing : kInf;
    std::string problem = check_window(r, Window{early, late}, window_slack(10, closing));
    if (r.status == CcdStatus::Hit) {
      ++hits;
      // The normal points into the plane; A's witness is on the plane grown by the target.
      if (!(glm::dot(dv(r.normal), -m) > 0.9999)) problem += fmt(" normal . -m = %.9g", glm::dot(dv(r.normal), -m));
      const double witness = glm::dot(m, dv(r.point_a)) - offset - double(o.target_distance);
      if (!(std::abs(witness) <= double(tol) + 1e-4)) problem += fmt(" witness at %.9g from the target", witness);
    } else {
      ++misses;
    }
    if (!problem.empty()) wrong.add(problem + ": " + text(a, pa, s, h, pb));
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(hits, test::sweep_share(400));
  EXPECT_GT(misses, test::sweep_share(400));
}

// ---------------------------------------------------------------------------------------
// Against time_of_impact

// What a sweep saw. Wrong answers are counted per kind of pair, the first few described in
// full (shapes, poses, translation) so that each reproduces on its own.
struct SweepTally {
  int cases = 0, hits = 0, separated = 0, overlaps = 0, band = 0, toi_capped = 0, grazing = 0;
  int wrong = 0;
  double worst_t = 0;  // worst |t_cast - t_toi| x closing / tolerance
  std::string examples;
  std::string wrong_pairs;

  void fail(const std::string& what, const std::string& label, const std::string& repro) {
    if (++wrong <= 4) examples += "\n  " + label + ": " + what + "\n    " + repro;
  }
  void add(const SweepTally& t, const std::string& pair) {
    cases += t.cases, hits += t.hits, separated += t.separated, overlaps += t.overlaps, band += t.band;
    toi_capped += t.toi_capped, grazing += t.grazing, wrong += t.wrong;
    worst_t = std::max(worst_t, t.worst_t);
    if (wrong - t.wrong < 4) examples += t.examples;
    if (t.wrong > 0) wrong_pairs += " " + pair + " (" + std::to_string(t.wrong) + ")";
  }
};

// One case: the cast and the TOI of the same translation, both with the default tolerance
// (raised to the pair's floor); the checks allow the documented floor (cast_tolerance).
void compare_with_toi(ShapeRef a, const Transform& pa, const Vec3& s, ShapeRef b, const Transform& pb, Real target,
                      SweepTally& tally, const std::string& label) {
  CastOptions co;
  co.target_distance = target;
  ToiOptions to;
  to.target_distance = target;
  const CastResult c = cast(a, pa, s, b, pb, co);
  const Result<ToiResult> toi = time_of_impact(a, Motion{pa, moved(pa, s, Real(1))}, b, Motion::stationary(pb), to);
  ASSERT_TRUE(toi.ok());
  ++tally.cases;
  const Real tol = cast_tolerance(a, pa, s, b, pb, co.tolerance), eps = kGapAccuracy;
  const Real gap0 = gap_at(a, pa, s, Real(0), b, pb);
  const auto fail = [&](const std::string& what) { tally.fail(what, label, text(a, pa, s, b, pb)); };
  const auto both = [&] {
    return std::string("cast ") + to_string(c.status) + fmt(" t %.9g, toi ", c.t) + to_string(toi->status) +
           fmt(" t %.9g", toi->toi);
  };
  // The cast on its own: each status checked on the narrow phase's distance.
  switch (c.status) {
    case CcdStatus::InitiallyOverlapping:
      ++tally.overlaps;
      if (!(gap0 < -tol + eps)) fail(both() + fmt(": overlap but the gap at 0 is %.9g", gap0));
      if (!(std::abs(c.depth + gap0) <= kDepthAccuracy)) {
        fail(both() + fmt(": depth %.9g, gap at 0 %.9g", c.depth, gap0));
      }
      break;
    case CcdStatus::Hit: {
      ++tally.hits;
      const Real g = gap_at(a, pa, s, c.t, b, pb);
      if (!(g <= target + tol + eps)) fail(both() + fmt(": gap %.9g at the hit, target %.9g", g, target));
      if (!(g >= (c.t > Real(0) ? target - eps : -tol - eps))) {
        fail(both() + fmt(": gap %.9g at the hit, deeper than the target %.9g", g, target));
      }
      if (!(glm::dot(c.normal, s) > Real(0))) fail(both() + fmt(": normal . s = %.9g at a hit", glm::dot(c.normal, s)));
      break;
    }
    case CcdStatus::Separated: {
      ++tally.separated;
      if (gap0 > target + tol + eps) {
        const Real least = least_gap(a, pa, s, b, pb);
        if (!(least > target - eps)) fail(both() + fmt(": missed, the gap falls to %.9g on the way", least));
      }
      break;
    }
    default: fail(both() + ": no answer (iteration cap)"); return;
  }
  // Against the TOI.
  if (toi->status == CcdStatus::MaxIterations) {
    ++tally.toi_capped;
    return;
  }
  if (c.status == toi->status) {
    if (c.status != CcdStatus::Hit) return;
    // Both times lie where the gap is within [target, target + tol] before first contact;
    // the gap is convex in t, so that window is at most tol / closing long.
    const Real closing = std::max(glm::dot(c.normal, s), Real(1e-3) * glm::length(s));
    if (closing < Real(0.05) * glm::length(s)) ++tally.grazing;
    const double dt = std::abs(double(c.t) - double(toi->toi)) * double(closing);
    tally.worst_t = std::max(tally.worst_t, dt / double(tol));
    if (!(dt <= double(tol + 2 * eps))) fail(both() + fmt(": |dt| x closing = %.9g", dt));
    return;
  }
  // Different classifications: only inside the tolerance band.
  ++tally.band;
  const auto is = [&](CcdStatus p, CcdStatus q) {
    return (c.status == p && toi->status == q) || (c.status == q && toi->status == p);
  };
  if (is(CcdStatus::Hit, CcdStatus::Separated)) {
    const Real t = c.status == CcdStatus::Hit ? c.t : toi->toi;
    const Real g = gap_at(a, pa, s, t, b, pb);
    if (!(g >= target - eps && g <= target + tol + eps)) fail(both() + fmt(": the hit's gap is %.9g", g));
  } else if (!(std::abs(gap0 + tol) <= tol + eps)) {
    // Overlap against a touching answer at t = 0: the gap is near -tol (the floors may differ).
    fail(both() + fmt(": classified apart at a gap of %.9g at t = 0", gap0));
  }
}

// A case of the sweep: A and B of the given kinds, B still; the translation aims near B.
void sweep_pair(test::Random& rng, ShapeType ka, ShapeType kb, int count, SweepTally& tally) {
  for (int i = 0; i < count; ++i) {
    const Shape a = random_convex(rng, ka, rng.uniform(Real(0.4), Real(1.2)));
    const Real target = i % 4 == 3 ? rng.uniform(Real(0.02), Real(0.2)) : Real(0);
    const std::string label = std::string(to_string(ka)) + " vs " + to_string(kb) + " case " + std::to_string(i);
    if (kb == ShapeType::HalfSpace) {
      const HalfSpace h = HalfSpace::create(rng.unit_vector(), rng.uniform(Real(-1), Real(1))).value();
      const Transform pb = rng.pose(Real(2));
      const Vec3 m = pb.apply_vector(h.normal());
      Transform pa = rng.pose(Real(2));
      pa.position = pb.position + m * (h.offset() + rng.uniform(Real(-0.5), Real(3))) + rng.in_ball(Real(2));
      const Vec3 s = -m * rng.uniform(Real(0), Real(4)) + rng.in_ball(Real(3));
      compare_with_toi(a, pa, s, h, pb, target, tally, label);
    } else {
      const Shape b = random_convex(rng, kb, rng.uniform(Real(0.4), Real(1.2)));
      const Transform pa = rng.pose(Real(2.5)), pb = rng.pose(Real(2.5));
      const Vec3 s = (pb.position - pa.position + rng.in_ball(Real(1.2))) * rng.uniform(Real(0.3), Real(1.8));
      compare_with_toi(a, pa, s, b, pb, target, tally, label);
    }
  }
}

TEST_F(ShapeCast, AgreesWithTimeOfImpactOverEveryConvexPair) {
  test::Random rng(1201);
  SweepTally all;
  std::vector<ShapeType> kinds_b(kConvexKinds.begin(), kConvexKinds.end());
  kinds_b.push_back(ShapeType::HalfSpace);
  const int per_pair = test::sweep_size(40);
  for (const ShapeType ka : kConvexKinds) {
    for (const ShapeType kb : kinds_b) {
      SweepTally t;
      sweep_pair(rng, ka, kb, per_pair, t);
      all.add(t, std::string(to_string(ka)) + "/" + to_string(kb));
    }
  }
  std::printf(
      "cast vs TOI: %d cases (%d hits, %d separated, %d overlapping); %d classified apart inside the band, %d TOI "
      "capped, %d grazing hits; worst |dt| x closing = %.3g x tolerance; %d wrong\n",
      all.cases, all.hits, all.separated, all.overlaps, all.band, all.toi_capped, all.grazing, all.worst_t, all.wrong);
  EXPECT_EQ(all.wrong, 0) << "by pair:" << all.wrong_pairs << all.examples;
  EXPECT_GT(all.hits, all.cases / 5);
  EXPECT_GT(all.separated, all.cases / 5);
  EXPECT_GT(all.overlaps, all.cases / 50);
  EXPECT_LT(all.band, all.cases / 100 + 1);
  EXPECT_LT(all.toi_capped, all.cases / 100 + 1);
}

// ---------------------------------------------------------------------------------------
// Meshes and compounds against brute force over their parts

// Tolerance of the part tests: above the precision floor of every part and of the whole (the
// floor follows the moving geometry's size, which differs between a mesh and one triangle).
const Real kPartTol = kFloat ? Real(3e-4) : Real(1e-7);

// A convex, still or moving, at its pose: one part of a mesh (a Triangle) or a compound.
struct Part {
  Shape shape;
  Transform pose;
  std::uint32_t index = 0;
};

// The triangles of `mesh` placed at `pose`, without those that culling drops: a triangle is
// culled when the other shape, moving by `relative` (world) with respect to the mesh, would
// reach it from behind (along its normal).
std::vector<Part> triangle_parts(const TriangleMesh& mesh, const Transform& pose, const Vec3& relative, bool cull) {
  std::vector<Part> parts;
  const Vec3 local = pose.inverse_apply_vector(relative);
  for (std::uint32_t i = 0; i < mesh.triangle_count(); ++i) {
    const std::array<Vec3, 3> v = mesh.triangle(i);
    if (cull && glm::dot(glm::cross(v[1] - v[0], v[2] - v[0]), local) > Real(0)) continue;
    const Result<Triangle> t = Triangle::create(v[0], v[1], v[2]);
    if (t) parts.push_back({*t, pose, i});
  }
  return parts;
}

std::vector<Part> child_parts(const Compound& compound, const Transform& pose) {
  std::vector<Part> parts;
  const auto kids = compound.children();
  for (std::uint32_t k = 0; k < kids.size(); ++k) parts.push_back({kids[k].shape, pose * kids[k].pose, k});
  return parts;
}

// Overlap first, then the least t among hits: the answer of a set of parts.
bool better(const CastResult& r, const CastResult& best) {
  const auto rank = [](const CastResult& x) {
    return x.status == CcdStatus::InitiallyOverlapping ? 0 : x.status == CcdStatus::Hit ? 1 : 2;
  };
  return rank(r) < rank(best) || (rank(r) == 1 && rank(best) == 1 && r.t < best.t);
}

// Brute force: every part cast on its own (each validated by its own t = 0 rule), the best
// kept; `index` receives the part that gave it. `moving_parts`: the parts move by s against
// `other` at `pose_other`; else `other` moves by s against the parts.
CastResult brute_force(const std::vector<Part>& parts, bool moving_parts, ShapeRef other, const Transform& pose_other,
                       const Vec3& s, const CastOptions& o, std::uint32_t& index) {
  CastResult best;
  index = kNoIndex;
  for (const Part& part : parts) {
    const CastResult r = moving_parts ? cast(part.shape, part.pose, s, other, pose_other, o)
                                      : cast(other, pose_other, s, part.shape, part.pose, o);
    if (better(r, best)) {
      best = r;
      index = part.index;
    }
  }
  return best;
}

// Empty when the whole's answer equals the parts' (same status; t within rounding, or within
// the tolerance band when `band` is set: a different algorithm answered).
std::string compare_with_parts(const CastResult& whole, const CastResult& parts, const Vec3& s, bool band) {
  const std::string got = std::string(to_string(whole.status)) + fmt(" t %.9g, parts ", double(whole.t)) +
                          to_string(parts.status) + fmt(" t %.9g", double(parts.t));
  if (whole.status != parts.status) return got;
  if (whole.status != CcdStatus::Hit) return {};
  const double closing = std::max(double(glm::dot(parts.normal, s)), 1e-3 * double(glm::length(s)));
  const double allowed = band ? 2 * double(kPartTol + kGapAccuracy) / closing : window_slack(10, closing);
  if (std::abs(double(whole.t) - double(parts.t)) > allowed) return got + fmt(" (allowed %.3g)", allowed);
  return {};
}

// An open terrain: an n x n grid over [-half, half]^2 with seeded heights, facing up.
TriangleMesh terrain(test::Random& rng, int n, Real half, Real bumps) {
  IndexedMesh m;
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n; ++i) {
      const Real x = -half + Real(2) * half * Real(i) / Real(n), y = -half + Real(2) * half * Real(j) / Real(n);
      m.vertices.push_back(Vec3(x, y, rng.uniform(-bumps, bumps)));
    }
  }
  const auto id = [&](int i, int j) { return static_cast<std::uint32_t>(j * (n + 1) + i); };
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      m.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  }
  return TriangleMesh::create(m).value();
}

// The moving convex shapes of the part tests.
Shape part_test_shape(test::Random& rng, int i) {
  constexpr std::array<ShapeType, 4> kinds{ShapeType::Sphere, ShapeType::Box, ShapeType::Capsule,
                                           ShapeType::ConvexHull};
  return random_convex(rng, kinds[std::size_t(i % 4)], rng.uniform(Real(0.3), Real(0.8)));
}

struct PartTally {
  int cases = 0, hits = 0, overlaps = 0;
  Failures wrong;
};

// Convex A against mesh B (and, mirrored, mesh A against convex B) versus the triangles.
void mesh_case(const Shape& convex, const TriangleMesh& mesh, const Transform& p_convex, const Transform& p_mesh,
               const Vec3& s, bool cull, bool mesh_moves, PartTally& tally) {
  CastOptions o;
  o.tolerance = kPartTol;
  o.cull_back_faces = cull;
  const CastResult whole =
      mesh_moves ? cast(mesh, p_mesh, s, convex, p_convex, o) : cast(convex, p_convex, s, mesh, p_mesh, o);
  std::uint32_t index = kNoIndex;
  const std::vector<Part> parts = triangle_parts(mesh, p_mesh, mesh_moves ? -s : s, cull);
  const CastResult brute = brute_force(parts, mesh_moves, convex, p_convex, s, o, index);
  ++tally.cases;
  tally.hits += whole.status == CcdStatus::Hit;
  tally.overlaps += whole.status == CcdStatus::InitiallyOverlapping;
  std::string problem = compare_with_parts(whole, brute, s, false);
  const std::uint32_t reported = mesh_moves ? whole.sub_a.triangle : whole.sub_b.triangle;
  if (problem.empty() && whole.status == CcdStatus::Hit && reported == kNoIndex) problem = "no triangle named";
  if (!problem.empty()) {
    const std::string who = mesh_moves ? "mesh moving against " : "moving against mesh, ";
    tally.wrong.add(problem + (cull ? " (culling) " : " ") + who + text(convex) + " at " + text(p_convex) +
                    ", mesh at " + text(p_mesh) + " along " + text(s));
  }
}

TEST_F(ShapeCast, MeshesEqualTheirTrianglesCastOneByOne) {
  test::Random rng(1301);
  const TriangleMesh torus = TriangleMesh::create(test::torus_mesh(Real(2), Real(0.7), 20, 10)).value();
  ASSERT_TRUE(torus.is_closed());
  const TriangleMesh ground = terrain(rng, 10, Real(4), Real(0.4));
  PartTally tally;
  const int n = test::sweep_size(240);
  for (int i = 0; i < n; ++i) {
    const Shape a = part_test_shape(rng, i);
    const bool cull = i % 3 == 2, mesh_moves = i % 5 == 4;
    const Transform pa = rng.pose(Real(1));
    if (i % 2 == 0) {
      // The torus: aim at its ring or through its hole, from anywhere around it.
      const Transform pb = rng.pose(Real(1));
      const Vec3 from = pb.position + rng.vector_of_length(Real(2.5), Real(5));
      const Vec3 ring = pb.apply(Vec3(glm::normalize(Vec3(rng.vec3(Real(-1), Real(1)).x, rng.uniform(-1, 1), 0)) *
                                      (i % 4 == 0 ? Real(2) : Real(0))));
      const Vec3 s = (ring - from + rng.in_ball(Real(0.8))) * rng.uniform(Real(0.5), Real(1.8));
      mesh_case(a, torus, Transform{from, pa.rotation}, pb, s, cull, mesh_moves, tally);
    } else {
      // The terrain: from above (now and then from below), towards it, at a slant.
      const Transform pb{rng.vec3(Real(-1), Real(1)),
                         glm::angleAxis(rng.uniform(Real(-0.3), Real(0.3)), glm::normalize(rng.unit_vector()))};
      const Real side = i % 7 == 1 ? Real(-1) : Real(1);
      const Vec3 from =
          pb.apply(Vec3(rng.uniform(-3, 3), rng.uniform(-3, 3), side * rng.uniform(Real(0.3), Real(2.5))));
      const Vec3 s =
          pb.apply_vector(Vec3(rng.uniform(-3, 3), rng.uniform(-3, 3), -side * rng.uniform(Real(0), Real(4))));
      mesh_case(a, ground, Transform{from, pa.rotation}, pb, s, cull, mesh_moves, tally);
    }
  }
  std::printf("mesh casts vs their triangles: %d cases, %d hits, %d overlapping, %d wrong\n", tally.cases, tally.hits,
              tally.overlaps, tally.wrong.count);
  EXPECT_EQ(tally.wrong.count, 0) << tally.wrong.examples;
  EXPECT_GT(tally.hits, tally.cases / 4);
  EXPECT_GT(tally.overlaps, 0);
}

TEST_F(ShapeCast, BackFaceCullingDropsTrianglesReachedFromBehind) {
  test::Random rng(1302);
  const TriangleMesh ground = terrain(rng, 8, Real(4), Real(0.1));
  const Sphere ball = Sphere::create(Real(0.4)).value();
  CastOptions culled;
  culled.cull_back_faces = true;
  int cases = 0;
  for (int i = 0; i < 50; ++i) {
    // From below, straight up through the terrain: the front faces look up, so the ball
    // reaches only their backs.
    const Vec3 from(rng.uniform(-3, 3), rng.uniform(-3, 3), rng.uniform(Real(-3), Real(-1)));
    const Vec3 up(rng.uniform(Real(-0.3), Real(0.3)), rng.uniform(Real(-0.3), Real(0.3)),
                  rng.uniform(Real(3), Real(6)));
    const Transform pa{from, kIdentityQuat};
    const CastResult both_sides = cast(ball, pa, up, ground, Transform{});
    const CastResult one_side = cast(ball, pa, up, ground, Transform{}, culled);
    EXPECT_EQ(both_sides.status, CcdStatus::Hit) << "case " << i;
    EXPECT_EQ(one_side.status, CcdStatus::Separated) << "case " << i;
    // From above, down: the front faces are hit alike with and without culling.
    const Transform above{Vec3(from.x, from.y, -from.z), kIdentityQuat};
    const CastResult down = cast(ball, above, -up, ground, Transform{});
    const CastResult down_culled = cast(ball, above, -up, ground, Transform{}, culled);
    EXPECT_EQ(down.status, CcdStatus::Hit) << "case " << i;
    EXPECT_EQ(down_culled.status, CcdStatus::Hit) << "case " << i;
    EXPECT_EQ(down.t, down_culled.t) << "case " << i;
    EXPECT_EQ(down.sub_b.triangle, down_culled.sub_b.triangle) << "case " << i;
    // The mesh moving up against a ball above it meets the ball with its front faces.
    const CastResult lifted = cast(ground, Transform{}, up, ball, above, culled);
    EXPECT_EQ(lifted.status, CcdStatus::Hit) << "case " << i;
    EXPECT_EQ(lifted.sub_a.triangle == kNoIndex, false) << "case " << i;
    ++cases;
  }
  EXPECT_EQ(cases, 50);
}

// A compound of boxes, spheres, capsules and hulls, one nested compound and one closed mesh.
Compound random_compound(test::Random& rng, Real spread) {
  std::vector<CompoundChild> kids;
  for (int k = 0; k < 7; ++k) kids.push_back({part_test_shape(rng, k), rng.pose(spread)});
  std::vector<CompoundChild> nested;
  nested.push_back({Box::create(Vec3(0.4f, 0.2f, 0.3f)).value(), rng.pose(Real(0.5))});
  nested.push_back({Sphere::create(Real(0.3)).value(), rng.pose(Real(0.5))});
  kids.push_back({Compound::create(nested).value(), rng.pose(spread)});
  kids.push_back({TriangleMesh::create(test::icosphere_mesh(1, Real(0.5))).value(), rng.pose(spread)});
  return Compound::create(kids).value();
}

TEST_F(ShapeCast, CompoundsEqualTheirChildrenCastOneByOne) {
  test::Random rng(1303);
  PartTally tally;
  std::vector<Compound> compounds;
  for (int k = 0; k < 12; ++k) compounds.push_back(random_compound(rng, Real(2.5)));
  const int n = test::sweep_size(300);
  for (int i = 0; i < n; ++i) {
    const Compound& compound = compounds[std::size_t(i) % compounds.size()];
    const Shape convex = part_test_shape(rng, i);
    const Transform pc = rng.pose(Real(1));
    const Transform px{pc.position + rng.vector_of_length(Real(3), Real(6)), rng.rotation()};
    // Aim at one child (the others may come first).
    const auto kids = compound.children();
    const Vec3 aim = (pc * kids[std::size_t(rng.integer(0, int(kids.size()) - 1))].pose).position;
    const Vec3 s = (aim - px.position + rng.in_ball(Real(0.5))) * rng.uniform(Real(0.4), Real(1.6));
    const bool compound_moves = i % 2 == 1;
    CastOptions o;
    o.tolerance = kPartTol;
    const CastResult whole =
        compound_moves ? cast(compound, pc, s, convex, px, o) : cast(convex, px, s, compound, pc, o);
    std::uint32_t index = kNoIndex;
    const CastResult brute = brute_force(child_parts(compound, pc), compound_moves, convex, px, s, o, index);
    ++tally.cases;
    tally.hits += whole.status == CcdStatus::Hit;
    tally.overlaps += whole.status == CcdStatus::InitiallyOverlapping;
    std::string problem = compare_with_parts(whole, brute, s, false);
    const std::uint32_t child = compound_moves ? whole.sub_a.child : whole.sub_b.child;
    if (problem.empty() && whole.status == CcdStatus::Hit && child == kNoIndex) problem = "no child named";
    if (!problem.empty()) {
      tally.wrong.add(problem + (compound_moves ? " compound moving against " : " moving against compound, ") +
                      text(convex) + " at " + text(px) + " along " + text(s) + fmt(" (case %d)", i));
    }
  }
  std::printf("compound casts vs their children: %d cases, %d hits, %d overlapping, %d wrong\n", tally.cases,
              tally.hits, tally.overlaps, tally.wrong.count);
  EXPECT_EQ(tally.wrong.count, 0) << tally.wrong.examples;
  EXPECT_GT(tally.hits, tally.cases / 4);
}

// Two non-convex geometries (time_of_impact inside) against the parts of the moving one.
TEST_F(ShapeCast, NonConvexPairsEqualTheMovingPartsWithinTheBand) {
  test::Random rng(1304);
  const TriangleMesh ground = terrain(rng, 6, Real(3), Real(0.3));
  const TriangleMesh ball = TriangleMesh::create(test::icosphere_mesh(1, Real(0.6))).value();
  PartTally tally;
  const int n = test::sweep_size(40);
  for (int i = 0; i < n; ++i) {
    const Transform pg{rng.vec3(Real(-0.5), Real(0.5)), kIdentityQuat};
    const Transform pm{pg.position + Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(Real(1), Real(3))),
                       rng.rotation()};
    const Vec3 s(rng.uniform(-2, 2), rng.uniform(-2, 2), -rng.uniform(Real(0.5), Real(4)));
    CastOptions o;
    o.tolerance = kPartTol;
    std::uint32_t index = kNoIndex;
    CastResult whole, brute;
    if (i % 2 == 0) {
      // Mesh against mesh: each triangle of the moving one cast against the other.
      whole = cast(ball, pm, s, ground, pg, o);
      brute = brute_force(triangle_parts(ball, pm, Vec3(0), false), true, ground, pg, s, o, index);
    } else {
      // A compound against a mesh: each child cast against the mesh.
      const Compound c = random_compound(rng, Real(0.8));
      whole = cast(c, pm, s, ground, pg, o);
      brute = brute_force(child_parts(c, pm), true, ground, pg, s, o, index);
    }
    ++tally.cases;
    tally.hits += whole.status == CcdStatus::Hit;
    const std::string problem = compare_with_parts(whole, brute, s, true);
    if (!problem.empty()) tally.wrong.add(problem + fmt(" (case %d)", i));
  }
  EXPECT_EQ(tally.wrong.count, 0) << tally.wrong.examples;
  EXPECT_GT(tally.hits, tally.cases / 3);
}

// The grazing case: a shape resting on a mesh (a ridge's crest edge, a flat floor of many
// triangles) slides along it into a wall: the triangles touched at t = 0 are not moved into,
// so the wall's t must come out, not 0. Lifting off: the wall too; pressing in: a hit at 0.
IndexedMesh ridge_and_wall(bool flat) {
  IndexedMesh m;
  if (flat) {
    // A floor of 6 x 3 quads in z = 0 (edges and vertices under the sliding shape).
    for (int j = 0; j <= 3; ++j) {
      for (int i = 0; i <= 6; ++i) m.vertices.push_back(Vec3(Real(-6 + 2 * i), Real(-3 + 2 * j), Real(0)));
    }
    for (std::uint32_t j = 0; j < 3; ++j) {
      for (std::uint32_t i = 0; i < 6; ++i) {
        const std::uint32_t v = j * 7 + i;
        m.triangles.push_back({v, v + 1, v + 8});
        m.triangles.push_back({v, v + 8, v + 7});
      }
    }
  } else {
    // Two slopes meeting at the crest edge y = 0, z = 0 along x.
    m.vertices = {{-6, -2, -1}, {6, -2, -1}, {6, 0, 0}, {-6, 0, 0}, {6, 2, -1}, {-6, 2, -1}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}, {3, 2, 4}, {3, 4, 5}};
  }
  // The wall x = 3, facing -x.
  const auto w = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.insert(m.vertices.end(), {{3, -3, -2}, {3, 3, -2}, {3, 3, 3}, {3, -3, 3}});
  m.triangles.push_back({w, w + 2, w + 1});
  m.triangles.push_back({w, w + 3, w + 2});
  return m;
}

// Slides each shape along `mesh` (resting on it at z = 0) towards the wall at x = 3.
void slide_into_wall(const TriangleMesh& mesh, const char* name, Failures& wrong) {
  {
    const Box box = Box::create(Vec3(0.5f)).value();
    const Sphere ball = Sphere::create(Real(0.5)).value();
    const Capsule capsule = Capsule::create(Real(0.5), Real(0.6)).value();
    const Quat lying = glm::angleAxis(kPi / 2, Vec3(1, 0, 0));  // the capsule's axis along y
    for (int shape = 0; shape < 3; ++shape) {
      const ShapeRef a = shape == 0 ? ShapeRef(box) : shape == 1 ? ShapeRef(ball) : ShapeRef(capsule);
      const Transform pa{Vec3(0, 0, 0.5f), shape == 2 ? lying : kIdentityQuat};
      for (const Real sideways : {Real(0), Real(0.5), Real(-0.5)}) {
        for (const Real lift : {Real(0), Real(0.01), Real(-0.01)}) {
          const Vec3 s(5, sideways, lift);
          const CastResult r = cast(a, pa, s, mesh, Transform{});
          const std::string label = std::string(name) + ", " + text(a) + " along " + text(s);
          if (lift < Real(0)) {
            // Pressing into the surface it rests on.
            if (!(r.status == CcdStatus::Hit && r.t == Real(0))) {
              wrong.add(label + ": " + to_string(r.status) + fmt(" t %.9g, expected a hit at 0", r.t));
            }
            continue;
          }
          // The wall: the front face at x = 2.5 (x = 3 less the half width 0.5).
          const double late = 2.5 / 5.0, early = late - double(cast_tolerance(a, pa, s, mesh, {}, Real(1e-4))) / 5.0;
          const std::string problem = check_window(r, Window{early, late}, window_slack(10, 5));
          if (!problem.empty()) wrong.add(label + ": " + problem);
          if (r.status == CcdStatus::Hit && glm::dot(r.normal, Vec3(1, 0, 0)) < Real(0.999)) {
            wrong.add(label + ": the hit's normal is not the wall's");
          }
        }
      }
    }
  }
}

TEST_F(ShapeCast, SlidingAlongATouchedCrestEdgeReportsTheWallAhead) {
  Failures wrong;
  slide_into_wall(TriangleMesh::create(ridge_and_wall(false)).value(), "crest", wrong);
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
}

// The same over a flat floor of many triangles: the shape, touching the floor from t = 0,
// reaches seams (edges of triangles it was not touching at t = 0) on the way; it never
// moves into the floor, so the wall must come out, not a ghost hit on a seam.
TEST_F(ShapeCast, SlidingOverAFlatFloorsSeamsReportsTheWallAhead) {
  Failures wrong;
  slide_into_wall(TriangleMesh::create(ridge_and_wall(true)).value(), "floor", wrong);
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
}

// ---------------------------------------------------------------------------------------
// The t = 0 contract

// The solids of the contract tests, about `size` across.
Shape contract_shape(test::Random& rng, int i) {
  constexpr std::array<ShapeType, 7> kinds{ShapeType::Sphere,   ShapeType::Box,       ShapeType::Capsule,
                                           ShapeType::Cylinder, ShapeType::Ellipsoid, ShapeType::ConvexHull,
                                           ShapeType::Cone};
  return random_convex(rng, kinds[std::size_t(i % 7)], rng.uniform(Real(0.4), Real(1)));
}

// A unit vector perpendicular to n.
Vec3 tangent_of(test::Random& rng, const Vec3& n) {
  for (;;) {
    const Vec3 t = glm::cross(n, rng.unit_vector());
    if (glm::length(t) > Real(0.1)) return glm::normalize(t);
  }
}

TEST_F(ShapeCast, OverlapAtTheStartGivesDepthAndPushOutNormal) {
  test::Random rng(1401);
  Failures wrong;
  int overlaps = 0;
  const int n = test::sweep_size(700);
  for (int i = 0; i < n; ++i) {
    const Shape a = contract_shape(rng, i), b = contract_shape(rng, i / 7);
    const Transform pa = rng.pose(Real(1));
    const Transform pb{pa.position + rng.in_ball(Real(0.6)), rng.rotation()};
    const DistanceResult d = distance(a, pa, b, pb);
    const Real tol = cast_tolerance(a, pa, Vec3(0), b, pb, CastOptions{}.tolerance);
    if (!(d.signed_distance < -Real(2) * tol)) continue;
    ++overlaps;
    // Any translation, zero included: the overlap at t = 0 is the answer.
    const Vec3 s = i % 4 == 0 ? Vec3(0) : rng.vector_of_length(Real(0.1), Real(5));
    const CastResult r = cast(a, pa, s, b, pb);
    const std::string label = text(a, pa, s, b, pb);
    if (r.status != CcdStatus::InitiallyOverlapping) {
      wrong.add(std::string(to_string(r.status)) + fmt(" at a gap of %.9g: ", d.signed_distance) + label);
      continue;
    }
    if (!(std::abs(r.depth + d.signed_distance) <= kDepthAccuracy)) {
      wrong.add(fmt("depth %.9g, distance says %.9g: ", r.depth, -d.signed_distance) + label);
    }
    // The push-out normal (from A to B): B moved by the depth (and a little more) along it
    // comes free of A, and not far from it.
    const Real extra = Real(0.01);
    const Transform freed{pb.position + (r.depth + extra) * r.normal, pb.rotation};
    const Real after = distance(a, pa, b, freed).signed_distance;
    if (!(after > Real(0) && after <= extra + Real(2e-3))) {
      wrong.add(fmt("B pushed out by depth + 0.01 along the normal is at %.9g: ", after) + label);
    }
    // Two spheres: the normal joins the centres, the depth is the radii less the distance.
    if (a.index() == std::size_t(ShapeType::Sphere) && b.index() == std::size_t(ShapeType::Sphere)) {
      const Vec3 join = pb.position - pa.position;
      if (glm::length(join) > Real(1e-3) && glm::dot(r.normal, glm::normalize(join)) < Real(0.9999)) {
        wrong.add("two spheres: the normal does not join the centres: " + label);
      }
    }
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(overlaps, test::sweep_share(300));
}

// True when the independent reference (the support-function search of
// tests/narrowphase/reference_distance.hpp, not the narrow phase) finds no overlap deeper than
// `tol` along A's path `s` from a touching start. The overlap of two convex sets along a line
// is one interval of t (D - t s holds the origin for a convex set of t), and the start
// touches, so an overlap anywhere on the path begins at t = 0 and covers the first sample.
// The narrow phase's normal at each sample seeds the search: the reference only evaluates it
// by the support functions, so a wrong one cannot raise the answer, while a right one on a
// narrow ridge is found (a cone's base sliding along a box's face, the motion along the face
// to 4e-13: the search alone stalled 1e-4 short of the face's direction).
bool path_stays_apart(const Shape& a, const Transform& pa, const Vec3& s, const Shape& b, const Transform& pb,
                      Real tol) {
  for (const double t : {1.0 / 256, 1.0 / 64, 1.0 / 16, 0.25, 1.0}) {
    const Transform moved{pa.position + Real(t) * s, pa.rotation};
    const std::vector<test::D3v> seeds{test::d3v(distance(a, moved, b, pb).normal)};
    if (!(test::reference_signed_distance(a, moved, b, pb, 1500, 8, seeds).signed_distance > -double(tol))) {
      return false;
    }
  }
  return true;
}

// A motion with a component along the contact normal moves the shapes into each other where
// the contact is smooth; at an apex against a rim (a vertex of D), the normal is one of many,
// and a motion leaving D's tangent cone separates them: there "no hit" is right when the
// independent reference finds them apart all along the path (a cone's apex on another's rim,
// moving along the normal plus half a tangent: apart by 1e-5 at t = 1e-5, by 1.7 at t = 1).
TEST_F(ShapeCast, TouchingShapesHitOnlyWhenMovingIn) {
  test::Random rng(1402);
  Failures wrong;
  int touching = 0;
  const int n = test::sweep_size(700);
  for (int i = 0; i < n; ++i) {
    const Shape a = contract_shape(rng, i), b = contract_shape(rng, i / 7);
    const Transform pa = rng.pose(Real(1));
    Transform pb{pa.position + rng.vector_of_length(Real(2.5), Real(3)), rng.rotation()};
    // Bring B against A along the normal: the gap closes by exactly the distance.
    const DistanceResult apart = distance(a, pa, b, pb);
    if (!(apart.signed_distance > Real(0.1))) continue;
    pb.position -= apart.signed_distance * apart.normal;
    const DistanceResult d = distance(a, pa, b, pb);
    const Real tol = cast_tolerance(a, pa, Vec3(5), b, pb, CastOptions{}.tolerance);
    if (!(std::abs(d.signed_distance) <= Real(0.25) * tol)) continue;
    ++touching;
    const Vec3 nrm = d.normal, side = tangent_of(rng, nrm);
    const Real len = rng.uniform(Real(0.5), Real(4));
    struct Motion {
      const char* name;
      Vec3 s;
      bool hit;
    };
    const std::array<Motion, 5> motions{{{"moving apart", len * (-nrm + Real(0.5) * side), false},
                                         {"moving straight apart", -len * nrm, false},
                                         {"moving in", len * (nrm + Real(0.5) * side), true},
                                         {"moving straight in", len * nrm, true},
                                         {"standing still", Vec3(0), false}}};
    for (const Motion& m : motions) {
      const CastResult r = cast(a, pa, m.s, b, pb);
      // A hit "at 0": within the tolerance of the start along s.
      const bool at_zero = r.t * glm::length(m.s) <= tol;
      bool ok = m.hit ? (r.status == CcdStatus::Hit && at_zero) : r.status == CcdStatus::Separated;
      if (!ok && m.hit && r.status == CcdStatus::Separated) ok = path_stays_apart(a, pa, m.s, b, pb, tol);
      if (!ok) {
        wrong.add(std::string(m.name) + ": " + to_string(r.status) +
                  fmt(" t %.9g (gap %.3g): ", r.t, d.signed_distance) + text(a, pa, m.s, b, pb));
      }
    }
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(touching, test::sweep_share(300));
}

// Sliding: a translation along the contact plane of two touching shapes never moves them
// into each other (the gap of two convex shapes cannot shrink along their separating plane),
// so it is no hit. Here the contacts are face on face (a box on a box, a box on a hull's
// face), so the gap stays zero all along.
TEST_F(ShapeCast, TouchingShapesSlidingAlongTheContactPlaneAreNoHit) {
  test::Random rng(1403);
  Failures wrong;
  const int n = test::sweep_size(300);
  for (int i = 0; i < n; ++i) {
    const Box a = Box::create(rng.vec3(Real(0.3), Real(1))).value();
    const Box b = Box::create(rng.vec3(Real(0.3), Real(1))).value();
    // B's top face z = h_b at its pose; A resting on it (A's bottom face on B's top face).
    const Transform pb = i % 3 == 0 ? Transform{rng.vec3(Real(-3), Real(3)), kIdentityQuat} : rng.pose(Real(3));
    const Vec3 offset(rng.uniform(Real(-0.2), Real(0.2)), rng.uniform(Real(-0.2), Real(0.2)),
                      b.half_extents().z + a.half_extents().z);
    const Quat spin = glm::angleAxis(rng.uniform(Real(0), Real(6.2)), Vec3(0, 0, 1));
    const Transform pa{pb.apply(offset), glm::normalize(pb.rotation * spin)};
    const Real gap = distance(a, pa, b, pb).signed_distance;
    // A slides along B's face; B is A's "still" partner (normal A to B: -z of B).
    const Vec3 along = pb.apply_vector(Vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), Real(0)));
    const CastResult r = cast(a, pa, along, b, pb);
    if (r.status != CcdStatus::Separated) {
      wrong.add(std::string(to_string(r.status)) +
                fmt(" t %.9g, gap at 0 %.3g, normal . s %.3g: ", r.t, gap, glm::dot(r.normal, along)) +
                text(a, pa, along, b, pb));
    }
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
}

TEST_F(ShapeCast, ZeroTranslationIsTheStaticTest) {
  test::Random rng(1404);
  Failures wrong;
  int overlapping = 0, apart = 0;
  const int n = test::sweep_size(1000);
  for (int i = 0; i < n; ++i) {
    const Shape a = random_convex(rng, kConvexKinds[std::size_t(i % 10)], Real(0.8));
    const Shape b = random_convex(rng, kConvexKinds[std::size_t((i / 10) % 10)], Real(0.8));
    const Transform pa = rng.pose(Real(0.8)), pb = rng.pose(Real(0.8));
    const Real gap = distance(a, pa, b, pb).signed_distance;
    const Real tol = cast_tolerance(a, pa, Vec3(0), b, pb, CastOptions{}.tolerance);
    const CastResult r = cast(a, pa, Vec3(0), b, pb);
    // Overlap beyond the tolerance: InitiallyOverlapping; anything else: no hit (a touching
    // pair that does not move does not move in).
    if (gap < -tol - kGapAccuracy) {
      ++overlapping;
      if (r.status != CcdStatus::InitiallyOverlapping) {
        wrong.add(std::string(to_string(r.status)) + fmt(" at gap %.9g: ", gap) + text(a, pa, Vec3(0), b, pb));
      }
    } else if (gap > -tol + kGapAccuracy) {
      ++apart;
      if (r.status != CcdStatus::Separated) {
        wrong.add(std::string(to_string(r.status)) + fmt(" at gap %.9g: ", gap) + text(a, pa, Vec3(0), b, pb));
      }
    }
  }
  EXPECT_EQ(wrong.count, 0) << wrong.examples;
  EXPECT_GT(overlapping, test::sweep_share(200));
  EXPECT_GT(apart, test::sweep_share(200));
}

// ---------------------------------------------------------------------------------------
// Scale and offset

// Closed-form cases at length scale `scale` around `offset` (tolerance 0: the floor). The
// windows are those of the closed forms with the documented floor; the slack is relative.
void scaled_cases(Real scale, const Vec3& offset, Failures& wrong, int& hits) {
  test::Random rng(1501);  // the same cases at every scale and offset
  const int n = test::sweep_size(300);
  CastOptions o;
  o.tolerance = Real(0);
  for (int i = 0; i < n; ++i) {
    const Transform pa{offset + scale * rng.vec3(Real(-1), Real(1)), rng.rotation()};
    const Transform pb{offset + scale * rng.vec3(Real(-1), Real(1)), rng.rotation()};
    const Vec3 s = (pb.position - pa.position + scale * rng.in_ball(Real(0.4))) * rng.uniform(Real(0.3), Real(1.6));
    const Real ra = scale * rng.uniform(Real(0.05), Real(0.3)), rb = scale * rng.uniform(Real(0.05), Real(0.3));
    const Sphere a = Sphere::create(ra).value();
    const D3 p = dv(pa.position) - dv(pb.position);  // exact: the inputs as rounded
    Window w;
    CastResult r;
    std::string label;
    double closing = 0;
    if (i % 3 == 0) {
      const Sphere b = Sphere::create(rb).value();
      const Real tol = cast_tolerance(a, pa, s, b, pb, Real(0));
      if (glm::length(p) <= double(ra + rb + tol) * 1.01) continue;
      r = cast(a, pa, s, b, pb, o);
      w = {ray_ball(p, dv(s), double(ra) + double(rb) + double(tol)), ray_ball(p, dv(s), double(ra) + double(rb))};
      if (w.late <= 1) closing = -glm::dot(glm::normalize(p + w.late * dv(s)), dv(s));
      label = text(a, pa, s, b, pb);
    } else if (i % 3 == 1) {
      const Box b = Box::create(scale * rng.vec3(Real(0.05), Real(0.3))).value();
      const Real tol = cast_tolerance(a, pa, s, b, pb, Real(0));
      const D3 local = dv(pb.inverse_apply(pa.position)), d = dv(pb.inverse_apply_vector(s));
      if (ray_rounded_box(local, D3(0), dv(b.half_extents()), double(ra + tol) * 1.01) == 0) continue;
      r = cast(a, pa, s, b, pb, o);
      w = {ray_rounded_box(local, d, dv(b.half_extents()), double(ra + tol)),
           ray_rounded_box(local, d, dv(b.half_extents()), double(ra))};
      closing = r.status == CcdStatus::Hit ? double(glm::dot(r.normal, s)) : 0;
      label = text(a, pa, s, b, pb);
    } else {
      const Capsule c = Capsule::create(ra, rb).value();
      const HalfSpace h = HalfSpace::create(rng.unit_vector(), Real(0)).value();
      const D3 m = dv(pb.apply_vector(h.normal()));
      const D3 centre = p;  // A's centre from B's origin, exactly (float A.apply would round at the offset)
      const double height = std::min(glm::dot(m, centre + dv(pa.apply_vector(c.top()))),
                                     glm::dot(m, centre + dv(pa.apply_vector(c.bottom())))) -
                            double(ra);
      const Real tol = cast_tolerance(c, pa, s, h, pb, Real(0));
      if (height <= double(tol) * 1.01) continue;
      closing = -glm::dot(m, dv(s));
      r = cast(c, pa, s, h, pb, o);
      w = {closing > 0 ? (height - double(tol)) / closing : kInf, closing > 0 ? height / closing : kInf};
      label = text(c, pa, s, h, pb);
    }
    const std::string problem = check_window(r, w, window_slack(3 * double(scale), closing));
    if (!problem.empty())
      wrong.add(fmt("scale %g, offset %g: ", double(scale), double(offset.x)) + problem + ": " + label);
    hits += r.status == CcdStatus::Hit;
  }
}

TEST_F(ShapeCast, AccuracyFollowsTheScaleNotTheOffset) {
  const Real far = kFloat ? Real(1e4) : Real(1e6);
  for (const Real scale : {Real(5), Real(50), Real(500)}) {
    for (const Vec3& offset : {Vec3(0), Vec3(far, -far, far)}) {
      Failures wrong;
      int hits = 0;
      scaled_cases(scale, offset, wrong, hits);
      EXPECT_EQ(wrong.count, 0) << "scale " << scale << ", offset " << offset.x << wrong.examples;
      EXPECT_GT(hits, test::sweep_share(60)) << "scale " << scale << ", offset " << offset.x;
    }
  }
}

// ---------------------------------------------------------------------------------------
// Bad input

TEST_F(ShapeCast, EveryBadFieldIsNamedAndNothingIsNaN) {
  test::ScopedNoFpTraps no_traps;  // NaN inputs on purpose
  const Real nan = std::numeric_limits<Real>::quiet_NaN(), inf = std::numeric_limits<Real>::infinity();
  const Real huge = kMaxCoordinate * Real(10);
  const Box a = Box::create(Vec3(0.5f)).value();
  const Sphere b = Sphere::create(Real(0.5)).value();
  const Transform pa{Vec3(-2, 0, 0), kIdentityQuat}, pb{Vec3(2, 0, 0), kIdentityQuat};
  const Vec3 s(4, 0, 0);
  struct Bad {
    const char* field;
    ErrorCode code;
    Transform pa, pb;
    Vec3 s;
    CastOptions o;
  };
  std::vector<Bad> cases;
  const auto add = [&](const char* field, ErrorCode code, auto&& change) {
    Bad c{field, code, pa, pb, s, CastOptions{}};
    change(c);
    cases.push_back(c);
  };
  add("pose_a.position.x", ErrorCode::NotFinite, [&](Bad& c) { c.pa.position.x = nan; });
  add("pose_a.position.y", ErrorCode::NotFinite, [&](Bad& c) { c.pa.position.y = inf; });
  add("pose_a.position.z", ErrorCode::OutOfRange, [&](Bad& c) { c.pa.position.z = huge; });
  add("pose_a.rotation", ErrorCode::NotFinite, [&](Bad& c) { c.pa.rotation.x = nan; });
  add("pose_a.rotation", ErrorCode::InvalidArgument, [&](Bad& c) { c.pa.rotation = Quat(2, 0, 0, 0); });
  add("translation.x", ErrorCode::NotFinite, [&](Bad& c) { c.s.x = nan; });
  add("translation.y", ErrorCode::NotFinite, [&](Bad& c) { c.s.y = -inf; });
  add("translation.z", ErrorCode::OutOfRange, [&](Bad& c) { c.s.z = huge; });
  add("pose_b.position.x", ErrorCode::NotFinite, [&](Bad& c) { c.pb.position.x = nan; });
  add("pose_b.position.z", ErrorCode::OutOfRange, [&](Bad& c) { c.pb.position.z = -huge; });
  add("pose_b.rotation", ErrorCode::NotFinite, [&](Bad& c) { c.pb.rotation.w = inf; });
  add("pose_b.rotation", ErrorCode::InvalidArgument, [&](Bad& c) { c.pb.rotation = Quat(0.5f, 0, 0, 0); });
  add("options.target_distance", ErrorCode::Negative, [&](Bad& c) { c.o.target_distance = Real(-1e-3); });
  add("options.target_distance", ErrorCode::NotFinite, [&](Bad& c) { c.o.target_distance = nan; });
  add("options.tolerance", ErrorCode::Negative, [&](Bad& c) { c.o.tolerance = Real(-1); });
  add("options.tolerance", ErrorCode::NotFinite, [&](Bad& c) { c.o.tolerance = inf; });
  add("options.max_iterations", ErrorCode::OutOfRange, [&](Bad& c) { c.o.max_iterations = 0; });
  add("options.max_iterations", ErrorCode::OutOfRange, [&](Bad& c) { c.o.max_iterations = -5; });
  for (const Bad& c : cases) {
    const Result<CastResult> r = shape_cast(a, c.pa, c.s, b, c.pb, c.o);
    ASSERT_FALSE(r.ok()) << c.field;
    EXPECT_EQ(r.error().field, c.field);
    EXPECT_EQ(r.error().code, c.code) << c.field << ": " << to_string(r.error().code);
  }
  // Two bad fields: the first in the documented order (pose_a, translation, pose_b, options).
  Bad two{"", ErrorCode::NotFinite, pa, pb, s, CastOptions{}};
  two.s.x = nan;
  two.pb.position.y = nan;
  two.o.tolerance = Real(-1);
  const Result<CastResult> first = shape_cast(a, two.pa, two.s, b, two.pb, two.o);
  ASSERT_FALSE(first.ok());
  EXPECT_EQ(first.error().field, "translation.x");
}

TEST_F(ShapeCast, ExtremeValidInputsGiveFiniteAnswers) {
  // Valid but extreme: every answer well formed (cast() checks it; the FE_INVALID trap of
  // the test main catches any NaN computed on the way).
  test::Random rng(1601);
  const Real far = kFloat ? Real(1e5) : Real(1e9);
  for (int i = 0; i < 200; ++i) {
    const Shape a = random_convex(rng, kConvexKinds[std::size_t(i % 10)], Real(1));
    const Shape b = random_convex(rng, kConvexKinds[std::size_t((i / 10) % 10)], Real(1));
    const Transform pa = rng.pose(Real(2)), pb = rng.pose(Real(2));
    CastOptions o;
    switch (i % 5) {
      case 0: o.max_iterations = 1; break;
      case 1: o.tolerance = Real(10); break;
      case 2: o.target_distance = Real(1e3); break;
      case 3: o.tolerance = Real(0); break;
      default: o.target_distance = Real(0.5); break;
    }
    for (const Vec3& s :
         {Vec3(0), rng.unit_vector() * far, rng.unit_vector() * Real(1e-12), pb.position - pa.position}) {
      (void)cast(a, pa, s, b, pb, o);
    }
    (void)cast(a, Transform{pa.position + Vec3(far), pa.rotation}, Vec3(-far), b, pb, o);
    const HalfSpace h = HalfSpace::create(rng.unit_vector(), Real(0)).value();
    (void)cast(a, pa, rng.unit_vector() * far, h, pb, o);
  }
}

// ---------------------------------------------------------------------------------------
// Regressions: single cases found by the sweeps above (float build), each against its
// reference. They reproduce with these exact inputs (printed to 9 digits). Each checks its
// own defect only (no audit of the other fields: not the ShapeCast fixture).

// A pose from 9-digit values: unit to float precision, so normalised in the double build only
// (normalising in float would move the case off the failing input).
Transform pose_of(Real x, Real y, Real z, Real qw, Real qx, Real qy, Real qz) {
  const Quat q(qw, qx, qy, qz);
  return {Vec3(x, y, z), kFloat ? q : glm::normalize(q)};
}

// Empty when the cast of the point at `from` along s against `shape` at `pose` matches the
// raycast of that point.
std::string point_cast_against_ray(ShapeRef shape, const Transform& pose, const Vec3& from, const Vec3& s) {
  const Point point = Point::create().value();
  const CastResult r = cast(point, Transform{from, kIdentityQuat}, s, shape, pose);
  const std::optional<RayHit> ray = raycast(shape, pose, Ray{from, s}, Real(1));
  const Real tol = cast_tolerance(point, Transform{from, kIdentityQuat}, s, shape, pose, CastOptions{}.tolerance);
  return check_against_ray(r, ray, s, tol, [&](Real t) {
    return gap_at(point, Transform{from, kIdentityQuat}, s, t, shape, pose);
  });
}

// GJK ray casting stops on a repeated support point without an advance and reports a miss
// although v . w / |v| (the lower bound of the distance) does not separate: the point runs
// 0.19 deep through the cone (time_of_impact: hit at 0.632).
TEST(ShapeCastRegression, PointThroughAConeIsAHit) {
  const Cone cone = Cone::create(Real(0.568271458), Real(0.372399509)).value();
  const Transform pose =
      pose_of(1.28455925f, 0.462019712f, 2.46860552f, -0.532759845f, 0.255102545f, 0.801973104f, -0.0890451595f);
  const Vec3 point(-1.63113546f, -1.97789025f, 0.494002134f), s(-4.7003212f, -3.50900435f, -2.84179974f);
  // The cone moving by s against the still point = the point moving by -s against the cone.
  const CastResult moving_cone = cast(cone, pose, s, Point::create().value(), Transform{point, kIdentityQuat});
  EXPECT_EQ(moving_cone.status, CcdStatus::Hit) << "t " << moving_cone.t;
  EXPECT_EQ(point_cast_against_ray(cone, pose, point, -s), "");
}

// Polytopes too (found against Bullet, test_shape_cast_peers.cpp): |v| stalls at 1.06e-4,
// just above the tolerance 1e-4, on a repeated support pair, and the cast reports a miss
// while the boxes end 0.19 deep in each other.
TEST(ShapeCastRegression, BoxThroughABoxIsAHit) {
  const Box a = Box::create(Vec3(0.380244434f, 0.45102337f, 0.377971739f)).value();
  const Box b = Box::create(Vec3(0.533439159f, 0.442136437f, 0.856935978f)).value();
  const Transform pa =
      pose_of(2.91075087f, -1.36254728f, -1.58877492f, 0.23189728f, -0.346433252f, 0.679368615f, -0.603875756f);
  const Transform pb =
      pose_of(2.62828517f, 0.821180582f, 2.73871398f, -0.539140999f, 0.698438287f, 0.182569757f, 0.433796495f);
  const Vec3 s(0.167410895f, 2.18870211f, 3.40407443f);
  const Result<ToiResult> toi = time_of_impact(a, Motion{pa, moved(pa, s, Real(1))}, b, Motion::stationary(pb));
  ASSERT_TRUE(toi.ok());
  ASSERT_EQ(toi->status, CcdStatus::Hit);
  EXPECT_LT(gap_at(a, pa, s, Real(1), b, pb), Real(-0.1));  // deep at the end: no tolerance matter
  const CastResult r = cast(a, pa, s, b, pb);
  EXPECT_EQ(r.status, CcdStatus::Hit);
  EXPECT_NEAR(r.t, toi->toi, 1e-3) << "toi " << toi->toi;
}

// Also on ordinary casts: the cone passes 0.53 deep through the triangle.
TEST(ShapeCastRegression, ConeThroughATriangleIsAHit) {
  const Cone cone = Cone::create(Real(0.701608837), Real(0.730057538)).value();
  const Transform pa =
      pose_of(-1.06578934f, 1.04728389f, 1.67153203f, -0.226285577f, 0.564129949f, -0.0401409678f, 0.793057978f);
  const Vec3 s(1.34674001f, -3.9318378f, -5.68526125f);
  const Triangle tri =
      Triangle::create(Vec3(0.181295618f, 0.55989337f, 0.161478713f), Vec3(0.314036041f, 0.0314975381f, 0.423300296f),
                       Vec3(0.20139733f, -0.173462778f, -0.149572462f))
          .value();
  const Transform pb =
      pose_of(-0.463825017f, -1.70480132f, -1.65211105f, 0.511133194f, -0.680496395f, -0.483735383f, 0.204126805f);
  const CastResult r = cast(cone, pa, s, tri, pb);
  const Result<ToiResult> toi =
      time_of_impact(cone, Motion{pa, moved(pa, s, Real(1))}, tri, Motion::stationary(pb), ToiOptions{});
  ASSERT_TRUE(toi.ok());
  ASSERT_EQ(toi->status, CcdStatus::Hit);
  EXPECT_LT(least_gap(cone, pa, s, tri, pb), Real(-0.1));  // a deep pass, no tolerance matter
  EXPECT_EQ(r.status, CcdStatus::Hit);
  EXPECT_NEAR(r.t, toi->toi, 1e-3) << "toi " << toi->toi;
}

// The iteration cap (64 by default) stops casts on curved shapes that the raycast answers
// at once: a point against a cylinder, and a static test of a touching cone and box.
TEST(ShapeCastRegression, CurvedCastsAnswerWithinTheDefaultIterations) {
  const Cylinder cylinder = Cylinder::create(Real(0.811885536), Real(0.946917415)).value();
  const Transform pose =
      pose_of(1.01122451f, -0.884249032f, -0.222990736f, -0.119771868f, 0.0326477885f, 0.0696597025f, -0.989816308f);
  EXPECT_EQ(point_cast_against_ray(cylinder, pose, Vec3(-1.06232548f, -2.75600815f, -0.794958413f),
                                   Vec3(1.57295966f, 1.49471259f, 0.215910211f)),
            "");
  const Cone cone = Cone::create(Real(0.43737179), Real(0.345566183)).value();
  const Box box = Box::create(Vec3(0.455541283f, 0.833670557f, 0.696428895f)).value();
  const Transform pa =
      pose_of(-0.473217219f, -0.313639432f, -0.981857419f, 0.104838446f, -0.198208794f, -0.792925954f, -0.566560328f);
  const Transform pb =
      pose_of(-1.81832647f, -0.254567504f, -0.276699066f, -0.220228016f, -0.330531836f, 0.8261711f, 0.39961189f);
  const Real gap = distance(cone, pa, box, pb).signed_distance;
  ASSERT_LT(std::abs(gap), Real(5e-5));  // touching within the tolerance
  const CastResult r = cast(cone, pa, Vec3(0), box, pb);
  EXPECT_EQ(r.status, CcdStatus::Separated) << "static test of a touching pair, gap " << gap;
}

// The hit's normal is (point_b - point_a) / |v|: in float, at a gap of about the tolerance,
// those points carry rounding of the same order as the gap, so the normal is neither unit
// nor reliable (0.4 long here).
TEST(ShapeCastRegression, HitNormalsAreUnit) {
  const Point point = Point::create().value();
  const Cylinder cylinder = Cylinder::create(Real(0.288711935), Real(0.963573575)).value();
  const Transform pc =
      pose_of(0.990828872f, 1.28032339f, 2.15910864f, -0.441639096f, 0.104788192f, 0.879422188f, 0.143495619f);
  const Transform from{Vec3(-1.94420409f, -2.16012716f, 1.06156802f), kIdentityQuat};
  const Vec3 s1(2.45803308f, 3.7899003f, 0.763961136f);
  const Box a = Box::create(Vec3(0.465892822f, 0.54026258f, 0.597142637f)).value();
  const Box b = Box::create(Vec3(0.725430906f, 0.665312648f, 0.613873482f)).value();
  const Transform pa =
      pose_of(2.00191832f, -1.91463172f, -1.28863847f, -0.294643879f, 0.0307292659f, 0.123405993f, 0.947107017f);
  const Transform pb =
      pose_of(1.54030502f, -0.126899451f, 2.25268531f, 0.816004336f, 0.519686818f, -0.208936915f, 0.142856419f);
  const Vec3 s2(-0.158924848f, 3.24803329f, 5.14939165f);
  for (const auto& [r, name] : {std::pair{shape_cast(point, from, s1, cylinder, pc), "point against cylinder"},
                                std::pair{shape_cast(a, pa, s2, b, pb), "box against box"}}) {
    ASSERT_TRUE(r.ok());
    EXPECT_EQ(r->status, CcdStatus::Hit) << name;
    EXPECT_NEAR(glm::length(r->normal), Real(1), Real(1e-3)) << name;
    EXPECT_GT(glm::dot(r->normal, name[0] == 'p' ? s1 : s2), Real(0)) << name;
  }
}

// "Moving in" is normal . s > 0 with no tolerance: a box sliding on a box's face (n . s =
// 6e-8 |s| from rounding) is reported as a hit at t = 0.
TEST(ShapeCastRegression, SlidingOnAFaceIsNoHit) {
  const Box a = Box::create(Vec3(0.572800338f, 0.959105849f, 0.599920034f)).value();
  const Box b = Box::create(Vec3(0.321812481f, 0.449137092f, 0.307086259f)).value();
  const Transform pa =
      pose_of(-2.09614706f, -1.37857437f, -0.111024916f, -0.769477487f, 0.302961826f, -0.391520441f, 0.403522372f);
  const Transform pb =
      pose_of(-2.8364861f, -1.40257859f, -0.652957559f, 0.588539481f, 0.300006956f, 0.393789202f, 0.639176965f);
  // Along B's top face (its local x, y): the test's construction, so exact up to rounding.
  const Vec3 s(-0.620349407f, -1.05740452f, 1.34226179f);
  ASSERT_LT(std::abs(glm::dot(pb.apply_vector(Vec3(0, 0, 1)), s)), Real(1e-5));
  const CastResult r = cast(a, pa, s, b, pb);
  EXPECT_EQ(r.status, CcdStatus::Separated) << "t " << r.t << ", normal . s " << glm::dot(r.normal, s);
}

}  // namespace test_shape_cast
}  // namespace proxima
