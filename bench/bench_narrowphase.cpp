// The narrow phase of Proxima against the peer libraries, on the shared workloads, in one run.
//
//   1. W2 hull pairs (convex_pairs_{8,32,128}.txt): the convex hulls of the point clouds.
//      - Boolean, every pair: Proxima intersect (plain GJK, Nesterov GJK), libccd
//        ccdGJKIntersect and ccdMPRIntersect, FCL fcl::collide (GJKSolver_libccd and
//        GJKSolver_indep, fcl::Convex), Bullet btGjkPairDetector (btVoronoiSimplexSolver,
//        btConvexHullShape, margin 0, Bullet's EPA as penetration solver; distance <= 0 is a hit).
//      - Distance, the separated pairs: Proxima distance (plain, Nesterov), FCL fcl::distance
//        (both solvers), Bullet btGjkPairDetector (libccd has no distance query).
//      - Penetration depth and normal, the overlapping pairs: Proxima distance (GJK + EPA),
//        libccd ccdGJKPenetration (GJK + EPA), ccdMPRPenetration and ccdGJKSeparate, Bullet
//        btGjkEpaSolver2::Penetration, FCL fcl::collide with contacts (both solvers).
//      - Warm start: every pair's pose B moves along a small periodic path (8 frames; one
//        frame per pass), Proxima plain GJK with a PairCache kept per pair against the same
//        poses without a cache (cold).
//   2. W3 box pairs (box_pairs.txt): the full contact manifold (up to 4 points): Proxima
//      collide, ODE dCollide (dBoxBox), Bullet btBoxBoxDetector, FCL fcl::collide on fcl::Box.
//      Warm start: pose B moves along the same small periodic path as W2's, Proxima collide
//      with a PairCache kept per pair against the same poses without a cache (cold).
//   3. W7 sphere and capsule pairs: Proxima intersect / distance / collide over the
//      1,000,000 materialised query records (streamed from memory) and over the 25,000
//      distinct pairs (in cache), the memory-bound floor of bench_floor on the same records,
//      and the peers' own queries on the distinct pairs.
//
// Every benchmark reports per_query and the counters that show each library computed the
// same thing: `hits` (and `mismatch`, the pairs whose answer differs from the reference),
// `mean` (distance, depth or deepest point, mean over the queries) and, where a
// reference value exists, `max_err`. References, computed in double before timing (W2: on
// first use of each size): W2 boolean and penetration depth from an exact separating-axis
// test over the facet directions of the Minkowski difference (exact_polytope_pair); W2
// distance from the smaller of FCL's two GJK distances; W3 from a 15-axis separating-axis
// test; W7 from the closed forms.
// Shapes are converted to each library's representation before timing.
#include <benchmark/benchmark.h>

#include <proxima/geometry/closest_points.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/convex_hull.hpp>
#include <proxima/shapes/sphere.hpp>

// The library's narrow phase is benchmarked when it is linked (set to 0 to time the peers
// alone while it is missing).
#ifndef PROXIMA_BENCH_NARROWPHASE
#define PROXIMA_BENCH_NARROWPHASE 1
#endif
#if PROXIMA_BENCH_NARROWPHASE
#include <proxima/narrowphase/narrowphase.hpp>
#endif

#if PROXIMA_HAVE_FCL
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/capsule.h>
#include <fcl/geometry/shape/convex.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#endif
#if PROXIMA_HAVE_CCD
#include <ccd/ccd.h>
#endif
#if PROXIMA_HAVE_BULLET
#include <BulletCollision/CollisionDispatch/btBoxBoxDetector.h>
#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btCapsuleShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>
#endif
#if PROXIMA_HAVE_ODE
#include <ode/ode.h>
#endif

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "support/workloads.hpp"

