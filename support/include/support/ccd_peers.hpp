#pragma once
/// @file ccd_peers.hpp
/// The W6 continuous-collision workload (`ccd_pairs.txt`, shared/bench/FORMATS.md) prepared
/// for Proxima's time_of_impact and for the peer libraries' continuous queries, and the
/// comparison of a peer's answer with Proxima's certified bracket. Header-only, shared by
/// bench/bench_ccd.cpp and tests/ccd/test_ccd_peers.cpp; the Bullet part needs
/// PROXIMA_HAVE_BULLET and the FCL part PROXIMA_HAVE_FCL (the including target links the peer,
/// see cmake/ProximaPeers.cmake).
///
/// The motion model is W6's for every library: the local origin moves linearly and the
/// rotation turns at constant angular velocity about a fixed world axis by the shortest arc.
///   - Proxima: Motion{pose at t = 0, pose at t = 1} (motion.hpp, the same model).
///   - FCL: fcl::continuousCollide with CCDM_LINEAR, i.e. fcl::InterpMotion: linear velocity
///     tf2 * 0 - tf1 * 0, rotation AngleAxis(t * angle, axis) * R0 with the angle and axis of
///     R1 R0^T (angle in [0, pi]: the shortest arc), reference point the local origin: the
///     same model.
///   - Bullet: btConvexCast::calcTimeOfImpact(fromA, toA, fromB, toB) computes the linear and
///     angular velocity over dt = 1 (btTransformUtil::calculateVelocity: the shortest arc) and
///     moves the bodies with btTransformUtil::integrateTransform, the same model up to its
///     clamp: integrateTransform limits the angle turned by a step to ANGULAR_MOTION_THRESHOLD
///     = pi/4 (it shortens the rotation part of the exponential map and renormalises), so a
///     body whose arc exceeds pi/4 turns less than W6 says once t * arc > pi/4 (for an arc of
///     2 rad, 1.63 rad instead of 2 at t = 1). `bullet_model_exact` names the cases free of
///     that (every body that is not a sphere turns by at most pi/4).
///
/// Peer answers are judged against Proxima's bracket (judge_peer); where FCL is present,
/// FclCcdCases::distance_at gives an independent double-precision distance at any time of a
/// case (FCL's GJK with libccd, tolerance 1e-9) to check Proxima's answers and to arbitrate
/// disagreements.

#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/sphere.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "support/workloads.hpp"

#if PROXIMA_HAVE_BULLET
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btContinuousConvexCollision.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btSubSimplexConvexCast.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#endif
#if PROXIMA_HAVE_FCL
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/continuous_collision.h>
#include <fcl/narrowphase/distance.h>
#endif

