/// @file uniform_grid.cpp
/// The cell engine behind UniformGrid, SpatialHash and HierarchicalGrid.
///
/// Steps (Ericson, Real-Time Collision Detection, 7.1-7.2; Mirtich 1996 for the hierarchy):
/// 1. choose the cell size (given, or from the box sizes) and, for the dense grid, the world
///    bounds (grow only) and the cell counts per axis;
/// 2. compute each proxy's integer cell range (monotone floor, clamped, so overlapping boxes
///    always share a cell) and its level (hgrid);
/// 3. emit one entry per covered cell (dense index, or a hash-table cell for the hashed
///    modes) and counting-sort the entries by cell, copying the boxes next to each other;
/// 4. test every two entries of a cell; report a pair only in the cell that is, on every
///    axis, the larger of the two ranges' lower cells (each entry carries three bits "this is
///    my lower cell on axis k": the rule is bits_a | bits_b == 0b111);
/// 5. hgrid: probe coarser levels per box; oversized boxes (> 64 cells) test everyone;
/// 6. radix-sort the pairs.
/// Ray queries on the built dense grid march the cells along the segment (march_ray, a
/// conservative 3D DDA after Amanatides and Woo, "A fast voxel traversal algorithm", 1987).

#include <proxima/broadphase/uniform_grid.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>

#include "broadphase/structure_support.hpp"

