#pragma once
/// @file uniform_grid.hpp
/// Cell-based broad phases: UniformGrid ("grid", a dense grid over growing world bounds),
/// SpatialHash ("hash", cells hashed into an open-addressing table, unbounded worlds) and
/// HierarchicalGrid ("hgrid", hashed levels of doubling cell size for widely varying box
/// sizes). All three share one engine (detail::CellEngine).
///
/// Steps of find_pairs (Ericson, Real-Time Collision Detection, 7.1 and 7.2; Mirtich's
/// hierarchical hash grid for "hgrid"):
/// 1. If anything changed since the last build, bin every proxy: compute its integer cell
///    range per axis (monotone floor of (x - origin) / cell size, clamped), emit one entry per
///    covered cell, and counting-sort the entries by cell (boxes copied next to each other).
///    Boxes covering more than 64 cells go to an "oversized" list tested against everyone.
/// 2. In every cell, test every two entries; a pair is reported only in the cell that holds
///    the lower corner of the two cell ranges' intersection (on each axis the cell equals the
///    larger of the two lower cell indices), so each pair is found exactly once.
/// 3. hgrid: each box also probes the cells of every coarser occupied level that its box
///    covers, with the same once-only rule at that level.
/// 4. Sort the pairs by (lo, hi) (radix sort), so the output is deterministic.
///
/// Box and point queries use the cells when the structure is built (after find_pairs or
/// rebuild) and scan every proxy otherwise. Ray queries on the built dense grid march the
/// cells along the segment (O(cells crossed + boxes in them)); otherwise, and for the hashed
/// modes, they scan every proxy (slab test, O(n)).
/// Memory: O(largest id + entries + cells); after the first frames no allocation happens in
/// steady state (buffers keep their capacity).

#include <proxima/broadphase/broadphase.hpp>
#include <proxima/broadphase/broadphase_queries.hpp>
#include <proxima/broadphase/parallel_pairs.hpp>
#include <proxima/broadphase/proxy_table.hpp>
#include <proxima/core/executor.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace proxima {