namespace proxima::bench {

// -------------------------------------------------------------------------------------
// The W6 motion model in double
// -------------------------------------------------------------------------------------

/// Angle in radians, in [0, pi], of the shortest rotation from q0 to q1 (unit quaternions).
inline double ccd_arc(const Quatd& q0, const Quatd& q1) {
  const double d = std::abs(q0.w * q1.w + q0.x * q1.x + q0.y * q1.y + q0.z * q1.z);
  return 2.0 * std::acos(std::min(1.0, d));
}

/// Pose at t in [0, 1] of the W6 model, in double: position p0 + t (p1 - p0), rotation
/// slerp(q0, q1, t) along the shortest arc.
inline Pose ccd_pose_at(const Pose& p0, const Pose& p1, double t) {
  Pose out;
  out.position = {p0.position.x + t * (p1.position.x - p0.position.x),
                  p0.position.y + t * (p1.position.y - p0.position.y),
                  p0.position.z + t * (p1.position.z - p0.position.z)};
  const Quatd& a = p0.rotation;
  Quatd b = p1.rotation;
  double c = a.w * b.w + a.x * b.x + a.y * b.y + a.z * b.z;
  if (c < 0) {
    b = {-b.w, -b.x, -b.y, -b.z};
    c = -c;
  }
  double ka = 1 - t, kb = t;
  if (c < 1 - 1e-12) {
    const double theta = std::acos(std::min(1.0, c));
    const double s = std::sin(theta);
    ka = std::sin((1 - t) * theta) / s;
    kb = std::sin(t * theta) / s;
  }
  Quatd q{ka * a.w + kb * b.w, ka * a.x + kb * b.x, ka * a.y + kb * b.y, ka * a.z + kb * b.z};
  const double n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  out.rotation = {q.w / n, q.x / n, q.y / n, q.z / n};
  return out;
}

/// The case with both rotations removed: each body keeps its start orientation and only
/// translates (the rotation-free set of the linear casts).
inline CcdCase without_rotation(CcdCase c) {
  c.a1.rotation = c.a0.rotation;
  c.b1.rotation = c.b0.rotation;
  return c;
}

/// True when Bullet's integrateTransform follows W6 on the whole step for this case: every
/// body that is not a sphere turns by at most pi/4 (see the file comment).
inline bool bullet_model_exact(const CcdCase& c) {
  constexpr double kQuarterPi = 0.78539816339744830962;
  const bool a_ok = c.a.kind == CcdShapeKind::Sphere || ccd_arc(c.a0.rotation, c.a1.rotation) <= kQuarterPi;
  const bool b_ok = c.b.kind == CcdShapeKind::Sphere || ccd_arc(c.b0.rotation, c.b1.rotation) <= kQuarterPi;
  return a_ok && b_ok;
}

// -------------------------------------------------------------------------------------
// Hulls: one polytope for every library
// -------------------------------------------------------------------------------------

/// The W2 hulls a W6 file names, built once with Proxima's ConvexHull (qhull); the peers get
/// the same vertices (the file's double points that the hull kept) and faces.
struct CcdHulls {
  std::vector<ConvexHull> hulls;             ///< Proxima hull by id
  std::vector<std::vector<Vec3d>> vertices;  ///< hull vertices (file points, double) by id
  std::vector<std::vector<int>> faces;       ///< by id, FCL layout: [n, i0 .. in-1] per face
  std::vector<int> face_count;               ///< by id
  std::vector<double> radius;                ///< by id: largest |vertex|
};

/// Builds every hull of the shapes file (an Error when qhull rejects one).
inline Result<CcdHulls> build_ccd_hulls(const ConvexShapes& shapes) {
  CcdHulls out;
  for (const ConvexShape& s : shapes.shapes) {
    std::vector<Vec3> pts;
    for (const Vec3d& p : s.points) pts.push_back(to_vec3(p));
    auto hull = ConvexHull::create(pts);
    if (!hull) return hull.error();
    std::vector<Vec3d> verts;
    double r2 = 0;
    for (const Vec3& v : hull->vertices()) {
      std::size_t found = 0;
      for (std::size_t j = 0; j < pts.size(); ++j) {
        if (pts[j] == v) {
          found = j;
          break;
        }
      }
      const Vec3d& p = s.points[found];
      verts.push_back(p);
      r2 = std::max(r2, p.x * p.x + p.y * p.y + p.z * p.z);
    }
    std::vector<int> faces;
    for (std::uint32_t f = 0; f < hull->faces().size(); ++f) {
      const auto loop = hull->face_vertices(f);
      faces.push_back(static_cast<int>(loop.size()));
      for (std::uint32_t v : loop) faces.push_back(static_cast<int>(v));
    }
    out.face_count.push_back(static_cast<int>(hull->faces().size()));
    out.faces.push_back(std::move(faces));
    out.vertices.push_back(std::move(verts));
    out.radius.push_back(std::sqrt(r2));
    out.hulls.push_back(*hull);
  }
  return out;
}

/// Radius of a W6 shape about its local origin (double).
inline double ccd_shape_radius(const CcdShape& s, const CcdHulls& hulls) {
  switch (s.kind) {
    case CcdShapeKind::Sphere: return s.radius;
    case CcdShapeKind::Box:
      return std::sqrt(s.half_extents.x * s.half_extents.x + s.half_extents.y * s.half_extents.y +
                       s.half_extents.z * s.half_extents.z);
    case CcdShapeKind::Hull: return hulls.radius[s.hull];
  }
  return 0;
}

/// The tolerance time_of_impact works to on a case with the given requested tolerance: the
/// request raised to 64 epsilon of proxima::Real times the pair's scale (time_of_impact.cpp),
/// computed here in double from the case.
inline double ccd_effective_tolerance(const CcdCase& c, const CcdHulls& hulls, double tolerance) {
  auto len = [](const Vec3d& a, const Vec3d& b) {
    return std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
  };
  const Vec3d& o = c.b0.position;
  const double reach = std::max({len(c.a0.position, o), len(c.a1.position, o), len(c.b1.position, o)});
  const double scale = std::max(1.0, reach + ccd_shape_radius(c.a, hulls) + ccd_shape_radius(c.b, hulls));
  return std::max(tolerance, 64.0 * static_cast<double>(std::numeric_limits<Real>::epsilon()) * scale);
}

// -------------------------------------------------------------------------------------
// Proxima
// -------------------------------------------------------------------------------------

/// Proxima's shapes and motions of every case.
struct ProximaCcdCases {
  std::vector<Shape> a, b;     ///< the shapes (hulls share their data)
  std::vector<Motion> ma, mb;  ///< the motions
};

/// Converts the cases (an Error when a sphere or box is rejected).
inline Result<ProximaCcdCases> proxima_ccd_cases(const std::vector<CcdCase>& cases, const CcdHulls& hulls) {
  ProximaCcdCases out;
  auto shape = [&](const CcdShape& s) -> Result<Shape> {
    switch (s.kind) {
      case CcdShapeKind::Sphere: {
        auto r = Sphere::create(static_cast<Real>(s.radius));
        if (!r) return r.error();
        return Shape(*r);
      }
      case CcdShapeKind::Box: {
        auto r = Box::create(to_vec3(s.half_extents));
        if (!r) return r.error();
        return Shape(*r);
      }
      case CcdShapeKind::Hull: return Shape(hulls.hulls[s.hull]);
    }
    return Shape(hulls.hulls.front());
  };
  for (const CcdCase& c : cases) {
    auto a = shape(c.a);
    if (!a) return a.error();
    auto b = shape(c.b);
    if (!b) return b.error();
    out.a.push_back(*a);
    out.b.push_back(*b);
    out.ma.push_back(Motion{to_transform(c.a0), to_transform(c.a1)});
    out.mb.push_back(Motion{to_transform(c.b0), to_transform(c.b1)});
  }
  return out;
}

// -------------------------------------------------------------------------------------
// A peer's answer against Proxima's bracket
// -------------------------------------------------------------------------------------

/// A peer's continuous answer: a hit and its time, or no hit.
struct PeerToi {
  bool hit = false;  ///< the peer reports a contact in [0, 1]
  double toi = 1;    ///< its time (meaningful when hit)
};

/// How a peer's answer compares with Proxima's certified bracket.
enum class PeerVerdict : std::uint8_t {
  Agree,      ///< same answer (a hit within [t_lower - slack, t_upper + slack], or both no hit)
  Miss,       ///< Proxima: Hit (or InitiallyOverlapping); the peer: no hit
  FalseHit,   ///< Proxima: certified Separated; the peer: a hit
  Off,        ///< both hit, the peer's time outside [t_lower - slack, t_upper + slack]
  Undecided,  ///< Proxima's answer is a bracket only (MaxIterations, Failed): the peer's no hit
              ///< or a hit not before t_lower - slack cannot be judged
};

/// Judges a peer's answer against Proxima's result. `slack` is the time tolerance (1e-3).
inline PeerVerdict judge_peer(const ToiResult& r, const PeerToi& p, double slack = 1e-3) {
  const double lo = static_cast<double>(r.t_lower) - slack;
  const double hi = static_cast<double>(r.t_upper) + slack;
  switch (r.status) {
    case CcdStatus::Hit:
    case CcdStatus::InitiallyOverlapping:
      if (!p.hit) return PeerVerdict::Miss;
      return p.toi >= lo && p.toi <= hi ? PeerVerdict::Agree : PeerVerdict::Off;
    case CcdStatus::Separated: return p.hit ? PeerVerdict::FalseHit : PeerVerdict::Agree;
    case CcdStatus::MaxIterations:
    case CcdStatus::Failed:
      if (p.hit && p.toi < lo) return PeerVerdict::Off;
      return PeerVerdict::Undecided;
  }
  return PeerVerdict::Undecided;
}

/// Counts of a peer's verdicts over a run.
struct PeerTally {
  std::uint64_t hits = 0;        ///< the peer's hits
  std::uint64_t agree = 0;       ///< PeerVerdict::Agree
  std::uint64_t misses = 0;      ///< PeerVerdict::Miss
  std::uint64_t false_hits = 0;  ///< PeerVerdict::FalseHit
  std::uint64_t off = 0;         ///< PeerVerdict::Off
  std::uint64_t undecided = 0;   ///< PeerVerdict::Undecided

