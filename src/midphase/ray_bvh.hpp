#pragma once
/// @file ray_bvh.hpp
/// RayBvh (internal): a 4-wide bounding-volume hierarchy for ray casts, collapsed from the
/// binary Bvh of a TriangleMesh, with the four child boxes of a node stored as float
/// structure-of-arrays rows so that one SSE slab test handles all four children.
///
/// Steps:
///  1. Collapse (as in the BVH4 of Embree, Wald et al., "Embree: A Kernel Framework for
///     Efficient CPU Ray Tracing", SIGGRAPH 2014, and Dammertz et al., "Shallow Bounding
///     Volume Hierarchies for Fast SIMD Ray Tracing of Incoherent Rays", EGSR 2008): a wide
///     node starts with the two children of a binary node and repeatedly replaces its inner
///     child of largest surface area by that child's two children, up to four. Leaves keep
///     their binary ranges of Bvh::primitives(), so the corners stored in leaf order serve
///     both hierarchies.
///  2. Boxes are stored in float, rounded outward (the double build rounds each bound away
///     from the box), so a float box always contains the exact one.
///  3. Slab test of the four children at once (Kay-Kajiya with a precomputed inverse
///     direction; the near plane of each axis chosen once per ray from the direction's
///     sign), made conservative as in Ize, "Robust BVH Ray Traversal" (JCGT 2013): the exit
///     distance is widened by a few ulps of float so that rounding never culls a box the ray
///     touches. In the double build the origin is bracketed by two floats, the near planes
///     measured from one and the far planes from the other, which again only widens.
///  4. Traversal nearest child first with a fixed stack of (child, entry distance); a popped
///     entry beyond the best hit so far is skipped. Only the exact triangle test decides
///     hits, so the answers equal those of the binary traversal.
/// Rays whose float form cannot be bounded this way (a zero, tiny or huge direction
/// component, an origin beyond 1e30) and meshes whose bounds exceed 1e30 use the binary
/// traversal instead.

#include <proxima/midphase/bvh.hpp>
#include <proxima/midphase/triangle_mesh.hpp>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define PROXIMA_RAY_BVH_SSE 1
#else
#define PROXIMA_RAY_BVH_SSE 0
#endif

namespace proxima::detail {

/// One node of the 4-wide hierarchy: 128 bytes (two cache lines).
struct alignas(64) RayNode4 {
  /// Child boxes: rows min x, max x, min y, max y, min z, max z; column = child. An unused
  /// child has min +inf and max -inf (never hit).
  float box[6][4];
  /// Inner child: index of its RayNode4; leaf child: first slot in Bvh::primitives().
  std::uint32_t child[4];
  /// 0 for an inner (or unused) child, else the leaf's triangle count (1..255).
  std::uint8_t count[4];
  std::uint8_t padding[12];
};
static_assert(sizeof(RayNode4) == 128);

/// The 4-wide hierarchy of one mesh (node 0 is the root; empty when not usable).
struct RayBvh {
  std::vector<RayNode4> nodes;

