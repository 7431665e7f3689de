// proxima_bench_broadphase: the broad phases on the W1 workloads (shared/bench FORMATS.md),
// every Proxima structure beside the peer libraries' broad phases in the same run.
//
//   BroadPhase/<workload>/<mode>/<structure>[/threads:T]
//     workload   uniform_10k, uniform_100k, clustered_100k (shared files), and with
//                --large=FILE any other W1 file (e.g. 1M boxes written by
//                proxima_make_workload into the build folder; see bench/RESULTS.md)
//     mode       frame:   one iteration = one frame: update every box (W1 motion rule) and
//                         enumerate every pair; 100 frames at 10k, 20 at 100k, 10 at 1M
//                moving10: only every 10th box moves (the others stay at frame 0)
//                oneshot: build from scratch (insert all + first pair list), frame 1 boxes
//                floor:   read every box, one key each, radix sort (the least work of a frame)
//     counters   per_frame (time), pairs (per frame), check (1 when the pair checksum of the
//                frames run equals the exact reference: the published W1 checksum for full
//                runs, a double-precision sort-and-sweep otherwise; 2 when it equals the
//                reference of the boxes rounded to proxima::Real, which a float build and
//                Bullet see; 0 otherwise), build_ms (insert all), mem_MB
//                (peak malloc'd bytes during build + frames, mallinfo2), missing (pairs per
//                frame that the structure did not report, relative to the reference)
//
// Peers: Bullet btDbvtBroadphase (deferred collide) and bt32BitAxisSweep3, FCL
// DynamicAABBTreeCollisionManager, SaPCollisionManager, IntervalTreeCollisionManager,
// SpatialHashingCollisionManager (boxes as fcl::Box objects; only the broad phase runs, the
// callback counts pairs). Bullet's pair caches hold candidate pairs (fattened leaves,
// quantised sweep); the enumeration keeps those whose exact boxes overlap, inside the timed
// region. FCL's SaP and interval-tree managers treat touching boxes as separate: their
// `missing` counter says how many W1 pairs (exactly touching ones) they drop per frame.
// FCL's spatial hash reports candidates that share a cell (about 5 reports per true pair
// here, duplicates included); the benchmark de-duplicates them and keeps exact overlaps
// inside the timed region.

#include <benchmark/benchmark.h>

#include <proxima/broadphase/dynamic_aabb_tree.hpp>
#include <proxima/broadphase/kd_tree.hpp>
#include <proxima/broadphase/loose_octree.hpp>
#include <proxima/broadphase/uniform_grid.hpp>

#include <malloc.h>
#if __has_include(<proxima/broadphase/any_broadphase.hpp>)
#include <proxima/broadphase/any_broadphase.hpp>
#define PROXIMA_BENCH_HAVE_REGISTRY 1
#endif

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "support/bench_main.hpp"
#include "support/workloads.hpp"

#if defined(PROXIMA_HAVE_FCL)
#include <fcl/broadphase/broadphase_SaP.h>
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/broadphase/broadphase_interval_tree.h>
#include <fcl/broadphase/broadphase_spatialhash.h>
#include <fcl/broadphase/detail/hierarchy_tree.h>
#include <fcl/broadphase/detail/sparse_hash_table.h>
#include <fcl/broadphase/detail/spatial_hash.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/narrowphase/collision_object.h>
#endif
#if defined(PROXIMA_HAVE_BULLET)
#include <BulletCollision/BroadphaseCollision/btAxisSweep3.h>
#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/BroadphaseCollision/btOverlappingPairCache.h>
#endif

namespace {

using proxima::Aabb;
using proxima::ProxyId;
using proxima::ProxyPair;
using proxima::ProxyUpdate;
using proxima::Real;
using proxima::Vec3;
using proxima::bench::BroadphaseBox;
using proxima::bench::BroadphaseWorkload;
using proxima::bench::PairChecksum;

/// Boxes of a frame in double: lo = c - h, hi = c + h (FORMATS.md).
struct BoxD {
  double lo[3];
  double hi[3];
};

void boxes_of(const std::vector<BroadphaseBox>& boxes, std::vector<BoxD>& out) {
  out.resize(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      out[i].lo[k] = boxes[i].center[k] - boxes[i].half_extents[k];
      out[i].hi[k] = boxes[i].center[k] + boxes[i].half_extents[k];
    }
  }
}

