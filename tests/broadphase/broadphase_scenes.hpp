#pragma once
/// @file broadphase_scenes.hpp
/// Seeded broad-phase scenes and the typed differential harness every structure's tests use.
///
/// - `Scene` describes a seeded scene: layout of the boxes (uniform, clustered, on a line,
///   huge and tiny, zero-size, lattice with exact touching, far from the origin), the mix of
///   static and moving proxies, layers/masks, and what happens each frame (moves, batch or
///   single updates, insert/remove churn, rebuilds, rejected calls).
/// - `standard_scenes()` lists the scenes every structure must pass.
/// - `SceneGenerator` draws boxes, moves, kinds and filters for a scene (benchmarks can use it).
/// - `run_differential(structure, scene, frames)` drives the structure and the brute-force
///   reference through the same calls, frame after frame, and checks after every step:
///   same status, same size(), validate(); after every frame: identical sorted pair lists,
///   identical begun/ended deltas (PairTracker on the structure's list against
///   std::set_difference on the reference's), query_aabb / query_point / query_ray identical
///   to brute force (ray t values exactly equal: structures must report
///   geometry::ray_aabb(ray, max_t, stored box)->t), early-out callbacks honoured.
///   Rejected calls (non-finite, inverted or too-large boxes, unknown or duplicate ids, a batch
///   with one bad entry) must return the reference's status and leave the contents unchanged.
///
/// Use in a test file:
///   PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(MyGrid, [] { return UniformGrid(); }, 20)
/// defines one test per standard scene, or call run_differential<MyGrid>(scene, frames) in a
/// TEST yourself (structures that are not default-constructible: the overload taking an
/// instance). `OnExecutor(structure, executor)` runs the harness on a structure's parallel
/// find_pairs(out, executor).

#include <gtest/gtest.h>

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/brute_force.hpp>
#include <proxima/broadphase/pair_tracker.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "support/random.hpp"

namespace proxima::test {

/// A structure S whose find_pairs(out) is S's find_pairs(out, executor): the harnesses then
/// drive the parallel path. Forwards everything else. The executor must outlive it.
template <class S>
class OnExecutor {
 public:
  OnExecutor(S structure, Executor& executor) : s_(std::move(structure)), executor_(&executor) {}
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter = {}) {
    return s_.insert(id, box, kind, filter);
  }
  BroadPhaseStatus remove(ProxyId id) { return s_.remove(id); }
  BroadPhaseStatus update(ProxyId id, const Aabb& box) { return s_.update(id, box); }
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates) { return s_.update(updates); }
  void rebuild() { s_.rebuild(); }
  void find_pairs(std::vector<ProxyPair>& out) { s_.find_pairs(out, *executor_); }
  template <class F>
  decltype(auto) query_aabb(const Aabb& box, F&& on_overlap) const {
    return s_.query_aabb(box, on_overlap);
  }
  template <class F>
  decltype(auto) query_point(const Vec3& point, F&& on_overlap) const {
    return s_.query_point(point, on_overlap);
  }
  template <class F>
  decltype(auto) query_ray(const Ray& ray, Real max_t, F&& on_ray) const {
    return s_.query_ray(ray, max_t, on_ray);
  }
  bool validate() const { return s_.validate(); }
  BroadPhaseStats stats() const { return s_.stats(); }
  std::size_t size() const { return s_.size(); }

 private:
  S s_;
  Executor* executor_;
};

/// Where the centres of a scene's boxes lie and how big the boxes are.
enum class SceneLayout {
  Uniform,      ///< centres uniform in the world cube
  Clustered,    ///< centres in a few balls (clusters) inside the world cube
  LineX,        ///< centres on the x axis line: y and z intervals all overlap (single-axis clustering)
  LineY,        ///< centres on the y axis line
  HugeAndTiny,  ///< edge lengths log-uniform over five orders of magnitude (some span the world)
  ZeroSize,     ///< many point boxes and flat boxes, on a coarse lattice so they coincide
  Flat,         ///< a 2D world: centres and boxes in the plane z = 0 (z extent [0, 0])
};

