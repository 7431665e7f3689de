/// @file bvh.cpp
/// Bvh: binned-SAH build, bottom-up refit and statistics.
///
/// Build (Wald, "On fast construction of SAH-based bounding volume hierarchies", IEEE
/// Symposium on Interactive Ray Tracing 2007):
///  1. Copy every primitive's box, centre and index into one working array (the only
///     allocation besides the output arrays, sized once: 2n - 1 nodes at most).
///  2. Per node (depth first, children stored adjacently at the end of the node array so a
///     child always has a larger index than its parent): a node of at most max_leaf_size
///     primitives is a leaf; every larger node is split (so the SAH cost only ranks the
///     planes, and the traversal/primitive cost options do not change the tree). Bin the
///     centres into bin_count bins spanning the node's centroid bounds (on the widest
///     centroid axis for nodes of more than 32 primitives, on all three below, with
///     max(4, n / 2) bins for those small nodes; bins are plain arrays grown with branch-free
///     min/max, 4-wide with SSE2 in float, the axis loops are compiled per axis), sweep the bins to
///     evaluate A_L N_L + A_R N_R of every bin plane, and take the cheapest.
///  3. Partition the working range in place in one pass (Hoare style) by each primitive's
///     bin on the chosen axis, recomputed with the binning pass's exact expression (so
///     exactly its decision, without storing a bin per primitive), collecting the
///     children's centroid bounds on the way; the children's boxes are the unions of their
///     bins' boxes, so no further pass over the primitives is needed.
///  4. Fallback to an object-median split on the widest centroid axis (nth_element; by
///     position when every centre coincides) when the centroid bounds are flat on every
///     axis, when the best plane leaves one side empty, or when the node is so deep that an
///     unlucky SAH split could exceed kMaxDepth. Median splits halve the count, so the
///     depth stays below kMaxDepth for any input of fewer than 2^32 primitives.
/// Refit walks the nodes in reverse index order (children after parents), so one pass
/// recomputes every box bottom-up.

#include <proxima/core/tolerance.hpp>
#include <proxima/spatial/bvh.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cstddef>

#if defined(__SSE2__) && !PROXIMA_DOUBLE
#include <emmintrin.h>
#define PROXIMA_BVH_BUILD_SSE 1
#else
#define PROXIMA_BVH_BUILD_SSE 0
#endif