Aabb to_aabb(const BoxD& b) {
  return {Vec3(Real(b.lo[0]), Real(b.lo[1]), Real(b.lo[2])), Vec3(Real(b.hi[0]), Real(b.hi[1]), Real(b.hi[2]))};
}

bool overlap_d(const BoxD& a, const BoxD& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] && a.lo[2] <= b.hi[2] &&
         b.lo[2] <= a.hi[2];
}

std::size_t heap_bytes() {
  const struct mallinfo2 m = mallinfo2();
  return m.uordblks + m.hblkhd;
}

/// One broad phase under test; virtual calls at frame granularity only.
class Runner {
 public:
  virtual ~Runner() = default;
  /// Inserts box i with id i (moving), then prepares for queries.
  virtual void build(const std::vector<BoxD>& boxes) = 0;
  /// New boxes of the `moved` indices.
  virtual void update(const std::vector<BoxD>& boxes, const std::vector<std::uint32_t>& moved) = 0;
  /// Every pair into pairs() (any order, each once).
  virtual void find_pairs() = 0;
  /// The pairs of the last find_pairs.
  virtual const std::vector<ProxyPair>& pairs() const = 0;
};

/// True when S offers find_pairs(out, threads).
template <class S>
constexpr bool kParallel = requires(S& s, std::vector<ProxyPair>& out) {
  s.find_pairs(out, 2u);
};

/// A Proxima structure (templated: no virtual call inside).
template <class S>
class ProximaRunner final : public Runner {
 public:
  explicit ProximaRunner(int threads) : threads_(threads) {}
  void build(const std::vector<BoxD>& boxes) override {
    s_ = std::make_unique<S>();
    if constexpr (requires(S & s) { s.set_thread_count(2); }) s_->set_thread_count(threads_);
    for (std::size_t i = 0; i < boxes.size(); ++i)
      s_->insert(ProxyId(i), to_aabb(boxes[i]), proxima::ProxyKind::Moving, {});
    s_->rebuild();
  }
  void update(const std::vector<BoxD>& boxes, const std::vector<std::uint32_t>& moved) override {
    updates_.resize(moved.size());
    for (std::size_t k = 0; k < moved.size(); ++k) updates_[k] = {moved[k], to_aabb(boxes[moved[k]])};
    s_->update(std::span<const ProxyUpdate>(updates_));
  }
  void find_pairs() override {
    if constexpr (kParallel<S>) {
      s_->find_pairs(pairs_, unsigned(threads_));
    } else {
      s_->find_pairs(pairs_);
    }
  }
  const std::vector<ProxyPair>& pairs() const override { return pairs_; }

 private:
  int threads_;
  std::unique_ptr<S> s_;
  std::vector<ProxyUpdate> updates_;
  std::vector<ProxyPair> pairs_;
};

#if defined(PROXIMA_BENCH_HAVE_REGISTRY)
/// A Proxima structure through the type-erased registry (one virtual call per operation).
class RegistryRunner final : public Runner {
 public:
  RegistryRunner(std::string name, int threads) : name_(std::move(name)), threads_(threads) {}
  void build(const std::vector<BoxD>& boxes) override {
    auto made = proxima::make_broadphase(name_);
    if (!made) throw std::runtime_error(made.error().what());
    s_ = std::move(made).value();
    for (std::size_t i = 0; i < boxes.size(); ++i)
      s_->insert(ProxyId(i), to_aabb(boxes[i]), proxima::ProxyKind::Moving, {});
    s_->rebuild();
  }
  void update(const std::vector<BoxD>& boxes, const std::vector<std::uint32_t>& moved) override {
    updates_.resize(moved.size());
    for (std::size_t k = 0; k < moved.size(); ++k) updates_[k] = {moved[k], to_aabb(boxes[moved[k]])};
    s_->update(std::span<const ProxyUpdate>(updates_));
  }
  void find_pairs() override { s_->find_pairs(pairs_, unsigned(threads_)); }
  const std::vector<ProxyPair>& pairs() const override { return pairs_; }

