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
//                runs, a double-precision grid search otherwise; 2 when it equals the
//                reference of the boxes rounded to proxima::Real, which a float build and
//                Bullet see; 0 otherwise), build_ms (insert all, CPU), mem_MB
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
#include <proxima/broadphase/region_quadtree.hpp>
#include <proxima/broadphase/uniform_grid.hpp>
#include <proxima/core/executor.hpp>

#include <csignal>
#include <ctime>
#include <fstream>
#include <malloc.h>
#include <poll.h>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>
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

#include "bench_main.hpp"
#include "support/w1_grid_pairs.hpp"
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

/// True when S offers find_pairs(out, executor).
template <class S>
constexpr bool kParallel = requires(S& s, std::vector<ProxyPair>& out, proxima::Executor& executor) {
  s.find_pairs(out, executor);
};

/// The executor of a run on `threads` threads: the serial executor for 1, else a ThreadPool
/// started once per thread count and kept for the whole program (outside the timings). The
/// parent of run_large's child processes starts none before forking (only runners use it).
proxima::Executor& executor_for(int threads) {
  if (threads <= 1) return proxima::serial_executor();
  static std::map<int, std::unique_ptr<proxima::ThreadPool>> pools;
  std::unique_ptr<proxima::ThreadPool>& pool = pools[threads];
  if (!pool) pool = std::make_unique<proxima::ThreadPool>(std::size_t(threads));
  return *pool;
}

/// A Proxima structure (templated: no virtual call inside).
template <class S>
class ProximaRunner final : public Runner {
 public:
  explicit ProximaRunner(int threads) : executor_(&executor_for(threads)) {}
  void build(const std::vector<BoxD>& boxes) override {
    s_ = std::make_unique<S>();
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
      s_->find_pairs(pairs_, *executor_);
    } else {
      s_->find_pairs(pairs_);
    }
  }
  const std::vector<ProxyPair>& pairs() const override { return pairs_; }

 private:
  proxima::Executor* executor_;
  std::unique_ptr<S> s_;
  std::vector<ProxyUpdate> updates_;
  std::vector<ProxyPair> pairs_;
};

#if defined(PROXIMA_BENCH_HAVE_REGISTRY)
/// A Proxima structure through the type-erased registry (one virtual call per operation).
class RegistryRunner final : public Runner {
 public:
  RegistryRunner(std::string name, int threads) : name_(std::move(name)), executor_(&executor_for(threads)) {}
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
  void find_pairs() override { s_->find_pairs(pairs_, *executor_); }
  const std::vector<ProxyPair>& pairs() const override { return pairs_; }