namespace proxima::detail {

namespace {

constexpr std::int64_t kMaxCellsPerProxy = 64;
constexpr std::int32_t kHashHalfRange = 1 << 18;  // hashed coordinates in [-2^18, 2^18)
constexpr int kMaxLevels = 32;

std::uint64_t pack_key(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z) {
  return (std::uint64_t(level) << 57) | (std::uint64_t(x + kHashHalfRange) << 38) |
         (std::uint64_t(y + kHashHalfRange) << 19) | std::uint64_t(z + kHashHalfRange);
}

void unpack_key(std::uint64_t key, std::int32_t& level, std::int32_t& x, std::int32_t& y, std::int32_t& z) {
  constexpr std::uint64_t mask = (std::uint64_t(1) << 19) - 1;
  level = std::int32_t(key >> 57);
  x = std::int32_t((key >> 38) & mask) - kHashHalfRange;
  y = std::int32_t((key >> 19) & mask) - kHashHalfRange;
  z = std::int32_t(key & mask) - kHashHalfRange;
}

std::uint64_t hash_key(std::uint64_t key) {
  key ^= key >> 31;
  key *= 0xbf58476d1ce4e5b9ull;
  key ^= key >> 29;
  return key;
}

bool overlaps(const Vec3& amin, const Vec3& amax, const Vec3& bmin, const Vec3& bmax) {
  return amin.x <= bmax.x && bmin.x <= amax.x && amin.y <= bmax.y && bmin.y <= amax.y && amin.z <= bmax.z &&
         bmin.z <= amax.z;
}

Real max_extent(const Aabb& box) {
  const Vec3 e = box.extents();
  return std::max(e.x, std::max(e.y, e.z));
}

}  // namespace

CellEngine::CellEngine(CellMode mode, Real cell_size) : mode_(mode), fixed_cell_(cell_size) {}

BroadPhaseStatus CellEngine::insert(ProxyId id, const Aabb& box, ProxyKind kind, ProxyFilter filter) {
  const BroadPhaseStatus status = proxies_.insert(id, box, kind, filter);
  if (status == BroadPhaseStatus::Ok) dirty_ = true;
  return status;
}

BroadPhaseStatus CellEngine::remove(ProxyId id) {
  const BroadPhaseStatus status = proxies_.remove(id);
  if (status == BroadPhaseStatus::Ok) dirty_ = true;
  return status;
}

BroadPhaseStatus CellEngine::update(ProxyId id, const Aabb& box) {
  const BroadPhaseStatus status = proxies_.check_update(id, box);
  if (status != BroadPhaseStatus::Ok) return status;
  proxies_[id].box = box;
  dirty_ = true;
  return status;
}

BroadPhaseStatus CellEngine::update(std::span<const ProxyUpdate> updates) {
  const BroadPhaseStatus status = proxies_.check_updates(updates);
  if (status != BroadPhaseStatus::Ok) return status;
  for (const ProxyUpdate& u : updates) proxies_[u.id].box = u.box;
  if (!updates.empty()) dirty_ = true;
  return status;
}

void CellEngine::rebuild() {
  bounds_ = Aabb::empty();
  build();
}

void CellEngine::choose_cell_size() {
  const auto ids = proxies_.ids();
  const std::size_t n = ids.size();
  Real sum = 0;
  Real smallest = kRealMax;
  Real smallest_positive = kRealMax;
  Real largest = 0;
  Aabb world = Aabb::empty();
  for (const ProxyId id : ids) {
    const Aabb& box = proxies_[id].box;
    const Real e = max_extent(box);
    sum += e;
    smallest = std::min(smallest, e);
    if (e > 0) smallest_positive = std::min(smallest_positive, e);
    largest = std::max(largest, e);
    world.grow(box);
  }
  const Real world_extent = max_extent(world);
  const Real world_reach = std::max(max_abs_component(world.min), max_abs_component(world.max));
  Real base = fixed_cell_;
  if (!(base > 0)) {
    if (mode_ == CellMode::Hierarchical) {
      base = smallest > 0 ? smallest : smallest_positive;
    } else {
      base = Real(1.5) * (sum / Real(n));
    }
  }
  if (!(base > 0) || base == kRealMax) {
    base = world_extent > 0 ? world_extent / std::cbrt(Real(n)) : Real(1);
  }
  if (mode_ != CellMode::Dense) {
    // Keep coordinates within the hashed range where possible (clamping stays exact).
    base = std::max(base, world_reach * Real(1.0 / double(kHashHalfRange)));
  }
  if (mode_ == CellMode::Hierarchical) {
    base = std::max(base, std::ldexp(largest, -(kMaxLevels - 1)));
  }
  if (mode_ == CellMode::Dense) {
    bounds_.grow(world);
    origin_ = bounds_.min;
    const Vec3 ext = bounds_.extents();
    const double max_cells = std::max(64.0, 2.0 * double(n));
    for (;;) {
      double total = 1;
      for (int k = 0; k < 3; ++k) {
        const double d = std::min(std::ceil(double(ext[k]) / double(base)), 1048576.0);
        dims_[k] = std::max(1, int(d));
        total *= double(dims_[k]);
      }
      if (total <= max_cells) break;
      base *= Real(1.26);
    }
  }
  // A cell below the smallest normal number (a fixed size of 1e-310, or a world of points
  // at one place) has an infinite inverse, and an offset of 0 times it is NaN.
  base = std::max(base, std::numeric_limits<Real>::min());
  cell_ = base;
  inv_cell_ = Real(1) / base;
}

CellEngine::Range CellEngine::range_of(const Aabb& box, int level) const {
  Range r{};
  r.level = level;
  const Real inv = level == 0 ? inv_cell_ : std::ldexp(inv_cell_, -level);
  for (int k = 0; k < 3; ++k) {
    Real lo;
    Real hi;
    Real top;
    Real bottom;
    if (mode_ == CellMode::Dense) {
      lo = std::floor((box.min[k] - origin_[k]) * inv);
      hi = std::floor((box.max[k] - origin_[k]) * inv);
      bottom = 0;
      top = Real(dims_[k] - 1);
    } else {
      lo = std::floor(box.min[k] * inv);
      hi = std::floor(box.max[k] * inv);
      bottom = Real(-kHashHalfRange);
      top = Real(kHashHalfRange - 1);
    }
    r.lo[k] = std::int32_t(std::clamp(lo, bottom, top));
    r.hi[k] = std::int32_t(std::clamp(hi, bottom, top));
  }
  return r;
}

int CellEngine::level_of(const Aabb& box) const {
  const Real e = max_extent(box);
  Real s = cell_;
  int level = 0;
  while (s < e && level < kMaxLevels - 1) {
    s *= 2;
    ++level;
  }
  return level;
}

std::uint32_t CellEngine::find_hashed_cell(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z) const {
  if (table_.empty()) return kNoCell;
  const std::uint64_t key = pack_key(level, x, y, z);
  const std::size_t mask = table_.size() - 1;
  for (std::size_t h = hash_key(key) & mask;; h = (h + 1) & mask) {
    if (table_[h].key == key) return table_[h].cell;
    if (table_[h].key == kEmptyKey) return kNoCell;
  }
}

std::uint32_t CellEngine::find_or_add_cell(std::int32_t level, std::int32_t x, std::int32_t y, std::int32_t z) {
  if (mode_ == CellMode::Dense) return std::uint32_t((z * dims_[1] + y) * dims_[0] + x);
  const std::uint64_t key = pack_key(level, x, y, z);
  const std::size_t mask = table_.size() - 1;
  for (std::size_t h = hash_key(key) & mask;; h = (h + 1) & mask) {
    if (table_[h].key == key) return table_[h].cell;
    if (table_[h].key == kEmptyKey) {
      table_[h].key = key;
      table_[h].cell = std::uint32_t(cell_key_.size());
      cell_key_.push_back(key);
      return table_[h].cell;
    }
  }
}

void CellEngine::build() {
  dirty_ = false;
  const auto ids = proxies_.ids();
  const std::size_t n = ids.size();
  ranges_.resize(n);
  is_oversized_.assign(n, 0);
  oversized_.clear();
  level_mask_ = 0;
  cell_key_.clear();
  if (n == 0) {
    entries_.clear();
    cell_start_.assign(1, 0);
    table_.clear();
    return;
  }
  choose_cell_size();

  // Pass 1: ranges, levels and the number of entries.
  std::size_t total = 0;
  for (std::size_t s = 0; s < n; ++s) {
    const Aabb& box = proxies_[ids[s]].box;
    const int level = mode_ == CellMode::Hierarchical ? level_of(box) : 0;
    const Range r = range_of(box, level);
    ranges_[s] = r;
    const std::int64_t count =
        std::int64_t(r.hi[0] - r.lo[0] + 1) * std::int64_t(r.hi[1] - r.lo[1] + 1) * std::int64_t(r.hi[2] - r.lo[2] + 1);
    if (count > kMaxCellsPerProxy) {
      is_oversized_[s] = 1;
      oversized_.push_back(std::uint32_t(s));
      continue;
    }
    level_mask_ |= 1u << level;
    total += std::size_t(count);
  }

  if (mode_ != CellMode::Dense) {
    std::size_t capacity = 64;
    while (capacity < 2 * total) capacity *= 2;
    table_.resize(capacity);
    std::fill(table_.begin(), table_.end(), Slot{});
  }

  // Pass 2: raw entries (cell, slot | bits << 29).
  raw_cell_.resize(total);
  raw_slot_.resize(total);
  std::size_t k = 0;
  for (std::size_t s = 0; s < n; ++s) {
    if (is_oversized_[s] != 0) continue;
    const Range& r = ranges_[s];
    for (std::int32_t z = r.lo[2]; z <= r.hi[2]; ++z) {
      for (std::int32_t y = r.lo[1]; y <= r.hi[1]; ++y) {
        for (std::int32_t x = r.lo[0]; x <= r.hi[0]; ++x) {
          const std::uint32_t bits = (x == r.lo[0] ? 1u : 0u) | (y == r.lo[1] ? 2u : 0u) | (z == r.lo[2] ? 4u : 0u);
          raw_cell_[k] = find_or_add_cell(r.level, x, y, z);
          raw_slot_[k] = std::uint32_t(s) | (bits << 29);
          ++k;
        }
      }
    }
  }

  // Counting sort by cell.
  const std::size_t cells = mode_ == CellMode::Dense
                                ? std::size_t(dims_[0]) * std::size_t(dims_[1]) * std::size_t(dims_[2])
                                : cell_key_.size();
  cell_start_.assign(cells + 1, 0);
  for (std::size_t e = 0; e < total; ++e) ++cell_start_[raw_cell_[e]];
  std::uint32_t sum = 0;
  for (std::size_t c = 0; c < cells; ++c) {
    const std::uint32_t v = cell_start_[c];
    cell_start_[c] = sum;
    sum += v;
  }
  cell_start_[cells] = sum;
  entries_.resize(total);
  for (std::size_t e = 0; e < total; ++e) {
    const std::uint32_t slot = raw_slot_[e] & 0x1fffffffu;
    const ProxyId id = ids[slot];
    const Aabb& box = proxies_[id].box;
    Entry& out = entries_[cell_start_[raw_cell_[e]]++];
    out.min = box.min;
    out.max = box.max;
    out.id = id;
    out.bits = raw_slot_[e] >> 29;
  }
  // cell_start_[c] now holds the end of cell c: shift to starts.
  for (std::size_t c = cells; c > 0; --c) cell_start_[c] = cell_start_[c - 1];
  cell_start_[0] = 0;
}

void CellEngine::pairs_in_cells(std::uint32_t cell_begin, std::uint32_t cell_end, std::vector<ProxyPair>& out,
                                BroadPhaseStats& st) const {
  const Entry* entries = entries_.data();
  for (std::uint32_t c = cell_begin; c < cell_end; ++c) {
    const std::uint32_t b = cell_start_[c];
    const std::uint32_t e = cell_start_[c + 1];
    if (e - b < 2) continue;
    ++st.nodes_visited;
    st.pairs_tested += std::uint64_t(e - b) * (e - b - 1) / 2;
    for (std::uint32_t i = b; i + 1 < e; ++i) {
      const Entry& a = entries[i];
      for (std::uint32_t j = i + 1; j < e; ++j) {
        const Entry& o = entries[j];
        if (!overlaps(a.min, a.max, o.min, o.max)) continue;
        if ((a.bits | o.bits) != 7u) continue;
        if (!may_pair(proxies_[a.id], proxies_[o.id])) continue;
        out.push_back(detail::ordered_pair(a.id, o.id));
      }
    }
  }
}

void CellEngine::pairs_across_levels(std::size_t begin, std::size_t end, std::vector<ProxyPair>& out,
                                     BroadPhaseStats& st) const {
  const auto ids = proxies_.ids();
  for (std::size_t s = begin; s < end; ++s) {
    if (is_oversized_[s] != 0) continue;
    const int la = ranges_[s].level;
    std::uint32_t higher = la + 1 < 32 ? (level_mask_ >> (la + 1)) << (la + 1) : 0u;
    if (higher == 0) continue;
    const ProxyId id = ids[s];
    const ProxyRecord& rec = proxies_[id];
    while (higher != 0) {
      const int lb = std::countr_zero(higher);
      higher &= higher - 1;
      const Range r = range_of(rec.box, lb);
      for (std::int32_t z = r.lo[2]; z <= r.hi[2]; ++z) {
        for (std::int32_t y = r.lo[1]; y <= r.hi[1]; ++y) {
          for (std::int32_t x = r.lo[0]; x <= r.hi[0]; ++x) {
            const std::uint32_t c = find_cell(lb, x, y, z);
            if (c == kNoCell) continue;
            ++st.nodes_visited;
            const std::uint32_t bits = (x == r.lo[0] ? 1u : 0u) | (y == r.lo[1] ? 2u : 0u) | (z == r.lo[2] ? 4u : 0u);
            for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
              const Entry& o = entries_[i];
              ++st.pairs_tested;
              if (!overlaps(rec.box.min, rec.box.max, o.min, o.max)) continue;
              if ((bits | o.bits) != 7u) continue;
              if (!may_pair(rec, proxies_[o.id])) continue;
              out.push_back(detail::ordered_pair(id, o.id));
            }
          }
        }
      }
    }
  }
}