/// A seeded broad-phase scene (see the file comment). Lengths in world units.
struct Scene {
  std::string name;        ///< test name (letters, digits, underscores)
  std::uint64_t seed = 1;  ///< seed of everything drawn
  SceneLayout layout = SceneLayout::Uniform;
  int count = 300;                     ///< proxies inserted before the first frame
  Vec3 origin{Real(0)};                ///< centre of the world cube
  Real extent = Real(100);             ///< half edge of the world cube
  Real min_size = Real(1);             ///< smallest box edge
  Real max_size = Real(10);            ///< largest box edge
  Real quantum = Real(0);              ///< > 0: corners on multiples of it (exact touching)
  int clusters = 6;                    ///< Clustered: number of clusters
  Real cluster_radius = Real(8);       ///< Clustered: radius of a cluster
  double static_fraction = 0.0;        ///< fraction of proxies inserted as Static
  bool filters = false;                ///< random layers/masks (else the default filter)
  bool sparse_ids = false;             ///< ids with gaps (up to ~50x the count)
  double move_fraction = 1.0;          ///< fraction of moving proxies updated per frame
  double static_move_fraction = 0.02;  ///< fraction of static proxies updated per frame
  Real step = Real(1);                 ///< largest move per axis per frame
  double resize_fraction = 0.1;        ///< fraction of updates that also draw a new size
  double churn = 0.02;                 ///< fraction of proxies removed and inserted per frame
  double batch_probability = 0.5;      ///< probability that a frame's updates go in one batch
  int rebuild_every = 0;               ///< > 0: rebuild() every this many frames
  bool bad_calls = true;               ///< try rejected calls every frame
};

/// The scenes every structure must pass (names unique; small enough for the brute force).
inline std::vector<Scene> standard_scenes() {
  // Designated initializers: fields in declaration order; unnamed fields keep their defaults.
  return {
      {.name = "uniform", .seed = 101},
      {.name = "uniform_dense", .seed = 102, .count = 250, .extent = Real(20), .step = Real(0.5), .rebuild_every = 4},
      {.name = "clustered", .seed = 103, .layout = SceneLayout::Clustered, .count = 400},
      {.name = "line_x", .seed = 104, .layout = SceneLayout::LineX, .count = 300, .extent = Real(400)},
      {.name = "line_y_static_mix",
       .seed = 105,
       .layout = SceneLayout::LineY,
       .count = 300,
       .extent = Real(400),
       .static_fraction = 0.5},
      {.name = "huge_and_tiny",
       .seed = 106,
       .layout = SceneLayout::HugeAndTiny,
       .count = 250,
       .min_size = Real(0.001),
       .max_size = Real(200)},
      {.name = "zero_size",
       .seed = 107,
       .layout = SceneLayout::ZeroSize,
       .count = 300,
       .extent = Real(10),
       .quantum = Real(1),
       .step = Real(1)},
      {.name = "lattice_touching",
       .seed = 108,
       .count = 300,
       .extent = Real(16),
       .min_size = Real(0.5),
       .max_size = Real(3),
       .quantum = Real(0.5),
       .step = Real(0.5)},
      {.name = "far_1e4",
       .seed = 109,
       .count = 300,
       .origin = Vec3(Real(1e4), Real(-2e4), Real(1.5e4)),
       .extent = Real(50)},
      {.name = "far_1e5_lattice",
       .seed = 110,
       .count = 300,
       .origin = Vec3(Real(-1e5), Real(3e5), Real(1e5)),
       .extent = Real(40),
       .min_size = Real(0.5),
       .max_size = Real(6),
       .quantum = Real(0.5)},
      {.name = "far_1e6",
       .seed = 111,
       .count = 250,
       .origin = Vec3(Real(1e6), Real(1e6), Real(-1e6)),
       .extent = Real(400),
       .min_size = Real(2),
       .max_size = Real(40),
       .step = Real(4)},
      {.name = "churn", .seed = 112, .count = 300, .sparse_ids = true, .churn = 0.3},
      {.name = "layers", .seed = 113, .count = 300, .extent = Real(40), .filters = true},
      {.name = "static_mix",
       .seed = 114,
       .count = 400,
       .extent = Real(50),
       .static_fraction = 0.6,
       .filters = true,
       .rebuild_every = 5},
      {.name = "mostly_static_few_moving",
       .seed = 115,
       .layout = SceneLayout::Clustered,
       .count = 400,
       .static_fraction = 0.95,
       .move_fraction = 0.5},
      {.name = "tiny_counts", .seed = 116, .count = 2, .extent = Real(3), .churn = 0.5},
      // inserts still happen: see run_differential (at least one per frame)
      {.name = "from_empty_churn", .seed = 117, .count = 0, .extent = Real(10), .churn = 0.0},
      {.name = "fast_movers", .seed = 118, .count = 300, .extent = Real(60), .step = Real(30), .resize_fraction = 0.5},
      {.name = "flat_2d", .seed = 119, .layout = SceneLayout::Flat, .count = 400, .extent = Real(40)},
      {.name = "flat_2d_lattice_static_mix",
       .seed = 120,
       .layout = SceneLayout::Flat,
       .count = 300,
       .extent = Real(16),
       .min_size = Real(0.5),
       .max_size = Real(3),
       .quantum = Real(0.5),
       .static_fraction = 0.5,
       .filters = true,
       .step = Real(0.5),
       .rebuild_every = 4},
  };
}