 private:
  std::string name_;
  int threads_;
  std::unique_ptr<proxima::AnyBroadPhase> s_;
  std::vector<ProxyUpdate> updates_;
  std::vector<ProxyPair> pairs_;
};
#endif

#if defined(PROXIMA_HAVE_BULLET)
/// Bullet broad phases: btDbvtBroadphase (deferred collide) or bt32BitAxisSweep3.
class BulletRunner final : public Runner {
 public:
  enum class Kind { Dbvt, AxisSweep };
  explicit BulletRunner(Kind kind) : kind_(kind) {}
  ~BulletRunner() override { clear(); }
  void build(const std::vector<BoxD>& boxes) override {
    clear();
    boxes_ = &boxes;
    if (kind_ == Kind::Dbvt) {
      auto* dbvt = new btDbvtBroadphase();
      dbvt->m_deferedcollide = true;
      broadphase_ = dbvt;
    } else {
      btVector3 lo(BT_LARGE_FLOAT, BT_LARGE_FLOAT, BT_LARGE_FLOAT);
      btVector3 hi(-BT_LARGE_FLOAT, -BT_LARGE_FLOAT, -BT_LARGE_FLOAT);
      for (const BoxD& b : boxes) {
        lo.setMin(btVector3(btScalar(b.lo[0]), btScalar(b.lo[1]), btScalar(b.lo[2])));
        hi.setMax(btVector3(btScalar(b.hi[0]), btScalar(b.hi[1]), btScalar(b.hi[2])));
      }
      const btVector3 margin = (hi - lo) * btScalar(0.1);
      broadphase_ = new bt32BitAxisSweep3(lo - margin, hi + margin, unsigned(boxes.size() + 16));
    }
    proxies_.resize(boxes.size());
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      proxies_[i] = broadphase_->createProxy(min_of(boxes[i]), max_of(boxes[i]), 0, reinterpret_cast<void*>(i),
                                             short(btBroadphaseProxy::DefaultFilter),
                                             short(btBroadphaseProxy::AllFilter), nullptr);
    }
    broadphase_->calculateOverlappingPairs(nullptr);
  }
  void update(const std::vector<BoxD>& boxes, const std::vector<std::uint32_t>& moved) override {
    boxes_ = &boxes;
    for (const std::uint32_t i : moved) broadphase_->setAabb(proxies_[i], min_of(boxes[i]), max_of(boxes[i]), nullptr);
  }
  void find_pairs() override {
    broadphase_->calculateOverlappingPairs(nullptr);
    btOverlappingPairCache* cache = broadphase_->getOverlappingPairCache();
    const int count = cache->getNumOverlappingPairs();
    const btBroadphasePair* pairs = cache->getOverlappingPairArrayPtr();
    pairs_.clear();
    for (int k = 0; k < count; ++k) {
      const auto a = ProxyId(reinterpret_cast<std::uintptr_t>(pairs[k].m_pProxy0->m_clientObject));
      const auto b = ProxyId(reinterpret_cast<std::uintptr_t>(pairs[k].m_pProxy1->m_clientObject));
      // Candidates from fattened leaves or quantised bounds: keep the exact overlaps.
      if (overlap_d((*boxes_)[a], (*boxes_)[b])) pairs_.push_back(a < b ? ProxyPair{a, b} : ProxyPair{b, a});
    }
  }
  const std::vector<ProxyPair>& pairs() const override { return pairs_; }

 private:
  static btVector3 min_of(const BoxD& b) { return {btScalar(b.lo[0]), btScalar(b.lo[1]), btScalar(b.lo[2])}; }
  static btVector3 max_of(const BoxD& b) { return {btScalar(b.hi[0]), btScalar(b.hi[1]), btScalar(b.hi[2])}; }
  void clear() {
    if (broadphase_ == nullptr) return;
    for (btBroadphaseProxy* p : proxies_) broadphase_->destroyProxy(p, nullptr);
    delete broadphase_;
    broadphase_ = nullptr;
    proxies_.clear();
  }
  Kind kind_;
  btBroadphaseInterface* broadphase_ = nullptr;
  std::vector<btBroadphaseProxy*> proxies_;
  const std::vector<BoxD>* boxes_ = nullptr;
  std::vector<ProxyPair> pairs_;
};
#endif

