// Tightness and cost of every bounding-volume fitter on the shared workloads:
//   datasets: the W4 meshes (mesh_icosphere.obj, mesh_torusknot.obj: their vertices) and
//             the W2 point clouds (convex_shapes_8/32/128.txt: every shape's points);
//   fitters:  AABB; sphere by centroid, box centre, Ritter, minimal (Welzl); OBB by PCA of
//             the hull surface, DiTO-14, DiTO-26, minimum-volume search; capsule; k-DOP 6,
//             14, 18, 26; the convex hull itself.
// Each benchmark Fit/<fitter>/<dataset> times the fitting of every cloud of the dataset
// (per_fit: time per cloud) and reports the fitted volume relative to the convex hull's
// volume (volume_ratio: mean over the clouds; worst_ratio: largest), computed once before
// timing. Data folder: --workloads=DIR, else PROXIMA_WORKLOADS, else the build default.
#include <benchmark/benchmark.h>

#include <proxima/bounds/fit_aabb.hpp>
#include <proxima/bounds/fit_capsule.hpp>
#include <proxima/bounds/fit_hull.hpp>
#include <proxima/bounds/fit_kdop.hpp>
#include <proxima/bounds/fit_obb.hpp>
#include <proxima/bounds/fit_sphere.hpp>

#include <algorithm>
#include <functional>
#include <iostream>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "bench_main.hpp"
#include "support/workloads.hpp"

namespace {

using proxima::Real;
using proxima::Vec3;
namespace pb = proxima::bench;

/// A named set of point clouds with their hulls' volumes.
struct Dataset {
  std::string name;
  std::vector<std::vector<Vec3>> clouds;
  std::vector<double> hull_volumes;
};

/// A fitter: fits a cloud and returns the fitted volume's volume (negative on failure).
struct Fitter {
  std::string name;
  std::function<double(std::span<const Vec3>)> fit_and_measure;  // for the ratios
  std::function<void(std::span<const Vec3>)> fit_only;           // what is timed
};

template <class F>
Fitter make_fitter(std::string name, F fit) {
  Fitter f;
  f.name = std::move(name);
  f.fit_and_measure = [fit](std::span<const Vec3> p) -> double {
    auto r = fit(p);
    if (!r.ok()) return -1.0;
    if constexpr (std::is_same_v<std::decay_t<decltype(*r)>, proxima::ConvexHull>) {
      return double(r->mass_properties().volume);
    } else {
      return double(r->volume());
    }
  };
  f.fit_only = [fit](std::span<const Vec3> p) {
    auto r = fit(p);
    benchmark::DoNotOptimize(r);
  };
  return f;
}

std::vector<Fitter> fitters() {
  using namespace proxima;
  std::vector<Fitter> f;
  f.push_back(make_fitter("Aabb", [](std::span<const Vec3> p) { return fit_aabb(p); }));
  f.push_back(make_fitter("SphereCentroid", [](std::span<const Vec3> p) { return fit_sphere_centroid(p); }));
  f.push_back(make_fitter("SphereAabbCenter", [](std::span<const Vec3> p) { return fit_sphere_aabb_center(p); }));
  f.push_back(make_fitter("SphereRitter", [](std::span<const Vec3> p) { return fit_sphere_ritter(p); }));
  f.push_back(make_fitter("SphereMinimal", [](std::span<const Vec3> p) { return fit_sphere_minimal(p); }));
  f.push_back(make_fitter("ObbPca", [](std::span<const Vec3> p) { return fit_obb_pca(p); }));
  f.push_back(make_fitter("ObbDito14", [](std::span<const Vec3> p) { return fit_obb_dito(p, 14); }));
  f.push_back(make_fitter("ObbDito26", [](std::span<const Vec3> p) { return fit_obb_dito(p, 26); }));
  f.push_back(make_fitter("ObbMinVolume", [](std::span<const Vec3> p) { return fit_obb_min_volume(p); }));
  f.push_back(make_fitter("Capsule", [](std::span<const Vec3> p) { return fit_capsule(p); }));
  f.push_back(make_fitter("Kdop6", [](std::span<const Vec3> p) { return fit_kdop<6>(p); }));
  f.push_back(make_fitter("Kdop14", [](std::span<const Vec3> p) { return fit_kdop<14>(p); }));
  f.push_back(make_fitter("Kdop18", [](std::span<const Vec3> p) { return fit_kdop<18>(p); }));
  f.push_back(make_fitter("Kdop26", [](std::span<const Vec3> p) { return fit_kdop<26>(p); }));
  f.push_back(make_fitter("Hull", [](std::span<const Vec3> p) { return fit_hull(p); }));
  return f;
}

std::vector<Vec3> to_points(const std::vector<pb::Vec3d>& v) {
  std::vector<Vec3> out;
  out.reserve(v.size());
  for (const pb::Vec3d& p : v) out.push_back(pb::to_vec3(p));
  return out;
}

bool add_hull_volumes(Dataset& d) {
  for (const auto& c : d.clouds) {
    auto hull = proxima::fit_hull(c);
    if (!hull) {
      std::cerr << d.name << ": no hull: " << hull.error().what() << "\n";
      return false;
    }
    d.hull_volumes.push_back(double(hull->mass_properties().volume));
  }
  return true;
}

void run_fit(benchmark::State& state, const Dataset& data, const Fitter& fitter) {
  // Tightness, once, outside the timed loop.
  double sum = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < data.clouds.size(); ++i) {
    const double v = fitter.fit_and_measure(data.clouds[i]);
    if (v < 0.0) {
      state.SkipWithError("fitting failed");
      return;
    }
    const double ratio = v / data.hull_volumes[i];
    sum += ratio;
    worst = std::max(worst, ratio);
  }
  for (auto _ : state) {
    for (const auto& c : data.clouds) fitter.fit_only(c);
  }
  state.counters["per_fit"] = pb::time_per_item(data.clouds.size());
  state.counters["volume_ratio"] = sum / double(data.clouds.size());
  state.counters["worst_ratio"] = worst;
  state.counters["clouds"] = double(data.clouds.size());
  state.counters["points"] = double(data.clouds[0].size());
}

bool register_fitting(const std::string& dir) {
  static std::vector<Dataset> datasets;
  static const std::vector<Fitter> all = fitters();
  for (const char* mesh : {"mesh_icosphere.obj", "mesh_torusknot.obj"}) {
    auto m = pb::read_obj(pb::workload_path(dir, mesh));
    if (!m) return pb::report_load_error(m.error());
    Dataset d;
    d.name = std::string(mesh).substr(0, std::string(mesh).size() - 4);
    d.clouds.push_back(to_points(m->vertices));
    if (!add_hull_volumes(d)) return false;
    datasets.push_back(std::move(d));
  }
  for (int points : {8, 32, 128}) {
    const std::string file = "convex_shapes_" + std::to_string(points) + ".txt";
    auto s = pb::read_convex_shapes(pb::workload_path(dir, file));
    if (!s) return pb::report_load_error(s.error());
    Dataset d;
    d.name = "convex_shapes_" + std::to_string(points);
    for (const auto& shape : s->shapes) d.clouds.push_back(to_points(shape.points));
    if (!add_hull_volumes(d)) return false;
    datasets.push_back(std::move(d));
  }
  for (const Dataset& d : datasets) {
    for (const Fitter& f : all) {
      benchmark::RegisterBenchmark(("Fit/" + f.name + "/" + d.name).c_str(), [&d, &f](benchmark::State& s) {
        run_fit(s, d, f);
      })->Unit(benchmark::kMicrosecond);
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) { return pb::run_benchmarks(argc, argv, register_fitting); }