/// Draws boxes, moves, kinds and filters for a scene from its seed.
class SceneGenerator {
 public:
  /// Generator for `scene`, seeded by scene.seed.
  explicit SceneGenerator(const Scene& scene) : scene_(scene), rng_(scene.seed) {
    for (int k = 0; k < scene.clusters; ++k) {
      centres_.push_back(rng_.vec3(-scene.extent + scene.cluster_radius, scene.extent - scene.cluster_radius));
    }
  }

  /// The random source (shared by the harness for its own decisions).
  Random& rng() { return rng_; }
  /// Uniform in [0, 1).
  double chance() { return static_cast<double>(rng_.uniform(Real(0), Real(1))); }

  /// A fresh box for the scene's layout.
  Aabb box() {
    const Scene& s = scene_;
    Vec3 c;
    switch (s.layout) {
      case SceneLayout::Clustered: {
        const Vec3 offset = rng_.in_ball(s.cluster_radius);
        c = centres_[static_cast<std::size_t>(rng_.integer(0, static_cast<int>(centres_.size()) - 1))] + offset;
        break;
      }
      case SceneLayout::LineX: c = Vec3(rng_.uniform(-s.extent, s.extent), Real(0), Real(0)); break;
      case SceneLayout::LineY: c = Vec3(Real(0), rng_.uniform(-s.extent, s.extent), Real(0)); break;
      case SceneLayout::Flat:
        c = Vec3(rng_.uniform(-s.extent, s.extent), rng_.uniform(-s.extent, s.extent), Real(0));
        break;
      default: c = rng_.vec3(-s.extent, s.extent); break;
    }
    return make_box(c, size());
  }

  /// The box of a proxy after one frame's motion (reflected at the world's walls).
  Aabb moved(const Aabb& old) {
    const Scene& s = scene_;
    const Vec3 old_c = old.center() - s.origin;
    Vec3 d = rng_.vec3(-s.step, s.step);
    if (s.layout == SceneLayout::LineX) d.y = d.z = Real(0);
    if (s.layout == SceneLayout::LineY) d.x = d.z = Real(0);
    if (s.layout == SceneLayout::Flat) d.z = Real(0);
    Vec3 c = old_c + d;
    for (int a = 0; a < 3; ++a) {
      if (c[a] > s.extent || c[a] < -s.extent) c[a] = old_c[a] - d[a];
    }
    const Vec3 e = chance() < s.resize_fraction ? size() : old.extents();
    return make_box(c, e);
  }