namespace proxima {
namespace {

/// One primitive in the working array: its box, its centre and its index.
struct BuildRef {
  Vec3 min;
  std::uint32_t index;
  Vec3 max;
  Vec3 center;
};

/// One SAH bin: the box of its primitives and how many there are (plain arrays so the
/// growth compiles to branch-free scalar min/max).
struct Bin {
  alignas(16) Real lo[4];  // lane 3 unused
  alignas(16) Real hi[4];  // lane 3 unused
  std::uint32_t count;
};

[[maybe_unused]] inline Real fmin_(Real a, Real b) { return b < a ? b : a; }
[[maybe_unused]] inline Real fmax_(Real a, Real b) { return a < b ? b : a; }

/// Empties a bin.
inline void clear_bin(Bin& b) {
  b.lo[0] = b.lo[1] = b.lo[2] = kRealMax;
  b.hi[0] = b.hi[1] = b.hi[2] = -kRealMax;
  b.lo[3] = b.hi[3] = Real(0);
  b.count = 0;
}

#if PROXIMA_BVH_BUILD_SSE
/// Grows bin b by r's box: one 4-wide load per corner (lanes 0-2; lane 3, the next member
/// of BuildRef, is masked to zero so no bit pattern of it can reach the min/max).
inline void grow_bin(Bin& b, const BuildRef& r) {
  static_assert(offsetof(BuildRef, min) + 4 * sizeof(float) <= sizeof(BuildRef));
  static_assert(offsetof(BuildRef, max) + 4 * sizeof(float) <= sizeof(BuildRef));
  const __m128 mask = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
  const __m128 lo = _mm_and_ps(_mm_loadu_ps(&r.min.x), mask);
  const __m128 hi = _mm_and_ps(_mm_loadu_ps(&r.max.x), mask);
  _mm_store_ps(b.lo, _mm_min_ps(_mm_load_ps(b.lo), lo));
  _mm_store_ps(b.hi, _mm_max_ps(_mm_load_ps(b.hi), hi));
  ++b.count;
}
#else
/// Grows bin b by r's box.
inline void grow_bin(Bin& b, const BuildRef& r) {
  const Vec3& lo = r.min;
  const Vec3& hi = r.max;
  b.lo[0] = fmin_(b.lo[0], lo.x);
  b.lo[1] = fmin_(b.lo[1], lo.y);
  b.lo[2] = fmin_(b.lo[2], lo.z);
  b.hi[0] = fmax_(b.hi[0], hi.x);
  b.hi[1] = fmax_(b.hi[1], hi.y);
  b.hi[2] = fmax_(b.hi[2], hi.z);
  ++b.count;
}
#endif

/// Running box of a sweep: grows by whole bins, reports its half area.
#if PROXIMA_BVH_BUILD_SSE
struct SweepBox {
  __m128 lo = _mm_set_ps(0.0f, kRealMax, kRealMax, kRealMax);
  __m128 hi = _mm_set_ps(0.0f, -kRealMax, -kRealMax, -kRealMax);
  void grow(const Bin& b) {
    lo = _mm_min_ps(lo, _mm_load_ps(b.lo));
    hi = _mm_max_ps(hi, _mm_load_ps(b.hi));
  }
  /// (e0 e1 + e1 e2) + e2 e0, the scalar path's exact order.
  Real half_area() const {
    const __m128 e = _mm_max_ps(_mm_sub_ps(hi, lo), _mm_setzero_ps());
    const __m128 p = _mm_mul_ps(e, _mm_shuffle_ps(e, e, _MM_SHUFFLE(3, 0, 2, 1)));  // e0e1, e1e2, e2e0
    const __m128 s = _mm_add_ss(p, _mm_shuffle_ps(p, p, _MM_SHUFFLE(3, 2, 1, 1)));
    return _mm_cvtss_f32(_mm_add_ss(s, _mm_movehl_ps(p, p)));
  }
  Vec3 min_corner() const {
    alignas(16) float v[4];
    _mm_store_ps(v, lo);
    return Vec3(v[0], v[1], v[2]);
  }
  Vec3 max_corner() const {
    alignas(16) float v[4];
    _mm_store_ps(v, hi);
    return Vec3(v[0], v[1], v[2]);
  }
};
#else
struct SweepBox {
  Real lo0 = kRealMax, lo1 = kRealMax, lo2 = kRealMax;
  Real hi0 = -kRealMax, hi1 = -kRealMax, hi2 = -kRealMax;
  void grow(const Bin& b) {
    lo0 = fmin_(lo0, b.lo[0]);
    lo1 = fmin_(lo1, b.lo[1]);
    lo2 = fmin_(lo2, b.lo[2]);
    hi0 = fmax_(hi0, b.hi[0]);
    hi1 = fmax_(hi1, b.hi[1]);
    hi2 = fmax_(hi2, b.hi[2]);
  }
  Real half_area() const {
    const Real ex = fmax_(hi0 - lo0, Real(0));
    const Real ey = fmax_(hi1 - lo1, Real(0));
    const Real ez = fmax_(hi2 - lo2, Real(0));
    return ex * ey + ey * ez + ez * ex;
  }
  Vec3 min_corner() const { return Vec3(lo0, lo1, lo2); }
  Vec3 max_corner() const { return Vec3(hi0, hi1, hi2); }
};
#endif

#if PROXIMA_BVH_BUILD_SSE
/// Bounds of primitive centres. One 4-wide load per primitive from max.z: lanes 1-3 are
/// the centre (BuildRef keeps max and center adjacent), lane 0 (a finite coordinate) is
/// ignored.
struct CentroidBounds {
  __m128 lo = _mm_set1_ps(kRealMax);
  __m128 hi = _mm_set1_ps(-kRealMax);
  void grow(const BuildRef& r) {
    static_assert(offsetof(BuildRef, center) == offsetof(BuildRef, max) + 3 * sizeof(float));
    const __m128 c = _mm_loadu_ps(&r.max.z);
    lo = _mm_min_ps(lo, c);
    hi = _mm_max_ps(hi, c);
  }
  void get(Vec3& out_lo, Vec3& out_hi) const {
    alignas(16) float v[4];
    _mm_store_ps(v, lo);
    out_lo = Vec3(v[1], v[2], v[3]);
    _mm_store_ps(v, hi);
    out_hi = Vec3(v[1], v[2], v[3]);
  }
};
#else
/// Bounds of primitive centres.
struct CentroidBounds {
  Vec3 lo{kRealMax};
  Vec3 hi{-kRealMax};
  void grow(const BuildRef& r) {
    lo = glm::min(lo, r.center);
    hi = glm::max(hi, r.center);
  }
  void get(Vec3& out_lo, Vec3& out_hi) const {
    out_lo = lo;
    out_hi = hi;
  }
};
#endif

constexpr std::uint32_t kMaxBins = 64;
/// Nodes of at most this many primitives are binned on all three axes.
constexpr std::uint32_t kAllAxesBelow = 32;

/// ceil(log2(n)) for n >= 1.
inline std::uint32_t ceil_log2(std::uint32_t n) {
  return n <= 1 ? 0u : static_cast<std::uint32_t>(std::bit_width(n - 1));
}

class Builder {
 public:
  Builder(std::vector<BuildRef>& refs, std::vector<BvhNode>& nodes, const BvhBuildOptions& options)
      : refs_(refs), nodes_(nodes) {
    max_leaf_ = std::clamp<std::uint32_t>(options.max_leaf_size, 1u, 255u);
    bins_ = std::clamp<std::uint32_t>(options.bin_count, 2u, kMaxBins);
  }

