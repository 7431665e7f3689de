// Shape casts against Bullet's btGjkConvexCast and btSubsimplexConvexCast on seeded sphere,
// box and hull casts (every ordered pair of the three). Where Bullet and Proxima differ by
// more than 1e-3 in t (or one hits and the other does not), an independent reference
// decides: the closed form (sphere against sphere: a quadratic; sphere against box: the
// centre's ray against the rounded box) or, for the other pairs, time_of_impact with the
// same translation (conservative advancement on the narrow phase's distance). The counts of
// disagreements and of whom the reference supports are printed; only Proxima's agreement
// with the reference is asserted, on every case.
#include <gtest/gtest.h>

#if defined(PROXIMA_HAVE_BULLET)
#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape.hpp>

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "ccd/case_text.hpp"
#include "support/random.hpp"
#include "sweep_size.hpp"

namespace proxima {
namespace test_shape_cast_peers {

using test::num;
using test::text;

constexpr double kInf = std::numeric_limits<double>::infinity();
using D3 = glm::dvec3;
D3 dv(const Vec3& v) { return D3(double(v.x), double(v.y), double(v.z)); }

// Bullet's view of a Proxima shape (no collision margin: the exact solid; a sphere's margin
// is its radius).
std::unique_ptr<btConvexShape> bullet_shape(const Shape& s) {
  if (const auto* sphere = std::get_if<Sphere>(&s)) return std::make_unique<btSphereShape>(sphere->radius());
  std::unique_ptr<btConvexShape> out;
  if (const auto* box = std::get_if<Box>(&s)) {
    const Vec3 h = box->half_extents();
    out = std::make_unique<btBoxShape>(btVector3(btScalar(h.x), btScalar(h.y), btScalar(h.z)));
  } else {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const Vec3& v : std::get<ConvexHull>(s).vertices()) {
      hull->addPoint(btVector3(btScalar(v.x), btScalar(v.y), btScalar(v.z)), false);
    }
    hull->recalcLocalAabb();
    out = std::move(hull);
  }
  out->setMargin(0);
  return out;
}

btTransform bullet_transform(const Transform& t) {
  return btTransform(
      btQuaternion(btScalar(t.rotation.x), btScalar(t.rotation.y), btScalar(t.rotation.z), btScalar(t.rotation.w)),
      btVector3(btScalar(t.position.x), btScalar(t.position.y), btScalar(t.position.z)));
}

// A shape and its pose, to reproduce a case.
std::string text(const Shape& shape, const Transform& pose) {
  std::string out;
  if (const auto* sphere = std::get_if<Sphere>(&shape)) {
    out = "sphere r ";
    out += num(sphere->radius());
  } else if (const auto* box = std::get_if<Box>(&shape)) {
    out = "box ";
    out += text(box->half_extents());
  } else {
    out = "hull";
    for (const Vec3& v : std::get<ConvexHull>(shape).vertices()) {
      out += ' ';
      out += text(v);
    }
  }
  const Quat& q = pose.rotation;
  for (const std::string& part :
       {std::string(" at "), text(pose.position), std::string(" q("), num(q.w), std::string(", "), num(q.x),
        std::string(", "), num(q.y), std::string(", "), num(q.z), std::string(")")}) {
    out += part;
  }
  return out;
}

enum class Kind { Sphere, Box, Hull };
const char* name(Kind k) { return k == Kind::Sphere ? "sphere" : k == Kind::Box ? "box" : "hull"; }

Shape make(test::Random& rng, Kind kind) {
  switch (kind) {
    case Kind::Sphere: return Sphere::create(rng.uniform(Real(0.2), Real(1))).value();
    case Kind::Box: return Box::create(rng.vec3(Real(0.2), Real(1))).value();
    default: {
      std::vector<Vec3> points;
      for (int i = 0; i < 16; ++i) points.push_back(rng.in_ball(Real(1)));
      return ConvexHull::create(points).value();
    }
  }
}

// Least t >= 0 with |p + t s| = radius, +infinity when never (p outside).
double ray_ball(const D3& p, const D3& s, double radius) {
  const double a = glm::dot(s, s), b = glm::dot(p, s), c = glm::dot(p, p) - radius * radius;
  if (c <= 0) return 0;
  if (b >= 0 || a == 0) return kInf;
  const double disc = b * b - a * c;
  return disc < 0 ? kInf : c / (-b + std::sqrt(disc));
}

// The ray p + t s against the box |x_i| <= h_i rounded by `radius`: the least first entry of
// its pieces (three grown slabs, twelve edge cylinders, eight corner balls).
double ray_rounded_box(const D3& p, const D3& s, const D3& h, double radius) {
  const auto slab = [&](const D3& e) {
    double t0 = 0, t1 = kInf;
    for (int i = 0; i < 3; ++i) {
      if (s[i] == 0) {
        if (std::abs(p[i]) > e[i]) return kInf;
        continue;
      }
      double a = (-e[i] - p[i]) / s[i], b = (e[i] - p[i]) / s[i];
      if (a > b) std::swap(a, b);
      t0 = std::max(t0, a);
      t1 = std::min(t1, b);
    }
    return t0 <= t1 ? t0 : kInf;
  };
  double t = kInf;
  for (int i = 0; i < 3; ++i) {
    D3 grown = h;
    grown[i] += radius;
    t = std::min(t, slab(grown));
    for (int sj = -1; sj <= 1; sj += 2) {
      for (int sk = -1; sk <= 1; sk += 2) {
        D3 c(0);
        c[(i + 1) % 3] = sj * h[(i + 1) % 3];
        c[(i + 2) % 3] = sk * h[(i + 2) % 3];
        D3 q = p - c, d = s;
        q[i] = 0;
        d[i] = 0;
        const double te = ray_ball(q, d, radius);
        if (te < kInf && std::abs(p[i] + te * s[i]) <= h[i]) t = std::min(t, te);
      }
    }
  }
  for (int k = 0; k < 8; ++k) {
    const D3 corner((k & 1) ? h.x : -h.x, (k & 2) ? h.y : -h.y, (k & 4) ? h.z : -h.z);
    t = std::min(t, ray_ball(p - corner, s, radius));
  }
  return t;
}

// The reference answer: t of the first touch (+infinity: none in [0, 1]) and how wide the
// tolerance band makes it (in t).
struct Reference {
  double t = kInf;
  double band = 0;
  const char* source = "";
};

Reference reference(const Shape& a, const Transform& pa, const Vec3& s, const Shape& b, const Transform& pb) {
  const double tol = 1e-4 + 64 * double(kEpsilon) * 20;  // the cast's tolerance at this scale, or above
  const auto* sa = std::get_if<Sphere>(&a);
  const auto* sb = std::get_if<Sphere>(&b);
  Reference r;
  if (sa != nullptr && sb != nullptr) {
    const D3 p = dv(pa.position) - dv(pb.position);
    r.source = "closed form";
    r.t = ray_ball(p, dv(s), double(sa->radius()) + double(sb->radius()));
    if (r.t <= 1) r.band = tol / -glm::dot(glm::normalize(p + r.t * dv(s)), dv(s));
    return r;
  }
  const auto* box = std::get_if<Box>(sa != nullptr ? &b : &a);
  if ((sa != nullptr || sb != nullptr) && box != nullptr) {
    // The sphere's centre against the rounded box, in the box's frame (a moving box: the
    // sphere moves by -s against it).
    const Transform& box_pose = sa != nullptr ? pb : pa;
    const Transform& ball_pose = sa != nullptr ? pa : pb;
    const Vec3 d = sa != nullptr ? s : -s;
    const double radius = double((sa != nullptr ? sa : sb)->radius());
    const D3 p = dv(box_pose.inverse_apply(ball_pose.position)), dl = dv(box_pose.inverse_apply_vector(d));
    r.source = "closed form";
    r.t = ray_rounded_box(p, dl, dv(box->half_extents()), radius);
    if (r.t <= 1) {
      const D3 c = p + r.t * dl;
      const D3 nrm = glm::normalize(c - glm::clamp(c, -dv(box->half_extents()), dv(box->half_extents())));
      r.band = tol / std::max(-glm::dot(nrm, dl), 1e-3);
    }
    return r;
  }
  r.source = "time_of_impact";
  const Result<ToiResult> toi =
      time_of_impact(a, Motion{pa, {pa.position + s, pa.rotation}}, b, Motion::stationary(pb), ToiOptions{});
  if (toi.ok() && toi->status == CcdStatus::Hit) {
    r.t = double(toi->toi);
    r.band = 2 * tol / std::max(double(glm::dot(toi->normal, s)), 1e-3);
  }
  return r;
}

// Whether an answer t (+infinity for none) matches the reference within 1e-3 and its band.
bool agrees(double t, const Reference& r) {
  if (!(r.t <= 1)) return !(t <= 1) || t >= 1 - r.band - 1e-3;  // a hit at the very end may graze
  return t <= 1 && std::abs(t - r.t) <= 1e-3 + r.band;
}

struct Tally {
  int cases = 0, disagree = 0, reference_supports_proxima = 0, reference_supports_bullet = 0, neither = 0;
};

TEST(ShapeCastPeers, BulletConvexCastsAgainstTheReference) {
  test::Random rng(3101);
  const std::array<Kind, 3> kinds{Kind::Sphere, Kind::Box, Kind::Hull};
  Tally gjk, subsimplex;
  int cases = 0, overlapping = 0, proxima_wrong = 0;
  std::string examples;
  const int per_pair = test::sweep_size(300);
  for (const Kind ka : kinds) {
    for (const Kind kb : kinds) {
      for (int i = 0; i < per_pair; ++i) {
        const Shape a = make(rng, ka), b = make(rng, kb);
        const Transform pa = rng.pose(Real(3)), pb = rng.pose(Real(3));
        const Vec3 s = (pb.position - pa.position + rng.in_ball(Real(1.5))) * rng.uniform(Real(0.3), Real(1.6));
        const Result<CastResult> mine = shape_cast(a, pa, s, b, pb);
        ASSERT_TRUE(mine.ok());
        if (mine->status == CcdStatus::InitiallyOverlapping || distance(a, pa, b, pb).signed_distance < Real(1e-3)) {
          ++overlapping;
          continue;
        }
        ++cases;
        const double t_mine = mine->status == CcdStatus::Hit ? double(mine->t) : kInf;
        const Reference ref = reference(a, pa, s, b, pb);
        if (!agrees(t_mine, ref)) {
          if (++proxima_wrong <= 4) {
            char line[200];
            std::snprintf(line, sizeof(line), "\n  %s vs %s case %d: Proxima %s t %.9g, %s %.9g", name(ka), name(kb), i,
                          to_string(mine->status), t_mine, ref.source, ref.t);
            examples += line;
            for (const std::string& part : {std::string("\n    A "), text(a, pa), std::string(" along "), text(s),
                                            std::string("; B "), text(b, pb)}) {
              examples += part;
            }
          }
        }
        // Bullet, in its own precision.
        const auto ba = bullet_shape(a), bb = bullet_shape(b);
        const btTransform from_a = bullet_transform(pa), to_a = bullet_transform({pa.position + s, pa.rotation});
        const btTransform at_b = bullet_transform(pb);
        for (int which = 0; which < 2; ++which) {
          btVoronoiSimplexSolver simplex;
          btConvexCast::CastResult result;
          bool hit = false;
          {
            test::ScopedNoFpTraps no_traps;  // Bullet's own arithmetic
            if (which == 0) {
              btGjkConvexCast caster(ba.get(), bb.get(), &simplex);
              hit = caster.calcTimeOfImpact(from_a, to_a, at_b, at_b, result);
            } else {
              btSubsimplexConvexCast caster(ba.get(), bb.get(), &simplex);
              hit = caster.calcTimeOfImpact(from_a, to_a, at_b, at_b, result);
            }
          }
          const double t_bullet = hit && result.m_fraction <= btScalar(1) ? double(result.m_fraction) : kInf;
          Tally& tally = which == 0 ? gjk : subsimplex;
          ++tally.cases;
          const bool same = (t_mine <= 1) == (t_bullet <= 1) && (!(t_mine <= 1) || std::abs(t_mine - t_bullet) <= 1e-3);
          if (same) continue;
          ++tally.disagree;
          const bool mine_ok = agrees(t_mine, ref), bullet_ok = agrees(t_bullet, ref);
          if (mine_ok && !bullet_ok) {
            ++tally.reference_supports_proxima;
          } else if (bullet_ok && !mine_ok) {
            ++tally.reference_supports_bullet;
          } else {
            ++tally.neither;
          }
        }
      }
    }
  }
  for (const auto& [tally, what] :
       {std::pair{&gjk, "btGjkConvexCast"}, std::pair{&subsimplex, "btSubsimplexConvexCast"}}) {
    std::printf(
        "Bullet %s vs Proxima shape_cast: %d casts, %d differ by more than 1e-3 in t (or hit/miss); the reference "
        "supports Proxima in %d, Bullet in %d, both or neither in %d\n",
        what, tally->cases, tally->disagree, tally->reference_supports_proxima, tally->reference_supports_bullet,
        tally->neither);
  }
  EXPECT_EQ(proxima_wrong, 0) << "Proxima against the reference:" << examples;
  EXPECT_GT(cases, 9 * per_pair / 2);
  EXPECT_GT(overlapping, 0);
}

}  // namespace test_shape_cast_peers
}  // namespace proxima

#endif