  /// Static or Moving, by the scene's static fraction.
  ProxyKind kind() { return chance() < scene_.static_fraction ? ProxyKind::Static : ProxyKind::Moving; }

  /// A filter: the default one, or random layers among 4 bits and random masks.
  ProxyFilter filter() {
    if (!scene_.filters) return {};
    ProxyFilter f;
    f.layer = 1u << rng_.integer(0, 3);
    f.mask = static_cast<std::uint32_t>(rng_.integer(0, 15));
    if (chance() < 0.3) f.mask = ~0u;
    return f;
  }

 private:
  Vec3 size() {
    const Scene& s = scene_;
    if (s.layout == SceneLayout::HugeAndTiny) {
      const Real lo = std::log(s.min_size);
      const Real hi = std::log(s.max_size);
      const Real base = std::exp(rng_.uniform(lo, hi));
      return Vec3(base) * rng_.vec3(Real(0.5), Real(1));
    }
    Vec3 e = rng_.vec3(s.min_size, s.max_size);
    if (s.layout == SceneLayout::Flat) e.z = Real(0);
    if (s.layout == SceneLayout::ZeroSize) {
      const double u = chance();
      if (u < 0.4) {
        e = Vec3(Real(0));
      } else if (u < 0.7) {
        e[rng_.integer(0, 2)] = Real(0);
      }
    }
    return e;
  }

  /// The box of centre c (relative to the origin) and edges e, snapped to the quantum.
  Aabb make_box(const Vec3& c, const Vec3& e) const {
    const Scene& s = scene_;
    Vec3 lo = c - e * Real(0.5);
    Vec3 ext = e;
    if (s.quantum > Real(0)) {
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::round(lo[a] / s.quantum) * s.quantum;
        ext[a] = std::round(ext[a] / s.quantum) * s.quantum;
      }
    }
    Aabb b;
    b.min = s.origin + lo;
    b.max = s.origin + (lo + ext);
    b.max = glm::max(b.max, b.min);  // rounding far from the origin never inverts the box
    return b;
  }

  Scene scene_;
  Random rng_;
  std::vector<Vec3> centres_;
};

/// What run_differential checks besides pairs (all on by default).
struct DifferentialOptions {
  int queries_per_frame = 6;  ///< aabb, point and ray queries per frame (each kind)
  bool check_queries = true;  ///< compare query_aabb / query_point / query_ray
  bool check_stats = true;    ///< stats().pairs_found == pairs reported after find_pairs
};

