// Mesh against mesh on the W4 workload (mesh_icosphere.obj at the identity, 20,480
// triangles; mesh_torusknot.obj at each of the 1,000 poses of mesh_poses.txt, 50,000
// triangles), every pose per iteration:
//   MeshMesh/Boolean/proxima       narrow::mesh_mesh_intersect (oriented nodes)
//   MeshMesh/Boolean/proxima_aabb  the same on the axis-aligned nodes (the reference path)
//   MeshMesh/Boolean/fcl_obbrss    fcl::collide, BVHModel<OBBRSSd>, one contact asked
//   MeshMesh/Boolean/fcl_aabb      fcl::collide, BVHModel<AABBd>, one contact asked (every
//                                  20th pose only, argument /20: about 20 ms a query)
//   MeshMesh/Contacts/...          every contact: narrow::mesh_mesh_collide_all (narrow-phase
//                                  triangle manifolds); FCL with num_max_contacts = 1e6 and
//                                  enable_contact
//   MeshMesh/Distance/...          narrow::mesh_mesh_distance; fcl::distance with nearest
//                                  points (meshes that intersect: 0 in both)
//   MeshMesh/DistancePath/{mesh,capsule}/proxima_{cold,warm}
//                                  proxima::distance along a coherent path (the first 100
//                                  poses, 9 interpolated steps between each two), B the
//                                  torus knot or a capsule (radius 0.3, half length 1), with
//                                  a PairCache kept across frames (warm) or none (cold)
// Counters: per_query (time per pose), hits (poses found intersecting), pairs (contacts or
// contact pairs summed over the poses), sum_distance (sum of the distances).
// Build the BVHs once, outside the timing (see MeshMesh/Build for Proxima's build time and
// MeshMesh/BuildOriented for the oriented nodes of both meshes, built on the first
// mesh-mesh query and here before the timing).
#include <benchmark/benchmark.h>

#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/capsule.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include "bench_main.hpp"
#include "narrowphase/mesh_mesh.hpp"
#include "shapes/oriented_tree.hpp"
#include "support/workloads.hpp"

#if PROXIMA_HAVE_FCL
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/distance.h>
#endif

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
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

/// What the queries of one pass over the poses found.
struct Tally {
  std::uint64_t hits = 0;   ///< poses found intersecting
  std::uint64_t pairs = 0;  ///< contacts (or contact pairs) summed
  double sum = 0.0;         ///< distances summed
};

/// Times `query(pose_index, tally)` over `count` poses per iteration and reports the tally.
template <class Query>
void run_poses(benchmark::State& state, std::size_t count, Query&& query) {
  Tally tally;
  for (auto _ : state) {
    tally = {};
    for (std::size_t i = 0; i < count; ++i) query(i, tally);
    benchmark::DoNotOptimize(tally);
  }
  state.counters["per_query"] = pb::time_per_item(count);
  state.counters["hits"] = static_cast<double>(tally.hits);
  state.counters["pairs"] = static_cast<double>(tally.pairs);
  state.counters["sum_distance"] = tally.sum;
}

void proxima_build(benchmark::State& state) {
  const proxima::IndexedMesh b = to_indexed(g_obj_b);
  for (auto _ : state) {
    auto mesh = proxima::TriangleMesh::create(b);
    benchmark::DoNotOptimize(mesh);
  }
  state.counters["triangles"] = static_cast<double>(b.triangles.size());
}

/// The oriented nodes of both meshes (what the first mesh-mesh query of the pair builds).
void proxima_build_oriented(benchmark::State& state) {
  for (auto _ : state) {
    for (const proxima::TriangleMesh* m : {g_mesh_a.get(), g_mesh_b.get()}) {
      auto tree = proxima::detail::build_oriented_tree(m->bvh(), m->vertices(), m->triangles());
      benchmark::DoNotOptimize(tree);
    }
  }
  state.counters["triangles"] = static_cast<double>(g_mesh_a->triangle_count() + g_mesh_b->triangle_count());
}

