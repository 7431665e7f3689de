/// @file bench_mesh.cpp
/// Meshes: BVH build throughput and W5 closest-hit ray throughput, beside the peers.
///
///   BM_BvhBuild/<mesh>        Bvh::build over the triangle boxes of a shared W4 mesh
///                             (boxes and centres precomputed; counter tris_per_s)
///   BM_MeshCreate/<mesh>      TriangleMesh::create without repair (BVH, adjacency, edges)
///   BM_Rays/Proxima           TriangleMesh::raycast, every W5 ray (single thread)
///   BM_Rays/ProximaLeaf/<n>   the same with a BVH of leaves of at most n triangles
///   BM_Rays/ProximaBatch      raycast_batch on a ThreadPool of every hardware thread
///   BM_Rays/WorldBatch/<n>    the mesh as the one static object of a CollisionWorld:
///                             CollisionWorld::raycast_batch (closest hit) on a ThreadPool of
///                             n threads (1 and every hardware thread), beside
///   BM_Rays/ProximaBatchOn/<n> the mesh's own raycast_batch on the same pool sizes
///   BM_Rays/Embree            rtcIntersect1, robust scene, high build quality, 1 thread
///   BM_Rays/Bullet            btBvhTriangleMeshShape::performRaycast with a
///                             btTriangleRaycastCallback keeping the closest hit
/// Counter rays_per_s (items processed). Every ray-bench run checks its hit count against
/// Proxima's (printed once at start-up with the ratios' inputs).
///
/// Run: build/<dir>/bench/proxima_bench_mesh --benchmark_min_time=1

#include <benchmark/benchmark.h>

#include <proxima/shapes/ray_batch.hpp>
#include <proxima/shapes/triangle_mesh.hpp>
#include <proxima/spatial/bvh.hpp>
#include <proxima/world/collision_world.hpp>

#if PROXIMA_HAVE_BULLET
#include <BulletCollision/CollisionShapes/btBvhTriangleMeshShape.h>
#include <BulletCollision/CollisionShapes/btTriangleIndexVertexArray.h>
#include <BulletCollision/NarrowPhaseCollision/btRaycastCallback.h>
#endif

#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "bench_main.hpp"
#if PROXIMA_HAVE_EMBREE
#include "support/embree_scene.hpp"
#endif
#include "support/workloads.hpp"

namespace pb = proxima::bench;
using proxima::Real;

namespace {

proxima::IndexedMesh to_indexed(const pb::ObjMesh& m) {
  proxima::IndexedMesh out;
  out.vertices.reserve(m.vertices.size());
  for (const pb::Vec3d& v : m.vertices) out.vertices.push_back(pb::to_vec3(v));
  out.triangles.assign(m.triangles.begin(), m.triangles.end());
  return out;
}

struct BuildInput {
  std::vector<proxima::Aabb> boxes;
  std::vector<proxima::Vec3> centers;
};

BuildInput triangle_boxes(const proxima::IndexedMesh& m) {
  BuildInput in;
  for (const auto& t : m.triangles) {
    proxima::Aabb b = proxima::Aabb::empty();
    for (std::uint32_t i : t) b.grow(m.vertices[i]);
    in.boxes.push_back(b);
    in.centers.push_back(b.center());
  }
  return in;
}

std::vector<proxima::IndexedMesh> g_meshes;
std::vector<std::string> g_mesh_names;
std::unique_ptr<proxima::TriangleMesh> g_ray_mesh;
proxima::IndexedMesh g_ray_indexed;
const proxima::IndexedMesh& to_indexed_mesh_of_rays() { return g_ray_indexed; }
std::vector<pb::RayQuery> g_rays;
std::vector<proxima::BatchRay> g_batch;
std::size_t g_proxima_hits = 0;

void BM_BvhBuild(benchmark::State& state, std::size_t index) {
  const BuildInput in = triangle_boxes(g_meshes[index]);
  for (auto _ : state) {
    proxima::Bvh bvh = proxima::Bvh::build(in.boxes, in.centers);
    benchmark::DoNotOptimize(bvh.nodes().data());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(in.boxes.size()));
  const proxima::BvhStats s = proxima::Bvh::build(in.boxes, in.centers).stats();
  state.counters["triangles"] = double(in.boxes.size());
  state.counters["nodes"] = double(s.node_count);
  state.counters["depth"] = double(s.depth);
  state.counters["sah"] = double(s.sah_cost);
}

void BM_MeshCreate(benchmark::State& state, std::size_t index) {
  proxima::MeshCreateOptions opt;
  opt.repair = false;
  for (auto _ : state) {
    auto m = proxima::TriangleMesh::create(g_meshes[index], opt);
    benchmark::DoNotOptimize(m.ok());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(g_meshes[index].triangles.size()));
}

void BM_RaysProxima(benchmark::State& state) {
  std::size_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const proxima::BatchRay& r : g_batch) hits += g_ray_mesh->raycast(r.ray, r.max_t).has_value() ? 1 : 0;
    benchmark::DoNotOptimize(hits);
  }
  state.counters["hits"] = double(hits);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(g_batch.size()));
}

