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
///     max(4, n / 2) bins for those small nodes), remembering each primitive's bin, sweep
///     the bins to evaluate A_L N_L + A_R N_R of every bin plane, and take the cheapest.
///  3. Partition the working range in place in one pass (Hoare style) by the remembered
///     bins (no recomputation, so exactly the binning pass's decision), collecting the
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
#include <proxima/midphase/bvh.hpp>

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>

namespace proxima {
namespace {

/// One primitive in the working array: its box, its centre and its index.
struct BuildRef {
  Vec3 min;
  std::uint32_t index;
  Vec3 max;
  Vec3 center;
};

/// One SAH bin: the box of its primitives and how many there are.
struct Bin {
  Vec3 min{kRealMax};
  Vec3 max{-kRealMax};
  std::uint32_t count = 0;
};

constexpr std::uint32_t kMaxBins = 64;
/// Nodes of at most this many primitives are binned on all three axes.
constexpr std::uint32_t kAllAxesBelow = 32;

/// Half the surface area of the box [lo, hi] (the SAH only compares ratios).
inline Real half_area(const Vec3& lo, const Vec3& hi) {
  const Vec3 e = glm::max(hi - lo, Vec3(Real(0)));
  return e.x * e.y + e.y * e.z + e.z * e.x;
}

/// ceil(log2(n)) for n >= 1.
inline std::uint32_t ceil_log2(std::uint32_t n) {
  return n <= 1 ? 0u : static_cast<std::uint32_t>(std::bit_width(n - 1));
}

class Builder {
 public:
  Builder(std::vector<BuildRef>& refs, std::vector<BvhNode>& nodes, const BvhBuildOptions& options)
      : refs_(refs), nodes_(nodes), bin_of_(refs.size()) {
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
      for (std::uint32_t b = 0; b < k; ++b) bins[std::size_t(a)][b] = Bin{};
    if (all_axes) {
      for (std::uint32_t i = begin; i != end; ++i) {
        const BuildRef& r = refs_[i];
        const Vec3 f = (r.center - clo) * scale;
        for (int a = 0; a < 3; ++a) {
          const int b = std::min(static_cast<int>(f[a]), max_bin);
          bin_of_[i][std::size_t(a)] = static_cast<std::uint8_t>(b);
          Bin& bin = bins[std::size_t(a)][static_cast<std::size_t>(b)];
          bin.min = glm::min(bin.min, r.min);
          bin.max = glm::max(bin.max, r.max);
          ++bin.count;
        }
      }
    } else {
      const Real s = scale[widest];
      const Real o = clo[widest];
      auto& axis_bins = bins[std::size_t(widest)];
      for (std::uint32_t i = begin; i != end; ++i) {
        const BuildRef& r = refs_[i];
        const int b = std::min(static_cast<int>((r.center[widest] - o) * s), max_bin);
        bin_of_[i][std::size_t(widest)] = static_cast<std::uint8_t>(b);
        Bin& bin = axis_bins[static_cast<std::size_t>(b)];
        bin.min = glm::min(bin.min, r.min);
        bin.max = glm::max(bin.max, r.max);
        ++bin.count;
      }
    }
    // Sweep: right-to-left accumulated costs, then left-to-right evaluation.
    Real best_cost = kRealMax;
    int best_axis = -1;
    std::uint32_t best_plane = 0;  // bins [0, best_plane) go left
    std::array<Real, kMaxBins> right_cost;
    for (int a = axis_lo; a <= axis_hi; ++a) {
      if (!(cext[a] > Real(0))) continue;
      Vec3 lo(kRealMax), hi(-kRealMax);
      std::uint32_t n = 0;
      for (std::uint32_t b = k - 1; b > 0; --b) {
        const Bin& bin = bins[a][b];
        lo = glm::min(lo, bin.min);
        hi = glm::max(hi, bin.max);
        n += bin.count;
        right_cost[b] = n == 0 ? Real(0) : half_area(lo, hi) * Real(n);
      }
      lo = Vec3(kRealMax);
      hi = Vec3(-kRealMax);
      n = 0;
      for (std::uint32_t b = 0; b + 1 < k; ++b) {
        const Bin& bin = bins[a][b];
        lo = glm::min(lo, bin.min);
        hi = glm::max(hi, bin.max);
        n += bin.count;
        if (n == 0 || n == end - begin) continue;
        const Real cost = (n == 0 ? Real(0) : half_area(lo, hi) * Real(n)) + right_cost[b + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = a;
          best_plane = b + 1;
        }
      }
    }
    if (best_axis < 0) return false;
    // Children's boxes from the bins.
    left_lo = Vec3(kRealMax);
    left_hi = Vec3(-kRealMax);
    right_lo = Vec3(kRealMax);
    right_hi = Vec3(-kRealMax);
    const auto& axis_bins = bins[static_cast<std::size_t>(best_axis)];
    for (std::uint32_t b = 0; b < k; ++b) {
      if (b < best_plane) {
        left_lo = glm::min(left_lo, axis_bins[b].min);
        left_hi = glm::max(left_hi, axis_bins[b].max);
      } else {
        right_lo = glm::min(right_lo, axis_bins[b].min);
        right_hi = glm::max(right_hi, axis_bins[b].max);
      }
    }
    // In-place partition by the bin indices stored in the binning pass.
    const auto plane = static_cast<std::uint8_t>(best_plane);
    const auto axis = static_cast<std::size_t>(best_axis);
    auto goes_left = [&](std::uint32_t i) { return bin_of_[i][axis] < plane; };
    left_clo = Vec3(kRealMax);
    left_chi = Vec3(-kRealMax);
    right_clo = Vec3(kRealMax);
    right_chi = Vec3(-kRealMax);
    std::uint32_t i = begin;
    std::uint32_t j = end;
    while (true) {
      while (i < j && goes_left(i)) {
        left_clo = glm::min(left_clo, refs_[i].center);
        left_chi = glm::max(left_chi, refs_[i].center);
        ++i;
      }
      while (i < j && !goes_left(j - 1)) {
        --j;
        right_clo = glm::min(right_clo, refs_[j].center);
        right_chi = glm::max(right_chi, refs_[j].center);
      }
      if (i >= j) break;
      std::swap(refs_[i], refs_[j - 1]);
      std::swap(bin_of_[i], bin_of_[j - 1]);
    }
    mid = i;
    assert(mid != begin && mid != end);
    return true;
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
  /// Bin of each primitive (by position in refs_) on each axis binned for the current node,
  /// so the partition reads it instead of recomputing it.
  std::vector<std::array<std::uint8_t, 3>> bin_of_;
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
