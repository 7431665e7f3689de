/// @file bench_mesh_queries.cpp
/// Point queries on meshes: BSP build and quality, containment on closed and open meshes.
///
///   BM_BspBuild/<mesh>           BspPolyhedron::create (counters: depth, nodes, splits)
///   BM_Contains/<mesh>/Mesh      TriangleMesh::contains (closed: BSP, lazily built before
///                                the timed loop; open: winding number over the BVH)
///   BM_Contains/<mesh>/Reference the reference answer: closed meshes by the pseudo-normal at
///                                the nearest surface point (BVH descent), open meshes by the
///                                exact winding number summed over every triangle
///   BM_Contains/<mesh>/BspOnly   BspPolyhedron::classify alone
/// Meshes: the W4 meshes (mesh_icosphere.obj, mesh_torusknot.obj), a UV sphere of 64 x 32
/// quads, a box with each face a 24 x 24 grid, and an open mesh (the icosphere without the
/// triangles above z = 0.6 of its box). Points: 4096 uniform in the mesh box grown by 10 % per
/// side (seeded). Counter time per point. At start-up the BSP statistics of every mesh are
/// printed.
///
/// Run: build/<dir>/bench/proxima_bench_mesh_queries --benchmark_min_time=0.2

#include <benchmark/benchmark.h>

#include <proxima/shapes/bsp_polyhedron.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "shapes/mesh_point_queries.hpp"
#include "support/solid_test_meshes.hpp"
#include "support/workloads.hpp"

namespace pb = proxima::bench;
using proxima::Real;
using proxima::Vec3;

