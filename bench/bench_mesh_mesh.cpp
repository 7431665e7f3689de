// Mesh against mesh on the W4 workload (mesh_icosphere.obj at the identity, 20,480
// triangles; mesh_torusknot.obj at each of the 1,000 poses of mesh_poses.txt, 50,000
// triangles), every pose per iteration:
//   MeshMesh/Boolean/proxima       midphase::mesh_mesh_intersect
//   MeshMesh/Boolean/fcl_obbrss    fcl::collide, BVHModel<OBBRSSd>, one contact asked
//   MeshMesh/Boolean/fcl_aabb      fcl::collide, BVHModel<AABBd>, one contact asked (every
//                                  20th pose only, argument /20: about 20 ms a query)
//   MeshMesh/Contacts/...          every contact: midphase::mesh_mesh_collide_all (narrow-phase
//                                  triangle manifolds); FCL with num_max_contacts = 1e6 and
//                                  enable_contact
//   MeshMesh/Distance/...          midphase::mesh_mesh_distance; fcl::distance with nearest
//                                  points (meshes that intersect: 0 in both)
// Counters: per_query (time per pose), hits (poses found intersecting), pairs (contacts or
// contact pairs summed over the poses), sum_distance (sum of the distances).
// Build the BVHs once, outside the timing (see MeshMesh/Build for Proxima's build time).
#include <benchmark/benchmark.h>

#include <proxima/midphase/triangle_mesh.hpp>

#include "../src/midphase/mesh_mesh.hpp"
#include "support/bench_main.hpp"
#include "support/workloads.hpp"

#if PROXIMA_HAVE_FCL
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#endif

#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