namespace {

using proxima::Real;
using proxima::Transform;
using proxima::Vec3;
namespace pb = proxima::bench;

// -------------------------------------------------------------------------------------
// Double-precision helpers
// -------------------------------------------------------------------------------------

/// Row-major rotation matrix of a unit quaternion (FORMATS.md).
struct Mat3d {
  double m[3][3];
};

Mat3d rotation_matrix(const pb::Quatd& q) {
  const double w = q.w, x = q.x, y = q.y, z = q.z;
  return Mat3d{{{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
                {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
                {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}}};
}

double dot(const pb::Vec3d& a, const pb::Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
pb::Vec3d sub(const pb::Vec3d& a, const pb::Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
pb::Vec3d cross(const pb::Vec3d& a, const pb::Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// Column `c` of the rotation of `q` (the world direction of local axis c).
pb::Vec3d axis(const Mat3d& r, int c) { return {r.m[0][c], r.m[1][c], r.m[2][c]}; }

/// A capsule given by its segment, as a pose (centre, local z along the segment) and its
/// half length, in double.
struct CapsulePose {
  pb::Pose pose;
  double half_length = 0;
  double radius = 0;
};

CapsulePose capsule_pose(const pb::Vec3d& p0, const pb::Vec3d& p1, double radius) {
  CapsulePose c;
  c.pose.position = {0.5 * (p0.x + p1.x), 0.5 * (p0.y + p1.y), 0.5 * (p0.z + p1.z)};
  const pb::Vec3d d = sub(p1, p0);
  const double len = std::sqrt(dot(d, d));
  c.half_length = 0.5 * len;
  c.radius = radius;
  const pb::Vec3d u = len > 0 ? pb::Vec3d{d.x / len, d.y / len, d.z / len} : pb::Vec3d{0, 0, 1};
  // Shortest rotation taking +z to u: q = (1 + u.z, z x u) normalised.
  if (u.z < -1 + 1e-12) {
    c.pose.rotation = {0, 1, 0, 0};
  } else {
    const double w = 1 + u.z, x = -u.y, y = u.x;
    const double n = std::sqrt(w * w + x * x + y * y);
    c.pose.rotation = {w / n, x / n, y / n, 0};
  }
  return c;
}

/// Squared distance of segments in double (Ericson 5.1.9, clamped; segments of non-zero
/// length, as W7 has).
double segment_distance_squared(const pb::Vec3d& p0, const pb::Vec3d& p1, const pb::Vec3d& q0, const pb::Vec3d& q1) {
  const pb::Vec3d d1 = sub(p1, p0), d2 = sub(q1, q0), r = sub(p0, q0);
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r), c = dot(d1, r), b = dot(d1, d2);
  const double denom = a * e - b * b;
  double s = denom > 1e-12 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  double t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = std::clamp(-c / a, 0.0, 1.0);
  } else if (t > 1) {
    t = 1;
    s = std::clamp((b - c) / a, 0.0, 1.0);
  }
  const pb::Vec3d d{p0.x + d1.x * s - q0.x - d2.x * t, p0.y + d1.y * s - q0.y - d2.y * t,
                    p0.z + d1.z * s - q0.z - d2.z * t};
  return dot(d, d);
}

/// 15-axis separating-axis test of two oriented boxes in double (touching counts).
bool boxes_overlap(const pb::BoxPair& p) {
  const Mat3d ra = rotation_matrix(p.pose_a.rotation), rb = rotation_matrix(p.pose_b.rotation);
  std::array<pb::Vec3d, 15> axes;
  int n = 0;
  for (int i = 0; i < 3; ++i) axes[n++] = axis(ra, i);
  for (int i = 0; i < 3; ++i) axes[n++] = axis(rb, i);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) axes[n++] = cross(axis(ra, i), axis(rb, j));
  const pb::Vec3d t = sub(p.pose_b.position, p.pose_a.position);
  for (const pb::Vec3d& l : axes) {
    if (dot(l, l) < 1e-14) continue;  // parallel edges: covered by the face axes
    double ea = 0, eb = 0;
    for (int i = 0; i < 3; ++i) {
      ea += p.half_extents_a[i] * std::abs(dot(axis(ra, i), l));
      eb += p.half_extents_b[i] * std::abs(dot(axis(rb, i), l));
    }
    if (std::abs(dot(t, l)) > ea + eb) return false;
  }
  return true;
}

// -------------------------------------------------------------------------------------
// The timing loop and the checks
// -------------------------------------------------------------------------------------

/// One answer of one query: hit, a value (distance, depth, deepest point; `mean` is its
/// mean over the queries) and the number of contact points.
struct Answer {
  bool hit = false;
  double value = 0;
  int contacts = 0;
};

/// What an answer is checked against: a hit per query and optionally a value.
struct Reference {
  const std::vector<char>* hits = nullptr;      ///< expected hit per query
  const std::vector<double>* values = nullptr;  ///< expected value per query (or null)
};

/// Times `query(k)` over queries 0..count-1 per iteration, then runs one more untimed pass
/// to compare with the reference (max_err over the queries whose hit agrees), and sets
/// the counters.
template <class Query>
void run_queries(benchmark::State& state, std::size_t count, Query query, Reference reference = {}) {
  std::uint64_t hits = 0, contacts = 0;
  double sum = 0;
  for (auto _ : state) {
    hits = 0;
    contacts = 0;
    sum = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const Answer a = query(k);
      hits += a.hit ? 1u : 0u;
      contacts += static_cast<std::uint64_t>(a.contacts);
      sum += a.value;
    }
    benchmark::DoNotOptimize(hits);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["per_query"] = pb::time_per_item(count);
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["mean"] = count > 0 ? sum / static_cast<double>(count) : 0.0;
  if (contacts > 0) state.counters["contacts"] = static_cast<double>(contacts);
  if (reference.hits != nullptr) {
    std::uint64_t mismatch = 0;
    double max_err = 0;
    for (std::size_t k = 0; k < count; ++k) {
      const Answer a = query(k);
      if (a.hit != ((*reference.hits)[k] != 0)) ++mismatch;
      if (reference.values != nullptr && a.hit == ((*reference.hits)[k] != 0)) {
        max_err = std::max(max_err, std::abs(a.value - (*reference.values)[k]));
      }
    }
    state.counters["mismatch"] = static_cast<double>(mismatch);
    if (reference.values != nullptr) state.counters["max_err"] = max_err;
  }
}

// -------------------------------------------------------------------------------------
// W2 hull workloads
// -------------------------------------------------------------------------------------

constexpr int kWarmFrames = 8;

struct HullWorkload {
  int points = 0;
  std::vector<pb::ConvexShape> shapes;                     // the clouds, double
  std::vector<std::vector<pb::Vec3d>> vertices;            // hull vertices per shape, double
  std::vector<std::vector<int>> fcl_faces;                 // [n, i0 .. in-1]* per shape
  std::vector<int> face_count;                             // faces per shape
  std::vector<std::vector<pb::Vec3d>> face_normals;        // unit outward, local, double (Newell)
  std::vector<std::vector<proxima::HullEdge>> edges;       // every edge with its two faces
  std::vector<proxima::ConvexHull> hulls;                  // Proxima hulls (float or double)
  std::vector<pb::ConvexPair> pairs;                       // every query
  std::vector<Transform> pose_a, pose_b;                   // per pair, Real
  std::vector<std::uint32_t> all, separated, overlapping;  // query subsets (pair indices)
  std::vector<double> ref_distance;                        // per pair (<= 0: intersecting)
  std::vector<char> ref_hit_all, ref_hit_separated, ref_hit_overlapping;
  std::vector<double> ref_distance_separated, ref_depth_overlapping;
  bool references_ready = false;
  int overruled = 0;              // pairs whose FCL boolean the exact test overruled
  std::vector<Transform> warm_b;  // kWarmFrames * pairs: pose B along a small periodic path
};

std::array<HullWorkload, 3> g_hulls;

/// Builds the hull of every cloud with Proxima (qhull) and maps the hull's vertices and
/// faces back to the cloud's double points, so every library sees the same polytope.
bool build_hull_shapes(HullWorkload& w) {
  for (const pb::ConvexShape& s : w.shapes) {
    std::vector<Vec3> pts;
    for (const pb::Vec3d& p : s.points) pts.push_back(pb::to_vec3(p));
    auto hull = proxima::ConvexHull::create(pts);
    if (!hull) return pb::report_load_error(hull.error());
    std::vector<int> to_input;  // hull vertex -> cloud point
    for (const Vec3& v : hull->vertices()) {
      int found = 0;
      for (std::size_t j = 0; j < pts.size(); ++j) {
        if (pts[j] == v) {
          found = static_cast<int>(j);
          break;
        }
      }
      to_input.push_back(found);
    }
    std::vector<pb::Vec3d> verts;
    for (int j : to_input) verts.push_back(s.points[static_cast<std::size_t>(j)]);
    std::vector<int> faces;
    for (std::uint32_t f = 0; f < hull->faces().size(); ++f) {
      const auto loop = hull->face_vertices(f);
      faces.push_back(static_cast<int>(loop.size()));
      for (std::uint32_t v : loop) faces.push_back(static_cast<int>(v));
    }
    w.face_count.push_back(static_cast<int>(hull->faces().size()));
    std::vector<pb::Vec3d> normals;
    for (std::uint32_t f = 0; f < hull->faces().size(); ++f) {
      const auto loop = hull->face_vertices(f);
      pb::Vec3d n{0, 0, 0};
      for (std::size_t i = 0; i < loop.size(); ++i) {
        const pb::Vec3d& p = verts[loop[i]];
        const pb::Vec3d& q = verts[loop[(i + 1) % loop.size()]];
        n.x += (p.y - q.y) * (p.z + q.z);
        n.y += (p.z - q.z) * (p.x + q.x);
        n.z += (p.x - q.x) * (p.y + q.y);
      }
      const double len = std::sqrt(dot(n, n));
      normals.push_back({n.x / len, n.y / len, n.z / len});
    }
    w.face_normals.push_back(std::move(normals));
    w.edges.emplace_back(hull->edges().begin(), hull->edges().end());
    w.fcl_faces.push_back(std::move(faces));
    w.vertices.push_back(std::move(verts));
    w.hulls.push_back(*hull);
  }
  return true;
}

/// Pose B of pair k at warm-start frame f: translated by up to 0.004 and turned by up to
/// 0.01 rad about a fixed axis, periodically, so consecutive frames are coherent.
Transform warm_pose(const Transform& b, int frame) {
  const double phase = 2.0 * 3.14159265358979323846 * frame / kWarmFrames;
  const Real s = static_cast<Real>(std::sin(phase)), c = static_cast<Real>(std::cos(phase));
  Transform t = b;
  t.position += Vec3(Real(0.004) * s, Real(0.004) * (c - Real(1)), Real(0.002) * s);
  const proxima::Quat dq = glm::angleAxis(Real(0.01) * s, glm::normalize(Vec3(Real(0.3), Real(0.5), Real(0.8))));
  t.rotation = glm::normalize(dq * b.rotation);
  return t;
}

#if PROXIMA_HAVE_CCD
/// A hull for libccd: the double vertices and the pose.
struct CcdHull {
  const pb::Vec3d* vertices = nullptr;
  std::size_t count = 0;
  Mat3d r{};
  pb::Vec3d p;
};

void ccd_hull_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* h = static_cast<const CcdHull*>(obj);
  const double* d = dir->v;
  // Direction into the local frame (R^T d).
  const double lx = h->r.m[0][0] * d[0] + h->r.m[1][0] * d[1] + h->r.m[2][0] * d[2];
  const double ly = h->r.m[0][1] * d[0] + h->r.m[1][1] * d[1] + h->r.m[2][1] * d[2];
  const double lz = h->r.m[0][2] * d[0] + h->r.m[1][2] * d[1] + h->r.m[2][2] * d[2];
  std::size_t best = 0;
  double best_dot = -1e300;
  for (std::size_t i = 0; i < h->count; ++i) {
    const pb::Vec3d& v = h->vertices[i];
    const double s = v.x * lx + v.y * ly + v.z * lz;
    if (s > best_dot) {
      best_dot = s;
      best = i;
    }
  }
  const pb::Vec3d& v = h->vertices[best];
  for (int i = 0; i < 3; ++i) out->v[i] = h->r.m[i][0] * v.x + h->r.m[i][1] * v.y + h->r.m[i][2] * v.z + h->p[i];
}

void ccd_hull_center(const void* obj, ccd_vec3_t* out) {
  const auto* h = static_cast<const CcdHull*>(obj);
  for (int i = 0; i < 3; ++i) out->v[i] = h->p[i];
}

std::vector<std::array<CcdHull, 2>> ccd_hull_pairs(const HullWorkload& w) {
  std::vector<std::array<CcdHull, 2>> out;
  for (const pb::ConvexPair& p : w.pairs) {
    std::array<CcdHull, 2> o;
    o[0] = {w.vertices[p.a].data(), w.vertices[p.a].size(), rotation_matrix(p.pose_a.rotation), p.pose_a.position};
    o[1] = {w.vertices[p.b].data(), w.vertices[p.b].size(), rotation_matrix(p.pose_b.rotation), p.pose_b.position};
    out.push_back(o);
  }
  return out;
}

ccd_t ccd_hull_setup(double tolerance = 1e-6) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd_hull_support;
  ccd.support2 = ccd_hull_support;
  ccd.center1 = ccd_hull_center;
  ccd.center2 = ccd_hull_center;
  ccd.max_iterations = 500;
  ccd.epa_tolerance = tolerance;
  ccd.mpr_tolerance = tolerance;
  ccd.dist_tolerance = tolerance;
  return ccd;
}
#endif

#if PROXIMA_HAVE_FCL
fcl::Transform3d fcl_transform(const pb::Pose& pose) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = fcl::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z).toRotationMatrix();
  t.translation() = fcl::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return t;
}

