// Cross-validation of the narrow phase against peer libraries on seeded sweeps:
//   libccd   ccdGJKIntersect, ccdGJKPenetration (GJK + EPA), ccdMPRPenetration, driven by
//            support callbacks that call our shapes (so both sides see the same geometry);
//   FCL      fcl::distance and fcl::collide with GJKSolver_libccd and GJKSolver_indep on
//            Box / Sphere / Capsule / Cylinder / Cone / Convex;
//   Bullet   btGjkPairDetector (btVoronoiSimplexSolver + btGjkEpaPenetrationDepthSolver) and
//            btGjkEpaSolver2 Distance / Penetration;
//   ODE      dCollide box-box (dBoxBox depth).
// Families: polytopes (box, hull), rounded (sphere, capsule against all six), curved
// (cylinder, cone against all six); 10,000 cases each in release builds (PROXIMA_PEER_CASES
// overrides; 1,000 in unoptimised builds). Where a peer and Proxima differ by more than the
// tolerance, an independent reference decides (reference_distance.hpp: exact SAT depth and
// brute-force feature distance for polytopes, a support-function search otherwise) and the
// case counts as the peer's or our wrong answer. Proxima's wrong answers fail the test; the
// peers' are counted and printed ("[peer-tally]" lines, quoted in docs/validation.md).
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <memory>
#include <optional>
#include <string>

#include "narrowphase/narrowphase_test_util.hpp"
#include "narrowphase/reference_distance.hpp"

#if defined(PROXIMA_HAVE_CCD)
#include <ccd/ccd.h>
#endif
#if defined(PROXIMA_HAVE_FCL)
#include <fcl/fcl.h>
#endif
#if defined(PROXIMA_HAVE_BULLET)
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConeShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#endif
#if defined(PROXIMA_HAVE_ODE)
#include <ode/ode.h>
#endif

namespace proxima {
namespace test_crossvalidate_peers {

// ---------------------------------------------------------------------------------------
// Cases and tallies

int case_count() {
  if (const char* env = std::getenv("PROXIMA_PEER_CASES")) return std::max(1, std::atoi(env));
#ifdef NDEBUG
  return 10000;
#else
  return 1000;
#endif
}

struct Family {
  const char* name;
  std::vector<ShapeType> a;
  std::vector<ShapeType> b;
};

std::vector<Family> families() {
  const std::vector<ShapeType> six = {ShapeType::Sphere,   ShapeType::Capsule, ShapeType::Box,
                                      ShapeType::Cylinder, ShapeType::Cone,    ShapeType::ConvexHull};
  return {{"polytope", {ShapeType::Box, ShapeType::ConvexHull}, {ShapeType::Box, ShapeType::ConvexHull}},
          {"rounded", {ShapeType::Sphere, ShapeType::Capsule}, six},
          {"curved", {ShapeType::Cylinder, ShapeType::Cone}, six}};
}

struct Case {
  Shape a = Point::create().value();
  Shape b = Point::create().value();
  Transform pa;
  Transform pb;
  DistanceResult ours;
  bool our_hit = false;
  Real tol = 0;                             // our accuracy at this case's scale
  mutable std::optional<double> reference;  // decided once, on the first disagreement

  double decided() const {
    // Our normal is one more candidate direction for the reference's search (see
    // reference_signed_distance: it is evaluated there, not trusted).
    if (!reference) reference = test::decide_signed_distance(a, pa, b, pb, {test::d3v(ours.normal)});
    return *reference;
  }
};

Case make_case(test::Random& rng, const Family& f) {
  const ShapeType ta = f.a[std::size_t(rng.integer(0, int(f.a.size()) - 1))];
  const ShapeType tb = f.b[std::size_t(rng.integer(0, int(f.b.size()) - 1))];
  Case c;
  c.a = test::random_shape(rng, ta);
  c.b = test::random_shape(rng, tb);
  c.pa = rng.pose(Real(0.5));
  c.pb = rng.pose(Real(1.8));
  if (rng.integer(0, 1) == 0) std::swap(c.a, c.b);
  c.ours = distance(c.a, c.pa, c.b, c.pb);
  c.our_hit = intersect(c.a, c.pa, c.b, c.pb);
  c.tol = test::narrow_tolerance(std::max({test::shape_scale(c.a), test::shape_scale(c.b), Real(1)}));
  return c;
}

std::string reproducer(const Case& c) { return "A=" + test::describe(c.a, c.pa) + " B=" + test::describe(c.b, c.pb); }

// Agreement bookkeeping for one peer function on one family.
struct Tally {
  explicit Tally(std::string n) : name(std::move(n)) {}
  std::string name;
  int cases = 0;       // cases compared
  int agree = 0;       // within tolerance of each other
  int peer_wrong = 0;  // the reference sides with Proxima
  int ours_wrong = 0;  // the reference sides with the peer (or with neither)
  int peer_no_answer = 0;
  double peer_worst = 0;  // largest error of a wrong peer answer against the reference
  std::vector<std::string> ours_examples;
  std::vector<std::string> peer_examples;