/// The same rays against the mesh built with another leaf size.
void BM_RaysProximaLeaf(benchmark::State& state) {
  proxima::MeshCreateOptions opt;
  opt.bvh.max_leaf_size = static_cast<std::uint32_t>(state.range(0));
  const proxima::TriangleMesh mesh = proxima::TriangleMesh::create(to_indexed_mesh_of_rays(), opt).value();
  std::size_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const proxima::BatchRay& r : g_batch) hits += mesh.raycast(r.ray, r.max_t).has_value() ? 1 : 0;
    benchmark::DoNotOptimize(hits);
  }
  state.counters["hits"] = double(hits);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(g_batch.size()));
}

void BM_RaysProximaBatch(benchmark::State& state) {
  std::vector<proxima::RayHit> out(g_batch.size());
  std::size_t hits = 0;
  proxima::ThreadPool pool;  // every hardware thread
  for (auto _ : state) {
    hits = proxima::raycast_batch(*g_ray_mesh, g_batch, out, pool).value();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["hits"] = double(hits);
  state.counters["threads"] = double(pool.concurrency());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(g_batch.size()));
}

/// The mesh's own batch on a pool of state.range(0) threads (0: every hardware thread).
void BM_RaysProximaBatchOn(benchmark::State& state) {
  std::vector<proxima::RayHit> out(g_batch.size());
  std::size_t hits = 0;
  proxima::ThreadPool pool(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    hits = proxima::raycast_batch(*g_ray_mesh, g_batch, out, pool).value();
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["hits"] = double(hits);
  state.counters["threads"] = double(pool.concurrency());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(g_batch.size()));
}

/// The same rays through a CollisionWorld holding the mesh as its one static object.
void BM_RaysWorldBatch(benchmark::State& state) {
  proxima::CollisionWorld world = proxima::CollisionWorld::create().value();
  proxima::ObjectDesc desc;
  desc.geometry = *g_ray_mesh;
  desc.kind = proxima::ObjectKind::Static;
  world.add(desc).value();
  std::vector<proxima::WorldRay> rays;
  for (const proxima::BatchRay& r : g_batch) rays.push_back({r.ray.origin, r.ray.direction, r.max_t});
  std::vector<proxima::WorldHit> out(rays.size());
  std::size_t hits = 0;
  proxima::ThreadPool pool(static_cast<std::size_t>(state.range(0)));
  for (auto _ : state) {
    hits = world.raycast_batch(rays, out, {}, pool).value();
    benchmark::DoNotOptimize(out.data());
  }
  if (hits != g_proxima_hits) state.SkipWithError("the world's hit count differs from the mesh's");
  state.counters["hits"] = double(hits);
  state.counters["threads"] = double(pool.concurrency());
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(rays.size()));
}

#if PROXIMA_HAVE_EMBREE
std::unique_ptr<pb::EmbreeScene> g_embree;

void BM_RaysEmbree(benchmark::State& state) {
  std::size_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const pb::RayQuery& q : g_rays) hits += g_embree->intersect(q).has_value() ? 1 : 0;
    benchmark::DoNotOptimize(hits);
  }
  state.counters["hits"] = double(hits);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(g_rays.size()));
}
#endif

#if PROXIMA_HAVE_BULLET
struct Bullet {
  std::vector<btScalar> vertices;
  std::vector<int> indices;
  std::unique_ptr<btTriangleIndexVertexArray> array;
  std::unique_ptr<btBvhTriangleMeshShape> shape;
  explicit Bullet(const proxima::TriangleMesh& mesh) {
    for (const proxima::Vec3& v : mesh.vertices())
      for (int a = 0; a < 3; ++a) vertices.push_back(btScalar(v[a]));
    for (const auto& t : mesh.triangles())
      for (std::uint32_t i : t) indices.push_back(int(i));
    array = std::make_unique<btTriangleIndexVertexArray>(int(mesh.triangle_count()), indices.data(),
                                                         int(3 * sizeof(int)), int(mesh.vertices().size()),
                                                         vertices.data(), int(3 * sizeof(btScalar)));
    shape = std::make_unique<btBvhTriangleMeshShape>(array.get(), true, true);
  }
};
std::unique_ptr<Bullet> g_bullet;