struct FclPair {
  std::unique_ptr<fcl::CollisionObjectd> a, b;
};

std::vector<FclPair> fcl_hull_pairs(const HullWorkload& w) {
  std::vector<std::shared_ptr<fcl::Convexd>> shapes;
  for (std::size_t s = 0; s < w.vertices.size(); ++s) {
    auto verts = std::make_shared<std::vector<fcl::Vector3d>>();
    for (const pb::Vec3d& v : w.vertices[s]) verts->emplace_back(v.x, v.y, v.z);
    auto faces = std::make_shared<std::vector<int>>(w.fcl_faces[s]);
    shapes.push_back(std::make_shared<fcl::Convexd>(verts, w.face_count[s], faces));
  }
  std::vector<FclPair> out;
  for (const pb::ConvexPair& p : w.pairs) {
    FclPair o;
    o.a = std::make_unique<fcl::CollisionObjectd>(shapes[p.a], fcl_transform(p.pose_a));
    o.b = std::make_unique<fcl::CollisionObjectd>(shapes[p.b], fcl_transform(p.pose_b));
    out.push_back(std::move(o));
  }
  return out;
}
#endif

#if PROXIMA_HAVE_BULLET
btTransform bt_transform(const pb::Pose& pose) {
  return btTransform(btQuaternion(static_cast<btScalar>(pose.rotation.x), static_cast<btScalar>(pose.rotation.y),
                                  static_cast<btScalar>(pose.rotation.z), static_cast<btScalar>(pose.rotation.w)),
                     btVector3(static_cast<btScalar>(pose.position.x), static_cast<btScalar>(pose.position.y),
                               static_cast<btScalar>(pose.position.z)));
}

struct BulletHulls {
  std::vector<std::unique_ptr<btConvexHullShape>> shapes;
  std::vector<std::array<btTransform, 2>> poses;
};

BulletHulls bullet_hulls(const HullWorkload& w) {
  BulletHulls out;
  for (const auto& verts : w.vertices) {
    auto shape = std::make_unique<btConvexHullShape>();
    for (const pb::Vec3d& v : verts) {
      shape->addPoint(btVector3(static_cast<btScalar>(v.x), static_cast<btScalar>(v.y), static_cast<btScalar>(v.z)),
                      false);
    }
    shape->recalcLocalAabb();
    shape->setMargin(0);
    out.shapes.push_back(std::move(shape));
  }
  for (const pb::ConvexPair& p : w.pairs) out.poses.push_back({bt_transform(p.pose_a), bt_transform(p.pose_b)});
  return out;
}
#endif

/// Exact answer for a polytope pair in double, by the separating-axis theorem over every
/// facet direction of the Minkowski difference A - B: the face normals of A, of B, and the
/// cross products of the edge pairs whose Gauss-map arcs cross (Gregorius, "The Separating
/// Axis Test between Convex Polyhedra", GDC 2013). Gives the boolean (touching counts) and,
/// for overlapping pairs, the penetration depth: min over those directions n of
/// h_A(n) + h_B(-n) (every direction bounds the depth from above, the facet normals reach it).
struct ExactAnswer {
  bool overlap = false;
  double depth = 0;  ///< penetration depth when overlapping
};

ExactAnswer exact_polytope_pair(const HullWorkload& w, const pb::ConvexPair& p) {
  struct World {
    std::vector<pb::Vec3d> v, n;
  };
  auto place = [&](std::uint32_t s, const pb::Pose& pose) {
    World out;
    const Mat3d r = rotation_matrix(pose.rotation);
    auto rot = [&](const pb::Vec3d& x) {
      return pb::Vec3d{r.m[0][0] * x.x + r.m[0][1] * x.y + r.m[0][2] * x.z,
                       r.m[1][0] * x.x + r.m[1][1] * x.y + r.m[1][2] * x.z,
                       r.m[2][0] * x.x + r.m[2][1] * x.y + r.m[2][2] * x.z};
    };
    for (const pb::Vec3d& v : w.vertices[s]) {
      const pb::Vec3d x = rot(v);
      out.v.push_back({x.x + pose.position.x, x.y + pose.position.y, x.z + pose.position.z});
    }
    for (const pb::Vec3d& n : w.face_normals[s]) out.n.push_back(rot(n));
    return out;
  };
  const World a = place(p.a, p.pose_a), b = place(p.b, p.pose_b);
  double depth = 1e300;
  auto test = [&](const pb::Vec3d& n) {  // h_A(n) + h_B(-n) for unit n
    double ha = -1e300, lb = 1e300;
    for (const pb::Vec3d& v : a.v) ha = std::max(ha, dot(n, v));
    for (const pb::Vec3d& v : b.v) lb = std::min(lb, dot(n, v));
    depth = std::min(depth, ha - lb);
  };
  // Any direction with a negative value separates the pair: stop there.
  for (const pb::Vec3d& n : a.n) {
    test(n);
    if (depth < 0) return {false, 0};
  }
  for (const pb::Vec3d& m : b.n) {
    test({-m.x, -m.y, -m.z});
    if (depth < 0) return {false, 0};
  }
  const auto& ea = w.edges[p.a];
  const auto& eb = w.edges[p.b];
  for (const proxima::HullEdge& e : ea) {
    const pb::Vec3d& n0 = a.n[e.face0];
    const pb::Vec3d& n1 = a.n[e.face1];
    const pb::Vec3d bxa = cross(n1, n0);
    const pb::Vec3d da = sub(a.v[e.v1], a.v[e.v0]);
    for (const proxima::HullEdge& f : eb) {
      // Arcs (n0, n1) of A and (-m0, -m1) of -B.
      const pb::Vec3d c{-b.n[f.face0].x, -b.n[f.face0].y, -b.n[f.face0].z};
      const pb::Vec3d d{-b.n[f.face1].x, -b.n[f.face1].y, -b.n[f.face1].z};
      const double cba = dot(c, bxa), dba = dot(d, bxa);
      if (cba * dba >= 0) continue;
      const pb::Vec3d dxc = cross(d, c);
      const double adc = dot(n0, dxc), bdc = dot(n1, dxc);
      if (adc * bdc >= 0 || cba * bdc <= 0) continue;
      pb::Vec3d n = cross(da, sub(b.v[f.v1], b.v[f.v0]));
      const double len = std::sqrt(dot(n, n));
      if (len < 1e-12) continue;
      n = {n.x / len, n.y / len, n.z / len};
      test(n);
      test({-n.x, -n.y, -n.z});
      if (depth < 0) return {false, 0};
    }
  }
  return {depth >= 0, std::max(depth, 0.0)};
}