namespace detail {

/// How an engine maps cell coordinates to cells.
enum class CellMode : std::uint8_t {
  Dense,         ///< dense array over the world bounds (UniformGrid)
  Hashed,        ///< one hashed level (SpatialHash)
  Hierarchical,  ///< hashed levels of doubling cell size (HierarchicalGrid)
};

/// The engine behind UniformGrid, SpatialHash and HierarchicalGrid (see the file comment).
class CellEngine : public BroadPhaseQueries<CellEngine> {
 public:
  /// `cell_size` <= 0 chooses it from the boxes at each build.
  CellEngine(CellMode mode, Real cell_size);

  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter);
  BroadPhaseStatus remove(ProxyId id);
  BroadPhaseStatus update(ProxyId id, const Aabb& box);
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates);
  void rebuild();
  using BroadPhaseQueries::find_pairs;
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor);
  // Cells (or a scan when unbuilt or too many cells); pairs_found is not counted.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_aabb(const Aabb& box, OnOverlap&& on_overlap) const;
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const;
  bool validate() const;
  std::size_t size() const { return proxies_.size(); }
  Real cell_size() const { return cell_; }
  std::size_t cell_count() const { return cell_start_.empty() ? 0 : cell_start_.size() - 1; }
  std::size_t entry_count() const { return entries_.size(); }
  std::size_t memory_bytes() const;

  /// One binned proxy in a cell: its box, id and the "lower cell" bits (bit k set when this
  /// cell is the proxy's lowest cell on axis k).
  struct Entry {
    Vec3 min;
    Vec3 max;
    ProxyId id = 0;
    std::uint32_t bits = 0;
  };

 private:
  friend class BroadPhaseQueries<CellEngine>;
  struct Range {
    std::int32_t lo[3];
    std::int32_t hi[3];
    std::int32_t level;
  };
  struct Slot {
    std::uint64_t key = kEmptyKey;
    std::uint32_t cell = 0;
  };
  /// A ray marched through the built dense grid (march_ray): the segment (double precision)
  /// clipped to the grid widened by `eps`, the slab axis `a` (largest direction component)
  /// and the other two, the first and last slab and the step between them.
  struct RayMarch {
    double o[3];
    double d[3];
    int a;
    int b;
    int c;
    double eps;
    double t_in;
    double t_out;
    std::int32_t first;
    std::int32_t last;
    std::int32_t step;
  };
  /// Cell rectangle (axes b, c) of one slab of a march, and where the segment enters it.
  struct SlabRect {
    std::int32_t lo[2];
    std::int32_t hi[2];
    double t0;
  };
  static constexpr std::uint64_t kEmptyKey = ~std::uint64_t(0);
  static constexpr std::uint32_t kNoCell = 0xffffffffu;

  void build();
  void choose_cell_size();
  Range range_of(const Aabb& box, int level) const;
  std::uint32_t find_cell(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z) const {
    if (mode_ == CellMode::Dense) return std::uint32_t((z * dims_[1] + y) * dims_[0] + x);
    return find_hashed_cell(level, x, y, z);
  }
  std::uint32_t find_hashed_cell(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z) const;
  std::uint32_t find_or_add_cell(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z);
  int level_of(const Aabb& box) const;
  void pairs_in_cells(std::uint32_t cell_begin, std::uint32_t cell_end, std::vector<ProxyPair>& out,
                      BroadPhaseStats& st) const;
  void pairs_across_levels(std::size_t begin, std::size_t end, std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  void pairs_oversized(std::size_t begin, std::size_t end, std::vector<ProxyPair>& out, BroadPhaseStats& st) const;
  bool cells_within_budget(const Aabb& box) const;
  template <class OnOverlap>
  bool scan_query(const Aabb& box, OnOverlap& on_overlap, BroadPhaseStats& st) const;
  template <class OnOverlap>
  bool query_cells(const Aabb& box, OnOverlap& on_overlap, BroadPhaseStats& st) const;
  template <class OnRay>
  static bool offer_ray(const Ray& ray, Real& limit, const Aabb& box, ProxyId id, OnRay& on_ray, BroadPhaseStats& st);
  bool start_march(const Ray& ray, Real max_t, RayMarch& m) const;
  bool slab_rect(const RayMarch& m, std::int32_t s, SlabRect& r) const;
  bool first_visit(const RayMarch& m, const Entry& e, std::int32_t s, std::int32_t u, std::int32_t v,
                   const SlabRect& r) const;
  template <class OnRay>
  bool march_slab(const RayMarch& m, std::int32_t s, const SlabRect& r, const Ray& ray, Real& limit, OnRay& on_ray,
                  BroadPhaseStats& st) const;
  template <class OnRay>
  bool march_ray(const Ray& ray, Real max_t, OnRay& on_ray, BroadPhaseStats& st) const;

  CellMode mode_;
  Real fixed_cell_;    // user cell size, <= 0 for automatic
  Real cell_ = 1;      // cell size of the last build (level 0 for hgrid)
  Real inv_cell_ = 1;  // 1 / cell_
  Vec3 origin_{0};     // dense grid origin (world bounds min)
  Aabb bounds_;        // dense grid world bounds (grow only, reset by rebuild())
  std::int32_t dims_[3] = {1, 1, 1};
  std::uint32_t level_mask_ = 0;  // hgrid: occupied levels
  bool dirty_ = true;

  detail::ProxyTable proxies_;
  std::vector<Range> ranges_;               // per dense slot
  std::vector<std::uint32_t> raw_cell_;     // per raw entry: cell index
  std::vector<std::uint32_t> raw_slot_;     // per raw entry: dense slot | bits << 29
  std::vector<std::uint32_t> cell_start_;   // cells + 1 offsets into entries_
  std::vector<std::uint64_t> cell_key_;     // hashed modes: key of each cell
  std::vector<Slot> table_;                 // hashed modes: key -> cell
  std::vector<Entry> entries_;              // entries sorted by cell
  std::vector<std::uint32_t> oversized_;    // dense slots of oversized proxies
  std::vector<std::uint8_t> is_oversized_;  // per dense slot
  PairChunkLists part_pairs_;               // per-part pair lists of the parallel find_pairs
  std::vector<ProxyPair> sort_scratch_;
  BroadPhaseStats stats_;
};

}  // namespace detail

/// The public face shared by the three cell structures: every operation goes to one
/// detail::CellEngine in mode `Mode` (costs in the file comment and the classes below).
template <detail::CellMode Mode>
class CellBroadPhase {
 public:
  /// `cell_size` <= 0: automatic (see the structure's class comment).
  explicit CellBroadPhase(Real cell_size = 0) : engine_(Mode, cell_size) {}