  /// Adds one answer and its verdict.
  void add(const PeerToi& p, PeerVerdict v) {
    hits += p.hit ? 1u : 0u;
    switch (v) {
      case PeerVerdict::Agree: ++agree; break;
      case PeerVerdict::Miss: ++misses; break;
      case PeerVerdict::FalseHit: ++false_hits; break;
      case PeerVerdict::Off: ++off; break;
      case PeerVerdict::Undecided: ++undecided; break;
    }
  }
  /// Misses + false hits + off.
  std::uint64_t wrong() const { return misses + false_hits + off; }
};

// -------------------------------------------------------------------------------------
// Bullet
// -------------------------------------------------------------------------------------

#if PROXIMA_HAVE_BULLET
/// Bullet's continuous queries.
enum class BulletCast {
  ConservativeAdvancement,  ///< btContinuousConvexCollision (linear and angular motion)
  Subsimplex,               ///< btSubsimplexConvexCast (linear motion only)
  Gjk,                      ///< btGjkConvexCast (linear motion only)
};

/// The cases as Bullet shapes (btSphereShape; btBoxShape and btConvexHullShape with margin 0)
/// and transforms (single precision, as the installed Bullet is built).
class BulletCcdCases {
 public:
  BulletCcdCases(const std::vector<CcdCase>& cases, const CcdHulls& hulls) {
    for (const auto& verts : hulls.vertices) {
      auto h = std::make_unique<btConvexHullShape>();
      for (const Vec3d& v : verts) h->addPoint(vec(v), false);
      h->recalcLocalAabb();
      h->setMargin(0);
      hulls_.push_back(std::move(h));
    }
    auto shape = [&](const CcdShape& s) -> const btConvexShape* {
      switch (s.kind) {
        case CcdShapeKind::Sphere:
          own_.push_back(std::make_unique<btSphereShape>(static_cast<btScalar>(s.radius)));
          break;
        case CcdShapeKind::Box:
          // btBoxShape keeps its full half extents when the margin is changed afterwards.
          own_.push_back(std::make_unique<btBoxShape>(vec(s.half_extents)));
          own_.back()->setMargin(0);
          break;
        case CcdShapeKind::Hull: return hulls_[s.hull].get();
      }
      return own_.back().get();
    };
    for (const CcdCase& c : cases) {
      a_.push_back(shape(c.a));
      b_.push_back(shape(c.b));
      tf_.push_back({transform(c.a0), transform(c.a1), transform(c.b0), transform(c.b1)});
    }
  }