/// Loads one W2 size and computes its references.
bool load_hulls(const std::string& dir, int points, HullWorkload& w) {
  auto workload = pb::read_convex_workload(dir, points);
  if (!workload) return pb::report_load_error(workload.error());
  w.points = points;
  w.shapes = std::move(workload->shapes.shapes);
  w.pairs = std::move(workload->pairs.pairs);
  if (!build_hull_shapes(w)) return false;
  for (const pb::ConvexPair& p : w.pairs) {
    w.pose_a.push_back(pb::to_transform(p.pose_a));
    w.pose_b.push_back(pb::to_transform(p.pose_b));
  }
  const std::size_t n = w.pairs.size();
  w.warm_b.resize(kWarmFrames * n);
  for (int f = 0; f < kWarmFrames; ++f) {
    for (std::size_t k = 0; k < n; ++k) w.warm_b[static_cast<std::size_t>(f) * n + k] = warm_pose(w.pose_b[k], f);
  }
  return true;
}

/// Computes the references of a W2 size (a few seconds for 128 points; done on first use so
/// that a filtered run pays only for the sizes it times).
void compute_references(HullWorkload& w) {
  const std::size_t n = w.pairs.size();
  // Distance: the smaller of FCL's two GJK answers (double; each is the length of a point of
  // A - B, so an upper bound); boolean and depth: the exact separating-axis answer.
  w.ref_distance.assign(n, 0.0);
#if PROXIMA_HAVE_FCL
  {
    const std::vector<FclPair> objects = fcl_hull_pairs(w);
    for (const fcl::GJKSolverType solver : {fcl::GST_INDEP, fcl::GST_LIBCCD}) {
      const fcl::DistanceRequestd request(false, false, 0.0, 0.0, 1e-9, solver);
      for (std::size_t k = 0; k < n; ++k) {
        fcl::DistanceResultd result;
        fcl::distance(objects[k].a.get(), objects[k].b.get(), request, result);
        w.ref_distance[k] =
            solver == fcl::GST_INDEP ? result.min_distance : std::min(w.ref_distance[k], result.min_distance);
      }
    }
  }
#endif
  for (std::size_t k = 0; k < n; ++k) {
    const ExactAnswer e = exact_polytope_pair(w, w.pairs[k]);
    if (!e.overlap && w.ref_distance[k] <= 0) ++w.overruled;
    if (e.overlap && w.ref_distance[k] > 0) ++w.overruled;
    if (e.overlap) w.ref_distance[k] = 0;
    const auto idx = static_cast<std::uint32_t>(k);
    w.all.push_back(idx);
    w.ref_hit_all.push_back(e.overlap ? 1 : 0);
    if (e.overlap) {
      w.overlapping.push_back(idx);
      w.ref_hit_overlapping.push_back(1);
      w.ref_depth_overlapping.push_back(e.depth);
    } else if (w.ref_distance[k] > 0) {  // a separated pair both FCL solvers call touching is left out
      w.separated.push_back(idx);
      w.ref_hit_separated.push_back(0);
      w.ref_distance_separated.push_back(w.ref_distance[k]);
    }
  }
  // Pairs whose FCL answer the exact test overruled; separated pairs left out of the
  // distance set because FCL reports no distance for them.
  std::fprintf(stderr, "W2 %d points: reference overruled FCL on %d pairs, %zu pairs left out\n", w.points, w.overruled,
               n - w.overlapping.size() - w.separated.size());
  w.references_ready = true;
}

/// The W2 workload of a size, its references computed.
const HullWorkload& hulls_of(int points) {
  HullWorkload& w = g_hulls[points == 8 ? 0 : (points == 32 ? 1 : 2)];
  if (!w.references_ready) compute_references(w);
  return w;
}

/// The subsets a W2 benchmark runs on.
enum class Subset { All, Separated, Overlapping };

const std::vector<std::uint32_t>& subset_of(const HullWorkload& w, Subset s) {
  return s == Subset::All ? w.all : (s == Subset::Separated ? w.separated : w.overlapping);
}

Reference reference_of(const HullWorkload& w, Subset s) {
  switch (s) {
    case Subset::All: return {&w.ref_hit_all, nullptr};
    case Subset::Separated: return {&w.ref_hit_separated, &w.ref_distance_separated};
    case Subset::Overlapping:
      return {&w.ref_hit_overlapping, w.ref_depth_overlapping.empty() ? nullptr : &w.ref_depth_overlapping};
  }
  return {};
}

/// The kinds of W2 query.
enum class HullQuery { Boolean, Distance, Penetration };

Subset subset_for(HullQuery q) {
  return q == HullQuery::Boolean ? Subset::All : (q == HullQuery::Distance ? Subset::Separated : Subset::Overlapping);
}

template <class PerPair>
void run_hulls(benchmark::State& state, const HullWorkload& w, HullQuery q, PerPair per_pair) {
  const Subset s = subset_for(q);
  const std::vector<std::uint32_t>& idx = subset_of(w, s);
  run_queries(
      state, idx.size(), [&](std::size_t k) { return per_pair(idx[k]); }, reference_of(w, s));
}

#if PROXIMA_BENCH_NARROWPHASE
void proxima_hulls(benchmark::State& state, int points, HullQuery q, proxima::gjk::Variant variant) {
  const HullWorkload& w = hulls_of(points);
  proxima::PairRequest request;
  request.gjk = variant;
  request.max_contacts = 1;
  run_hulls(state, w, q, [&](std::uint32_t k) -> Answer {
    const proxima::ConvexHull& a = w.hulls[w.pairs[k].a];
    const proxima::ConvexHull& b = w.hulls[w.pairs[k].b];
    if (q == HullQuery::Boolean) return {proxima::intersect(a, w.pose_a[k], b, w.pose_b[k], request), 0.0, 0};
    const proxima::DistanceResult r = proxima::distance(a, w.pose_a[k], b, w.pose_b[k], request);
    const double d = static_cast<double>(r.signed_distance);
    if (q == HullQuery::Distance) return {d <= 0, std::max(d, 0.0), 0};
    return {d <= 0, -d, 0};
  });
}

/// Warm start: pass p uses frame p mod kWarmFrames for every pair; `warm` keeps one
/// PairCache per pair across passes, cold passes none. Boolean on all pairs, distance on
/// the pairs separated at frame 0.
void proxima_hulls_warm(benchmark::State& state, int points, HullQuery q, bool warm) {
  const HullWorkload& w = hulls_of(points);
  const Subset s = subset_for(q);
  const std::vector<std::uint32_t>& idx = subset_of(w, s);
  const std::size_t n = w.pairs.size();
  std::vector<proxima::PairCache> caches(n);
  proxima::PairRequest request;
  request.max_contacts = 1;
  std::uint64_t hits = 0, pass = 0;
  double sum = 0;
  for (auto _ : state) {
    const Transform* frame_b = &w.warm_b[(pass++ % kWarmFrames) * n];
    hits = 0;
    sum = 0;
    for (const std::uint32_t k : idx) {
      const proxima::ConvexHull& a = w.hulls[w.pairs[k].a];
      const proxima::ConvexHull& b = w.hulls[w.pairs[k].b];
      proxima::PairCache* cache = warm ? &caches[k] : nullptr;
      if (q == HullQuery::Boolean) {
        hits += proxima::intersect(a, w.pose_a[k], b, frame_b[k], request, cache) ? 1u : 0u;
      } else {
        const Real d = proxima::distance(a, w.pose_a[k], b, frame_b[k], request, cache).signed_distance;
        hits += d <= 0 ? 1u : 0u;
        sum += static_cast<double>(std::max(d, Real(0)));
      }
    }
    benchmark::DoNotOptimize(hits);
    benchmark::DoNotOptimize(sum);
  }
  state.counters["per_query"] = pb::time_per_item(idx.size());
  state.counters["hits"] = static_cast<double>(hits);
  if (q == HullQuery::Distance) state.counters["mean"] = sum / static_cast<double>(idx.size());
}
#endif

#if PROXIMA_HAVE_CCD
enum class CcdMethod { GjkIntersect, MprIntersect, GjkPenetration, MprPenetration, GjkSeparate };