#if defined(PROXIMA_HAVE_FCL)
/// FCL broad-phase managers over fcl::Box collision objects.
class FclRunner final : public Runner {
 public:
  enum class Kind { DynamicTree, SaP, IntervalTree, SpatialHash };
  explicit FclRunner(Kind kind) : kind_(kind) {}
  void build(const std::vector<BoxD>& boxes) override {
    objects_.clear();
    manager_.reset();
    boxes_ = &boxes;
    switch (kind_) {
      case Kind::DynamicTree: manager_ = std::make_unique<fcl::DynamicAABBTreeCollisionManager<double>>(); break;
      case Kind::SaP: manager_ = std::make_unique<fcl::SaPCollisionManager<double>>(); break;
      case Kind::IntervalTree: manager_ = std::make_unique<fcl::IntervalTreeCollisionManager<double>>(); break;
      case Kind::SpatialHash: {
        fcl::Vector3d lo(1e300, 1e300, 1e300);
        fcl::Vector3d hi(-1e300, -1e300, -1e300);
        double size = 0;
        for (const BoxD& b : boxes) {
          for (int k = 0; k < 3; ++k) {
            lo[k] = std::min(lo[k], b.lo[k]);
            hi[k] = std::max(hi[k], b.hi[k]);
            size += b.hi[k] - b.lo[k];
          }
        }
        const double cell = 1.5 * size / (3.0 * double(std::max<std::size_t>(1, boxes.size())));
        using Hash = fcl::detail::SpatialHash<double>;
        using Table = fcl::detail::SparseHashTable<fcl::AABB<double>, fcl::CollisionObject<double>*, Hash>;
        manager_ = std::make_unique<fcl::SpatialHashingCollisionManager<double, Table>>(cell, lo, hi);
        break;
      }
    }
    objects_.reserve(boxes.size());
    std::vector<fcl::CollisionObject<double>*> raw;
    for (std::size_t i = 0; i < boxes.size(); ++i) {
      const BoxD& b = boxes[i];
      auto shape = std::make_shared<fcl::Box<double>>(b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]);
      auto object = std::make_unique<fcl::CollisionObject<double>>(shape);
      object->setUserData(reinterpret_cast<void*>(i));
      place(*object, b);
      raw.push_back(object.get());
      objects_.push_back(std::move(object));
    }
    manager_->registerObjects(raw);
    manager_->setup();
  }
  void update(const std::vector<BoxD>& boxes, const std::vector<std::uint32_t>& moved) override {
    boxes_ = &boxes;
    for (const std::uint32_t i : moved) place(*objects_[i], boxes[i]);
    manager_->update();
  }
  void find_pairs() override {
    pairs_.clear();
    manager_->collide(&pairs_, [](fcl::CollisionObject<double>* a, fcl::CollisionObject<double>* b, void* data) {
      auto* out = static_cast<std::vector<ProxyPair>*>(data);
      const auto ia = ProxyId(reinterpret_cast<std::uintptr_t>(a->getUserData()));
      const auto ib = ProxyId(reinterpret_cast<std::uintptr_t>(b->getUserData()));
      out->push_back(ia < ib ? ProxyPair{ia, ib} : ProxyPair{ib, ia});
      return false;
    });
    if (kind_ == Kind::SpatialHash) {
      // FCL's spatial hash reports candidates that share a cell, possibly several times:
      // keep each exact overlap once (timed).
      reported_ = pairs_.size();
      std::sort(pairs_.begin(), pairs_.end());
      pairs_.erase(std::unique(pairs_.begin(), pairs_.end()), pairs_.end());
      std::erase_if(pairs_, [&](const ProxyPair& p) { return !overlap_d((*boxes_)[p.lo], (*boxes_)[p.hi]); });
    }
  }
  /// Reports of the last find_pairs before duplicates were removed.
  std::size_t reported() const { return reported_; }
  const std::vector<ProxyPair>& pairs() const override { return pairs_; }

 private:
  // The AABB is set directly to the W1 box (FCL would otherwise recompute it from the
  // box shape and translation, adding rounding).
  static void place(fcl::CollisionObject<double>& object, const BoxD& b) {
    object.setTranslation(
        fcl::Vector3d(0.5 * (b.lo[0] + b.hi[0]), 0.5 * (b.lo[1] + b.hi[1]), 0.5 * (b.lo[2] + b.hi[2])));
    fcl::AABB<double>& box = const_cast<fcl::AABB<double>&>(object.getAABB());
    box.min_ = fcl::Vector3d(b.lo[0], b.lo[1], b.lo[2]);
    box.max_ = fcl::Vector3d(b.hi[0], b.hi[1], b.hi[2]);
  }
  Kind kind_;
  std::size_t reported_ = 0;
  const std::vector<BoxD>* boxes_ = nullptr;
  std::unique_ptr<fcl::BroadPhaseCollisionManager<double>> manager_;
  std::vector<std::unique_ptr<fcl::CollisionObject<double>>> objects_;
  std::vector<ProxyPair> pairs_;
};
#endif