void CellEngine::pairs_oversized(std::size_t begin, std::size_t end, std::vector<ProxyPair>& out,
                                 BroadPhaseStats& st) const {
  const auto ids = proxies_.ids();
  for (std::size_t k = begin; k < end; ++k) {
    const std::uint32_t s = oversized_[k];
    const ProxyRecord& a = proxies_[ids[s]];
    for (std::size_t t = 0; t < ids.size(); ++t) {
      if (t == s || (is_oversized_[t] != 0 && t < s)) continue;
      const ProxyRecord& b = proxies_[ids[t]];
      ++st.pairs_tested;
      if (a.box.overlaps(b.box) && may_pair(a, b)) out.push_back(detail::ordered_pair(ids[s], ids[t]));
    }
  }
}

void CellEngine::find_pairs(std::vector<ProxyPair>& out, Executor& executor) {
  if (dirty_) build();
  out.clear();
  stats_ = {};
  const std::size_t n = proxies_.size();
  if (n == 0) return;
  const std::uint32_t cells = std::uint32_t(cell_start_.size() - 1);
  const std::size_t threads = std::min(executor.concurrency(), n / 1024 + 1);
  if (threads <= 1) {
    pairs_in_cells(0, cells, out, stats_);
    if (mode_ == CellMode::Hierarchical) pairs_across_levels(0, n, out, stats_);
    pairs_oversized(0, oversized_.size(), out, stats_);
  } else {
    // Parts of about equal entry counts (4 per thread), each with its share of the level
    // probes and of the oversized proxies; per-part lists joined in part order.
    const std::size_t parts = threads * 4;
    std::vector<BroadPhaseStats> st(parts);
    std::vector<std::uint32_t> bounds(parts + 1, cells);
    bounds[0] = 0;
    const std::size_t total = entries_.size();
    std::uint32_t c = 0;
    for (std::size_t p = 1; p < parts; ++p) {
      const std::size_t target = total * p / parts;
      while (c < cells && cell_start_[c] < target) ++c;
      bounds[p] = c;
    }
    run_pair_chunks(parts, parts, executor, part_pairs_, out,
                    [&](std::size_t begin, std::size_t end, std::vector<ProxyPair>& mine) {
                      for (std::size_t p = begin; p < end; ++p) {
                        pairs_in_cells(bounds[p], bounds[p + 1], mine, st[p]);
                        if (mode_ == CellMode::Hierarchical)
                          pairs_across_levels(n * p / parts, n * (p + 1) / parts, mine, st[p]);
                        pairs_oversized(oversized_.size() * p / parts, oversized_.size() * (p + 1) / parts, mine,
                                        st[p]);
                      }
                    });
    for (const BroadPhaseStats& s : st) {
      stats_.nodes_visited += s.nodes_visited;
      stats_.pairs_tested += s.pairs_tested;
    }
  }
  sort_pairs_radix(out, sort_scratch_);
  stats_.pairs_found = out.size();
}