void ccd_hulls(benchmark::State& state, int points, HullQuery q, CcdMethod method) {
  const HullWorkload& w = hulls_of(points);
  const auto objects = ccd_hull_pairs(w);
  const ccd_t ccd = ccd_hull_setup();
  run_hulls(state, w, q, [&](std::uint32_t k) -> Answer {
    const void* a = &objects[k][0];
    const void* b = &objects[k][1];
    ccd_real_t depth = 0;
    ccd_vec3_t dir, pos;
    switch (method) {
      case CcdMethod::GjkIntersect: return {ccdGJKIntersect(a, b, &ccd) != 0, 0.0, 0};
      case CcdMethod::MprIntersect: return {ccdMPRIntersect(a, b, &ccd) != 0, 0.0, 0};
      case CcdMethod::GjkPenetration: return {ccdGJKPenetration(a, b, &ccd, &depth, &dir, &pos) == 0, depth, 0};
      case CcdMethod::MprPenetration: return {ccdMPRPenetration(a, b, &ccd, &depth, &dir, &pos) == 0, depth, 0};
      case CcdMethod::GjkSeparate: {
        const int r = ccdGJKSeparate(a, b, &ccd, &dir);
        return {r == 0, r == 0 ? std::sqrt(ccdVec3Len2(&dir)) : 0.0, 0};
      }
    }
    return {};
  });
}
#endif

#if PROXIMA_HAVE_FCL
void fcl_hulls(benchmark::State& state, int points, HullQuery q, fcl::GJKSolverType solver) {
  const HullWorkload& w = hulls_of(points);
  const std::vector<FclPair> objects = fcl_hull_pairs(w);
  fcl::CollisionRequestd boolean_request(1, false, 1, false, true, solver);
  fcl::CollisionRequestd contact_request(1, true, 1, false, true, solver);
  fcl::DistanceRequestd distance_request(true, false, 0.0, 0.0, 1e-6, solver);
  run_hulls(state, w, q, [&](std::uint32_t k) -> Answer {
    const FclPair& o = objects[k];
    if (q == HullQuery::Boolean) {
      fcl::CollisionResultd result;
      return {fcl::collide(o.a.get(), o.b.get(), boolean_request, result) > 0, 0.0, 0};
    }
    if (q == HullQuery::Distance) {
      fcl::DistanceResultd result;
      const double d = fcl::distance(o.a.get(), o.b.get(), distance_request, result);
      return {d <= 0, std::max(d, 0.0), 0};
    }
    fcl::CollisionResultd result;
    const bool hit = fcl::collide(o.a.get(), o.b.get(), contact_request, result) > 0;
    return {hit, hit && result.numContacts() > 0 ? result.getContact(0).penetration_depth : 0.0, 0};
  });
}
#endif

#if PROXIMA_HAVE_BULLET
void bullet_hulls_query(benchmark::State& state, int points, HullQuery q) {
  const HullWorkload& w = hulls_of(points);
  const BulletHulls bt = bullet_hulls(w);
  run_hulls(state, w, q, [&](std::uint32_t k) -> Answer {
    const btConvexHullShape* a = bt.shapes[w.pairs[k].a].get();
    const btConvexHullShape* b = bt.shapes[w.pairs[k].b].get();
    if (q == HullQuery::Penetration) {
      btGjkEpaSolver2::sResults results;
      const bool hit = btGjkEpaSolver2::Penetration(a, bt.poses[k][0], b, bt.poses[k][1], btVector3(1, 0, 0), results);
      return {hit, hit ? -static_cast<double>(results.distance) : 0.0, 0};
    }
    // Boolean: with Bullet's EPA as the penetration solver, as btConvexConvexAlgorithm runs
    // it (without one, overlapping pairs whose GJK ends degenerate come back separated).
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    btGjkPairDetector detector(a, b, &simplex, q == HullQuery::Boolean ? &epa : nullptr);
    btGjkPairDetector::ClosestPointInput input;
    input.m_transformA = bt.poses[k][0];
    input.m_transformB = bt.poses[k][1];
    btPointCollector output;
    detector.getClosestPoints(input, output, nullptr);
    const bool hit = !output.m_hasResult || output.m_distance <= 0;
    return {hit, hit ? 0.0 : static_cast<double>(output.m_distance), 0};
  });
}
#endif

// -------------------------------------------------------------------------------------
// W3 box pairs
// -------------------------------------------------------------------------------------

std::vector<pb::BoxPair> g_boxes;
std::vector<char> g_box_ref;

#if PROXIMA_BENCH_NARROWPHASE
void proxima_boxes(benchmark::State& state) {
  struct Query {
    proxima::Box a;
    Transform ta;
    proxima::Box b;
    Transform tb;
  };
  std::vector<Query> queries;
  for (const pb::BoxPair& p : g_boxes) {
    queries.push_back({*proxima::Box::create(pb::to_vec3(p.half_extents_a)), pb::to_transform(p.pose_a),
                       *proxima::Box::create(pb::to_vec3(p.half_extents_b)), pb::to_transform(p.pose_b)});
  }
  const proxima::PairRequest request;  // up to 4 contacts
  run_queries(state, queries.size(),
              [&](std::size_t k) -> Answer {
                const Query& q = queries[k];
                const proxima::ContactManifold m = proxima::collide(q.a, q.ta, q.b, q.tb, request);
                Real deepest = 0;
                for (int i = 0; i < m.count; ++i)
                  deepest = std::max(deepest, m.points[static_cast<std::size_t>(i)].depth);
                return {m.count > 0, static_cast<double>(deepest), m.count};
              },
              {&g_box_ref, nullptr});
}
#endif

#if PROXIMA_BENCH_NARROWPHASE
/// Warm start on W3: pass p moves every pair's pose B to frame p mod kWarmFrames (warm_pose);
/// `warm` keeps one PairCache per pair across passes, cold passes none. Full manifold.
void proxima_boxes_warm(benchmark::State& state, bool warm) {
  const std::size_t n = g_boxes.size();
  std::vector<proxima::Box> a, b;
  std::vector<Transform> pose_a, frames(kWarmFrames * n);
  for (std::size_t k = 0; k < n; ++k) {
    const pb::BoxPair& p = g_boxes[k];
    a.push_back(*proxima::Box::create(pb::to_vec3(p.half_extents_a)));
    b.push_back(*proxima::Box::create(pb::to_vec3(p.half_extents_b)));
    pose_a.push_back(pb::to_transform(p.pose_a));
    for (int f = 0; f < kWarmFrames; ++f)
      frames[static_cast<std::size_t>(f) * n + k] = warm_pose(pb::to_transform(p.pose_b), f);
  }
  std::vector<proxima::PairCache> caches(n);
  const proxima::PairRequest request;  // up to 4 contacts
  std::uint64_t hits = 0, contacts = 0, pass = 0;
  for (auto _ : state) {
    const Transform* frame_b = &frames[(pass++ % kWarmFrames) * n];
    hits = 0;
    contacts = 0;
    for (std::size_t k = 0; k < n; ++k) {
      const proxima::ContactManifold m =
          proxima::collide(a[k], pose_a[k], b[k], frame_b[k], request, warm ? &caches[k] : nullptr);
      hits += m.count > 0 ? 1u : 0u;
      contacts += static_cast<std::uint64_t>(m.count);
    }
    benchmark::DoNotOptimize(hits);
    benchmark::DoNotOptimize(contacts);
  }
  state.counters["per_query"] = pb::time_per_item(n);
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["contacts"] = static_cast<double>(contacts);
}
#endif

#if PROXIMA_HAVE_ODE
void ode_set_pose(dGeomID g, const pb::Pose& pose) {
  dGeomSetPosition(g, pose.position.x, pose.position.y, pose.position.z);
  const dQuaternion q{pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z};
  dGeomSetQuaternion(g, q);
}