  // Compares signed distances (negative = depth) of Proxima and the peer.
  void compare(const Case& c, double ours, double peer, double peer_tol) {
    ++cases;
    const double tol = std::max(double(c.tol), peer_tol);
    if (std::abs(ours - peer) <= tol) {
      ++agree;
      return;
    }
    const double ref = c.decided();
    const bool ours_ok = std::abs(ref - ours) <= double(c.tol) * 2;
    if (ours_ok) {
      ++peer_wrong;
      peer_worst = std::max(peer_worst, std::abs(ref - peer));
      if (peer_examples.size() < 3) {
        peer_examples.push_back("ours=" + std::to_string(ours) + " peer=" + std::to_string(peer) +
                                " reference=" + std::to_string(ref) + " " + reproducer(c));
      }
    } else {
      ++ours_wrong;
      if (ours_examples.size() < 5) {
        ours_examples.push_back("ours=" + std::to_string(ours) + " peer=" + std::to_string(peer) +
                                " reference=" + std::to_string(ref) + " status=" + test::status_name(c.ours.status) +
                                " " + reproducer(c));
      }
    }
  }

  // Compares booleans (skipping cases within tolerance of touching).
  void compare_bool(const Case& c, bool peer) {
    if (std::abs(c.ours.signed_distance) <= c.tol) return;
    ++cases;
    if (peer == c.our_hit) {
      ++agree;
      return;
    }
    const double ref = c.decided();
    if ((ref < 0) == c.our_hit) {
      ++peer_wrong;
      if (peer_examples.size() < 3) {
        peer_examples.push_back("ours=" + std::to_string(c.our_hit) + " peer=" + std::to_string(peer) +
                                " reference sd=" + std::to_string(ref) + " " + reproducer(c));
      }
    } else {
      ++ours_wrong;
      if (ours_examples.size() < 5) {
        ours_examples.push_back("ours hit=" + std::to_string(c.our_hit) + " peer=" + std::to_string(peer) +
                                " reference sd=" + std::to_string(ref) + " " + reproducer(c));
      }
    }
  }

  void report() const {
    std::cout << "[peer-tally] " << name << ": compared " << cases << ", agree " << agree << ", peer wrong "
              << peer_wrong << " (worst error " << peer_worst << "), proxima wrong " << ours_wrong
              << ", peer without answer " << peer_no_answer << "\n";
    for (const std::string& e : peer_examples) std::cout << "    peer wrong: " << e << "\n";
    for (const std::string& e : ours_examples) std::cout << "    PROXIMA WRONG: " << e << "\n";
    EXPECT_EQ(ours_wrong, 0) << name << " Proxima disagrees with the reference in " << ours_wrong << " cases";
  }
};

double case_scale(const Case& c) {
  return std::max({double(test::shape_scale(c.a)), double(test::shape_scale(c.b)), 1.0});
}

// ---------------------------------------------------------------------------------------
// libccd: support callbacks on our shapes

#if defined(PROXIMA_HAVE_CCD)
struct CcdObject {
  const Shape* shape;
  Transform pose;
};

void ccd_support_fn(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* o = static_cast<const CcdObject*>(obj);
  const test::D3v s = test::reference_support(*o->shape, o->pose, {dir->v[0], dir->v[1], dir->v[2]});
  ccdVec3Set(out, s.x, s.y, s.z);
}

void ccd_center_fn(const void* obj, ccd_vec3_t* out) {
  // The mean of the six axis supports: inside every convex shape.
  const auto* o = static_cast<const CcdObject*>(obj);
  test::D3v sum{};
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      test::D3v d{};
      (axis == 0 ? d.x : axis == 1 ? d.y : d.z) = sign;
      sum = sum + test::reference_support(*o->shape, o->pose, d);
    }
  }
  ccdVec3Set(out, sum.x / 6, sum.y / 6, sum.z / 6);
}