  /// Builds the subtree of node `node` over refs_[begin, end) whose box is [lo, hi] and
  /// centroid bounds [clo, chi]; `depth` counts nodes from the root (root = 1).
  void build(std::uint32_t node, std::uint32_t begin, std::uint32_t end, Vec3 clo, Vec3 chi, std::uint32_t depth) {
    const std::uint32_t count = end - begin;
    BvhNode& n = nodes_[node];
    if (count <= max_leaf_) {
      n.first = begin;
      n.count = count;
      return;
    }
    std::uint32_t mid = 0;
    Vec3 left_lo, left_hi, right_lo, right_hi;      // children's boxes
    Vec3 left_clo, left_chi, right_clo, right_chi;  // children's centroid bounds
    bool split = false;
    const Vec3 cext = chi - clo;
    const bool deep = depth + 1 + ceil_log2(count) >= Bvh::kMaxDepth;
    if (!deep && (cext.x > Real(0) || cext.y > Real(0) || cext.z > Real(0))) {
      split = sah_split(begin, end, clo, chi, mid, left_lo, left_hi, right_lo, right_hi, left_clo, left_chi, right_clo,
                        right_chi);
    }
    if (!split) {
      median_split(begin, end, clo, chi, mid, left_lo, left_hi, right_lo, right_hi, left_clo, left_chi, right_clo,
                   right_chi);
    }
    const auto left = static_cast<std::uint32_t>(used_);
    used_ += 2;
    n.first = left;
    n.count = 0;
    nodes_[left].min = left_lo;
    nodes_[left].max = left_hi;
    nodes_[left + 1].min = right_lo;
    nodes_[left + 1].max = right_hi;
    build(left, begin, mid, left_clo, left_chi, depth + 1);
    build(left + 1, mid, end, right_clo, right_chi, depth + 1);
  }

  std::size_t used_ = 1;