void ode_boxes(benchmark::State& state) {
  std::vector<dGeomID> geoms;
  for (const pb::BoxPair& p : g_boxes) {
    dGeomID a = dCreateBox(nullptr, 2 * p.half_extents_a.x, 2 * p.half_extents_a.y, 2 * p.half_extents_a.z);
    dGeomID b = dCreateBox(nullptr, 2 * p.half_extents_b.x, 2 * p.half_extents_b.y, 2 * p.half_extents_b.z);
    ode_set_pose(a, p.pose_a);
    ode_set_pose(b, p.pose_b);
    geoms.push_back(a);
    geoms.push_back(b);
  }
  run_queries(state, g_boxes.size(),
              [&](std::size_t k) -> Answer {
                std::array<dContactGeom, 4> contacts;
                const int n = dCollide(geoms[2 * k], geoms[2 * k + 1], 4, contacts.data(), sizeof(dContactGeom));
                double deepest = 0;
                for (int i = 0; i < n; ++i)
                  deepest = std::max(deepest, static_cast<double>(contacts[static_cast<std::size_t>(i)].depth));
                return {n > 0, deepest, n};
              },
              {&g_box_ref, nullptr});
  for (dGeomID g : geoms) dGeomDestroy(g);
}
#endif

#if PROXIMA_HAVE_BULLET
/// Collects the points of a Bullet detector (its depth is negative for penetration).
struct BulletContacts : btDiscreteCollisionDetectorInterface::Result {
  int count = 0;
  double deepest = 0;
  void setShapeIdentifiersA(int, int) override {}
  void setShapeIdentifiersB(int, int) override {}
  void addContactPoint(const btVector3&, const btVector3&, btScalar depth) override {
    ++count;
    deepest = std::max(deepest, -static_cast<double>(depth));
  }
};

void bullet_boxes(benchmark::State& state) {
  std::vector<std::unique_ptr<btBoxShape>> shapes;
  std::vector<std::array<btTransform, 2>> poses;
  auto make = [](const pb::Vec3d& h) {
    auto s = std::make_unique<btBoxShape>(
        btVector3(static_cast<btScalar>(h.x), static_cast<btScalar>(h.y), static_cast<btScalar>(h.z)));
    s->setMargin(0);  // keeps the half extents (Bullet subtracts the margin inside)
    return s;
  };
  for (const pb::BoxPair& p : g_boxes) {
    shapes.push_back(make(p.half_extents_a));
    shapes.push_back(make(p.half_extents_b));
    poses.push_back({bt_transform(p.pose_a), bt_transform(p.pose_b)});
  }
  run_queries(state, g_boxes.size(),
              [&](std::size_t k) -> Answer {
                btBoxBoxDetector detector(shapes[2 * k].get(), shapes[2 * k + 1].get());
                btDiscreteCollisionDetectorInterface::ClosestPointInput input;
                input.m_transformA = poses[k][0];
                input.m_transformB = poses[k][1];
                BulletContacts out;
                detector.getClosestPoints(input, out, nullptr);
                return {out.count > 0, out.deepest, out.count};
              },
              {&g_box_ref, nullptr});
}
#endif

#if PROXIMA_HAVE_FCL
void fcl_boxes(benchmark::State& state, fcl::GJKSolverType solver) {
  std::vector<FclPair> objects;
  for (const pb::BoxPair& p : g_boxes) {
    FclPair o;
    o.a = std::make_unique<fcl::CollisionObjectd>(
        std::make_shared<fcl::Boxd>(2 * p.half_extents_a.x, 2 * p.half_extents_a.y, 2 * p.half_extents_a.z),
        fcl_transform(p.pose_a));
    o.b = std::make_unique<fcl::CollisionObjectd>(
        std::make_shared<fcl::Boxd>(2 * p.half_extents_b.x, 2 * p.half_extents_b.y, 2 * p.half_extents_b.z),
        fcl_transform(p.pose_b));
    objects.push_back(std::move(o));
  }
  const fcl::CollisionRequestd request(4, true, 1, false, true, solver);
  run_queries(state, objects.size(),
              [&](std::size_t k) -> Answer {
                fcl::CollisionResultd result;
                const auto n = static_cast<int>(fcl::collide(objects[k].a.get(), objects[k].b.get(), request, result));
                double deepest = 0;
                for (int i = 0; i < n; ++i)
                  deepest = std::max(deepest, result.getContact(static_cast<std::size_t>(i)).penetration_depth);
                return {n > 0, deepest, n};
              },
              {&g_box_ref, nullptr});
}
#endif

// -------------------------------------------------------------------------------------
// W7 sphere and capsule pairs
// -------------------------------------------------------------------------------------

pb::PrimitivePairs<pb::SpherePair> g_spheres;
pb::PrimitivePairs<pb::CapsulePair> g_capsules;
std::vector<char> g_sphere_ref, g_capsule_ref;                // per distinct pair
std::vector<double> g_sphere_ref_dist, g_capsule_ref_dist;    // per distinct pair
std::vector<char> g_sphere_ref_stream, g_capsule_ref_stream;  // per streamed query

enum class PrimitiveQuery { Intersect, Distance, Collide };

/// The floor of bench_floor on the streamed records: |c1 - c2|^2 <= (r1 + r2)^2.
void floor_spheres(benchmark::State& state) {
  struct Record {
    Vec3 c1;
    Real r1;
    Vec3 c2;
    Real r2;
  };
  const auto records = pb::materialize<Record>(g_spheres, [](const pb::SpherePair& p) {
    return Record{pb::to_vec3(p.center1), static_cast<Real>(p.radius1), pb::to_vec3(p.center2),
                  static_cast<Real>(p.radius2)};
  });
  run_queries(state, records.size(),
              [&](std::size_t k) -> Answer {
                const Record& q = records[k];
                const Vec3 d = q.c1 - q.c2;
                const Real r = q.r1 + q.r2;
                return {glm::dot(d, d) <= r * r, 0.0, 0};
              },
              {&g_sphere_ref_stream, nullptr});
}

/// The floor of bench_floor for capsules: the library's segment-segment distance.
void floor_capsules(benchmark::State& state) {
  struct Record {
    Vec3 a0, a1;
    Real ra;
    Vec3 b0, b1;
    Real rb;
  };
  const auto records = pb::materialize<Record>(g_capsules, [](const pb::CapsulePair& p) {
    return Record{pb::to_vec3(p.a0), pb::to_vec3(p.a1), static_cast<Real>(p.radius_a),
                  pb::to_vec3(p.b0), pb::to_vec3(p.b1), static_cast<Real>(p.radius_b)};
  });
  run_queries(state, records.size(),
              [&](std::size_t k) -> Answer {
                const Record& q = records[k];
                const Real r = q.ra + q.rb;
                return {
                    proxima::geometry::closest_points_segment_segment(q.a0, q.a1, q.b0, q.b1).distance_squared <= r * r,
                    0.0, 0};
              },
              {&g_capsule_ref_stream, nullptr});
}

#if PROXIMA_BENCH_NARROWPHASE
/// One W7 query for Proxima: two shapes of type S with their poses.
template <class S>
struct PrimitiveRecord {
  S a;
  Transform ta;
  S b;
  Transform tb;
};

PrimitiveRecord<proxima::Sphere> make_record(const pb::SpherePair& p) {
  return {*proxima::Sphere::create(static_cast<Real>(p.radius1)),
          Transform{pb::to_vec3(p.center1), proxima::kIdentityQuat},
          *proxima::Sphere::create(static_cast<Real>(p.radius2)),
          Transform{pb::to_vec3(p.center2), proxima::kIdentityQuat}};
}

PrimitiveRecord<proxima::Capsule> make_record(const pb::CapsulePair& p) {
  const CapsulePose ca = capsule_pose(p.a0, p.a1, p.radius_a);
  const CapsulePose cb = capsule_pose(p.b0, p.b1, p.radius_b);
  return {*proxima::Capsule::create(static_cast<Real>(ca.radius), static_cast<Real>(ca.half_length)),
          pb::to_transform(ca.pose),
          *proxima::Capsule::create(static_cast<Real>(cb.radius), static_cast<Real>(cb.half_length)),
          pb::to_transform(cb.pose)};
}