/// Keeps the closest hit: returning the fraction shortens the ray for later triangles.
struct ClosestCallback : btTriangleRaycastCallback {
  bool hit = false;
  ClosestCallback(const btVector3& from, const btVector3& to) : btTriangleRaycastCallback(from, to) {}
  btScalar reportHit(const btVector3&, btScalar fraction, int, int) override {
    hit = true;
    return fraction;
  }
};

void BM_RaysBullet(benchmark::State& state) {
  std::size_t hits = 0;
  for (auto _ : state) {
    hits = 0;
    for (const pb::RayQuery& q : g_rays) {
      const btVector3 from(btScalar(q.origin.x), btScalar(q.origin.y), btScalar(q.origin.z));
      const btVector3 to(btScalar(q.origin.x + q.max_t * q.direction.x), btScalar(q.origin.y + q.max_t * q.direction.y),
                         btScalar(q.origin.z + q.max_t * q.direction.z));
      ClosestCallback cb(from, to);
      g_bullet->shape->performRaycast(&cb, from, to);
      hits += cb.hit ? 1 : 0;
    }
    benchmark::DoNotOptimize(hits);
  }
  state.counters["hits"] = double(hits);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(g_rays.size()));
}
#endif

bool register_mesh(const std::string& dir) {
  for (const char* name : {"mesh_icosphere.obj", "mesh_torusknot.obj"}) {
    auto m = pb::read_obj(pb::workload_path(dir, name));
    if (!m) return pb::report_load_error(m.error());
    g_meshes.push_back(to_indexed(m.value()));
    g_mesh_names.push_back(name);
  }
  auto rays = pb::read_rays(pb::workload_path(dir, "rays.txt"));
  if (!rays) return pb::report_load_error(rays.error());
  g_rays = rays.value().rays;
  auto obj = pb::read_obj(pb::workload_path(dir, rays.value().mesh));
  if (!obj) return pb::report_load_error(obj.error());
  g_ray_indexed = to_indexed(obj.value());
  auto mesh = proxima::TriangleMesh::create(g_ray_indexed);
  if (!mesh) return pb::report_load_error(mesh.error());
  g_ray_mesh = std::make_unique<proxima::TriangleMesh>(std::move(mesh).value());
  for (const pb::RayQuery& q : g_rays)
    g_batch.push_back({{pb::to_vec3(q.origin), pb::to_vec3(q.direction)}, static_cast<Real>(q.max_t)});
  for (const proxima::BatchRay& r : g_batch) g_proxima_hits += g_ray_mesh->raycast(r.ray, r.max_t) ? 1 : 0;
  std::printf("W5: %zu rays against %s (%u triangles), Proxima hits %zu\n", g_rays.size(), rays.value().mesh.c_str(),
              g_ray_mesh->triangle_count(), g_proxima_hits);

  for (std::size_t i = 0; i < g_meshes.size(); ++i) {
    benchmark::RegisterBenchmark(("BM_BvhBuild/" + g_mesh_names[i]).c_str(), BM_BvhBuild, i)
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark(("BM_MeshCreate/" + g_mesh_names[i]).c_str(), BM_MeshCreate, i)
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("BM_Rays/Proxima", BM_RaysProxima)->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_Rays/ProximaLeaf", BM_RaysProximaLeaf)
      ->Arg(1)
      ->Arg(2)
      ->Arg(8)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_Rays/ProximaBatch", BM_RaysProximaBatch)
      ->Unit(benchmark::kMillisecond)
      ->UseRealTime();
  for (const char* name : {"BM_Rays/ProximaBatchOn", "BM_Rays/WorldBatch"}) {
    benchmark::RegisterBenchmark(name, name[8] == 'W' ? BM_RaysWorldBatch : BM_RaysProximaBatchOn)
        ->Arg(1)
        ->Arg(0)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
#if PROXIMA_HAVE_EMBREE
  g_embree = std::make_unique<pb::EmbreeScene>(*g_ray_mesh);
  benchmark::RegisterBenchmark("BM_Rays/Embree", BM_RaysEmbree)->Unit(benchmark::kMillisecond);
#endif
#if PROXIMA_HAVE_BULLET
  g_bullet = std::make_unique<Bullet>(*g_ray_mesh);
  benchmark::RegisterBenchmark("BM_Rays/Bullet", BM_RaysBullet)->Unit(benchmark::kMillisecond);
#endif
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_mesh); }