TEST(CrossValidatePeers, Libccd) {
  for (const Family& f : families()) {
    test::Random rng(1001);
    Tally gjk_bool{std::string("libccd ccdGJKIntersect / ") + f.name};
    Tally epa{std::string("libccd ccdGJKPenetration / ") + f.name};
    Tally mpr{std::string("libccd ccdMPRPenetration / ") + f.name};
    for (int i = 0; i < case_count(); ++i) {
      const Case c = make_case(rng, f);
      const CcdObject oa{&c.a, c.pa};
      const CcdObject ob{&c.b, c.pb};
      ccd_t ccd;
      CCD_INIT(&ccd);
      ccd.support1 = ccd_support_fn;
      ccd.support2 = ccd_support_fn;
      ccd.center1 = ccd_center_fn;
      ccd.center2 = ccd_center_fn;
      ccd.max_iterations = 1000;
      int hit = 0;
      int epa_rc = -1;
      int mpr_rc = -1;
      ccd_real_t epa_depth = 0;
      ccd_real_t mpr_depth = 0;
      {
        test::ScopedNoFpTraps no_traps;
        ccd_vec3_t dir, pos;
        hit = ccdGJKIntersect(&oa, &ob, &ccd);
        if (c.ours.signed_distance < -c.tol) {
          epa_rc = ccdGJKPenetration(&oa, &ob, &ccd, &epa_depth, &dir, &pos);
          mpr_rc = ccdMPRPenetration(&oa, &ob, &ccd, &mpr_depth, &dir, &pos);
        }
      }
      gjk_bool.compare_bool(c, hit != 0);
      if (c.ours.signed_distance < -c.tol) {
        const double tol = 1e-3 * case_scale(c);
        if (epa_rc == 0) {
          epa.compare(c, double(c.ours.signed_distance), -double(epa_depth), tol);
        } else {
          ++epa.peer_no_answer;
        }
        if (mpr_rc == 0) {
          mpr.compare(c, double(c.ours.signed_distance), -double(mpr_depth), tol);
        } else {
          ++mpr.peer_no_answer;
        }
      }
    }
    gjk_bool.report();
    epa.report();
    mpr.report();
  }
}
#endif

// ---------------------------------------------------------------------------------------
// FCL

#if defined(PROXIMA_HAVE_FCL)
std::shared_ptr<fcl::CollisionGeometryd> fcl_geometry(const Shape& s) {
  if (const auto* sp = std::get_if<Sphere>(&s)) return std::make_shared<fcl::Sphered>(sp->radius());
  if (const auto* cp = std::get_if<Capsule>(&s)) {
    return std::make_shared<fcl::Capsuled>(cp->radius(), 2.0 * double(cp->half_length()));
  }
  if (const auto* b = std::get_if<Box>(&s)) {
    const Vec3 h = b->half_extents();
    return std::make_shared<fcl::Boxd>(2.0 * h.x, 2.0 * h.y, 2.0 * h.z);
  }
  if (const auto* cy = std::get_if<Cylinder>(&s)) {
    return std::make_shared<fcl::Cylinderd>(cy->radius(), 2.0 * double(cy->half_length()));
  }
  if (const auto* co = std::get_if<Cone>(&s))
    return std::make_shared<fcl::Coned>(co->radius(), 2.0 * double(co->half_length()));
  const auto& hull = std::get<ConvexHull>(s);
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  for (const Vec3& v : hull.vertices()) vertices->emplace_back(v.x, v.y, v.z);
  auto faces = std::make_shared<std::vector<int>>();
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) {
    const auto loop = hull.face_vertices(f);
    faces->push_back(int(loop.size()));
    for (std::uint32_t v : loop) faces->push_back(int(v));
  }
  return std::make_shared<fcl::Convexd>(vertices, int(hull.faces().size()), faces);
}

