// The W7 sphere pairs (the 25,000 distinct pairs of sphere_pairs.txt) through each peer
// library found at configure time, beside Proxima's own exact test in the same run:
//   1. Peers/SpherePairs/proxima: |c1 - c2|^2 <= (r1 + r2)^2 in proxima::Real;
//   2. Peers/SpherePairs/fcl: fcl::collide on two fcl::Sphered collision objects;
//   3. Peers/SpherePairs/libccd: ccdGJKIntersect with sphere support functions;
//   4. Peers/SpherePairs/bullet: btGjkEpaSolver2::Distance on two btSphereShape (core
//      distance against r1 + r2);
//   5. Peers/SpherePairs/ode: dCollide on two dCreateSphere geoms.
// Each reports the time per query (per_query), the hits, and the hits computed in double
// from the file (hits_double). The peers are optional: the program builds with none of
// them, and Embree (a ray tracer) is only listed in the context here.
#include <benchmark/benchmark.h>

#include "bench_main.hpp"
#include "support/workloads.hpp"

#if PROXIMA_HAVE_FCL
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#endif
#if PROXIMA_HAVE_CCD
#include <ccd/ccd.h>
#endif
#if PROXIMA_HAVE_BULLET
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpa2.h>
#endif
#if PROXIMA_HAVE_ODE
#include <ode/ode.h>
#endif
#if PROXIMA_HAVE_EMBREE
#include <embree3/rtcore.h>
#endif

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace {

namespace pb = proxima::bench;

std::vector<pb::SpherePair> g_pairs;
std::uint64_t g_hits_double = 0;

/// Runs `test(pair)` over every pair per iteration and reports the counters.
template <class Test>
void run_pairs(benchmark::State& state, Test test) {
  std::uint64_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const pb::SpherePair& p : g_pairs) hits += test(p) ? 1u : 0u;
    benchmark::DoNotOptimize(hits);
  }
  state.counters["per_query"] = pb::time_per_item(g_pairs.size());
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["hits_double"] = static_cast<double>(g_hits_double);
}

void proxima_spheres(benchmark::State& state) {
  using proxima::Real;
  struct Record {
    proxima::Vec3 c1;
    Real r1;
    proxima::Vec3 c2;
    Real r2;
  };
  std::vector<Record> records;
  for (const pb::SpherePair& p : g_pairs) {
    records.push_back(
        {pb::to_vec3(p.center1), static_cast<Real>(p.radius1), pb::to_vec3(p.center2), static_cast<Real>(p.radius2)});
  }
  std::uint64_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const Record& q : records) {
      const proxima::Vec3 d = q.c1 - q.c2;
      const Real r = q.r1 + q.r2;
      hits += glm::dot(d, d) <= r * r ? 1u : 0u;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.counters["per_query"] = pb::time_per_item(records.size());
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["hits_double"] = static_cast<double>(g_hits_double);
}

#if PROXIMA_HAVE_FCL
void fcl_spheres(benchmark::State& state) {
  struct Objects {
    std::unique_ptr<fcl::CollisionObjectd> a, b;
  };
  std::vector<Objects> objects;
  for (const pb::SpherePair& p : g_pairs) {
    Objects o;
    fcl::Transform3d ta = fcl::Transform3d::Identity();
    ta.translation() = fcl::Vector3d(p.center1.x, p.center1.y, p.center1.z);
    fcl::Transform3d tb = fcl::Transform3d::Identity();
    tb.translation() = fcl::Vector3d(p.center2.x, p.center2.y, p.center2.z);
    o.a = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Sphered>(p.radius1), ta);
    o.b = std::make_unique<fcl::CollisionObjectd>(std::make_shared<fcl::Sphered>(p.radius2), tb);
    objects.push_back(std::move(o));
  }
  std::size_t k = 0;
  const fcl::CollisionRequestd request;
  run_pairs(state, [&](const pb::SpherePair&) {
    fcl::CollisionResultd result;
    const Objects& o = objects[k];
    k = k + 1 == objects.size() ? 0 : k + 1;
    return fcl::collide(o.a.get(), o.b.get(), request, result) > 0;
  });
}
#endif

#if PROXIMA_HAVE_CCD
struct CcdSphere {
  double c[3];
  double r;
};

void ccd_sphere_support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* s = static_cast<const CcdSphere*>(obj);
  const double n = std::sqrt(dir->v[0] * dir->v[0] + dir->v[1] * dir->v[1] + dir->v[2] * dir->v[2]);
  const double k = n > 0 ? s->r / n : 0.0;
  for (int i = 0; i < 3; ++i) out->v[i] = static_cast<ccd_real_t>(s->c[i] + k * dir->v[i]);
}

void ccd_sphere_center(const void* obj, ccd_vec3_t* out) {
  const auto* s = static_cast<const CcdSphere*>(obj);
  for (int i = 0; i < 3; ++i) out->v[i] = static_cast<ccd_real_t>(s->c[i]);
}