bool CellEngine::cells_within_budget(const Aabb& box) const {
  // Cells of the box's ranges over the occupied levels, against a budget of the entry count.
  const std::int64_t budget = std::max<std::int64_t>(64, std::int64_t(entries_.size()));
  std::int64_t cells = 0;
  const std::uint32_t levels = mode_ == CellMode::Hierarchical ? level_mask_ : 1u;
  for (std::uint32_t m = levels; m != 0; m &= m - 1) {
    const Range r = range_of(box, std::countr_zero(m));
    cells +=
        std::int64_t(r.hi[0] - r.lo[0] + 1) * std::int64_t(r.hi[1] - r.lo[1] + 1) * std::int64_t(r.hi[2] - r.lo[2] + 1);
  }
  return cells <= budget;
}

// ---- the dense-grid ray march (CellEngine::march_ray in uniform_grid.hpp) ------------------
// March the cells the segment crosses, slab by slab along the axis of the largest direction
// component (a 3D DDA made conservative: each slab's stretch of the segment is widened by
// `eps` and every cell its box touches is visited, so rounding cannot skip a cell). A box is
// reported in the first visited cell of its range only, found by recomputing the earlier
// slabs' cell rectangles (no marks).

bool CellEngine::start_march(const Ray& ray, Real max_t, RayMarch& m) const {
  // Input left to the scan: a zero or non-finite direction, NaN.
  m.a = 0;
  for (int k = 0; k < 3; ++k) {
    m.o[k] = double(ray.origin[k]);
    m.d[k] = double(ray.direction[k]);
    if (!std::isfinite(m.o[k]) || !std::isfinite(m.d[k])) return false;
    if (std::abs(m.d[k]) > std::abs(m.d[m.a])) m.a = k;
  }
  if (m.d[m.a] == 0 || !(max_t >= Real(0))) return false;
  m.b = (m.a + 1) % 3;
  m.c = (m.a + 2) % 3;
  const double cell = double(cell_);
  double reach = 0;
  for (int k = 0; k < 3; ++k) reach = std::max(reach, std::abs(double(origin_[k])) + double(dims_[k]) * cell);
  m.eps = 1e-3 * cell + 64.0 * double(std::numeric_limits<Real>::epsilon()) * reach;
  // Clip the segment to the grid's cells, widened by eps.
  m.t_in = 0;
  m.t_out = double(max_t);
  for (int k = 0; k < 3; ++k) {
    const double lo = double(origin_[k]) - m.eps;
    const double hi = double(origin_[k]) + double(dims_[k]) * cell + m.eps;
    if (m.d[k] == 0) {
      if (m.o[k] < lo || m.o[k] > hi) m.t_out = -1;
      continue;
    }
    double ta = (lo - m.o[k]) / m.d[k];
    double tb = (hi - m.o[k]) / m.d[k];
    if (ta > tb) std::swap(ta, tb);
    m.t_in = std::max(m.t_in, ta);
    m.t_out = std::min(m.t_out, tb);
  }
  auto slab_of = [&](double t) {
    const double x = std::floor((m.o[m.a] + t * m.d[m.a] - double(origin_[m.a])) / cell);
    return std::int32_t(std::clamp(x, 0.0, double(dims_[m.a] - 1)));
  };
  m.first = slab_of(m.t_in);
  m.last = slab_of(m.t_out);
  m.step = m.d[m.a] > 0 ? 1 : -1;
  return true;
}