namespace {

struct Case {
  std::string name;
  proxima::IndexedMesh indexed;
  std::optional<proxima::TriangleMesh> mesh;
  std::vector<Vec3> points;
};

std::vector<Case> g_cases;

proxima::IndexedMesh to_indexed(const pb::ObjMesh& m) {
  proxima::IndexedMesh out;
  for (const pb::Vec3d& v : m.vertices) out.vertices.push_back(pb::to_vec3(v));
  out.triangles.assign(m.triangles.begin(), m.triangles.end());
  return out;
}

proxima::detail::MeshView view_of(const proxima::TriangleMesh& mesh) {
  proxima::detail::MeshView v;
  v.vertices = mesh.vertices();
  v.triangles = mesh.triangles();
  v.closed = mesh.is_closed();
  v.scale = proxima::max_abs_component(mesh.local_aabb().extents());
  return v;
}

void BM_BspBuild(benchmark::State& state, std::size_t i) {
  const Case& c = g_cases[i];
  proxima::BspStats stats;
  for (auto _ : state) {
    auto bsp = proxima::BspPolyhedron::create(c.indexed);
    benchmark::DoNotOptimize(bsp);
    stats = bsp.value().stats();
  }
  state.counters["depth"] = double(stats.depth);
  state.counters["nodes"] = double(stats.node_count);
  state.counters["splits"] = double(stats.split_faces);
  state.counters["tris_per_s"] =
      benchmark::Counter(double(c.indexed.triangles.size()), benchmark::Counter::kIsIterationInvariantRate);
}

void BM_ContainsMesh(benchmark::State& state, std::size_t i) {
  const Case& c = g_cases[i];
  std::size_t inside = 0;
  for (const Vec3& p : c.points) inside += c.mesh->contains(p);  // builds what is built lazily
  for (auto _ : state) {
    for (const Vec3& p : c.points) benchmark::DoNotOptimize(c.mesh->contains(p));
  }
  state.counters["inside"] = double(inside);
  state.counters["per_point"] = pb::time_per_item(c.points.size());
}

void BM_ContainsReference(benchmark::State& state, std::size_t i) {
  const Case& c = g_cases[i];
  proxima::detail::MeshView view = view_of(*c.mesh);
  std::vector<std::array<std::uint32_t, 3>> neighbors(c.mesh->triangle_count());
  for (std::uint32_t t = 0; t < c.mesh->triangle_count(); ++t) neighbors[t] = c.mesh->neighbors(t);
  view.neighbors = neighbors;
  std::size_t inside = 0;
  for (auto _ : state) {
    inside = 0;
    for (const Vec3& p : c.points) {
      const bool in = view.closed ? proxima::detail::mesh_contains(view, c.mesh->bvh(), p)
                                  : proxima::detail::mesh_winding_number(view, p) >= 0.5;
      inside += in;
    }
    benchmark::DoNotOptimize(inside);
  }
  state.counters["inside"] = double(inside);
  state.counters["per_point"] = pb::time_per_item(c.points.size());
}

void BM_ContainsBspOnly(benchmark::State& state, std::size_t i) {
  const Case& c = g_cases[i];
  const proxima::BspPolyhedron bsp = proxima::BspPolyhedron::create(c.indexed).value();
  for (auto _ : state) {
    for (const Vec3& p : c.points) benchmark::DoNotOptimize(bsp.classify(p));
  }
  state.counters["per_point"] = pb::time_per_item(c.points.size());
}

void add_case(std::string name, proxima::IndexedMesh indexed) {
  proxima::MeshCreateOptions options;
  options.repair = false;
  auto mesh = proxima::TriangleMesh::create(indexed, options);
  if (!mesh) {
    std::fprintf(stderr, "%s: %s\n", name.c_str(), mesh.error().what().c_str());
    return;
  }
  Case c;
  c.name = std::move(name);
  c.indexed = std::move(indexed);
  c.mesh = std::move(mesh.value());
  const proxima::Aabb box = c.mesh->local_aabb();
  const Vec3 pad = box.extents() * Real(0.1);
  std::mt19937_64 rng(20261121);
  std::uniform_real_distribution<double> u(0, 1);
  for (int k = 0; k < 4096; ++k) {
    Vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = box.min[a] - pad[a] + Real(u(rng)) * (box.max[a] - box.min[a] + 2 * pad[a]);
    c.points.push_back(p);
  }
  g_cases.push_back(std::move(c));
}

bool register_mesh_queries(const std::string& dir) {
  proxima::IndexedMesh icosphere;
  for (const char* name : {"mesh_icosphere.obj", "mesh_torusknot.obj"}) {
    auto m = pb::read_obj(pb::workload_path(dir, name));
    if (!m) return pb::report_load_error(m.error());
    proxima::IndexedMesh indexed = to_indexed(m.value());
    if (icosphere.triangles.empty()) icosphere = indexed;
    add_case(std::string(name).substr(5, std::string(name).size() - 9), std::move(indexed));
  }
  add_case("uv_sphere_64x32", proxima::test::tessellate_sphere(Real(1), 64, 32));
  {
    // The box's faces do not share vertices: weld them (the only repair needed).
    auto box = proxima::TriangleMesh::create(proxima::test::tessellate_box(Vec3(1, 0.5, 0.75), 24));
    proxima::IndexedMesh welded;
    welded.vertices.assign(box.value().vertices().begin(), box.value().vertices().end());
    welded.triangles.assign(box.value().triangles().begin(), box.value().triangles().end());
    add_case("box_24x24", std::move(welded));
  }
  {
    proxima::IndexedMesh open = icosphere;
    Real top = -proxima::kRealMax;
    for (const Vec3& v : open.vertices) top = std::max(top, v.z);
    std::vector<proxima::TriangleIndices> kept;
    for (const proxima::TriangleIndices& t : open.triangles) {
      bool above = true;
      for (std::uint32_t k : t) above = above && open.vertices[k].z > Real(0.6) * top;
      if (!above) kept.push_back(t);
    }
    open.triangles = kept;
    add_case("open_icosphere", std::move(open));
  }
  for (std::size_t i = 0; i < g_cases.size(); ++i) {
    const Case& c = g_cases[i];
    std::printf("%s: %zu triangles, closed %d\n", c.name.c_str(), c.indexed.triangles.size(), int(c.mesh->is_closed()));
    if (c.mesh->is_closed()) {
      const auto t0 = std::chrono::steady_clock::now();
      auto bsp = proxima::BspPolyhedron::create(c.indexed);
      const auto t1 = std::chrono::steady_clock::now();
      if (!bsp) {
        std::printf("  BSP: %s\n", bsp.error().what().c_str());
        continue;
      }
      const proxima::BspStats& s = bsp.value().stats();
      std::printf("  BSP: depth %u, nodes %u, split faces %u, inside leaves %u, outside leaves %u, build %.2f ms\n",
                  s.depth, s.node_count, s.split_faces, s.inside_leaves, s.outside_leaves,
                  std::chrono::duration<double, std::milli>(t1 - t0).count());
      benchmark::RegisterBenchmark(("BM_BspBuild/" + c.name).c_str(), BM_BspBuild, i)->Unit(benchmark::kMillisecond);
      benchmark::RegisterBenchmark(("BM_Contains/" + c.name + "/BspOnly").c_str(), BM_ContainsBspOnly, i);
    }
    benchmark::RegisterBenchmark(("BM_Contains/" + c.name + "/Mesh").c_str(), BM_ContainsMesh, i);
    benchmark::RegisterBenchmark(("BM_Contains/" + c.name + "/Reference").c_str(), BM_ContainsReference, i);
  }
  std::fflush(stdout);
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_mesh_queries); }