/// Proxima on W7: `stream` over the count * repeat materialised records, else over the
/// distinct pairs (in cache, like the peers).
template <class S, class Pair>
void proxima_primitives(benchmark::State& state, const pb::PrimitivePairs<Pair>* pairs, bool stream, PrimitiveQuery q,
                        const std::vector<char>* ref_stream, const std::vector<char>* ref_distinct,
                        const std::vector<double>* ref_dist) {
  std::vector<PrimitiveRecord<S>> queries;
  if (stream) {
    queries = pb::materialize<PrimitiveRecord<S>>(*pairs, [](const Pair& p) { return make_record(p); });
  } else {
    for (const Pair& p : pairs->distinct) queries.push_back(make_record(p));
  }
  proxima::PairRequest request;
  request.max_contacts = 1;
  const Reference reference{stream ? ref_stream : ref_distinct,
                            stream || q != PrimitiveQuery::Distance ? nullptr : ref_dist};
  run_queries(
      state, queries.size(),
      [&](std::size_t k) -> Answer {
        const PrimitiveRecord<S>& x = queries[k];
        switch (q) {
          case PrimitiveQuery::Intersect: return {proxima::intersect(x.a, x.ta, x.b, x.tb, request), 0.0, 0};
          case PrimitiveQuery::Distance: {
            const double d = static_cast<double>(proxima::distance(x.a, x.ta, x.b, x.tb, request).signed_distance);
            return {d <= 0, d, 0};
          }
          case PrimitiveQuery::Collide: {
            const proxima::ContactManifold m = proxima::collide(x.a, x.ta, x.b, x.tb, request);
            return {m.count > 0, m.count > 0 ? static_cast<double>(m.points[0].depth) : 0.0, m.count};
          }
        }
        return {};
      },
      reference);
}
#endif

/// A W7 pair for the peers: both shapes as capsules of half length h (0 for spheres).
struct PrimitivePeerPair {
  CapsulePose a, b;
};

std::vector<PrimitivePeerPair> peer_pairs(bool capsules) {
  std::vector<PrimitivePeerPair> out;
  if (capsules) {
    for (const pb::CapsulePair& p : g_capsules.distinct) {
      out.push_back({capsule_pose(p.a0, p.a1, p.radius_a), capsule_pose(p.b0, p.b1, p.radius_b)});
    }
  } else {
    for (const pb::SpherePair& p : g_spheres.distinct) {
      PrimitivePeerPair q;
      q.a.pose.position = p.center1;
      q.a.radius = p.radius1;
      q.b.pose.position = p.center2;
      q.b.radius = p.radius2;
      out.push_back(q);
    }
  }
  return out;
}

Reference primitive_reference(bool capsules, bool with_distance) {
  return {capsules ? &g_capsule_ref : &g_sphere_ref,
          with_distance ? (capsules ? &g_capsule_ref_dist : &g_sphere_ref_dist) : nullptr};
}

#if PROXIMA_HAVE_FCL
void fcl_primitives(benchmark::State& state, bool capsules, bool distance) {
  std::vector<FclPair> objects;
  auto make = [&](const CapsulePose& c) -> std::shared_ptr<fcl::CollisionGeometryd> {
    if (capsules) return std::make_shared<fcl::Capsuled>(c.radius, 2 * c.half_length);
    return std::make_shared<fcl::Sphered>(c.radius);
  };
  for (const PrimitivePeerPair& p : peer_pairs(capsules)) {
    FclPair o;
    o.a = std::make_unique<fcl::CollisionObjectd>(make(p.a), fcl_transform(p.a.pose));
    o.b = std::make_unique<fcl::CollisionObjectd>(make(p.b), fcl_transform(p.b.pose));
    objects.push_back(std::move(o));
  }
  const fcl::CollisionRequestd request;
  const fcl::DistanceRequestd distance_request(true);
  run_queries(
      state, objects.size(),
      [&](std::size_t k) -> Answer {
        if (distance) {
          fcl::DistanceResultd result;
          const double d = fcl::distance(objects[k].a.get(), objects[k].b.get(), distance_request, result);
          return {d <= 0, d, 0};
        }
        fcl::CollisionResultd result;
        return {fcl::collide(objects[k].a.get(), objects[k].b.get(), request, result) > 0, 0.0, 0};
      },
      primitive_reference(capsules, false));
}
#endif

#if PROXIMA_HAVE_ODE
void ode_primitives(benchmark::State& state, bool capsules) {
  std::vector<dGeomID> geoms;
  for (const PrimitivePeerPair& p : peer_pairs(capsules)) {
    for (const CapsulePose* c : {&p.a, &p.b}) {
      dGeomID g = capsules ? dCreateCapsule(nullptr, c->radius, 2 * c->half_length) : dCreateSphere(nullptr, c->radius);
      ode_set_pose(g, c->pose);
      geoms.push_back(g);
    }
  }
  run_queries(
      state, geoms.size() / 2,
      [&](std::size_t k) -> Answer {
        dContactGeom contact;
        const int n = dCollide(geoms[2 * k], geoms[2 * k + 1], 1, &contact, sizeof(dContactGeom));
        return {n > 0, n > 0 ? static_cast<double>(contact.depth) : 0.0, n};
      },
      primitive_reference(capsules, false));
  for (dGeomID g : geoms) dGeomDestroy(g);
}
#endif

#if PROXIMA_HAVE_BULLET
void bullet_primitives(benchmark::State& state, bool capsules) {
  std::vector<std::unique_ptr<btConvexShape>> shapes;
  std::vector<std::array<btTransform, 2>> poses;
  for (const PrimitivePeerPair& p : peer_pairs(capsules)) {
    for (const CapsulePose* c : {&p.a, &p.b}) {
      if (capsules) {
        shapes.push_back(std::make_unique<btCapsuleShapeZ>(static_cast<btScalar>(c->radius),
                                                           static_cast<btScalar>(2 * c->half_length)));
      } else {
        shapes.push_back(std::make_unique<btSphereShape>(static_cast<btScalar>(c->radius)));
      }
    }
    poses.push_back({bt_transform(p.a.pose), bt_transform(p.b.pose)});
  }
  run_queries(
      state, poses.size(),
      [&](std::size_t k) -> Answer {
        btVoronoiSimplexSolver simplex;
        btGjkPairDetector detector(shapes[2 * k].get(), shapes[2 * k + 1].get(), &simplex, nullptr);
        btGjkPairDetector::ClosestPointInput input;
        input.m_transformA = poses[k][0];
        input.m_transformB = poses[k][1];
        btPointCollector output;
        detector.getClosestPoints(input, output, nullptr);
        const bool hit = !output.m_hasResult || output.m_distance <= 0;
        return {hit, output.m_hasResult ? static_cast<double>(output.m_distance) : 0.0, 0};
      },
      primitive_reference(capsules, false));
}
#endif

#if PROXIMA_HAVE_CCD
/// A capsule (or sphere, h = 0) for libccd: centre, unit axis, half length, radius.
struct CcdCapsule {
  double c[3];
  double u[3];
  double h;
  double r;
};

void ccd_capsule_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* s = static_cast<const CcdCapsule*>(obj);
  const double* d = dir->v;
  const double side = s->u[0] * d[0] + s->u[1] * d[1] + s->u[2] * d[2] >= 0 ? s->h : -s->h;
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  const double k = n > 0 ? s->r / n : 0.0;
  for (int i = 0; i < 3; ++i) out->v[i] = s->c[i] + side * s->u[i] + k * d[i];
}

void ccd_capsule_center(const void* obj, ccd_vec3_t* out) {
  const auto* s = static_cast<const CcdCapsule*>(obj);
  for (int i = 0; i < 3; ++i) out->v[i] = s->c[i];
}

void ccd_primitives(benchmark::State& state, bool capsules) {
  std::vector<std::array<CcdCapsule, 2>> objects;
  for (const PrimitivePeerPair& p : peer_pairs(capsules)) {
    std::array<CcdCapsule, 2> o;
    const CapsulePose* c[2] = {&p.a, &p.b};
    for (int i = 0; i < 2; ++i) {
      const pb::Vec3d u = axis(rotation_matrix(c[i]->pose.rotation), 2);
      o[i] = {{c[i]->pose.position.x, c[i]->pose.position.y, c[i]->pose.position.z},
              {u.x, u.y, u.z},
              c[i]->half_length,
              c[i]->radius};
    }
    objects.push_back(o);
  }
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd_capsule_support;
  ccd.support2 = ccd_capsule_support;
  ccd.center1 = ccd_capsule_center;
  ccd.center2 = ccd_capsule_center;
  ccd.max_iterations = 100;
  run_queries(
      state, objects.size(),
      [&](std::size_t k) -> Answer {
        return {ccdGJKIntersect(&objects[k][0], &objects[k][1], &ccd) != 0, 0.0, 0};
      },
      primitive_reference(capsules, false));
}
#endif