namespace detail {

inline std::string describe(const Aabb& b) {
  std::ostringstream o;
  o.precision(9);
  o << "[" << b.min.x << " " << b.min.y << " " << b.min.z << " | " << b.max.x << " " << b.max.y << " " << b.max.z
    << "]";
  return o.str();
}

inline std::string describe_pairs_diff(const std::vector<ProxyPair>& got, const std::vector<ProxyPair>& want) {
  std::vector<ProxyPair> extra;
  std::vector<ProxyPair> missing;
  std::set_difference(got.begin(), got.end(), want.begin(), want.end(), std::back_inserter(extra));
  std::set_difference(want.begin(), want.end(), got.begin(), got.end(), std::back_inserter(missing));
  std::ostringstream o;
  o << got.size() << " pairs vs " << want.size() << " expected; extra:";
  for (std::size_t i = 0; i < std::min<std::size_t>(extra.size(), 8); ++i) {
    o << " (" << extra[i].lo << "," << extra[i].hi << ")";
  }
  o << " missing:";
  for (std::size_t i = 0; i < std::min<std::size_t>(missing.size(), 8); ++i) {
    o << " (" << missing[i].lo << "," << missing[i].hi << ")";
  }
  if (!std::is_sorted(got.begin(), got.end())) o << " [output not sorted]";
  if (std::adjacent_find(got.begin(), got.end()) != got.end()) o << " [duplicates]";
  return o.str();
}

/// Ids reported by an overlap query, sorted (duplicates kept so they are caught).
template <class S>
std::vector<ProxyId> overlap_ids_aabb(const S& s, const Aabb& box) {
  std::vector<ProxyId> ids;
  s.query_aabb(box, [&](ProxyId id) {
    ids.push_back(id);
    return true;
  });
  std::sort(ids.begin(), ids.end());
  return ids;
}

template <class S>
std::vector<ProxyId> overlap_ids_point(const S& s, const Vec3& p) {
  std::vector<ProxyId> ids;
  s.query_point(p, [&](ProxyId id) {
    ids.push_back(id);
    return true;
  });
  std::sort(ids.begin(), ids.end());
  return ids;
}

template <class S>
std::vector<std::pair<ProxyId, Real>> ray_hits(const S& s, const Ray& ray, Real max_t) {
  std::vector<std::pair<ProxyId, Real>> hits;
  s.query_ray(ray, max_t, [&](ProxyId id, Real t) {
    hits.emplace_back(id, t);
    return kRealMax;  // never clips
  });
  std::sort(hits.begin(), hits.end());
  return hits;
}

template <class S>
Real ray_closest(const S& s, const Ray& ray, Real max_t) {
  Real best = max_t;
  bool bad = false;
  s.query_ray(ray, max_t, [&](ProxyId, Real t) {
    if (t > best) bad = true;  // reported beyond the clipped fraction
    best = std::min(best, t);
    return t;
  });
  return bad ? Real(-1) : best;
}

}  // namespace detail