 private:
  std::string name_;
  proxima::Executor* executor_;
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
  proxima("region_quadtree", std::type_identity<proxima::RegionQuadtree>{});
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

/// Every overlapping pair of the boxes (closed, double; rounded to Real first when `round`,
/// which is what a float build stores) into `sum`, by w1_grid_pairs (linear at constant
/// density; a sweep on one axis is O(n^(5/3)) there: 10^10 tests per frame at 1M boxes,
/// which is why the first 1M runs never finished their reference).
void add_rounded_pairs(const std::vector<BroadphaseBox>& state, PairChecksum& sum, bool round = true) {
  std::vector<BoxD> boxes;
  boxes_of(state, boxes);
  if (round) {
    for (BoxD& b : boxes) {
      for (int k = 0; k < 3; ++k) {
        b.lo[k] = double(Real(b.lo[k]));
        b.hi[k] = double(Real(b.hi[k]));
      }
    }
  }
  proxima::bench::w1_grid_pairs(boxes, sum);
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
    // CPU time of the build (the machine may be shared; builds run on one thread).
    timespec t0{}, t1{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t0);
    runner->build(boxes);
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t1);
    build_ms = double(t1.tv_sec - t0.tv_sec) * 1e3 + double(t1.tv_nsec - t0.tv_nsec) * 1e-6;
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
struct FloorBuffers {
  std::vector<BoxD> boxes;
  std::vector<Aabb> stored;
  std::vector<std::uint64_t> keys;
  std::vector<std::uint64_t> scratch;
};

void floor_pass(const Loaded& w, FloorBuffers& f) {
  const std::size_t n = f.boxes.size();
  const double scale = 4294967295.0 / std::max(1e-30, (w.workload.hi - w.workload.lo) * 1.25);
  for (std::size_t i = 0; i < n; ++i) f.stored[i] = to_aabb(f.boxes[i]);
  for (std::size_t i = 0; i < n; ++i) {
    const double x = std::clamp((double(f.stored[i].min.x) - w.workload.lo) * scale + 1e8, 0.0, 4294967295.0);
    f.keys[i] = (std::uint64_t(x) << 32) | i;
  }
  std::uint64_t* src = f.keys.data();
  std::uint64_t* dst = f.scratch.data();
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

FloorBuffers floor_buffers(const Loaded& w) {
  FloorBuffers f;
  boxes_of(w.workload.boxes, f.boxes);
  f.stored.resize(f.boxes.size());
  f.keys.resize(f.boxes.size());
  f.scratch.resize(f.boxes.size());
  return f;
}

void run_floor(benchmark::State& bm, Loaded& w) {
  FloorBuffers f = floor_buffers(w);
  for (auto _ : bm) floor_pass(w, f);
  bm.counters["ns_per_box"] = benchmark::Counter(
      double(f.boxes.size()), benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
}

/// CPU seconds of this process (all threads).
double process_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

double wall_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }

/// CPU seconds (user + system) used so far by child process `pid`, from /proc (0 if gone).
double child_cpu_s(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text;
  std::getline(in, text);
  const std::size_t close = text.rfind(')');
  if (close == std::string::npos) return 0;
  std::istringstream f(text.substr(close + 2));
  std::string field;
  double user = 0, system = 0;
  for (int k = 3; k <= 15 && (f >> field); ++k) {
    if (k == 14) user = std::stod(field);
    if (k == 15) system = std::stod(field);
  }
  return (user + system) / double(sysconf(_SC_CLK_TCK));
}

/// Large-workload runs (--large=FILE): each structure and peer runs `frames` frames in a
/// forked child under a time budget, so that a structure far too slow at this size is
/// stopped and recorded as such ("> X s") instead of holding the whole run. The child
/// reports over a pipe, one line per step:
///   build <wall ms> <cpu ms>  |  frame <cpu ms> <wall ms> <pairs>  |  end <check> <mem MB>
/// The budget is CPU time. The child stops by itself after the frame during which the budget
/// ran out; the parent kills it 5 CPU seconds after the budget (a build or a frame that
/// alone takes longer) or after 4 budgets of wall time.
void large_child(int fd, Loaded& w, const Contestant& who, int threads, int frames, double budget_s,
                 const std::vector<PairChecksum>& exact, const std::vector<PairChecksum>& rounded) {
  auto say = [fd](const std::string& line) {
    const std::string text = line + "\n";
    if (write(fd, text.data(), text.size()) < 0) _exit(3);
  };
  const double start = wall_s();
  const double cpu_start = process_cpu_s();
  const std::size_t heap0 = heap_bytes();
  std::vector<BroadphaseBox> state = w.workload.boxes;
  std::vector<BoxD> boxes;
  std::vector<std::uint32_t> moved;
  boxes_of(state, boxes);
  std::unique_ptr<Runner> runner = who.make(threads);
  const double c0 = process_cpu_s();
  runner->build(boxes);
  const double c1 = process_cpu_s();
  say("build " + std::to_string((wall_s() - start) * 1e3) + " " + std::to_string((c1 - c0) * 1e3));
  std::size_t peak = heap_bytes();
  PairChecksum sum;
  int done = 0;
  for (int f = 0; f < frames; ++f) {
    advance(w, state, Mode::Frame, moved);
    boxes_of(state, boxes);
    const double a0 = process_cpu_s();
    const double b0 = wall_s();
    runner->update(boxes, moved);
    runner->find_pairs();
    const double a1 = process_cpu_s();
    const double b1 = wall_s();
    PairChecksum frame_sum;
    for (const ProxyPair& p : runner->pairs()) frame_sum.add(p.lo, p.hi, state.size());
    sum.merge(frame_sum);
    peak = std::max(peak, heap_bytes());
    ++done;
    say("frame " + std::to_string((a1 - a0) * 1e3) + " " + std::to_string((b1 - b0) * 1e3) + " " +
        std::to_string(frame_sum.pairs));
    if (process_cpu_s() - cpu_start > budget_s) break;
  }
  const int check = sum == exact[std::size_t(done)] ? 1 : (sum == rounded[std::size_t(done)] ? 2 : 0);
  say("end " + std::to_string(check) + " " + std::to_string(double(peak > heap0 ? peak - heap0 : 0) / 1e6) + " " +
      std::to_string((double(exact[std::size_t(done)].pairs) - double(sum.pairs)) / double(std::max(1, done))));
}

/// Runs every contestant on one large file (see large_child) and appends one JSON object per
/// run, in Google Benchmark's layout plus `frames_done` and `over_budget` (1: stopped by the
/// budget; cpu_time is then a lower bound when no frame finished).
void run_large(Loaded& w, int frames, double budget_s, int max_threads, const std::string& only,
               std::vector<std::string>& json) {
  frames = std::min(frames, w.frames);
  // Cumulative references after 0..frames frames (a stopped run is checked on its frames).
  std::vector<PairChecksum> exact(1), rounded(1);
  {
    const double t0 = wall_s();
    std::vector<BroadphaseBox> state = w.workload.boxes;
    std::vector<std::uint32_t> moved;
    for (int f = 0; f < frames; ++f) {
      advance(w, state, Mode::Frame, moved);
      PairChecksum e = exact.back(), r = rounded.back();
      add_rounded_pairs(state, e, false);
      add_rounded_pairs(state, r, true);
      exact.push_back(e);
      rounded.push_back(r);
    }
    std::cerr << w.name << ": reference of " << frames << " frames in " << (wall_s() - t0) << " s, "
              << double(exact.back().pairs) / frames << " pairs per frame\n";
  }
  {
    // The floor at this size (see run_floor): 3 passes, the fastest kept.
    FloorBuffers f = floor_buffers(w);
    double best = 1e300;
    for (int k = 0; k < 3; ++k) {
      const double c0 = process_cpu_s();
      floor_pass(w, f);
      best = std::min(best, process_cpu_s() - c0);
    }
    std::ostringstream o;
    o << "{\"name\": \"BroadPhase/" << w.name << "/floor\", \"run_type\": \"iteration\", \"iterations\": 3"
      << ", \"real_time\": " << best * 1e3 << ", \"cpu_time\": " << best * 1e3 << ", \"time_unit\": \"ms\"}";
    json.push_back(o.str());
  }
  for (const Contestant& c : contestants()) {
    if (!only.empty() && ("," + only + ",").find("," + c.name + ",") == std::string::npos) continue;
    bool one_thread_over = false;
    for (const int threads : {1, 2}) {
      // Two threads only where one thread finished within the budget.
      if (threads == 2 && (!c.threaded || one_thread_over || max_threads < 2)) continue;
      int fds[2];
      if (pipe(fds) != 0) throw std::runtime_error("pipe");
      std::cout.flush();
      std::cerr.flush();
      const pid_t pid = fork();
      if (pid == 0) {
        close(fds[0]);
        try {
          large_child(fds[1], w, c, threads, frames, budget_s, exact, rounded);
        } catch (const std::exception& e) {
          std::cerr << c.name << ": " << e.what() << "\n";
          _exit(2);
        }
        _exit(0);
      }
      close(fds[1]);
      const double start = wall_s();
      std::string text;
      bool killed = false;
      double child_cpu = 0;
      for (;;) {
        // The budget is CPU time (the machine may be shared): the child's CPU time is read
        // from /proc; it is killed once over budget + 5 s, or after 4 budgets of wall time.
        child_cpu = child_cpu_s(pid);
        const double left = std::min(budget_s + 5 - child_cpu, 4 * budget_s - (wall_s() - start));
        if (left <= 0) {
          kill(pid, SIGKILL);
          killed = true;
          break;
        }
        pollfd p{fds[0], POLLIN, 0};
        if (poll(&p, 1, int(std::min(left, 1.0) * 1000) + 1) > 0) {
          char buf[4096];
          const ssize_t got = read(fds[0], buf, sizeof buf);
          if (got <= 0) break;
          text.append(buf, std::size_t(got));
        }
      }
      close(fds[0]);
      int status = 0;
      waitpid(pid, &status, 0);
      const double elapsed = wall_s() - start;
      // Parse the child's lines.
      double build_ms = -1, build_cpu = -1, cpu = 0, wall = 0, pairs = 0, mem = 0, missing = 0;
      int done = 0, check = -1;
      std::istringstream in(text);
      std::string line;
      while (std::getline(in, line)) {
        std::istringstream f(line);
        std::string tag;
        f >> tag;
        if (tag == "build") f >> build_ms >> build_cpu;
        if (tag == "frame") {
          double a = 0, b = 0, p = 0;
          f >> a >> b >> p;
          cpu += a;
          wall += b;
          pairs += p;
          ++done;
        }
        if (tag == "end") f >> check >> mem >> missing;
      }
      const bool over = killed || done < frames;
      if (threads == 1) one_thread_over = over;
      double cpu_ms = done > 0 ? cpu / done : 0;
      double wall_ms = done > 0 ? wall / done : 0;
      if (done == 0) {
        // No frame finished: the frame took at least the CPU time left after the build.
        cpu_ms = (child_cpu - std::max(0.0, build_cpu) / 1e3) * 1e3;
        wall_ms = (elapsed - std::max(0.0, build_ms) / 1e3) * 1e3;
      }
      std::string name = "BroadPhase/" + w.name + "/frame/" + c.name;
      if (threads == 2) name += "/threads:2";
      std::ostringstream o;
      o << "{\"name\": \"" << name << "\", \"run_type\": \"iteration\", \"iterations\": " << done
        << ", \"real_time\": " << wall_ms << ", \"cpu_time\": " << cpu_ms << ", \"time_unit\": \"ms\""
        << ", \"build_ms\": " << (build_ms < 0 ? elapsed * 1e3 : build_ms)
        << ", \"build_cpu_ms\": " << (build_cpu < 0 ? child_cpu * 1e3 : build_cpu)
        << ", \"build_done\": " << (build_ms >= 0) << ", \"pairs\": " << (done > 0 ? pairs / done : 0)
        << ", \"check\": " << check << ", \"mem_MB\": " << mem << ", \"missing\": " << missing
        << ", \"frames_done\": " << done << ", \"over_budget\": " << int(over) << ", \"budget_s\": " << budget_s
        << ", \"label\": \"" << (c.peer ? "peer" : "proxima") << "\"}";
      json.push_back(o.str());
      std::cout << o.str() << std::endl;
    }
  }
}

std::vector<std::unique_ptr<Loaded>> g_loaded;

std::string short_name(const std::string& name) {
  const std::string prefix = "broadphase_";
  return name.rfind(prefix, 0) == 0 ? name.substr(prefix.size()) : name;
}

bool register_all(const std::string& dir) {
  std::vector<std::string> files;
  for (const char* f : {"broadphase_uniform_10k.txt", "broadphase_uniform_100k.txt", "broadphase_clustered_100k.txt"}) {
    files.push_back(proxima::bench::workload_path(dir, f));
  }
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
          // bt32BitAxisSweep3 inserts one box at a time into sorted arrays (1.5 s of CPU
          // for 10k boxes, quadratic): 10k only here; the --large runs try it under a budget.
          const std::size_t n = lw->workload.boxes.size();
          if (c.name == "bullet_axis_sweep" && n > 20000) continue;
          const int frames = n >= 100000 ? std::min(20, lw->frames) : lw->frames;
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
  // --large=FILE (repeatable): W1 files of any size (e.g. 1M boxes from
  // proxima_make_workload), every structure and peer run in a child process under a budget
  // (run_large); --large-frames=N (default 5), --large-budget=S CPU seconds per run (default
  // 60), --large-threads=1 (no two-thread runs),
  // --large-only=a,b (those contestants only), --large-out=FILE (JSON, default
  // bench_broadphase_large.json); with any --large the Google Benchmark runs on the shared
  // files are skipped unless --standard is given too.
  std::vector<std::string> large;
  int large_frames = 5;
  int large_threads = 2;
  double budget = 60;
  std::string only;
  std::string large_out = "bench_broadphase_large.json";
  bool standard = false;
  int kept = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--large=", 0) == 0) {
      large.push_back(arg.substr(8));
    } else if (arg.rfind("--large-frames=", 0) == 0) {
      large_frames = std::stoi(arg.substr(15));
    } else if (arg.rfind("--large-threads=", 0) == 0) {
      large_threads = std::stoi(arg.substr(16));
    } else if (arg.rfind("--large-budget=", 0) == 0) {
      budget = std::stod(arg.substr(15));
    } else if (arg.rfind("--large-only=", 0) == 0) {
      only = arg.substr(13);
    } else if (arg.rfind("--large-out=", 0) == 0) {
      large_out = arg.substr(12);
    } else if (arg == "--standard") {
      standard = true;
    } else {
      argv[kept++] = argv[i];
    }
  }
  argc = kept;
  if (!large.empty()) {
    std::vector<std::string> json;
    for (const std::string& path : large) {
      auto read = proxima::bench::read_broadphase(path);
      if (!read) return proxima::bench::report_load_error(read.error()) ? 0 : 1;
      Loaded w;
      w.workload = std::move(*read);
      w.name = short_name(w.workload.name);
      w.frames = w.workload.frames;
      run_large(w, large_frames, budget, large_threads, only, json);
    }
    std::ofstream out(large_out);
    out << "{\"context\": {\"large_frames\": " << large_frames << ", \"budget_s\": " << budget
        << ", \"proxima_real\": \"" << (sizeof(Real) == 4 ? "float" : "double") << "\"},\n \"benchmarks\": [\n";
    for (std::size_t i = 0; i < json.size(); ++i) out << "  " << json[i] << (i + 1 < json.size() ? ",\n" : "\n");
    out << "]}\n";
    if (!standard) return 0;
  }
  return proxima::bench::run_benchmarks(argc, argv, [&](const std::string& dir) { return register_all(dir); });
}