/// A named runner factory.
struct Contestant {
  std::string name;
  bool peer = false;
  bool threaded = false;  // also run with 2 threads
  std::function<std::unique_ptr<Runner>(int threads)> make;
};

std::vector<Contestant> contestants() {
  std::vector<Contestant> c;
  auto proxima = [&](const std::string& name, auto tag) {
    using S = typename decltype(tag)::type;
    c.push_back({name, false, kParallel<S>, [](int t) { return std::make_unique<ProximaRunner<S>>(t); }});
  };
  proxima("grid", std::type_identity<proxima::UniformGrid>{});
  proxima("hash", std::type_identity<proxima::SpatialHash>{});
  proxima("hgrid", std::type_identity<proxima::HierarchicalGrid>{});
  proxima("octree", std::type_identity<proxima::LooseOctree>{});
  proxima("quadtree", std::type_identity<proxima::LooseQuadtree>{});
  proxima("tree", std::type_identity<proxima::DynamicAabbTree>{});
  proxima("kdtree", std::type_identity<proxima::KdTree>{});
#if defined(PROXIMA_BENCH_HAVE_REGISTRY)
  // The registry's other structures (those not listed above by type).
  for (const std::string_view view : proxima::broadphase_names()) {
    const std::string n(view);
    if (n == "brute") continue;
    if (std::any_of(c.begin(), c.end(), [&](const Contestant& k) { return k.name == n; })) continue;
    auto probe = proxima::make_broadphase(n);
    const bool parallel = probe && (*probe)->parallel();
    c.push_back({n, false, parallel, [n](int t) { return std::make_unique<RegistryRunner>(n, t); }});
  }
#endif
#if defined(PROXIMA_HAVE_BULLET)
  c.push_back(
      {"bullet_dbvt", true, false, [](int) { return std::make_unique<BulletRunner>(BulletRunner::Kind::Dbvt); }});
  c.push_back({"bullet_axis_sweep", true, false,
               [](int) { return std::make_unique<BulletRunner>(BulletRunner::Kind::AxisSweep); }});
#endif
#if defined(PROXIMA_HAVE_FCL)
  c.push_back(
      {"fcl_dynamic_tree", true, false, [](int) { return std::make_unique<FclRunner>(FclRunner::Kind::DynamicTree); }});
  c.push_back({"fcl_sap", true, false, [](int) { return std::make_unique<FclRunner>(FclRunner::Kind::SaP); }});
  c.push_back({"fcl_interval_tree", true, false,
               [](int) { return std::make_unique<FclRunner>(FclRunner::Kind::IntervalTree); }});
  c.push_back(
      {"fcl_spatial_hash", true, false, [](int) { return std::make_unique<FclRunner>(FclRunner::Kind::SpatialHash); }});
#endif
  return c;
}

enum class Mode { Frame, Moving10, OneShot };