 private:
  bool sah_split(std::uint32_t begin, std::uint32_t end, const Vec3& clo, const Vec3& chi, std::uint32_t& mid,
                 Vec3& left_lo, Vec3& left_hi, Vec3& right_lo, Vec3& right_hi, Vec3& left_clo, Vec3& left_chi,
                 Vec3& right_clo, Vec3& right_chi) {
    auto& bins = bins_storage_;  // reused by every node (no per-node initialisation of 192 bins)
    // Small nodes get fewer bins (about one per two primitives, at least 4): the sweep over
    // 3 x bins planes would otherwise cost more than binning their few primitives.
    const std::uint32_t count = end - begin;
    const std::uint32_t k = count <= kAllAxesBelow ? std::min(bins_, std::max(4u, count / 2)) : bins_;
    // Bin index = floor((c - clo) * scale), clamped: scale maps the centroid range onto
    // [0, k) (a flat axis gets scale 0: everything in bin 0, never chosen).
    const Vec3 cext = chi - clo;
    Vec3 scale;
    for (int a = 0; a < 3; ++a)
      scale[a] = cext[a] > Real(0) ? Real(k) * (Real(1) - Real(4) * kEpsilon) / cext[a] : Real(0);
    const auto max_bin = static_cast<int>(k - 1);
    // Large nodes are binned on their widest centroid axis only (three times less work; the
    // tree's SAH cost barely changes), small ones on all three.
    int widest = 0;
    if (cext.y > cext[widest]) widest = 1;
    if (cext.z > cext[widest]) widest = 2;
    const bool all_axes = count <= kAllAxesBelow;
    const int axis_lo = all_axes ? 0 : widest;
    const int axis_hi = all_axes ? 2 : widest;
    for (int a = axis_lo; a <= axis_hi; ++a)
      for (std::uint32_t b = 0; b < k; ++b) clear_bin(bins[std::size_t(a)][b]);
    if (all_axes) {
      const Real o0 = clo.x, o1 = clo.y, o2 = clo.z;
      const Real s0 = scale.x, s1 = scale.y, s2 = scale.z;
      for (std::uint32_t i = begin; i != end; ++i) {
        const BuildRef& r = refs_[i];
        const int b0 = std::min(static_cast<int>((r.center.x - o0) * s0), max_bin);
        const int b1 = std::min(static_cast<int>((r.center.y - o1) * s1), max_bin);
        const int b2 = std::min(static_cast<int>((r.center.z - o2) * s2), max_bin);
        grow_bin(bins[0][static_cast<std::size_t>(b0)], r);
        grow_bin(bins[1][static_cast<std::size_t>(b1)], r);
        grow_bin(bins[2][static_cast<std::size_t>(b2)], r);
      }
    } else {
      switch (widest) {
        case 0: bin_one_axis<0>(begin, end, clo.x, scale.x, max_bin, bins[0]); break;
        case 1: bin_one_axis<1>(begin, end, clo.y, scale.y, max_bin, bins[1]); break;
        default: bin_one_axis<2>(begin, end, clo.z, scale.z, max_bin, bins[2]); break;
      }
    }
    // Sweep: right-to-left accumulated costs, then left-to-right evaluation.
    Real best_cost = kRealMax;
    int best_axis = -1;
    std::uint32_t best_plane = 0;  // bins [0, best_plane) go left
    std::array<Real, kMaxBins> right_cost;
    for (int a = axis_lo; a <= axis_hi; ++a) {
      if (!(cext[a] > Real(0))) continue;
      const auto& axis_bins = bins[std::size_t(a)];
      SweepBox right;
      std::uint32_t n = 0;
      for (std::uint32_t b = k - 1; b > 0; --b) {
        const Bin& bin = axis_bins[b];
        right.grow(bin);
        n += bin.count;
        right_cost[b] = n == 0 ? Real(0) : right.half_area() * Real(n);
      }
      SweepBox left;
      n = 0;
      for (std::uint32_t b = 0; b + 1 < k; ++b) {
        const Bin& bin = axis_bins[b];
        left.grow(bin);
        n += bin.count;
        if (n == 0 || n == count) continue;
        const Real cost = left.half_area() * Real(n) + right_cost[b + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = a;
          best_plane = b + 1;
        }
      }
    }
    if (best_axis < 0) return false;
    // Children's boxes from the bins.
    {
      const auto& axis_bins = bins[static_cast<std::size_t>(best_axis)];
      SweepBox l, r;
      for (std::uint32_t b = 0; b < best_plane; ++b) l.grow(axis_bins[b]);
      for (std::uint32_t b = best_plane; b < k; ++b) r.grow(axis_bins[b]);
      left_lo = l.min_corner();
      left_hi = l.max_corner();
      right_lo = r.min_corner();
      right_hi = r.max_corner();
    }
    // In-place partition by the bin index, recomputed with the binning pass's exact
    // expression (bin < plane <=> unclamped bin < plane, as plane <= k - 1).
    const auto plane = static_cast<int>(best_plane);
    switch (best_axis) {
      case 0: mid = partition<0>(begin, end, clo.x, scale.x, plane, left_clo, left_chi, right_clo, right_chi); break;
      case 1: mid = partition<1>(begin, end, clo.y, scale.y, plane, left_clo, left_chi, right_clo, right_chi); break;
      default: mid = partition<2>(begin, end, clo.z, scale.z, plane, left_clo, left_chi, right_clo, right_chi); break;
    }
    // Cannot happen (same arithmetic as the binning); a median split covers it if it does.
    return mid != begin && mid != end;
  }