  /// Number of cases.
  std::size_t size() const { return tf_.size(); }

  /// Case k through `method`: the hit and its fraction of the step.
  PeerToi query(std::size_t k, BulletCast method) const {
    btVoronoiSimplexSolver simplex;
    btConvexCast::CastResult result;
    const std::array<btTransform, 4>& t = tf_[k];
    bool hit = false;
    switch (method) {
      case BulletCast::ConservativeAdvancement: {
        btGjkEpaPenetrationDepthSolver epa;
        btContinuousConvexCollision cast(a_[k], b_[k], &simplex, &epa);
        hit = cast.calcTimeOfImpact(t[0], t[1], t[2], t[3], result);
        break;
      }
      case BulletCast::Subsimplex: {
        btSubsimplexConvexCast cast(a_[k], b_[k], &simplex);
        hit = cast.calcTimeOfImpact(t[0], t[1], t[2], t[3], result);
        break;
      }
      case BulletCast::Gjk: {
        btGjkConvexCast cast(a_[k], b_[k], &simplex);
        hit = cast.calcTimeOfImpact(t[0], t[1], t[2], t[3], result);
        break;
      }
    }
    return {hit, hit ? static_cast<double>(result.m_fraction) : 1.0};
  }

 private:
  static btVector3 vec(const Vec3d& v) {
    return btVector3(static_cast<btScalar>(v.x), static_cast<btScalar>(v.y), static_cast<btScalar>(v.z));
  }
  static btTransform transform(const Pose& p) {
    return btTransform(btQuaternion(static_cast<btScalar>(p.rotation.x), static_cast<btScalar>(p.rotation.y),
                                    static_cast<btScalar>(p.rotation.z), static_cast<btScalar>(p.rotation.w)),
                       vec(p.position));
  }

