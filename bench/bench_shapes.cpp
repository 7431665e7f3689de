// Cost of the per-shape primitives every later phase is built on, for each shape type:
//   1. Support/<shape>: local support point in 1024 random directions (fixed seed);
//   2. WorldSupport/<shape>: support of the placed shape (direction into the local frame,
//      support, point back to the world) over 1024 random poses and directions;
//   3. WorldAabb/<shape>: the tight world box under 1024 random poses.
// Convex hulls are built from the W2 shared point clouds (shape 0 of convex_shapes_8,
// _32 and _128.txt) and from 1000 random points on a sphere. Each reports ns per call
// (per_query).
#include <benchmark/benchmark.h>

#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape.hpp>

#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "bench_main.hpp"
#include "support/workloads.hpp"

namespace {

using proxima::Real;
using proxima::Transform;
using proxima::Vec3;
namespace pb = proxima::bench;

constexpr std::size_t kSamples = 1024;

/// Fixed-seed inputs shared by every benchmark of the program.
struct Inputs {
  std::vector<Vec3> directions;  // unit, uniform on the sphere
  std::vector<Transform> poses;  // positions in [-10, 10]^3, uniform rotations
};

Inputs make_inputs() {
  std::mt19937_64 engine(0x5eed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform(-10.0, 10.0);
  Inputs in;
  while (in.directions.size() < kSamples) {
    // One draw per statement (the order of evaluation of arguments is unspecified); the
    // last coordinate first, as GCC evaluated the former argument form.
    const double vz = normal(engine);
    const double vy = normal(engine);
    const double vx = normal(engine);
    const glm::dvec3 v(vx, vy, vz);
    const double n = glm::length(v);
    if (n < 1e-6) continue;
    in.directions.push_back(Vec3(v / n));
  }
  while (in.poses.size() < kSamples) {
    const double qw = normal(engine);
    const double qz = normal(engine);
    const double qy = normal(engine);
    const double qx = normal(engine);
    const glm::dvec4 q(qx, qy, qz, qw);
    const double n = glm::length(q);
    if (n < 1e-6) continue;
    const proxima::Quat rotation(static_cast<Real>(q.x / n), static_cast<Real>(q.y / n), static_cast<Real>(q.z / n),
                                 static_cast<Real>(q.w / n));
    const auto pz = static_cast<Real>(uniform(engine));
    const auto py = static_cast<Real>(uniform(engine));
    const auto px = static_cast<Real>(uniform(engine));
    in.poses.push_back(Transform{Vec3(px, py, pz), glm::normalize(rotation)});
  }
  return in;
}

const Inputs& inputs() {
  static const Inputs in = make_inputs();
  return in;
}

template <class S>
void support_local(benchmark::State& state, const S& shape) {
  const auto& dirs = inputs().directions;
  for (auto _ : state) {
    for (const Vec3& d : dirs) {
      Vec3 p = shape.support(d);
      benchmark::DoNotOptimize(p);
    }
  }
  state.counters["per_query"] = pb::time_per_item(kSamples);
}

template <class S>
void support_world(benchmark::State& state, const S& shape) {
  const auto& dirs = inputs().directions;
  const auto& poses = inputs().poses;
  for (auto _ : state) {
    for (std::size_t i = 0; i < kSamples; ++i) {
      Vec3 p = proxima::support(shape, poses[i], dirs[i]);
      benchmark::DoNotOptimize(p);
    }
  }
  state.counters["per_query"] = pb::time_per_item(kSamples);
}

template <class S>
void world_aabb(benchmark::State& state, const S& shape) {
  const auto& poses = inputs().poses;
  for (auto _ : state) {
    for (const Transform& pose : poses) {
      proxima::Aabb box = shape.world_aabb(pose);
      benchmark::DoNotOptimize(box);
    }
  }
  state.counters["per_query"] = pb::time_per_item(kSamples);
}

/// Registers the three benchmarks of one shape (kept alive by value in the lambdas).
template <class S>
void register_shape(const std::string& name, const S& shape) {
  benchmark::RegisterBenchmark(("Support/" + name).c_str(), [shape](benchmark::State& s) { support_local(s, shape); });
  benchmark::RegisterBenchmark(("WorldSupport/" + name).c_str(),
                               [shape](benchmark::State& s) { support_world(s, shape); });
  benchmark::RegisterBenchmark(("WorldAabb/" + name).c_str(), [shape](benchmark::State& s) { world_aabb(s, shape); });
}

/// Unwraps a construction result of a shape the program builds itself (always valid).
template <class T>
T must(proxima::Result<T> r, const char* what) {
  if (!r) {
    std::cerr << "cannot build " << what << ": " << r.error().what() << "\n";
    std::exit(1);
  }
  return std::move(r).value();
}

bool register_shapes(const std::string& dir) {
  using namespace proxima;
  register_shape("point", must(Point::create(), "point"));
  register_shape("segment", must(Segment::create(Vec3(-1, 0, 0), Vec3(1, Real(0.5), 0)), "segment"));
  register_shape("triangle", must(Triangle::create(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, Real(0.2))), "triangle"));
  register_shape("sphere", must(Sphere::create(Real(0.7)), "sphere"));
  register_shape("capsule", must(Capsule::create(Real(0.3), Real(0.8)), "capsule"));
  register_shape("box", must(Box::create(Vec3(Real(0.5), Real(1.0), Real(0.25))), "box"));
  register_shape("cylinder", must(Cylinder::create(Real(0.4), Real(0.9)), "cylinder"));
  register_shape("cone", must(Cone::create(Real(0.5), Real(0.8)), "cone"));
  register_shape("ellipsoid", must(Ellipsoid::create(Vec3(Real(0.5), Real(1.0), Real(0.3))), "ellipsoid"));
  register_shape("halfspace", must(HalfSpace::create(Vec3(0, 0, 1), Real(0.5)), "halfspace"));

  for (const int points : {8, 32, 128}) {
    const std::string file = "convex_shapes_" + std::to_string(points) + ".txt";
    auto shapes = pb::read_convex_shapes(pb::workload_path(dir, file));
    if (!shapes) return pb::report_load_error(shapes.error());
    std::vector<Vec3> cloud;
    for (const pb::Vec3d& p : shapes->shapes.front().points) cloud.push_back(pb::to_vec3(p));
    register_shape("convex_hull_" + std::to_string(points), must(ConvexHull::create(cloud), file.c_str()));
  }
  std::vector<Vec3> sphere_cloud(inputs().directions.begin(), inputs().directions.begin() + 1000);
  const ConvexHull round_hull = must(ConvexHull::create(sphere_cloud), "1000-point hull");
  register_shape("convex_hull_" + std::to_string(round_hull.vertices().size()) + "v_sphere", round_hull);
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_shapes); }