  /// Component A of v, with A known at compile time.
  template <int A>
  static Real comp(const Vec3& v) {
    if constexpr (A == 0)
      return v.x;
    else if constexpr (A == 1)
      return v.y;
    else
      return v.z;
  }

  /// Bins refs_[begin, end) on axis A only.
  template <int A>
  void bin_one_axis(std::uint32_t begin, std::uint32_t end, Real o, Real s, int max_bin,
                    std::array<Bin, kMaxBins>& axis_bins) {
    for (std::uint32_t i = begin; i != end; ++i) {
      const BuildRef& r = refs_[i];
      const int b = std::min(static_cast<int>((comp<A>(r.center) - o) * s), max_bin);
      grow_bin(axis_bins[static_cast<std::size_t>(b)], r);
    }
  }

  /// Hoare partition of refs_[begin, end) by (bin on axis A) < plane; returns the split
  /// position and the two sides' centroid bounds.
  template <int A>
  std::uint32_t partition(std::uint32_t begin, std::uint32_t end, Real o, Real s, int plane, Vec3& left_clo,
                          Vec3& left_chi, Vec3& right_clo, Vec3& right_chi) {
    BuildRef* refs = refs_.data();
    auto goes_left = [&](std::uint32_t i) { return static_cast<int>((comp<A>(refs[i].center) - o) * s) < plane; };
    CentroidBounds left, right;
    std::uint32_t i = begin;
    std::uint32_t j = end;
    while (true) {
      while (i < j && goes_left(i)) {
        left.grow(refs[i]);
        ++i;
      }
      while (i < j && !goes_left(j - 1)) {
        --j;
        right.grow(refs[j]);
      }
      if (i >= j) break;
      std::swap(refs[i], refs[j - 1]);
    }
    left.get(left_clo, left_chi);
    right.get(right_clo, right_chi);
    return i;
  }

  void median_split(std::uint32_t begin, std::uint32_t end, const Vec3& clo, const Vec3& chi, std::uint32_t& mid,
                    Vec3& left_lo, Vec3& left_hi, Vec3& right_lo, Vec3& right_hi, Vec3& left_clo, Vec3& left_chi,
                    Vec3& right_clo, Vec3& right_chi) {
    const Vec3 cext = chi - clo;
    int axis = 0;
    if (cext.y > cext[axis]) axis = 1;
    if (cext.z > cext[axis]) axis = 2;
    mid = begin + (end - begin) / 2;
    if (cext[axis] > Real(0)) {
      std::nth_element(refs_.begin() + begin, refs_.begin() + mid, refs_.begin() + end,
                       [axis](const BuildRef& a, const BuildRef& b) { return a.center[axis] < b.center[axis]; });
    }
    auto gather = [&](std::uint32_t from, std::uint32_t to, Vec3& lo, Vec3& hi, Vec3& c_lo, Vec3& c_hi) {
      lo = Vec3(kRealMax);
      hi = Vec3(-kRealMax);
      c_lo = Vec3(kRealMax);
      c_hi = Vec3(-kRealMax);
      for (std::uint32_t i = from; i != to; ++i) {
        lo = glm::min(lo, refs_[i].min);
        hi = glm::max(hi, refs_[i].max);
        c_lo = glm::min(c_lo, refs_[i].center);
        c_hi = glm::max(c_hi, refs_[i].center);
      }
    };
    gather(begin, mid, left_lo, left_hi, left_clo, left_chi);
    gather(mid, end, right_lo, right_hi, right_clo, right_chi);
  }