bool CellEngine::slab_rect(const RayMarch& m, std::int32_t s, SlabRect& r) const {
  // False when the segment misses the widened slab.
  const double cell = double(cell_);
  const double x0 = double(origin_[m.a]) + double(s) * cell - m.eps;
  const double x1 = double(origin_[m.a]) + double(s + 1) * cell + m.eps;
  double ta = (x0 - m.o[m.a]) / m.d[m.a];
  double tb = (x1 - m.o[m.a]) / m.d[m.a];
  if (ta > tb) std::swap(ta, tb);
  ta = std::max(ta, m.t_in);
  tb = std::min(tb, m.t_out);
  if (ta > tb) return false;
  r.t0 = ta;
  const int axes[2] = {m.b, m.c};
  for (int j = 0; j < 2; ++j) {
    const int k = axes[j];
    const double pa = m.o[k] + ta * m.d[k];
    const double pb = m.o[k] + tb * m.d[k];
    const double lo = std::floor((std::min(pa, pb) - m.eps - double(origin_[k])) / cell);
    const double hi = std::floor((std::max(pa, pb) + m.eps - double(origin_[k])) / cell);
    r.lo[j] = std::int32_t(std::clamp(lo, 0.0, double(dims_[k] - 1)));
    r.hi[j] = std::int32_t(std::clamp(hi, 0.0, double(dims_[k] - 1)));
  }
  return true;
}