// -------------------------------------------------------------------------------------
// Registration
// -------------------------------------------------------------------------------------

bool load_all(const std::string& dir) {
  const std::array<int, 3> sizes{8, 32, 128};
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    if (!load_hulls(dir, sizes[i], g_hulls[i])) return false;
  }
  auto boxes = pb::read_box_pairs(pb::workload_path(dir, "box_pairs.txt"));
  if (!boxes) return pb::report_load_error(boxes.error());
  g_boxes = std::move(*boxes);
  for (const pb::BoxPair& p : g_boxes) g_box_ref.push_back(boxes_overlap(p) ? 1 : 0);

  auto spheres = pb::read_sphere_pairs(pb::workload_path(dir, "sphere_pairs.txt"), pb::Materialize::No);
  if (!spheres) return pb::report_load_error(spheres.error());
  g_spheres = std::move(*spheres);
  auto capsules = pb::read_capsule_pairs(pb::workload_path(dir, "capsule_pairs.txt"), pb::Materialize::No);
  if (!capsules) return pb::report_load_error(capsules.error());
  g_capsules = std::move(*capsules);
  for (const pb::SpherePair& p : g_spheres.distinct) {
    const double d = std::sqrt(dot(sub(p.center1, p.center2), sub(p.center1, p.center2))) - p.radius1 - p.radius2;
    g_sphere_ref.push_back(d <= 0 ? 1 : 0);
    g_sphere_ref_dist.push_back(d);
  }
  for (const pb::CapsulePair& p : g_capsules.distinct) {
    const double d = std::sqrt(segment_distance_squared(p.a0, p.a1, p.b0, p.b1)) - p.radius_a - p.radius_b;
    g_capsule_ref.push_back(d <= 0 ? 1 : 0);
    g_capsule_ref_dist.push_back(d);
  }
  for (std::size_t k = 0; k < g_spheres.query_count(); ++k)
    g_sphere_ref_stream.push_back(g_sphere_ref[k % g_spheres.distinct.size()]);
  for (std::size_t k = 0; k < g_capsules.query_count(); ++k)
    g_capsule_ref_stream.push_back(g_capsule_ref[k % g_capsules.distinct.size()]);
  return true;
}

template <class... Args>
void add(const std::string& name, Args&&... args) {
  benchmark::RegisterBenchmark(name.c_str(), std::forward<Args>(args)...)->Unit(benchmark::kMicrosecond);
}

bool register_narrowphase(const std::string& dir) {
  if (!load_all(dir)) return false;
  std::string peers;
#if PROXIMA_HAVE_FCL
  peers += " fcl";
#endif
#if PROXIMA_HAVE_CCD
  peers += " libccd";
#endif
#if PROXIMA_HAVE_BULLET
  peers += " bullet";
#endif
#if PROXIMA_HAVE_ODE
  dInitODE2(0);
  peers += " ode";
#endif
  benchmark::AddCustomContext("peers", peers.empty() ? "none" : peers.substr(1));

  const std::array<std::pair<HullQuery, const char*>, 3> queries{
      {{HullQuery::Boolean, "Boolean"}, {HullQuery::Distance, "Distance"}, {HullQuery::Penetration, "Penetration"}}};
  for (const int points : {8, 32, 128}) {
    const std::string base = "NP/Hull" + std::to_string(points) + "/";
    for (const auto& [q, qname] : queries) {
      const std::string prefix = base + qname + "/";
#if PROXIMA_BENCH_NARROWPHASE
      add(prefix + "proxima_plain", proxima_hulls, points, q, proxima::gjk::Variant::Plain);
      if (q != HullQuery::Penetration)
        add(prefix + "proxima_nesterov", proxima_hulls, points, q, proxima::gjk::Variant::Nesterov);
      if (q != HullQuery::Penetration) {
        add(prefix + "proxima_plain_cold", proxima_hulls_warm, points, q, false);
        add(prefix + "proxima_plain_warm", proxima_hulls_warm, points, q, true);
      }
#endif
#if PROXIMA_HAVE_CCD
      if (q == HullQuery::Boolean) {
        add(prefix + "libccd_gjk", ccd_hulls, points, q, CcdMethod::GjkIntersect);
        add(prefix + "libccd_mpr", ccd_hulls, points, q, CcdMethod::MprIntersect);
      } else if (q == HullQuery::Penetration) {
        add(prefix + "libccd_gjk_epa", ccd_hulls, points, q, CcdMethod::GjkPenetration);
        add(prefix + "libccd_gjk_separate", ccd_hulls, points, q, CcdMethod::GjkSeparate);
        add(prefix + "libccd_mpr", ccd_hulls, points, q, CcdMethod::MprPenetration);
      }
#endif
#if PROXIMA_HAVE_FCL
      add(prefix + "fcl_libccd", fcl_hulls, points, q, fcl::GST_LIBCCD);
      add(prefix + "fcl_indep", fcl_hulls, points, q, fcl::GST_INDEP);
#endif
#if PROXIMA_HAVE_BULLET
      add(prefix + (q == HullQuery::Penetration ? "bullet_gjk_epa" : "bullet_gjk"), bullet_hulls_query, points, q);
#endif
    }
  }

#if PROXIMA_BENCH_NARROWPHASE
  add("NP/BoxBox/Manifold/proxima", proxima_boxes);
  add("NP/BoxBox/Manifold/proxima_cold", proxima_boxes_warm, false);
  add("NP/BoxBox/Manifold/proxima_warm", proxima_boxes_warm, true);
#endif
#if PROXIMA_HAVE_ODE
  add("NP/BoxBox/Manifold/ode", ode_boxes);
#endif
#if PROXIMA_HAVE_BULLET
  add("NP/BoxBox/Manifold/bullet", bullet_boxes);
#endif
#if PROXIMA_HAVE_FCL
  add("NP/BoxBox/Manifold/fcl_libccd", fcl_boxes, fcl::GST_LIBCCD);
  add("NP/BoxBox/Manifold/fcl_indep", fcl_boxes, fcl::GST_INDEP);
#endif

  for (const bool capsules : {false, true}) {
    const std::string base = capsules ? "NP/CapsulePairs/" : "NP/SpherePairs/";
    if (capsules) {
      add(base + "floor_stream", floor_capsules);
    } else {
      add(base + "floor_stream", floor_spheres);
    }
#if PROXIMA_BENCH_NARROWPHASE
    const std::array<std::pair<PrimitiveQuery, const char*>, 3> pq{{{PrimitiveQuery::Intersect, "intersect"},
                                                                    {PrimitiveQuery::Distance, "distance"},
                                                                    {PrimitiveQuery::Collide, "collide"}}};
    for (const auto& [q, qname] : pq) {
      for (const bool stream : {true, false}) {
        const std::string name = base + "proxima_" + qname + (stream ? "_stream" : "");
        if (capsules) {
          add(name, proxima_primitives<proxima::Capsule, pb::CapsulePair>, &g_capsules, stream, q,
              &g_capsule_ref_stream, &g_capsule_ref, &g_capsule_ref_dist);
        } else {
          add(name, proxima_primitives<proxima::Sphere, pb::SpherePair>, &g_spheres, stream, q, &g_sphere_ref_stream,
              &g_sphere_ref, &g_sphere_ref_dist);
        }
      }
    }
#endif
#if PROXIMA_HAVE_FCL
    add(base + "fcl_collide", fcl_primitives, capsules, false);
    add(base + "fcl_distance", fcl_primitives, capsules, true);
#endif
#if PROXIMA_HAVE_ODE
    add(base + "ode", ode_primitives, capsules);
#endif
#if PROXIMA_HAVE_BULLET
    add(base + "bullet_gjk", bullet_primitives, capsules);
#endif
#if PROXIMA_HAVE_CCD
    add(base + "libccd_gjk", ccd_primitives, capsules);
#endif
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_narrowphase); }