  /// Adds a proxy. O(1).
  BroadPhaseStatus insert(ProxyId id, const Aabb& box, ProxyKind kind = ProxyKind::Moving, ProxyFilter filter = {}) {
    return engine_.insert(id, box, kind, filter);
  }
  /// Removes a proxy. O(1).
  BroadPhaseStatus remove(ProxyId id) { return engine_.remove(id); }
  /// Moves a proxy. O(1) (binning happens at the next find_pairs / rebuild).
  BroadPhaseStatus update(ProxyId id, const Aabb& box) { return engine_.update(id, box); }
  /// Moves many proxies, all or nothing. O(m).
  BroadPhaseStatus update(std::span<const ProxyUpdate> updates) { return engine_.update(updates); }
  /// Re-chooses the cell size (and the dense grid's world bounds) and bins every proxy.
  void rebuild() { engine_.rebuild(); }
  /// Every pair, sorted (broadphase.hpp), on the calling thread.
  void find_pairs(std::vector<ProxyPair>& out) { engine_.find_pairs(out); }
  /// Every pair, sorted, with the cells split into parts run by `executor` (same output as
  /// serial).
  void find_pairs(std::vector<ProxyPair>& out, Executor& executor) { engine_.find_pairs(out, executor); }
  /// Proxies whose box overlaps `box` (closed), each once; returns the query's counters.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_aabb(const Aabb& box, OnOverlap&& on_overlap) const {
    return engine_.query_aabb(box, on_overlap);
  }
  /// Proxies whose box contains `point`, each once; returns the query's counters.
  template <OverlapCallback OnOverlap>
  BroadPhaseStats query_point(const Vec3& point, OnOverlap&& on_overlap) const {
    return engine_.query_point(point, on_overlap);
  }
  /// Proxies whose box the ray enters at t <= the current max fraction, each once. Built
  /// dense grid: O(cells crossed + their boxes); otherwise O(n). Returns the counters.
  template <RayCallback OnRay>
  BroadPhaseStats query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
    return engine_.query_ray(ray, max_t, on_ray);
  }
  /// Checks the proxy table and, when built, that every proxy sits in exactly its cells.
  bool validate() const { return engine_.validate(); }
  /// Counters of the last find_pairs.
  BroadPhaseStats stats() const { return engine_.stats(); }
  /// Number of proxies.
  std::size_t size() const { return engine_.size(); }
  /// Cell size of the last build (level 0 for the hierarchical grid).
  Real cell_size() const { return engine_.cell_size(); }
  /// Bytes held by the structure's buffers (capacity).
  std::size_t memory_bytes() const { return engine_.memory_bytes(); }

 private:
  detail::CellEngine engine_;
};

/// Dense uniform grid over the world bounds (which grow as boxes leave them; rebuild()
/// refits them). Best for bounded worlds of boxes of similar size. Cell size: the given one,
/// or 1.5 x the mean largest box extent; the grid has at most max(64, 2 n) cells (the cell
/// size grows when the bounds would need more). find_pairs: O(n + cells + k) for boxes of
/// similar size (k = candidate pairs in shared cells). Rays march the cells.
class UniformGrid : public CellBroadPhase<detail::CellMode::Dense> {
 public:
  using CellBroadPhase::CellBroadPhase;
};

/// Spatial hash: cells of a fixed (or automatic, as UniformGrid) size addressed by their
/// integer coordinates through an open-addressing hash table, so the world is unbounded and
/// memory follows the occupied cells only. Coordinates are clamped to +-2^18 cells (far
/// cells merge; results stay exact). Same costs as UniformGrid plus one hash probe per entry;
/// rays scan every proxy.
class SpatialHash : public CellBroadPhase<detail::CellMode::Hashed> {
 public:
  using CellBroadPhase::CellBroadPhase;
};

/// Hierarchical hash grid: level l has cells of size s 2^l (s: the given size, or the
/// smallest largest-extent of the boxes); a box lives at the lowest level whose cell is at
/// least its largest extent, so it covers at most 2 cells per axis there, and probes the
/// coarser occupied levels for partners. Up to 32 levels. Best when box sizes vary by orders
/// of magnitude (a few huge static boxes among many small ones). find_pairs: O(n L + k);
/// rays scan every proxy.
class HierarchicalGrid : public CellBroadPhase<detail::CellMode::Hierarchical> {
 public:
  using CellBroadPhase::CellBroadPhase;
};

namespace detail {

// ---- CellEngine queries (templates on the callback) --------------------------------------

template <class OnOverlap>
bool CellEngine::scan_query(const Aabb& box, OnOverlap& on_overlap, BroadPhaseStats& st) const {
  for (const ProxyId id : proxies_.ids()) {
    ++st.pairs_tested;
    if (proxies_[id].box.overlaps(box) && !on_overlap(id)) return false;
  }
  return true;
}

template <class OnOverlap>
bool CellEngine::query_cells(const Aabb& box, OnOverlap& on_overlap, BroadPhaseStats& st) const {
  const std::uint32_t levels = mode_ == CellMode::Hierarchical ? level_mask_ : 1u;
  for (std::uint32_t m = levels; m != 0; m &= m - 1) {
    const Range r = range_of(box, std::countr_zero(m));
    for (std::int32_t z = r.lo[2]; z <= r.hi[2]; ++z) {
      for (std::int32_t y = r.lo[1]; y <= r.hi[1]; ++y) {
        for (std::int32_t x = r.lo[0]; x <= r.hi[0]; ++x) {
          const std::uint32_t c = find_cell(r.level, x, y, z);
          if (c == kNoCell) continue;
          ++st.nodes_visited;
          // Report an entry only in the lowest cell of the intersection of the two ranges.
          const std::uint32_t bits = (x == r.lo[0] ? 1u : 0u) | (y == r.lo[1] ? 2u : 0u) | (z == r.lo[2] ? 4u : 0u);
          for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
            const Entry& o = entries_[i];
            ++st.pairs_tested;
            if ((bits | o.bits) != 7u || !Aabb{o.min, o.max}.overlaps(box)) continue;
            if (!on_overlap(o.id)) return false;
          }
        }
      }
    }
  }
  return true;
}