/// Drives `structure` and the brute-force reference through `frames` frames of `scene`
/// (see the file comment). Records gtest failures naming the scene, frame and step, and
/// stops at the first failing frame. Returns true when every check passed.
template <BroadPhaseStructure S>
bool run_differential(S& structure, const Scene& scene, int frames, const DifferentialOptions& options = {}) {
  SceneGenerator gen(scene);
  BruteForceBroadPhase ref;
  std::vector<ProxyPair> got;
  std::vector<ProxyPair> want;
  std::vector<ProxyPair> want_previous;
  PairTracker tracker;
  std::vector<ProxyId> free_ids;
  ProxyId next_id = 0;
  std::string where;

  auto fail = [&](const std::string& what) {
    ADD_FAILURE() << "scene " << scene.name << " (seed " << scene.seed << "), " << where << ": " << what;
    return false;
  };
  auto check_state = [&](const char* step) {
    if (structure.size() != ref.size()) {
      return fail(std::string(step) + ": size() " + std::to_string(structure.size()) +
                  " != " + std::to_string(ref.size()));
    }
    if (!structure.validate()) return fail(std::string(step) + ": validate() failed");
    return true;
  };
  auto check_status = [&](const char* step, BroadPhaseStatus a, BroadPhaseStatus b) {
    if (a != b) return fail(std::string(step) + ": status " + to_string(a) + ", reference " + to_string(b));
    return check_state(step);
  };
  // Full contents: every stored id (query over a box holding the whole world).
  auto check_contents = [&](const char* step) {
    const Aabb all{Vec3(-kMaxCoordinate), Vec3(kMaxCoordinate)};
    if (detail::overlap_ids_aabb(structure, all) != ref.ids()) {
      return fail(std::string(step) + ": contents changed (query over everything)");
    }
    return true;
  };
  auto fresh_id = [&]() -> ProxyId {
    if (!free_ids.empty() && gen.chance() < 0.5) {
      const std::size_t k = static_cast<std::size_t>(gen.rng().integer(0, static_cast<int>(free_ids.size()) - 1));
      const ProxyId id = free_ids[k];
      free_ids.erase(free_ids.begin() + static_cast<std::ptrdiff_t>(k));
      return id;
    }
    const ProxyId id = next_id;
    next_id += scene.sparse_ids ? static_cast<ProxyId>(gen.rng().integer(1, 100)) : 1u;
    return id;
  };
  auto insert_one = [&]() {
    const ProxyId id = fresh_id();
    const Aabb box = gen.box();
    const ProxyKind kind = gen.kind();
    const ProxyFilter filter = gen.filter();
    const BroadPhaseStatus want_status = ref.insert(id, box, kind, filter);
    return check_status("insert", structure.insert(id, box, kind, filter), want_status);
  };

  where = "initial inserts";
  for (int i = 0; i < scene.count; ++i) {
    if (!insert_one()) return false;
  }

  for (int frame = 0; frame < frames; ++frame) {
    where = "frame " + std::to_string(frame);
    std::vector<ProxyId> live = ref.ids();

    // 1. Moves: a batch or single updates.
    std::vector<ProxyUpdate> updates;
    for (ProxyId id : live) {
      const double p = ref.kind(id) == ProxyKind::Moving ? scene.move_fraction : scene.static_move_fraction;
      if (gen.chance() < p) updates.push_back({id, gen.moved(ref.box(id))});
    }
    if (!updates.empty() && gen.chance() < 0.2) updates.push_back(updates.front());  // repeated id: last wins
    if (gen.chance() < scene.batch_probability) {
      const BroadPhaseStatus want_status = ref.update(std::span<const ProxyUpdate>(updates));
      if (!check_status("batch update", structure.update(std::span<const ProxyUpdate>(updates)), want_status)) {
        return false;
      }
    } else {
      for (const ProxyUpdate& u : updates) {
        const BroadPhaseStatus want_status = ref.update(u.id, u.box);
        if (!check_status("update", structure.update(u.id, u.box), want_status)) return false;
      }
    }

    // 2. Rejected calls: each must leave both unchanged.
    if (scene.bad_calls) {
      const Real nan = std::numeric_limits<Real>::quiet_NaN();
      const Real inf = std::numeric_limits<Real>::infinity();
      const int which = gen.rng().integer(0, 9);
      const ProxyId some =
          live.empty() ? ProxyId{0}
                       : live[static_cast<std::size_t>(gen.rng().integer(0, static_cast<int>(live.size()) - 1))];
      Aabb bad = gen.box();
      const int axis = gen.rng().integer(0, 2);
      BroadPhaseStatus a = BroadPhaseStatus::Ok;
      BroadPhaseStatus b = BroadPhaseStatus::Ok;
      const ProxyId unused = next_id + 7;
      switch (which) {
        case 0:
          bad.min[axis] = nan;
          a = structure.insert(unused, bad, ProxyKind::Moving, {});
          b = ref.insert(unused, bad, ProxyKind::Moving, {});
          break;
        case 1:
          bad.max[axis] = inf;
          a = structure.insert(unused, bad, ProxyKind::Static, {});
          b = ref.insert(unused, bad, ProxyKind::Static, {});
          break;
        case 2:
          std::swap(bad.min[axis], bad.max[axis]);
          if (bad.min[axis] == bad.max[axis]) bad.max[axis] -= Real(1) + std::abs(bad.max[axis]) * Real(1e-3);
          a = structure.insert(unused, bad, ProxyKind::Moving, {});
          b = ref.insert(unused, bad, ProxyKind::Moving, {});
          break;
        case 3:
          bad.max[axis] = kMaxCoordinate * Real(4);
          a = structure.insert(unused, bad, ProxyKind::Moving, {});
          b = ref.insert(unused, bad, ProxyKind::Moving, {});
          break;
        case 4:
          if (live.empty()) break;
          a = structure.insert(some, gen.box(), ProxyKind::Moving, {});
          b = ref.insert(some, gen.box(), ProxyKind::Moving, {});
          break;
        case 5:
          a = structure.remove(unused);
          b = ref.remove(unused);
          break;
        case 6:
          a = structure.update(unused, bad);
          b = ref.update(unused, bad);
          break;
        case 7:
          if (live.empty()) break;
          bad.max[axis] = -inf;
          a = structure.update(some, bad);
          b = ref.update(some, bad);
          break;
        default: {
          // A batch whose middle entry is bad (NaN, or an unknown id): nothing may change.
          std::vector<ProxyUpdate> batch;
          for (std::size_t k = 0; k < std::min<std::size_t>(live.size(), 6); ++k) {
            batch.push_back({live[k], gen.moved(ref.box(live[k]))});
          }
          ProxyUpdate broken{unused, gen.box()};
          if (which == 9 && !live.empty()) {
            broken.id = some;
            broken.box.min[axis] = nan;
          }
          batch.insert(batch.begin() + static_cast<std::ptrdiff_t>(batch.size() / 2), broken);
          a = structure.update(std::span<const ProxyUpdate>(batch));
          b = ref.update(std::span<const ProxyUpdate>(batch));
          break;
        }
      }
      if (b == BroadPhaseStatus::Ok && which != 4 && which != 7) return fail("harness: a bad call was accepted");
      const std::string step = "rejected call #" + std::to_string(which);
      if (!check_status(step.c_str(), a, b)) return false;
      if (!check_contents(step.c_str())) return false;
    }

    // 3. Churn: removals then insertions (at least one insertion while the scene is small).
    const int churn = static_cast<int>(scene.churn * static_cast<double>(live.size()) + 0.5);
    for (int k = 0; k < churn && ref.size() > 0; ++k) {
      const std::vector<ProxyId> ids = ref.ids();
      const ProxyId id = ids[static_cast<std::size_t>(gen.rng().integer(0, static_cast<int>(ids.size()) - 1))];
      const BroadPhaseStatus want_status = ref.remove(id);
      if (!check_status("remove", structure.remove(id), want_status)) return false;
      free_ids.push_back(id);
    }
    const int inserts = std::max(churn, ref.size() < 8 ? 1 : 0);
    for (int k = 0; k < inserts; ++k) {
      if (!insert_one()) return false;
    }

    // 4. Rebuild.
    if (scene.rebuild_every > 0 && frame % scene.rebuild_every == scene.rebuild_every - 1) {
      structure.rebuild();
      if (!check_state("rebuild")) return false;
    }

    // 5. Pairs and deltas.
    structure.find_pairs(got);
    ref.find_pairs(want);
    if (!check_state("find_pairs")) return false;
    if (got != want) return fail("find_pairs: " + detail::describe_pairs_diff(got, want));
    if (options.check_stats && structure.stats().pairs_found != got.size()) {
      return fail("stats().pairs_found " + std::to_string(structure.stats().pairs_found) +
                  " != " + std::to_string(got.size()));
    }
    const PairDelta& delta = tracker.update(got);
    std::vector<ProxyPair> begun;
    std::vector<ProxyPair> ended;
    std::set_difference(want.begin(), want.end(), want_previous.begin(), want_previous.end(),
                        std::back_inserter(begun));
    std::set_difference(want_previous.begin(), want_previous.end(), want.begin(), want.end(),
                        std::back_inserter(ended));
    if (delta.begun != begun || delta.ended != ended) return fail("pair delta differs from the reference");
    want_previous = want;

    // 6. Queries.
    if (!options.check_queries) continue;
    live = ref.ids();
    const Real world = scene.extent;
    for (int q = 0; q < options.queries_per_frame; ++q) {
      // AABB: random boxes, some zero-size, some equal to a stored box (touching).
      Aabb qb = gen.box();
      if (q % 3 == 1) qb = Aabb::from_point(qb.center());
      if (q % 3 == 2 && !live.empty()) qb = ref.box(live[static_cast<std::size_t>(q) % live.size()]);
      if (detail::overlap_ids_aabb(structure, qb) != detail::overlap_ids_aabb(ref, qb)) {
        return fail("query_aabb " + detail::describe(qb));
      }
      // Point: random, or a corner of a stored box (closed boundary).
      Vec3 p = scene.origin + gen.rng().vec3(-world, world);
      if (q % 2 == 1 && !live.empty()) {
        const Aabb b = ref.box(live[static_cast<std::size_t>(gen.rng().integer(0, static_cast<int>(live.size()) - 1))]);
        p = Vec3(q % 4 == 1 ? b.min.x : b.max.x, b.min.y, q % 4 == 1 ? b.max.z : b.min.z);
      }
      if (detail::overlap_ids_point(structure, p) != detail::overlap_ids_point(ref, p)) {
        return fail("query_point at " + detail::describe(Aabb::from_point(p)));
      }
      // Ray: random origin and direction, some axis-aligned (zero components).
      Ray ray;
      ray.origin = scene.origin + gen.rng().vec3(-world * Real(1.2), world * Real(1.2));
      ray.direction = gen.rng().unit_vector() * (world * Real(2));
      if (q % 3 == 0) ray.direction = Vec3(Real(0));
      if (q % 3 == 0) ray.direction[q % 9 / 3] = (q % 2 ? Real(1) : Real(-1)) * world * Real(2);
      const Real max_t = q % 2 ? Real(1) : Real(0.3);
      if (detail::ray_hits(structure, ray, max_t) != detail::ray_hits(ref, ray, max_t)) {
        return fail("query_ray from " + detail::describe(Aabb::from_point(ray.origin)) + " dir " +
                    detail::describe(Aabb::from_point(ray.direction)));
      }
      const Real closest = detail::ray_closest(structure, ray, max_t);
      if (closest != detail::ray_closest(ref, ray, max_t)) return fail("query_ray with clipping callbacks");
      // Early outs: a callback that stops gets called at most once.
      int calls = 0;
      structure.query_aabb(Aabb{Vec3(-kMaxCoordinate), Vec3(kMaxCoordinate)}, [&](ProxyId) {
        ++calls;
        return false;
      });
      if (calls != (ref.size() > 0 ? 1 : 0)) return fail("query_aabb ignored a stopping callback");
      calls = 0;
      structure.query_ray(ray, max_t, [&](ProxyId, Real) {
        ++calls;
        return Real(0);
      });
      if (calls > 1) return fail("query_ray ignored a stopping callback");
    }
  }
  return true;
}