  /// Collapses `bvh`; leaves `nodes` empty when `bvh` is empty or its bounds exceed 1e30 in
  /// magnitude (the float layout could not hold them). O(n).
  static RayBvh build(const Bvh& bvh);
};

/// Largest coordinate magnitude of the float layout (boxes and ray origins).
inline constexpr Real kRayBvhMaxCoordinate = Real(1e30);

/// Relative widening of the exit distance: 1 + 2^-19, about 8 float ulps, above the
/// 1 + 2 gamma(3) of Ize plus the rounding of the widening itself and of the double build's
/// inverse (rounded twice).
inline constexpr float kWideSlabWiden = 1.0f + 1.0f / 524288.0f;

/// Rounds x to a float not above it.
inline float round_down_float(Real x) {
  float f = static_cast<float>(x);
  if (static_cast<Real>(f) > x) f = std::nextafter(f, -std::numeric_limits<float>::infinity());
  return f;
}

/// Rounds x to a float not below it (+inf stays +inf).
inline float round_up_float(Real x) {
  float f = static_cast<float>(x);
  if (static_cast<Real>(f) < x) f = std::nextafter(f, std::numeric_limits<float>::infinity());
  return f;
}

/// A ray prepared for the 4-wide slab test.
struct WideRay {
  float near_origin[3];  ///< origin (rounded towards the near planes) per axis
  float far_origin[3];   ///< origin (rounded towards the far planes) per axis
  float inv[3];          ///< 1 / direction, rounded to float
  int near_row[3];       ///< row of RayNode4::box holding the near plane of each axis
  bool valid = false;    ///< false: use the binary traversal
};

/// Prepares `ray`; valid only when every direction component lies in [1e-30, 1e30] in
/// magnitude and every origin coordinate within 1e30.
inline WideRay prepare_wide_ray(const Ray& ray) {
  WideRay r;
  for (int a = 0; a < 3; ++a) {
    const Real d = ray.direction[a];
    const Real o = ray.origin[a];
    const Real ad = std::abs(d);
    if (!(ad >= Real(1e-30) && ad <= Real(1e30)) || !(std::abs(o) <= kRayBvhMaxCoordinate)) return r;
    r.inv[a] = static_cast<float>(Real(1) / d);
    const float lo = round_down_float(o);
    const float hi = round_up_float(o);
    // Direction >= 0: entry at the min plane, measured from the upper origin bound (which
    // can only make the entry earlier), exit at the max plane from the lower bound.
    const bool positive = d > Real(0);
    r.near_origin[a] = positive ? hi : lo;
    r.far_origin[a] = positive ? lo : hi;
    r.near_row[a] = 2 * a + (positive ? 0 : 1);
  }
  r.valid = true;
  return r;
}

/// Slab test of the four children of `node` against [0, t_max]: returns the mask of the
/// children hit (bit i = child i) and their entry distances in `t_near`.
inline unsigned test_children(const RayNode4& node, const WideRay& r, float t_max, float t_near[4]) {
#if PROXIMA_RAY_BVH_SSE
  __m128 tn = _mm_setzero_ps();
  __m128 tf = _mm_set1_ps(t_max);
  for (int a = 0; a < 3; ++a) {
    const __m128 inv = _mm_set1_ps(r.inv[a]);
    const int nr = r.near_row[a];
    const __m128 n = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[nr]), _mm_set1_ps(r.near_origin[a])), inv);
    const __m128 f = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[nr ^ 1]), _mm_set1_ps(r.far_origin[a])), inv);
    tn = _mm_max_ps(tn, n);
    tf = _mm_min_ps(tf, f);
  }
  tf = _mm_mul_ps(tf, _mm_set1_ps(kWideSlabWiden));
  _mm_storeu_ps(t_near, tn);
  return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(tn, tf)));
#else
  unsigned mask = 0;
  for (int c = 0; c < 4; ++c) {
    float tn = 0.0f;
    float tf = t_max;
    for (int a = 0; a < 3; ++a) {
      const int nr = r.near_row[a];
      const float n = (node.box[nr][c] - r.near_origin[a]) * r.inv[a];
      const float f = (node.box[nr ^ 1][c] - r.far_origin[a]) * r.inv[a];
      tn = n > tn ? n : tn;
      tf = f < tf ? f : tf;
    }
    t_near[c] = tn;
    if (tn <= tf * kWideSlabWiden) mask |= 1u << c;
  }
  return mask;
#endif
}

/// Depth-first traversal, nearest child first. `leaf(first, count, t_max)` is called for
/// each leaf whose box the ray meets within [0, t_max]; it may lower t_max (a float not
/// below the best hit so far: subtrees entered beyond it are skipped) and returns false to
/// stop. No allocation; fixed stack.
template <class Leaf>
void traverse_wide(const RayBvh& bvh, const WideRay& r, float t_max, Leaf&& leaf) {
  struct Entry {
    std::uint32_t ref;    // node index or first leaf slot
    std::uint32_t count;  // 0: inner node
    float t;              // entry distance
  };
  Entry stack[3 * Bvh::kMaxDepth + 4];
  std::uint32_t top = 0;
  const RayNode4* nodes = bvh.nodes.data();
  Entry current{0, 0, 0.0f};
  while (true) {
    if (current.count == 0) {
      const RayNode4& node = nodes[current.ref];
      float tn[4];
      const unsigned mask = test_children(node, r, t_max, tn);
      if (mask != 0) {
        if ((mask & (mask - 1)) == 0) {  // one child: no ordering
          const int c = std::countr_zero(mask);
          current = {node.child[c], node.count[c], tn[c]};
          continue;
        }
        Entry hit[4];
        int k = 0;
        for (unsigned m = mask; m != 0; m &= m - 1) {
          const int c = std::countr_zero(m);
          Entry e{node.child[c], node.count[c], tn[c]};
          int j = k++;
          for (; j > 0 && hit[j - 1].t > e.t; --j) hit[j] = hit[j - 1];  // insertion by entry
          hit[j] = e;
        }
        for (int j = k - 1; j > 0; --j) stack[top++] = hit[j];  // farthest pushed first
        current = hit[0];
        continue;
      }
    } else if (!leaf(current.ref, current.count, t_max)) {
      return;
    }
    // Pop the next subtree that may still hold a hit no farther than t_max.
    while (true) {
      if (top == 0) return;
      const Entry& e = stack[--top];
      if (e.t <= t_max * kWideSlabWiden) {
        current = e;
        break;
      }
    }
  }
}

}  // namespace proxima::detail