namespace {

namespace pb = proxima::bench;
using proxima::Real;
/// The reader's OBJ mesh type (whatever its name).
using ObjMesh = std::remove_cvref_t<decltype(pb::read_obj(std::string()).value())>;

ObjMesh g_obj_a;
ObjMesh g_obj_b;
std::vector<pb::Pose> g_poses;
std::vector<proxima::Transform> g_transforms;
std::unique_ptr<proxima::TriangleMesh> g_mesh_a;
std::unique_ptr<proxima::TriangleMesh> g_mesh_b;

proxima::IndexedMesh to_indexed(const ObjMesh& m) {
  proxima::IndexedMesh out;
  for (const pb::Vec3d& v : m.vertices) out.vertices.push_back(pb::to_vec3(v));
  for (const auto& t : m.triangles) out.triangles.push_back({t[0], t[1], t[2]});
  return out;
}

void report(benchmark::State& state, std::uint64_t hits, std::uint64_t pairs, double sum_distance,
            std::size_t queries = g_poses.size()) {
  state.counters["per_query"] = pb::time_per_item(queries);
  state.counters["hits"] = static_cast<double>(hits);
  state.counters["pairs"] = static_cast<double>(pairs);
  state.counters["sum_distance"] = sum_distance;
}

void proxima_build(benchmark::State& state) {
  const proxima::IndexedMesh b = to_indexed(g_obj_b);
  for (auto _ : state) {
    auto mesh = proxima::TriangleMesh::create(b);
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["triangles"] = static_cast<double>(b.triangles.size());
}

void proxima_boolean(benchmark::State& state) {
  std::uint64_t hits = 0;
  const proxima::PairRequest request;
  for (auto _ : state) {
    hits = 0;
    for (const proxima::Transform& pose : g_transforms) {
      hits += proxima::midphase::mesh_mesh_intersect(*g_mesh_a, proxima::Transform{}, *g_mesh_b, pose, request);
    }
    benchmark::DoNotOptimize(hits);
  }
  report(state, hits, 0, 0.0);
}

void proxima_contacts(benchmark::State& state) {
  std::uint64_t hits = 0;
  std::uint64_t pairs = 0;
  const proxima::PairRequest request;
  std::vector<proxima::GeometryContact> contacts;
  for (auto _ : state) {
    hits = 0;
    pairs = 0;
    for (const proxima::Transform& pose : g_transforms) {
      contacts.clear();
      proxima::midphase::mesh_mesh_collide_all(*g_mesh_a, proxima::Transform{}, *g_mesh_b, pose, request, contacts);
      hits += contacts.empty() ? 0u : 1u;
      pairs += contacts.size();
    }
    benchmark::DoNotOptimize(pairs);
  }
  report(state, hits, pairs, 0.0);
}

void proxima_distance(benchmark::State& state) {
  double sum = 0.0;
  std::uint64_t hits = 0;
  const proxima::PairRequest request;
  for (auto _ : state) {
    sum = 0.0;
    hits = 0;
    for (const proxima::Transform& pose : g_transforms) {
      const proxima::GeometryDistance d =
          proxima::midphase::mesh_mesh_distance(*g_mesh_a, proxima::Transform{}, *g_mesh_b, pose, request);
      sum += static_cast<double>(d.result.signed_distance);
      hits += d.result.signed_distance <= Real(0) ? 1u : 0u;
    }
    benchmark::DoNotOptimize(sum);
  }
  report(state, hits, 0, sum);
}

#if PROXIMA_HAVE_FCL
template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> fcl_model(const ObjMesh& m) {
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
  for (const pb::Vec3d& v : m.vertices) vertices.emplace_back(v.x, v.y, v.z);
  for (const auto& t : m.triangles) triangles.emplace_back(t[0], t[1], t[2]);
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel();
  model->addSubModel(vertices, triangles);
  model->endModel();
  return model;
}

fcl::Transform3d fcl_transform(const pb::Pose& p) {
  fcl::Transform3d t = fcl::Transform3d::Identity();
  t.linear() = fcl::Quaterniond(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z).toRotationMatrix();
  t.translation() = fcl::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

template <class BV>
struct FclPair {
  std::unique_ptr<fcl::CollisionObjectd> a;
  std::unique_ptr<fcl::CollisionObjectd> b;
  std::vector<fcl::Transform3d> poses;
  /// `stride`: every stride-th pose only (FCL's AABB models are slow on this workload).
  explicit FclPair(std::size_t stride) {
    a = std::make_unique<fcl::CollisionObjectd>(fcl_model<BV>(g_obj_a), fcl::Transform3d::Identity());
    b = std::make_unique<fcl::CollisionObjectd>(fcl_model<BV>(g_obj_b), fcl::Transform3d::Identity());
    for (std::size_t i = 0; i < g_poses.size(); i += stride) poses.push_back(fcl_transform(g_poses[i]));
  }
};

template <class BV>
void fcl_boolean(benchmark::State& state) {
  FclPair<BV> pair(static_cast<std::size_t>(state.range(0)));
  fcl::CollisionRequestd request;
  request.num_max_contacts = 1;
  std::uint64_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const fcl::Transform3d& t : pair.poses) {
      pair.b->setTransform(t);
      pair.b->computeAABB();
      fcl::CollisionResultd result;
      fcl::collide(pair.a.get(), pair.b.get(), request, result);
      hits += result.isCollision() ? 1u : 0u;
    }
    benchmark::DoNotOptimize(hits);
  }
  report(state, hits, 0, 0.0, pair.poses.size());
}

template <class BV>
void fcl_contacts(benchmark::State& state) {
  FclPair<BV> pair(static_cast<std::size_t>(state.range(0)));
  fcl::CollisionRequestd request;
  request.num_max_contacts = 1000000;
  request.enable_contact = true;
  std::uint64_t hits = 0;
  std::uint64_t pairs = 0;
  for (auto _ : state) {
    hits = 0;
    pairs = 0;
    for (const fcl::Transform3d& t : pair.poses) {
      pair.b->setTransform(t);
      pair.b->computeAABB();
      fcl::CollisionResultd result;
      fcl::collide(pair.a.get(), pair.b.get(), request, result);
      hits += result.isCollision() ? 1u : 0u;
      pairs += result.numContacts();
    }
    benchmark::DoNotOptimize(pairs);
  }
  report(state, hits, pairs, 0.0, pair.poses.size());
}

template <class BV>
void fcl_distance(benchmark::State& state) {
  FclPair<BV> pair(static_cast<std::size_t>(state.range(0)));
  fcl::DistanceRequestd request;
  request.enable_nearest_points = true;
  double sum = 0.0;
  std::uint64_t hits = 0;
  for (auto _ : state) {
    sum = 0.0;
    hits = 0;
    for (const fcl::Transform3d& t : pair.poses) {
      pair.b->setTransform(t);
      pair.b->computeAABB();
      fcl::DistanceResultd result;
      fcl::distance(pair.a.get(), pair.b.get(), request, result);
      const double d = result.min_distance < 0.0 ? 0.0 : result.min_distance;
      sum += d;
      hits += d <= 0.0 ? 1u : 0u;
    }
    benchmark::DoNotOptimize(sum);
  }
  report(state, hits, 0, sum, pair.poses.size());
}
#endif

bool register_all(const std::string& dir) {
  auto poses = pb::read_mesh_poses(dir + "/mesh_poses.txt");
  if (!poses) return pb::report_load_error(poses.error());
  auto a = pb::read_obj(dir + "/" + poses->mesh_a);
  if (!a) return pb::report_load_error(a.error());
  auto b = pb::read_obj(dir + "/" + poses->mesh_b);
  if (!b) return pb::report_load_error(b.error());
  g_obj_a = std::move(*a);
  g_obj_b = std::move(*b);
  g_poses = poses->poses;
  for (const pb::Pose& p : g_poses) g_transforms.push_back(pb::to_transform(p));
  auto ma = proxima::TriangleMesh::create(to_indexed(g_obj_a));
  if (!ma) return pb::report_load_error(ma.error());
  auto mb = proxima::TriangleMesh::create(to_indexed(g_obj_b));
  if (!mb) return pb::report_load_error(mb.error());
  g_mesh_a = std::make_unique<proxima::TriangleMesh>(std::move(*ma));
  g_mesh_b = std::make_unique<proxima::TriangleMesh>(std::move(*mb));

  benchmark::RegisterBenchmark("MeshMesh/Build/proxima", proxima_build)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("MeshMesh/Boolean/proxima", proxima_boolean)->Unit(benchmark::kMillisecond);
#if PROXIMA_HAVE_FCL
  benchmark::RegisterBenchmark("MeshMesh/Boolean/fcl_obbrss", fcl_boolean<fcl::OBBRSSd>)
      ->Arg(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("MeshMesh/Boolean/fcl_aabb", fcl_boolean<fcl::AABBd>)
      ->Arg(20)
      ->Unit(benchmark::kMillisecond);
#endif
  benchmark::RegisterBenchmark("MeshMesh/Contacts/proxima", proxima_contacts)->Unit(benchmark::kMillisecond);
#if PROXIMA_HAVE_FCL
  benchmark::RegisterBenchmark("MeshMesh/Contacts/fcl_obbrss", fcl_contacts<fcl::OBBRSSd>)
      ->Arg(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("MeshMesh/Contacts/fcl_aabb", fcl_contacts<fcl::AABBd>)
      ->Arg(20)
      ->Unit(benchmark::kMillisecond);
#endif
  benchmark::RegisterBenchmark("MeshMesh/Distance/proxima", proxima_distance)->Unit(benchmark::kMillisecond);
#if PROXIMA_HAVE_FCL
  benchmark::RegisterBenchmark("MeshMesh/Distance/fcl_obbrss", fcl_distance<fcl::OBBRSSd>)
      ->Arg(1)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("MeshMesh/Distance/fcl_aabb", fcl_distance<fcl::AABBd>)
      ->Arg(20)
      ->Unit(benchmark::kMillisecond);
#endif
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_all); }
