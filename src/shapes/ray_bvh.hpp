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

#include <proxima/shapes/triangle_mesh.hpp>
#include <proxima/spatial/bvh.hpp>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
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
  /// Inner child: index of its RayNode4; leaf child: index of its first TriangleBlock4.
  std::uint32_t child[4];
  /// 0 for an inner (or unused) child, else the leaf's triangle count (1..255).
  std::uint8_t count[4];
  std::uint8_t padding[12];
};
static_assert(sizeof(RayNode4) == 128);

/// Up to four triangles of one leaf, corners as structure-of-arrays rows, for the
/// conservative rejection of four triangles at once. A leaf of n triangles owns
/// ceil(n / 4) consecutive blocks; unused lanes hold zeros and are masked out.
struct alignas(16) TriangleBlock4 {
  Real v[3][3][4];          ///< v[corner][axis][lane]
  std::uint32_t slot = 0;   ///< slot (in Bvh::primitives() order) of lane 0; lane i is slot + i
  std::uint32_t count = 0;  ///< used lanes (1..4)
};

/// The 4-wide hierarchy of one mesh (node 0 is the root; empty when not usable).
struct RayBvh {
  std::vector<RayNode4> nodes;
  std::vector<TriangleBlock4> blocks;  ///< leaf triangles in leaf order

  /// Collapses `bvh` over the triangle corners `corners` (in leaf order, as
  /// TriangleMesh::Data::leaf_triangles); leaves `nodes` empty when `bvh` is empty or its
  /// bounds exceed 1e30 in magnitude (the float layout could not hold them). O(n).
  static RayBvh build(const Bvh& bvh, std::span<const std::array<Vec3, 3>> corners);
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
#if PROXIMA_RAY_BVH_SSE
  __m128 near_origin[3];  ///< origin (rounded towards the near planes), broadcast, per axis
  __m128 far_origin[3];   ///< origin (rounded towards the far planes), broadcast, per axis
  __m128 inv[3];          ///< 1 / direction rounded to float, broadcast, per axis
#else
  float near_origin[3];
  float far_origin[3];
  float inv[3];
#endif
  int near_row[3] = {0, 2, 4};  ///< row of RayNode4::box holding the near plane of each axis
  bool valid = false;           ///< false: use the binary traversal
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
    const auto inv = static_cast<float>(Real(1) / d);
    const float lo = round_down_float(o);
    const float hi = round_up_float(o);
    // Direction > 0: entry at the min plane, measured from the upper origin bound (which
    // can only make the entry earlier), exit at the max plane from the lower bound.
    const bool positive = d > Real(0);
#if PROXIMA_RAY_BVH_SSE
    r.near_origin[a] = _mm_set1_ps(positive ? hi : lo);
    r.far_origin[a] = _mm_set1_ps(positive ? lo : hi);
    r.inv[a] = _mm_set1_ps(inv);
#else
    r.near_origin[a] = positive ? hi : lo;
    r.far_origin[a] = positive ? lo : hi;
    r.inv[a] = inv;
#endif
    r.near_row[a] = 2 * a + (positive ? 0 : 1);
  }
  r.valid = true;
  return r;
}

/// Slab test of the four children of `node` against [0, t_max]: returns the mask of the
/// children hit (bit i = child i) and their entry distances in `t_near`.
inline unsigned test_children(const RayNode4& node, const WideRay& r, float t_max, float t_near[4]) {
#if PROXIMA_RAY_BVH_SSE
  const __m128 nx = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[r.near_row[0]]), r.near_origin[0]), r.inv[0]);
  const __m128 fx = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[r.near_row[0] ^ 1]), r.far_origin[0]), r.inv[0]);
  const __m128 ny = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[r.near_row[1]]), r.near_origin[1]), r.inv[1]);
  const __m128 fy = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[r.near_row[1] ^ 1]), r.far_origin[1]), r.inv[1]);
  const __m128 nz = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[r.near_row[2]]), r.near_origin[2]), r.inv[2]);
  const __m128 fz = _mm_mul_ps(_mm_sub_ps(_mm_load_ps(node.box[r.near_row[2] ^ 1]), r.far_origin[2]), r.inv[2]);
  const __m128 tn = _mm_max_ps(_mm_max_ps(nx, ny), _mm_max_ps(nz, _mm_setzero_ps()));
  const __m128 tf = _mm_min_ps(_mm_min_ps(fx, fy), _mm_min_ps(fz, _mm_set1_ps(t_max)));
  _mm_storeu_ps(t_near, tn);
  return static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(tn, _mm_mul_ps(tf, _mm_set1_ps(kWideSlabWiden)))));
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