/// As above with a default-constructed structure.
template <BroadPhaseStructure S>
bool run_differential(const Scene& scene, int frames, const DifferentialOptions& options = {}) {
  S structure;
  return run_differential(structure, scene, frames, options);
}

/// gtest name of a scene (for value-parameterised suites).
struct SceneName {
  std::string operator()(const ::testing::TestParamInfo<Scene>& info) const { return info.param.name; }
};

}  // namespace proxima::test

/// Defines the value-parameterised test `Suite.Differential/<scene>` running
/// run_differential on every standard scene for `frames` frames, with the structure made by
/// the callable `factory` (e.g. `[] { return SweepAndPrune(); }`).
#define PROXIMA_BROADPHASE_DIFFERENTIAL_SUITE(Suite, factory, frames)                              \
  class Suite : public ::testing::TestWithParam<::proxima::test::Scene> {};                        \
  TEST_P(Suite, Differential) {                                                                    \
    auto structure = (factory)();                                                                  \
    EXPECT_TRUE(::proxima::test::run_differential(structure, GetParam(), (frames)));               \
  }                                                                                                \
  INSTANTIATE_TEST_SUITE_P(Scenes, Suite, ::testing::ValuesIn(::proxima::test::standard_scenes()), \
                           ::proxima::test::SceneName())