/// A loaded workload with its reference checksums per mode (computed once, lazily).
struct Loaded {
  std::string name;
  BroadphaseWorkload workload;
  int frames = 0;                                               // frames run per benchmark
  std::map<std::pair<Mode, int>, PairChecksum> reference;       // exact boxes (double)
  std::map<std::pair<Mode, int>, PairChecksum> reference_real;  // boxes rounded to proxima::Real
};

/// Sort-and-sweep on x over the boxes rounded to Real (what a float build stores): the
/// pairs a correct Real-precision broad phase reports.
void add_rounded_pairs(const std::vector<BroadphaseBox>& state, PairChecksum& sum, bool round = true) {
  std::vector<BoxD> boxes;
  boxes_of(state, boxes);
  for (BoxD& b : boxes) {
    if (!round) break;
    for (int k = 0; k < 3; ++k) {
      b.lo[k] = double(Real(b.lo[k]));
      b.hi[k] = double(Real(b.hi[k]));
    }
  }
  std::vector<std::uint32_t> order(boxes.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = std::uint32_t(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    return boxes[a].lo[0] < boxes[b].lo[0] || (boxes[a].lo[0] == boxes[b].lo[0] && a < b);
  });
  for (std::size_t i = 0; i < order.size(); ++i) {
    const BoxD& a = boxes[order[i]];
    for (std::size_t j = i + 1; j < order.size() && boxes[order[j]].lo[0] <= a.hi[0]; ++j) {
      if (overlap_d(a, boxes[order[j]])) sum.add(order[i], order[j], boxes.size());
    }
  }
}

/// Moves the boxes of one frame (all, or every 10th) and returns the moved indices.
void advance(Loaded& w, std::vector<BroadphaseBox>& state, Mode mode, std::vector<std::uint32_t>& moved) {
  const std::size_t n = state.size();
  moved.clear();
  if (mode == Mode::Moving10) {
    // Move every 10th box by the W1 rule (advance_frame on a one-box vector each).
    for (std::size_t i = 0; i < n; i += 10) {
      std::vector<BroadphaseBox> one{state[i]};
      proxima::bench::advance_frame(one, w.workload.dt, w.workload.lo, w.workload.hi);
      state[i] = one[0];
      moved.push_back(std::uint32_t(i));
    }
    return;
  }
  proxima::bench::advance_frame(state, w.workload.dt, w.workload.lo, w.workload.hi);
  for (std::size_t i = 0; i < n; ++i) moved.push_back(std::uint32_t(i));
}

/// The reference checksums of `frames` frames of a mode: exact (the published W1 checksum
/// or a double-precision sort-and-sweep) and with the boxes rounded to Real.
PairChecksum reference_of(Loaded& w, Mode mode, int frames) {
  const auto key = std::make_pair(mode, mode == Mode::OneShot ? 1 : frames);
  auto it = w.reference.find(key);
  if (it != w.reference.end()) return it->second;
  PairChecksum sum;
  PairChecksum rounded;
  {
    std::vector<BroadphaseBox> state = w.workload.boxes;
    std::vector<std::uint32_t> moved;
    for (int f = 0; f < key.second; ++f) {
      advance(w, state, mode == Mode::OneShot ? Mode::Frame : mode, moved);
      add_rounded_pairs(state, rounded);
    }
  }
  w.reference_real[key] = rounded;
  const auto published = proxima::bench::published_checksum(w.workload.name);
  if (mode == Mode::Frame && published.found && key.second == w.workload.frames) {
    sum = published.checksum;
  } else {
    std::vector<BroadphaseBox> state = w.workload.boxes;
    std::vector<std::uint32_t> moved;
    for (int f = 0; f < key.second; ++f) {
      advance(w, state, mode == Mode::OneShot ? Mode::Frame : mode, moved);
      add_rounded_pairs(state, sum, false);  // the same sweep on the exact boxes
    }
  }
  w.reference[key] = sum;
  return sum;
}