fcl::Transform3d fcl_transform(const Transform& t) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.translation() = fcl::Vector3d(t.position.x, t.position.y, t.position.z);
  tf.linear() =
      fcl::Quaterniond(t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z).normalized().toRotationMatrix();
  return tf;
}

TEST(CrossValidatePeers, Fcl) {
  for (const Family& f : families()) {
    for (fcl::GJKSolverType solver : {fcl::GST_LIBCCD, fcl::GST_INDEP}) {
      const std::string sname = solver == fcl::GST_LIBCCD ? "GJKSolver_libccd" : "GJKSolver_indep";
      test::Random rng(2002);
      Tally dist{"FCL distance " + sname + " / " + f.name};
      Tally depth{"FCL collide depth " + sname + " / " + f.name};
      Tally boolean{"FCL collide boolean " + sname + " / " + f.name};
      for (int i = 0; i < case_count(); ++i) {
        const Case c = make_case(rng, f);
        fcl::CollisionObjectd oa(fcl_geometry(c.a), fcl_transform(c.pa));
        fcl::CollisionObjectd ob(fcl_geometry(c.b), fcl_transform(c.pb));
        test::ScopedNoFpTraps no_traps;
        fcl::CollisionRequestd creq(8, true);  // every contact: the deepest one carries the depth
        creq.gjk_solver_type = solver;
        fcl::CollisionResultd cres;
        fcl::collide(&oa, &ob, creq, cres);
        boolean.compare_bool(c, cres.isCollision());
        const double tol = 1e-3 * case_scale(c);
        if (c.ours.signed_distance > c.tol) {
          fcl::DistanceRequestd dreq;
          dreq.gjk_solver_type = solver;
          dreq.enable_nearest_points = true;
          fcl::DistanceResultd dres;
          fcl::distance(&oa, &ob, dreq, dres);
          dist.compare(c, double(c.ours.signed_distance), dres.min_distance, tol);
        } else if (c.ours.signed_distance < -c.tol) {
          if (cres.isCollision()) {
            double d = 0;
            for (std::size_t k = 0; k < cres.numContacts(); ++k) d = std::max(d, cres.getContact(k).penetration_depth);
            depth.compare(c, double(c.ours.signed_distance), -d, tol);
          } else {
            ++depth.peer_no_answer;
          }
        }
      }
      dist.report();
      depth.report();
      boolean.report();
    }
  }
}
#endif

// ---------------------------------------------------------------------------------------
// Bullet

#if defined(PROXIMA_HAVE_BULLET)
std::unique_ptr<btConvexShape> bullet_shape(const Shape& s) {
  std::unique_ptr<btConvexShape> out;
  if (const auto* sp = std::get_if<Sphere>(&s)) return std::make_unique<btSphereShape>(sp->radius());
  if (const auto* cp = std::get_if<Capsule>(&s)) {
    return std::make_unique<btCapsuleShapeZ>(cp->radius(), Real(2) * cp->half_length());
  }
  if (const auto* b = std::get_if<Box>(&s)) {
    out = std::make_unique<btBoxShape>(btVector3(b->half_extents().x, b->half_extents().y, b->half_extents().z));
  } else if (const auto* cy = std::get_if<Cylinder>(&s)) {
    out = std::make_unique<btCylinderShapeZ>(btVector3(cy->radius(), cy->radius(), cy->half_length()));
  } else if (const auto* co = std::get_if<Cone>(&s)) {
    out = std::make_unique<btConeShapeZ>(co->radius(), Real(2) * co->half_length());
  } else {
    auto hull = std::make_unique<btConvexHullShape>();
    for (const Vec3& v : std::get<ConvexHull>(s).vertices()) hull->addPoint(btVector3(v.x, v.y, v.z), false);
    hull->recalcLocalAabb();
    out = std::move(hull);
  }
  out->setMargin(0);
  return out;
}

btTransform bullet_transform(const Transform& t) {
  return btTransform(btQuaternion(t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w),
                     btVector3(t.position.x, t.position.y, t.position.z));
}