template <OverlapCallback OnOverlap>
BroadPhaseStats CellEngine::query_aabb(const Aabb& box, OnOverlap&& on_overlap) const {
  BroadPhaseStats st;
  if (!box.is_valid()) return st;
  // Unbuilt, or cell ranges covering too many cells: scan every proxy.
  if (dirty_ || proxies_.size() == 0 || !cells_within_budget(box)) {
    scan_query(box, on_overlap, st);
    return st;
  }
  if (!query_cells(box, on_overlap, st)) return st;
  const auto ids = proxies_.ids();
  for (const std::uint32_t s : oversized_) {
    ++st.pairs_tested;
    if (proxies_[ids[s]].box.overlaps(box) && !on_overlap(ids[s])) break;
  }
  return st;
}

template <class OnRay>
bool CellEngine::offer_ray(const Ray& ray, Real& limit, const Aabb& box, ProxyId id, OnRay& on_ray,
                           BroadPhaseStats& st) {
  ++st.pairs_tested;
  Real t = 0;
  if (!ray_enters_box(ray, limit, box, t)) return true;
  const Real next = on_ray(id, t);
  if (next < 0) return true;
  if (next == 0) return false;
  limit = std::min(limit, next);
  return true;
}

template <class OnRay>
bool CellEngine::march_slab(const RayMarch& m, std::int32_t s, const SlabRect& r, const Ray& ray, Real& limit,
                            OnRay& on_ray, BroadPhaseStats& st) const {
  std::int32_t xyz[3];
  xyz[m.a] = s;
  for (std::int32_t u = r.lo[0]; u <= r.hi[0]; ++u) {
    for (std::int32_t v = r.lo[1]; v <= r.hi[1]; ++v) {
      xyz[m.b] = u;
      xyz[m.c] = v;
      const std::uint32_t cell = find_cell(0, xyz[0], xyz[1], xyz[2]);
      ++st.nodes_visited;
      for (std::uint32_t i = cell_start_[cell]; i < cell_start_[cell + 1]; ++i) {
        const Entry& e = entries_[i];
        if (!first_visit(m, e, s, u, v, r)) continue;
        if (!offer_ray(ray, limit, Aabb{e.min, e.max}, e.id, on_ray, st)) return false;
      }
    }
  }
  return true;
}

template <class OnRay>
bool CellEngine::march_ray(const Ray& ray, Real max_t, OnRay& on_ray, BroadPhaseStats& st) const {
  RayMarch m{};
  if (!start_march(ray, max_t, m)) return false;
  Real limit = max_t;
  if (m.t_in <= m.t_out) {
    for (std::int32_t s = m.first;; s += m.step) {
      SlabRect r{};
      if (slab_rect(m, s, r)) {
        if (r.t0 > double(limit) + m.eps / std::abs(m.d[m.a])) break;  // later slabs start later still
        if (!march_slab(m, s, r, ray, limit, on_ray, st)) return true;
      }
      if (s == m.last) break;
    }
  }
  const auto ids = proxies_.ids();
  for (const std::uint32_t slot : oversized_) {
    if (!offer_ray(ray, limit, proxies_[ids[slot]].box, ids[slot], on_ray, st)) return true;
  }
  return true;
}

template <RayCallback OnRay>
BroadPhaseStats CellEngine::query_ray(const Ray& ray, Real max_t, OnRay&& on_ray) const {
  BroadPhaseStats st;
  if (!detail::ray_input_ok(ray, max_t)) return st;
  if (mode_ == CellMode::Dense && !dirty_ && proxies_.size() != 0 && march_ray(ray, max_t, on_ray, st)) return st;
  Real limit = max_t;
  for (const ProxyId id : proxies_.ids()) {
    if (!offer_ray(ray, limit, proxies_[id].box, id, on_ray, st)) break;
  }
  return st;
}

}  // namespace detail

static_assert(BroadPhaseStructure<UniformGrid>);
static_assert(BroadPhaseStructure<SpatialHash>);
static_assert(BroadPhaseStructure<HierarchicalGrid>);

}  // namespace proxima