  std::vector<std::unique_ptr<btConvexHullShape>> hulls_;
  std::vector<std::unique_ptr<btConvexInternalShape>> own_;
  std::vector<const btConvexShape*> a_, b_;
  std::vector<std::array<btTransform, 4>> tf_;
};
#endif

// -------------------------------------------------------------------------------------
// FCL
// -------------------------------------------------------------------------------------

#if PROXIMA_HAVE_FCL
/// The cases as FCL geometries (fcl::Sphered, fcl::Boxd, fcl::Convexd; double) and
/// transforms.
class FclCcdCases {
 public:
  FclCcdCases(const std::vector<CcdCase>& cases, const CcdHulls& hulls) : cases_(cases) {
    for (std::size_t s = 0; s < hulls.vertices.size(); ++s) {
      auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
      for (const Vec3d& v : hulls.vertices[s]) verts->emplace_back(v.x, v.y, v.z);
      auto faces = std::make_shared<std::vector<int>>(hulls.faces[s]);
      hulls_.push_back(std::make_shared<fcl::Convexd>(verts, hulls.face_count[s], faces));
    }
    auto shape = [&](const CcdShape& s) -> std::shared_ptr<fcl::CollisionGeometryd> {
      switch (s.kind) {
        case CcdShapeKind::Sphere: return std::make_shared<fcl::Sphered>(s.radius);
        case CcdShapeKind::Box:  // FCL takes side lengths
          return std::make_shared<fcl::Boxd>(2 * s.half_extents.x, 2 * s.half_extents.y, 2 * s.half_extents.z);
        case CcdShapeKind::Hull: return hulls_[s.hull];
      }
      return hulls_.front();
    };
    for (const CcdCase& c : cases) {
      a_.push_back(shape(c.a));
      b_.push_back(shape(c.b));
      a0_.push_back(transform(c.a0));
      a1_.push_back(transform(c.a1));
      b0_.push_back(transform(c.b0));
      b1_.push_back(transform(c.b1));
    }
  }

  /// Number of cases.
  std::size_t size() const { return a_.size(); }

  /// Case k through fcl::continuousCollide, conservative advancement, InterpMotion
  /// (CCDM_LINEAR), with the given GJK solver.
  PeerToi query(std::size_t k, fcl::GJKSolverType solver) const {
    const fcl::ContinuousCollisionRequestd request(10, 1e-4, fcl::CCDM_LINEAR, solver,
                                                   fcl::CCDC_CONSERVATIVE_ADVANCEMENT);
    fcl::ContinuousCollisionResultd result;
    fcl::continuousCollide(a_[k].get(), a0_[k], a1_[k], b_[k].get(), b0_[k], b1_[k], request, result);
    return {result.is_collide, result.is_collide ? result.time_of_contact : 1.0};
  }