  std::vector<BuildRef>& refs_;
  std::vector<BvhNode>& nodes_;
  std::uint32_t max_leaf_ = 4;
  std::uint32_t bins_ = 16;
  std::array<std::array<Bin, kMaxBins>, 3> bins_storage_;
};

}  // namespace

Bvh Bvh::build(std::span<const Aabb> boxes, std::span<const Vec3> centers, const BvhBuildOptions& options) {
  Bvh bvh;
  const std::size_t n = std::min(boxes.size(), centers.size());
  if (n == 0) return bvh;
  assert(boxes.size() == centers.size());
  std::vector<BuildRef> refs(n);
  Vec3 lo(kRealMax), hi(-kRealMax), clo(kRealMax), chi(-kRealMax);
  for (std::size_t i = 0; i < n; ++i) {
    BuildRef& r = refs[i];
    r.min = boxes[i].min;
    r.max = boxes[i].max;
    r.center = centers[i];
    r.index = static_cast<std::uint32_t>(i);
    lo = glm::min(lo, r.min);
    hi = glm::max(hi, r.max);
    clo = glm::min(clo, r.center);
    chi = glm::max(chi, r.center);
  }
  bvh.nodes_.resize(2 * n - 1);
  bvh.nodes_[0].min = lo;
  bvh.nodes_[0].max = hi;
  Builder builder(refs, bvh.nodes_, options);
  builder.build(0, 0, static_cast<std::uint32_t>(n), clo, chi, 1);
  bvh.nodes_.resize(builder.used_);
  bvh.nodes_.shrink_to_fit();
  bvh.primitives_.resize(n);
  for (std::size_t i = 0; i < n; ++i) bvh.primitives_[i] = refs[i].index;
  return bvh;
}

void Bvh::refit(std::span<const Aabb> boxes) {
  assert(boxes.size() == primitives_.size());
  for (std::size_t i = nodes_.size(); i-- > 0;) {
    BvhNode& node = nodes_[i];
    if (node.is_leaf()) {
      Vec3 lo(kRealMax), hi(-kRealMax);
      for (std::uint32_t p = node.first; p != node.first + node.count; ++p) {
        const Aabb& b = boxes[primitives_[p]];
        lo = glm::min(lo, b.min);
        hi = glm::max(hi, b.max);
      }
      node.min = lo;
      node.max = hi;
    } else {
      const BvhNode& l = nodes_[node.first];
      const BvhNode& r = nodes_[node.first + 1];
      node.min = glm::min(l.min, r.min);
      node.max = glm::max(l.max, r.max);
    }
  }
}

BvhStats Bvh::stats() const {
  BvhStats s;
  if (nodes_.empty()) return s;
  s.node_count = static_cast<std::uint32_t>(nodes_.size());
  const Real root_area = nodes_[0].bounds().surface_area();
  struct Item {
    std::uint32_t node;
    std::uint32_t depth;
  };
  Item stack[kMaxDepth + 2];
  std::uint32_t top = 0;
  stack[top++] = {0, 1};
  Real cost = Real(0);
  while (top != 0) {
    const Item item = stack[--top];
    const BvhNode& node = nodes_[item.node];
    s.depth = std::max(s.depth, item.depth);
    const Real ratio = root_area > Real(0) ? node.bounds().surface_area() / root_area : Real(1);
    if (node.is_leaf()) {
      ++s.leaf_count;
      cost += ratio * Real(node.count);
    } else {
      cost += ratio;
      if (top + 2 > kMaxDepth + 2) continue;  // cannot happen for a built tree
      stack[top++] = {node.first + 1, item.depth + 1};
      stack[top++] = {node.first, item.depth + 1};
    }
  }
  s.sah_cost = cost;
  return s;
}

}  // namespace proxima