void run(benchmark::State& bm, Loaded& w, const Contestant& who, Mode mode, int threads, int frames) {
  const PairChecksum reference = reference_of(w, mode, frames);
  const PairChecksum reference_real = w.reference_real[std::make_pair(mode, mode == Mode::OneShot ? 1 : frames)];
  std::vector<BroadphaseBox> state = w.workload.boxes;
  std::vector<BoxD> boxes;
  std::vector<std::uint32_t> moved;
  const std::uint64_t n = state.size();
  PairChecksum sum;
  const std::size_t heap0 = heap_bytes();
  std::size_t peak = 0;
  double build_ms = 0;
  std::unique_ptr<Runner> runner = who.make(threads);
  if (mode == Mode::OneShot) {
    advance(w, state, Mode::Frame, moved);
    boxes_of(state, boxes);
    for (auto _ : bm) {
      runner = who.make(threads);
      runner->build(boxes);
      runner->find_pairs();
      bm.PauseTiming();
      peak = std::max(peak, heap_bytes());
      sum = {};
      for (const ProxyPair& p : runner->pairs()) sum.add(p.lo, p.hi, n);
      runner.reset();
      bm.ResumeTiming();
    }
    bm.counters["pairs"] = double(sum.pairs);
  } else {
    boxes_of(state, boxes);
    const auto t0 = std::chrono::steady_clock::now();
    runner->build(boxes);
    build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    peak = heap_bytes();
    int frame = 0;
    for (auto _ : bm) {
      bm.PauseTiming();
      advance(w, state, mode, moved);
      boxes_of(state, boxes);
      bm.ResumeTiming();
      runner->update(boxes, moved);
      runner->find_pairs();
      bm.PauseTiming();
      for (const ProxyPair& p : runner->pairs()) sum.add(p.lo, p.hi, n);
      if (++frame % 8 == 1) peak = std::max(peak, heap_bytes());
      bm.ResumeTiming();
    }
    bm.counters["pairs"] = double(sum.pairs) / double(std::max(1, frame));
    bm.counters["build_ms"] = build_ms;
    bm.counters["missing"] =
        (double(reference.pairs) - double(sum.pairs)) / double(std::max(1, mode == Mode::OneShot ? 1 : frame));
  }
  // check: 1 = the exact W1 pairs (checksum equal to the double-precision reference);
  // 2 = the pairs of the boxes rounded to Real (float build: rounding makes a few more
  // boxes touch); 0 = neither (a wrong result, or a peer dropping touching pairs).
  bm.counters["check"] = sum == reference ? 1 : (sum == reference_real ? 2 : 0);
  bm.counters["mem_MB"] = double(peak > heap0 ? peak - heap0 : 0) / 1e6;
  bm.counters["per_frame"] =
      benchmark::Counter(1, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  bm.SetLabel(who.peer ? "peer" : "proxima");
}

/// The floor of a frame: read every box (double to Real, as the updates do), make one 32-bit
/// key per box (its min x quantised over the world) and radix-sort (key, index) pairs, the
/// least work of a sort-based broad phase before any overlap test or output.
void run_floor(benchmark::State& bm, Loaded& w) {
  std::vector<BoxD> boxes;
  boxes_of(w.workload.boxes, boxes);
  const std::size_t n = boxes.size();
  std::vector<Aabb> stored(n);
  std::vector<std::uint64_t> keys(n);
  std::vector<std::uint64_t> scratch(n);
  const double scale = 4294967295.0 / std::max(1e-30, (w.workload.hi - w.workload.lo) * 1.25);
  for (auto _ : bm) {
    for (std::size_t i = 0; i < n; ++i) stored[i] = to_aabb(boxes[i]);
    for (std::size_t i = 0; i < n; ++i) {
      const double x = std::clamp((double(stored[i].min.x) - w.workload.lo) * scale + 1e8, 0.0, 4294967295.0);
      keys[i] = (std::uint64_t(x) << 32) | i;
    }
    std::uint64_t* src = keys.data();
    std::uint64_t* dst = scratch.data();
    for (int shift = 32; shift < 64; shift += 11) {
      std::size_t count[2048] = {};
      for (std::size_t i = 0; i < n; ++i) ++count[(src[i] >> shift) & 2047];
      std::size_t sum = 0;
      for (std::size_t& c : count) {
        const std::size_t v = c;
        c = sum;
        sum += v;
      }
      for (std::size_t i = 0; i < n; ++i) dst[count[(src[i] >> shift) & 2047]++] = src[i];
      std::swap(src, dst);
    }
    benchmark::DoNotOptimize(src[n / 2]);
  }
  bm.counters["ns_per_box"] =
      benchmark::Counter(double(n), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

std::vector<std::unique_ptr<Loaded>> g_loaded;

std::string short_name(const std::string& name) {
  const std::string prefix = "broadphase_";
  return name.rfind(prefix, 0) == 0 ? name.substr(prefix.size()) : name;
}

bool register_all(const std::string& dir, const std::vector<std::string>& large, bool large_peers) {
  std::vector<std::string> files;
  for (const char* f : {"broadphase_uniform_10k.txt", "broadphase_uniform_100k.txt", "broadphase_clustered_100k.txt"}) {
    files.push_back(proxima::bench::workload_path(dir, f));
  }
  files.insert(files.end(), large.begin(), large.end());
  const auto who = contestants();
  for (const std::string& path : files) {
    auto read = proxima::bench::read_broadphase(path);
    if (!read) return proxima::bench::report_load_error(read.error());
    auto w = std::make_unique<Loaded>();
    w->workload = std::move(*read);
    w->name = short_name(w->workload.name);
    w->frames = w->workload.frames;
    Loaded* lw = w.get();
    g_loaded.push_back(std::move(w));
    benchmark::RegisterBenchmark(("BroadPhase/" + lw->name + "/floor").c_str(), [lw](benchmark::State& st) {
      run_floor(st, *lw);
    })->Unit(benchmark::kMillisecond);
    for (const Mode mode : {Mode::Frame, Mode::Moving10, Mode::OneShot}) {
      const char* mode_name = mode == Mode::Frame ? "frame" : (mode == Mode::Moving10 ? "moving10" : "oneshot");
      for (const Contestant& c : who) {
        for (const int threads : {1, 2}) {
          if (threads == 2 && (!c.threaded || mode == Mode::Moving10)) continue;
          std::string name = "BroadPhase/" + lw->name + "/" + mode_name + "/" + c.name;
          if (threads == 2) name += "/threads:2";
          // The peers' slow cases: bt32BitAxisSweep3 inserts one box at a time into sorted
          // arrays (6 s for 10k boxes, quadratic): 10k only. Everyone runs 20 frames at
          // >= 100k boxes and 10 at >= 500k (checksums against references of those frames).
          const std::size_t n = lw->workload.boxes.size();
          if (c.name == "bullet_axis_sweep" && n > 20000) continue;
          if (c.peer && n >= 500000 && !large_peers) continue;
          // At >= 500k boxes: frame and one-shot only, without the structures meant for
          // other cases (BSP: static geometry; quadtree: flat worlds) or too slow there.
          if (n >= 500000 && (mode == Mode::Moving10 || c.name == "bsp" || c.name == "quadtree" || c.name == "octree" ||
                              c.name == "kdtree")) {
            continue;
          }
          const int frames =
              n >= 500000 ? std::min(10, lw->frames) : (n >= 100000 ? std::min(20, lw->frames) : lw->frames);
          auto* b = benchmark::RegisterBenchmark(name.c_str(), [lw, c, mode, threads, frames](benchmark::State& s) {
            run(s, *lw, c, mode, threads, frames);
          });
          b->Unit(benchmark::kMillisecond)->UseRealTime();
          b->Iterations(mode == Mode::OneShot ? 3 : frames);
        }
      }
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  // --large=FILE (repeatable): more W1 files, e.g. 1M boxes from proxima_make_workload;
  // --large-peers: also run the peers on files of >= 500k boxes (slow).
  std::vector<std::string> large;
  bool large_peers = false;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--large=", 0) == 0) {
      large.push_back(arg.substr(8));
    } else if (arg == "--large-peers") {
      large_peers = true;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  return proxima::bench::run_benchmarks(argc, argv,
                                        [&](const std::string& dir) { return register_all(dir, large, large_peers); });
}