using proxima::narrow::MeshMeshNodes;
enum class Query { Boolean, Contacts, Distance };

/// Proxima's query `q` on node kind state.range(0) (a MeshMeshNodes).
template <Query q>
void proxima_query(benchmark::State& state) {
  const auto nodes = static_cast<MeshMeshNodes>(state.range(0));
  const proxima::PairRequest request;
  const proxima::Transform identity;
  proxima::ContactVector contacts;
  run_poses(state, g_transforms.size(), [&](std::size_t i, Tally& t) {
    const proxima::Transform& pose = g_transforms[i];
    if constexpr (q == Query::Boolean) {
      t.hits += proxima::narrow::mesh_mesh_intersect(*g_mesh_a, identity, *g_mesh_b, pose, request, nodes) ? 1u : 0u;
    } else if constexpr (q == Query::Contacts) {
      contacts.contacts.clear();
      proxima::narrow::mesh_mesh_collide_all(*g_mesh_a, identity, *g_mesh_b, pose, request, contacts, nodes);
      t.hits += contacts.contacts.empty() ? 0u : 1u;
      t.pairs += contacts.contacts.size();
    } else {
      const proxima::DistanceResult d =
          proxima::narrow::mesh_mesh_distance(*g_mesh_a, identity, *g_mesh_b, pose, request, nodes);
      t.sum += static_cast<double>(d.signed_distance);
      t.hits += d.signed_distance <= Real(0) ? 1u : 0u;
    }
  });
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

/// FCL's query `q` with bounding volume BV, on every state.range(0)-th pose (FCL's AABB
/// models are slow on this workload).
template <class BV, Query q>
void fcl_query(benchmark::State& state) {
  fcl::CollisionObjectd a(fcl_model<BV>(g_obj_a), fcl::Transform3d::Identity());
  fcl::CollisionObjectd b(fcl_model<BV>(g_obj_b), fcl::Transform3d::Identity());
  std::vector<fcl::Transform3d> poses;
  for (std::size_t i = 0; i < g_poses.size(); i += static_cast<std::size_t>(state.range(0))) {
    poses.push_back(fcl_transform(g_poses[i]));
  }
  fcl::CollisionRequestd collision;
  collision.num_max_contacts = q == Query::Contacts ? 1000000 : 1;
  collision.enable_contact = q == Query::Contacts;
  fcl::DistanceRequestd distance;
  distance.enable_nearest_points = true;
  run_poses(state, poses.size(), [&](std::size_t i, Tally& t) {
    b.setTransform(poses[i]);
    b.computeAABB();
    if constexpr (q == Query::Distance) {
      fcl::DistanceResultd result;
      fcl::distance(&a, &b, distance, result);
      const double d = result.min_distance < 0.0 ? 0.0 : result.min_distance;
      t.sum += d;
      t.hits += d <= 0.0 ? 1u : 0u;
    } else {
      fcl::CollisionResultd result;
      fcl::collide(&a, &b, collision, result);
      t.hits += result.isCollision() ? 1u : 0u;
      t.pairs += q == Query::Contacts ? result.numContacts() : 0u;
    }
  });
}
#endif

/// A coherent path for the warm-start rows: each of the first 100 W4 poses followed by 9
/// steps towards the next (positions interpolated, rotations slerped), 1,000 frames.
std::vector<proxima::Transform> coherent_path() {
  std::vector<proxima::Transform> path;
  for (std::size_t i = 0; i + 1 < std::min<std::size_t>(g_transforms.size(), 101); ++i) {
    const proxima::Transform& from = g_transforms[i];
    const proxima::Transform& to = g_transforms[i + 1];
    for (int k = 0; k < 10; ++k) {
      const Real s = Real(k) / Real(10);
      path.push_back({from.position + s * (to.position - from.position), glm::slerp(from.rotation, to.rotation, s)});
    }
  }
  return path;
}

/// Distance along the coherent path through the public entry point: B = the second W4 mesh
/// (state.range(0) == 0) or a capsule (1), with a PairCache kept across frames (warm) or not.
template <bool warm>
void proxima_path_distance(benchmark::State& state) {
  static const std::vector<proxima::Transform> path = coherent_path();
  static const proxima::Capsule capsule = proxima::Capsule::create(Real(0.3), Real(1)).value();
  const proxima::ShapeRef b = state.range(0) == 0 ? proxima::ShapeRef(*g_mesh_b) : proxima::ShapeRef(capsule);
  const proxima::Transform identity;
  proxima::PairCache cache;
  run_poses(state, path.size(), [&](std::size_t i, Tally& t) {
    const proxima::DistanceResult d =
        proxima::distance(*g_mesh_a, identity, b, path[i], proxima::PairRequest{}, warm ? &cache : nullptr);
    t.sum += static_cast<double>(d.signed_distance);
    t.hits += d.signed_distance <= Real(0) ? 1u : 0u;
  });
}

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
  g_mesh_a->oriented_tree();  // built on the first query otherwise
  g_mesh_b->oriented_tree();

  benchmark::RegisterBenchmark("MeshMesh/Build/proxima", proxima_build)->Unit(benchmark::kMillisecond);
  for (const auto& [name, shape] : {std::pair{"mesh", 0}, std::pair{"capsule", 1}}) {
    const std::string base = std::string("MeshMesh/DistancePath/") + name + "/proxima_";
    benchmark::RegisterBenchmark((base + "cold").c_str(), proxima_path_distance<false>)
        ->Arg(shape)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((base + "warm").c_str(), proxima_path_distance<true>)
        ->Arg(shape)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("MeshMesh/BuildOriented/proxima", proxima_build_oriented)->Unit(benchmark::kMillisecond);
  const auto oriented = static_cast<std::int64_t>(MeshMeshNodes::Oriented);
  const auto aabb = static_cast<std::int64_t>(MeshMeshNodes::Aabb);
  const auto add = [&](const std::string& query, auto proxima_fn, auto fcl_obbrss_fn, auto fcl_aabb_fn) {
    const std::string base = "MeshMesh/" + query + "/";
    benchmark::RegisterBenchmark((base + "proxima").c_str(), proxima_fn)->Arg(oriented)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((base + "proxima_aabb").c_str(), proxima_fn)->Arg(aabb)->Unit(benchmark::kMillisecond);
#if PROXIMA_HAVE_FCL
    benchmark::RegisterBenchmark((base + "fcl_obbrss").c_str(), fcl_obbrss_fn)->Arg(1)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((base + "fcl_aabb").c_str(), fcl_aabb_fn)->Arg(20)->Unit(benchmark::kMillisecond);
#else
    (void)fcl_obbrss_fn;
    (void)fcl_aabb_fn;
#endif
  };
#if PROXIMA_HAVE_FCL
  add("Boolean", proxima_query<Query::Boolean>, fcl_query<fcl::OBBRSSd, Query::Boolean>,
      fcl_query<fcl::AABBd, Query::Boolean>);
  add("Contacts", proxima_query<Query::Contacts>, fcl_query<fcl::OBBRSSd, Query::Contacts>,
      fcl_query<fcl::AABBd, Query::Contacts>);
  add("Distance", proxima_query<Query::Distance>, fcl_query<fcl::OBBRSSd, Query::Distance>,
      fcl_query<fcl::AABBd, Query::Distance>);
#else
  add("Boolean", proxima_query<Query::Boolean>, nullptr, nullptr);
  add("Contacts", proxima_query<Query::Contacts>, nullptr, nullptr);
  add("Distance", proxima_query<Query::Distance>, nullptr, nullptr);
#endif
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_all); }