TEST(CrossValidatePeers, Bullet) {
  for (const Family& f : families()) {
    test::Random rng(3003);
    Tally pair{std::string("Bullet btGjkPairDetector / ") + f.name};
    Tally epa2{std::string("Bullet btGjkEpa2 / ") + f.name};
    for (int i = 0; i < case_count(); ++i) {
      const Case c = make_case(rng, f);
      const auto sa = bullet_shape(c.a);
      const auto sb = bullet_shape(c.b);
      const btTransform ta = bullet_transform(c.pa);
      const btTransform tb = bullet_transform(c.pb);
      // Bullet is built in single precision here: allow its float accuracy.
      const double tol = 5e-3 * case_scale(c);
      test::ScopedNoFpTraps no_traps;
      {
        btVoronoiSimplexSolver simplex;
        btGjkEpaPenetrationDepthSolver penetration;
        btGjkPairDetector detector(sa.get(), sb.get(), &simplex, &penetration);
        btGjkPairDetector::ClosestPointInput input;
        input.m_transformA = ta;
        input.m_transformB = tb;
        btPointCollector out;
        detector.getClosestPoints(input, out, nullptr);
        if (out.m_hasResult) {
          pair.compare(c, double(c.ours.signed_distance), double(out.m_distance), tol);
        } else {
          ++pair.peer_no_answer;
        }
      }
      btGjkEpaSolver2::sResults r;
      const btVector3 guess(c.pb.position.x - c.pa.position.x, c.pb.position.y - c.pa.position.y,
                            c.pb.position.z - c.pa.position.z);
      if (c.ours.signed_distance > c.tol) {
        if (btGjkEpaSolver2::Distance(sa.get(), ta, sb.get(), tb, guess, r)) {
          // Distance() works on the shapes without their margins: a sphere's or capsule's
          // radius is its margin, so it is subtracted here (zero for the other shapes).
          const double margins = double(sa->getMargin()) + double(sb->getMargin());
          epa2.compare(c, double(c.ours.signed_distance), double(r.distance) - margins, tol);
        } else {
          ++epa2.peer_no_answer;
        }
      } else if (c.ours.signed_distance < -c.tol) {
        if (btGjkEpaSolver2::Penetration(sa.get(), ta, sb.get(), tb, guess, r)) {
          epa2.compare(c, double(c.ours.signed_distance), double(r.distance), tol);
        } else {
          ++epa2.peer_no_answer;
        }
      }
    }
    pair.report();
    epa2.report();
  }
}
#endif

// ---------------------------------------------------------------------------------------
// ODE box-box

#if defined(PROXIMA_HAVE_ODE)
TEST(CrossValidatePeers, OdeBoxBox) {
  dInitODE2(0);
  test::Random rng(4004);
  const Family boxes{"box-box", {ShapeType::Box}, {ShapeType::Box}};
  Tally depth{"ODE dCollide box-box depth"};
  for (int i = 0; i < case_count(); ++i) {
    const Case c = make_case(rng, boxes);
    if (c.ours.signed_distance >= -c.tol) continue;
    auto make = [](const Box& b, const Transform& t) {
      const Vec3 h = b.half_extents();
      dGeomID g = dCreateBox(nullptr, 2.0 * h.x, 2.0 * h.y, 2.0 * h.z);
      dGeomSetPosition(g, t.position.x, t.position.y, t.position.z);
      const dQuaternion q = {t.rotation.w, t.rotation.x, t.rotation.y, t.rotation.z};
      dGeomSetQuaternion(g, q);
      return g;
    };
    dGeomID ga = make(std::get<Box>(c.a), c.pa);
    dGeomID gb = make(std::get<Box>(c.b), c.pb);
    dContactGeom contacts[8];
    int n = 0;
    {
      test::ScopedNoFpTraps no_traps;
      n = dCollide(ga, gb, 8, contacts, sizeof(dContactGeom));
    }
    dGeomDestroy(ga);
    dGeomDestroy(gb);
    if (n == 0) {
      ++depth.peer_no_answer;
      continue;
    }
    double d = 0;
    for (int k = 0; k < n; ++k) d = std::max(d, double(contacts[k].depth));
    depth.compare(c, double(c.ours.signed_distance), -d, 1e-3 * case_scale(c));
  }
  depth.report();
  dCloseODE();
}
#endif

}  // namespace test_crossvalidate_peers
}  // namespace proxima