/// The ray in the frame of the watertight triangle test (geometry::TriangleRay: axis
/// permutation kx, ky, kz and shear sx, sy), for the conservative rejection of a block.
struct BlockRay {
  Real origin[3];  ///< origin[kx], origin[ky], origin[kz]
  Real sx, sy;     ///< shear
  int kx, ky, kz;  ///< permutation
};

/// Lanes of `block` whose triangle the watertight test may hit (bit i = lane i, unused lanes
/// clear): the edge functions of Woop et al. on the sheared corners, with the same rounding
/// bound as the scalar rejection of triangle_mesh.cpp (16 eps times the magnitudes of the
/// products), so a lane is cleared only when two edge functions have surely opposite signs.
inline unsigned filter_block(const TriangleBlock4& block, const BlockRay& r) {
  const unsigned used = (1u << block.count) - 1u;
#if PROXIMA_RAY_BVH_SSE && !PROXIMA_DOUBLE
  const __m128 ox = _mm_set1_ps(r.origin[0]), oy = _mm_set1_ps(r.origin[1]), oz = _mm_set1_ps(r.origin[2]);
  const __m128 sx = _mm_set1_ps(r.sx), sy = _mm_set1_ps(r.sy);
  const __m128 sign = _mm_set1_ps(-0.0f);
  __m128 x[3], y[3], mx[3], my[3];
  for (int j = 0; j < 3; ++j) {
    const __m128 rx = _mm_sub_ps(_mm_load_ps(block.v[j][r.kx]), ox);
    const __m128 ry = _mm_sub_ps(_mm_load_ps(block.v[j][r.ky]), oy);
    const __m128 rz = _mm_sub_ps(_mm_load_ps(block.v[j][r.kz]), oz);
    const __m128 zx = _mm_mul_ps(sx, rz);
    const __m128 zy = _mm_mul_ps(sy, rz);
    x[j] = _mm_sub_ps(rx, zx);
    y[j] = _mm_sub_ps(ry, zy);
    mx[j] = _mm_add_ps(_mm_andnot_ps(sign, rx), _mm_andnot_ps(sign, zx));
    my[j] = _mm_add_ps(_mm_andnot_ps(sign, ry), _mm_andnot_ps(sign, zy));
  }
  const __m128 k = _mm_set1_ps(16.0f * std::numeric_limits<float>::epsilon());
  const __m128 u = _mm_sub_ps(_mm_mul_ps(x[1], y[2]), _mm_mul_ps(y[1], x[2]));
  const __m128 v = _mm_sub_ps(_mm_mul_ps(x[2], y[0]), _mm_mul_ps(y[2], x[0]));
  const __m128 w = _mm_sub_ps(_mm_mul_ps(x[0], y[1]), _mm_mul_ps(y[0], x[1]));
  const __m128 eu = _mm_mul_ps(k, _mm_add_ps(_mm_mul_ps(mx[1], my[2]), _mm_mul_ps(my[1], mx[2])));
  const __m128 ev = _mm_mul_ps(k, _mm_add_ps(_mm_mul_ps(mx[2], my[0]), _mm_mul_ps(my[2], mx[0])));
  const __m128 ew = _mm_mul_ps(k, _mm_add_ps(_mm_mul_ps(mx[0], my[1]), _mm_mul_ps(my[0], mx[1])));
  const __m128 negative =
      _mm_or_ps(_mm_or_ps(_mm_cmplt_ps(u, _mm_xor_ps(eu, sign)), _mm_cmplt_ps(v, _mm_xor_ps(ev, sign))),
                _mm_cmplt_ps(w, _mm_xor_ps(ew, sign)));
  const __m128 positive = _mm_or_ps(_mm_or_ps(_mm_cmpgt_ps(u, eu), _mm_cmpgt_ps(v, ev)), _mm_cmpgt_ps(w, ew));
  const auto rejected = static_cast<unsigned>(_mm_movemask_ps(_mm_and_ps(negative, positive)));
  return used & ~rejected;
#else
  unsigned mask = 0;
  constexpr Real k = Real(16) * std::numeric_limits<Real>::epsilon();
  for (unsigned lane = 0; lane < block.count; ++lane) {
    Real x[3], y[3], mx[3], my[3];
    for (int j = 0; j < 3; ++j) {
      const Real rx = block.v[j][r.kx][lane] - r.origin[0];
      const Real ry = block.v[j][r.ky][lane] - r.origin[1];
      const Real rz = block.v[j][r.kz][lane] - r.origin[2];
      const Real zx = r.sx * rz, zy = r.sy * rz;
      x[j] = rx - zx;
      y[j] = ry - zy;
      mx[j] = std::abs(rx) + std::abs(zx);
      my[j] = std::abs(ry) + std::abs(zy);
    }
    const Real u = x[1] * y[2] - y[1] * x[2];
    const Real v = x[2] * y[0] - y[2] * x[0];
    const Real w = x[0] * y[1] - y[0] * x[1];
    const Real eu = k * (mx[1] * my[2] + my[1] * mx[2]);
    const Real ev = k * (mx[2] * my[0] + my[2] * mx[0]);
    const Real ew = k * (mx[0] * my[1] + my[0] * mx[1]);
    const bool negative = u < -eu || v < -ev || w < -ew;
    const bool positive = u > eu || v > ev || w > ew;
    if (!(negative && positive)) mask |= 1u << lane;
  }
  return mask & used;
#endif
}