bool CellEngine::first_visit(const RayMarch& m, const Entry& e, std::int32_t s, std::int32_t u, std::int32_t v,
                             const SlabRect& r) const {
  // First visited cell of the box's range: first of this slab's rectangle, and no earlier
  // slab of its range met it.
  const Range g = range_of(Aabb{e.min, e.max}, 0);
  if (u != std::max(r.lo[0], g.lo[m.b]) || v != std::max(r.lo[1], g.lo[m.c])) return false;
  for (std::int32_t q = s - m.step; q >= g.lo[m.a] && q <= g.hi[m.a] && q - m.first != -m.step; q -= m.step) {
    SlabRect earlier{};
    if (slab_rect(m, q, earlier) && earlier.lo[0] <= g.hi[m.b] && g.lo[m.b] <= earlier.hi[0] &&
        earlier.lo[1] <= g.hi[m.c] && g.lo[m.c] <= earlier.hi[1]) {
      return false;
    }
  }
  return true;
}

bool CellEngine::validate() const {
  if (!proxies_.validate()) return false;
  if (dirty_) return true;
  const auto ids = proxies_.ids();
  if (ranges_.size() != ids.size() || is_oversized_.size() != ids.size()) return false;
  std::size_t expected = 0;
  for (std::size_t s = 0; s < ids.size(); ++s) {
    if (is_oversized_[s] != 0) continue;
    const Range& r = ranges_[s];
    expected +=
        std::size_t(r.hi[0] - r.lo[0] + 1) * std::size_t(r.hi[1] - r.lo[1] + 1) * std::size_t(r.hi[2] - r.lo[2] + 1);
  }
  if (expected != entries_.size() || cell_start_.empty() || cell_start_.back() != entries_.size()) return false;
  const std::size_t cells = cell_start_.size() - 1;
  for (std::size_t c = 0; c < cells; ++c) {
    if (cell_start_[c] > cell_start_[c + 1]) return false;
    std::int32_t level = 0;
    std::int32_t xyz[3];
    if (mode_ == CellMode::Dense) {
      xyz[0] = std::int32_t(c % std::size_t(dims_[0]));
      xyz[1] = std::int32_t((c / std::size_t(dims_[0])) % std::size_t(dims_[1]));
      xyz[2] = std::int32_t(c / (std::size_t(dims_[0]) * std::size_t(dims_[1])));
    } else {
      unpack_key(cell_key_[c], level, xyz[0], xyz[1], xyz[2]);
      if (find_cell(level, xyz[0], xyz[1], xyz[2]) != c) return false;
    }
    for (std::uint32_t i = cell_start_[c]; i < cell_start_[c + 1]; ++i) {
      const Entry& e = entries_[i];
      if (!proxies_.contains(e.id)) return false;
      const ProxyRecord& rec = proxies_[e.id];
      if (rec.box.min != e.min || rec.box.max != e.max) return false;
      const Range& r = ranges_[rec.dense];
      if (r.level != level) return false;
      std::uint32_t bits = 0;
      for (int k = 0; k < 3; ++k) {
        if (xyz[k] < r.lo[k] || xyz[k] > r.hi[k]) return false;
        if (xyz[k] == r.lo[k]) bits |= 1u << k;
      }
      if (bits != e.bits) return false;
    }
  }
  return true;
}

std::size_t CellEngine::memory_bytes() const {
  std::size_t bytes = detail::capacity_bytes(ranges_) + detail::capacity_bytes(raw_cell_) +
                      detail::capacity_bytes(raw_slot_) + detail::capacity_bytes(cell_start_) +
                      detail::capacity_bytes(cell_key_) + detail::capacity_bytes(table_) +
                      detail::capacity_bytes(entries_) + detail::capacity_bytes(oversized_) +
                      detail::capacity_bytes(is_oversized_) + detail::capacity_bytes(sort_scratch_);
  for (const auto& v : part_pairs_) bytes += detail::capacity_bytes(v);
  return bytes + proxies_.size() * (sizeof(ProxyRecord) + sizeof(ProxyId));
}

}  // namespace proxima::detail