void ccd_spheres(benchmark::State& state) {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = ccd_sphere_support;
  ccd.support2 = ccd_sphere_support;
  ccd.center1 = ccd_sphere_center;
  ccd.center2 = ccd_sphere_center;
  ccd.max_iterations = 100;
  run_pairs(state, [&](const pb::SpherePair& p) {
    const CcdSphere a{{p.center1.x, p.center1.y, p.center1.z}, p.radius1};
    const CcdSphere b{{p.center2.x, p.center2.y, p.center2.z}, p.radius2};
    return ccdGJKIntersect(&a, &b, &ccd) != 0;
  });
}
#endif

#if PROXIMA_HAVE_BULLET
void bullet_spheres(benchmark::State& state) {
  std::vector<std::unique_ptr<btSphereShape>> shapes;
  for (const pb::SpherePair& p : g_pairs) {
    shapes.push_back(std::make_unique<btSphereShape>(static_cast<btScalar>(p.radius1)));
    shapes.push_back(std::make_unique<btSphereShape>(static_cast<btScalar>(p.radius2)));
  }
  std::size_t k = 0;
  run_pairs(state, [&](const pb::SpherePair& p) {
    const btTransform ta(btQuaternion::getIdentity(),
                         btVector3(static_cast<btScalar>(p.center1.x), static_cast<btScalar>(p.center1.y),
                                   static_cast<btScalar>(p.center1.z)));
    const btTransform tb(btQuaternion::getIdentity(),
                         btVector3(static_cast<btScalar>(p.center2.x), static_cast<btScalar>(p.center2.y),
                                   static_cast<btScalar>(p.center2.z)));
    btGjkEpaSolver2::sResults results;
    const bool separated =
        btGjkEpaSolver2::Distance(shapes[k].get(), ta, shapes[k + 1].get(), tb, btVector3(1, 0, 0), results);
    k = k + 2 == shapes.size() ? 0 : k + 2;
    // Distance() works on the cores (the centres; a sphere is all margin), so the
    // spheres touch when the core distance is at most the sum of the radii.
    return !separated || results.distance <= static_cast<btScalar>(p.radius1 + p.radius2);
  });
}
#endif

#if PROXIMA_HAVE_ODE
void ode_spheres(benchmark::State& state) {
  std::vector<dGeomID> geoms;
  for (const pb::SpherePair& p : g_pairs) {
    dGeomID a = dCreateSphere(nullptr, p.radius1);
    dGeomSetPosition(a, p.center1.x, p.center1.y, p.center1.z);
    dGeomID b = dCreateSphere(nullptr, p.radius2);
    dGeomSetPosition(b, p.center2.x, p.center2.y, p.center2.z);
    geoms.push_back(a);
    geoms.push_back(b);
  }
  std::size_t k = 0;
  run_pairs(state, [&](const pb::SpherePair&) {
    dContactGeom contact;
    const int n = dCollide(geoms[k], geoms[k + 1], 1, &contact, sizeof(dContactGeom));
    k = k + 2 == geoms.size() ? 0 : k + 2;
    return n > 0;
  });
  for (dGeomID g : geoms) dGeomDestroy(g);
}
#endif

bool register_peers(const std::string& dir) {
  auto spheres = pb::read_sphere_pairs(pb::workload_path(dir, "sphere_pairs.txt"), pb::Materialize::No);
  if (!spheres) return pb::report_load_error(spheres.error());
  g_pairs = spheres->distinct;
  for (const pb::SpherePair& p : g_pairs) {
    const double dx = p.center1.x - p.center2.x, dy = p.center1.y - p.center2.y, dz = p.center1.z - p.center2.z;
    const double r = p.radius1 + p.radius2;
    g_hits_double += dx * dx + dy * dy + dz * dz <= r * r ? 1 : 0;
  }
  std::string peers;
  benchmark::RegisterBenchmark("Peers/SpherePairs/proxima", proxima_spheres);
#if PROXIMA_HAVE_FCL
  benchmark::RegisterBenchmark("Peers/SpherePairs/fcl", fcl_spheres);
  peers += " fcl";
#endif
#if PROXIMA_HAVE_CCD
  benchmark::RegisterBenchmark("Peers/SpherePairs/libccd", ccd_spheres);
  peers += " libccd";
#endif
#if PROXIMA_HAVE_BULLET
  benchmark::RegisterBenchmark("Peers/SpherePairs/bullet", bullet_spheres);
  peers += " bullet";
#endif
#if PROXIMA_HAVE_ODE
  dInitODE2(0);
  benchmark::RegisterBenchmark("Peers/SpherePairs/ode", ode_spheres);
  peers += " ode";
#endif
#if PROXIMA_HAVE_EMBREE
  if (RTCDevice device = rtcNewDevice(nullptr)) {
    peers += " embree-" + std::to_string(rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION));
    rtcReleaseDevice(device);
  }
#endif
  benchmark::AddCustomContext("peers", peers.empty() ? "none" : peers.substr(1));
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_peers); }