/// Depth-first traversal, nearest child first. `leaf(first_block, count, t_max)` is called
/// for each leaf (its first TriangleBlock4 and triangle count) whose box the ray meets
/// within [0, t_max]; it may lower t_max (a float not below the best hit so far: subtrees
/// entered beyond it are skipped) and returns false to stop. No allocation; fixed stack.
template <class Leaf>
void traverse_wide(const RayBvh& bvh, const WideRay& r, float t_max, Leaf&& leaf) {
  struct Entry {
    std::uint32_t ref;    // node index or first leaf block
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
        const int c0 = std::countr_zero(mask);
        const unsigned rest = mask & (mask - 1);
        if (rest == 0) {  // one child: no ordering
          current = {node.child[c0], node.count[c0], tn[c0]};
          continue;
        }
        const int c1 = std::countr_zero(rest);
        if ((rest & (rest - 1)) == 0) {  // two children: nearer first
          const Entry e0{node.child[c0], node.count[c0], tn[c0]};
          const Entry e1{node.child[c1], node.count[c1], tn[c1]};
          const bool swap = e1.t < e0.t;
          stack[top++] = swap ? e0 : e1;
          current = swap ? e1 : e0;
          continue;
        }
        Entry hit[4];
        int k = 0;
        for (unsigned m = mask; m != 0; m &= m - 1) {
          const int c = std::countr_zero(m);
          const Entry e{node.child[c], node.count[c], tn[c]};
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
    const float limit = t_max * kWideSlabWiden;
    while (true) {
      if (top == 0) return;
      const Entry& e = stack[--top];
      if (e.t <= limit) {
        current = e;
        break;
      }
    }
  }
}

}  // namespace proxima::detail