  /// Independent signed distance of case k at time t in double, at the W6 poses at t: the
  /// distance when apart (fcl::distance with libccd's GJK, tolerance 1e-9), minus the
  /// penetration depth when overlapping (fcl::collide with one contact: libccd's MPR or FCL's
  /// closed forms; FCL's signed-distance EPA is not used, its assertions abort on degenerate
  /// polytopes), 0 for an overlap without a contact.
  double distance_at(std::size_t k, double t) const {
    const CcdCase& c = cases_[k];
    const fcl::Transform3d ta = transform(ccd_pose_at(c.a0, c.a1, t));
    const fcl::Transform3d tb = transform(ccd_pose_at(c.b0, c.b1, t));
    const fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-9, fcl::GST_LIBCCD);
    fcl::DistanceResultd result;
    fcl::distance(a_[k].get(), ta, b_[k].get(), tb, request, result);
    if (result.min_distance > 0) return result.min_distance;
    const fcl::CollisionRequestd contact_request(1, true);
    fcl::CollisionResultd contact;
    fcl::collide(a_[k].get(), ta, b_[k].get(), tb, contact_request, contact);
    return contact.numContacts() > 0 ? -contact.getContact(0).penetration_depth : 0.0;
  }

 private:
  static fcl::Transform3d transform(const Pose& pose) {
    fcl::Transform3d t = fcl::Transform3d::Identity();
    t.linear() =
        fcl::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).toRotationMatrix();
    t.translation() = fcl::Vector3d(pose.position.x, pose.position.y, pose.position.z);
    return t;
  }

  std::vector<CcdCase> cases_;
  std::vector<std::shared_ptr<fcl::Convexd>> hulls_;
  std::vector<std::shared_ptr<fcl::CollisionGeometryd>> a_, b_;
  std::vector<fcl::Transform3d> a0_, a1_, b0_, b1_;
};

/// Proxima's answers checked with FCL's independent double distance.
struct ProximaCheck {
  std::uint64_t hits_checked = 0;        ///< Hit answers checked at t_upper
  std::uint64_t hits_not_confirmed = 0;  ///< distance at t_upper above the effective tolerance + slack
  double worst_hit_excess = -1e300;      ///< largest (distance at t_upper - effective tolerance)
  std::uint64_t samples = 0;             ///< times sampled in [0, t_lower]
  std::uint64_t samples_in_contact = 0;  ///< samples whose distance is <= -slack (contact before t_lower)
  std::uint64_t cases_in_contact = 0;    ///< cases with at least one such sample

  /// Hits not confirmed + cases found in contact before t_lower.
  std::uint64_t wrong() const { return hits_not_confirmed + cases_in_contact; }
};

/// Checks Proxima's answers: every Hit must be within its effective tolerance at t_upper
/// (FCL's distance, `slack` allowed for the float poses), and the shapes must be apart
/// (distance > -slack) at `samples` times in [0, t_lower], the midpoints of `samples` equal
/// parts (t_lower itself is a Hit's contact time, where the distance is within the tolerance
/// on either side of 0), and at t = 1 for Separated. Sampling cannot prove separation (a thin
/// plate can be crossed between samples); the peers' conservative advancement covers that.
inline ProximaCheck check_proxima(const std::vector<CcdCase>& cases, const CcdHulls& hulls,
                                  const std::vector<ToiResult>& results, const FclCcdCases& fcl, int samples,
                                  double tolerance = 1e-4, double slack = 1e-5) {
  ProximaCheck out;
  for (std::size_t k = 0; k < results.size(); ++k) {
    const ToiResult& r = results[k];
    if (r.status == CcdStatus::Hit) {
      const double d = fcl.distance_at(k, static_cast<double>(r.t_upper));
      const double excess = d - ccd_effective_tolerance(cases[k], hulls, tolerance);
      ++out.hits_checked;
      out.worst_hit_excess = std::max(out.worst_hit_excess, excess);
      if (excess > slack) ++out.hits_not_confirmed;
    }
    if (r.status == CcdStatus::InitiallyOverlapping) continue;
    bool contact = false;
    for (int j = 0; j <= samples; ++j) {
      if (j == samples && r.status != CcdStatus::Separated) break;
      const double t = j == samples ? 1.0 : static_cast<double>(r.t_lower) * (j + 0.5) / samples;
      ++out.samples;
      if (fcl.distance_at(k, t) <= -slack) {
        ++out.samples_in_contact;
        contact = true;
      }
    }
    out.cases_in_contact += contact ? 1u : 0u;
  }
  return out;
}
#endif

}  // namespace proxima::bench
