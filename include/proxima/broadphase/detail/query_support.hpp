#pragma once
/// @file detail/query_support.hpp
/// Helpers (namespace detail) of the structures' templated queries, which live in their
/// headers because they are templates on the callback: a traversal stack with fixed inline
/// storage, the ray-box slab test with the conventions of broadphase.hpp, the ray input
/// check and the ray-callback protocol (the box and point queries are stated once in
/// broadphase_queries.hpp). Not meant for use outside the broad phase.

#include <proxima/broadphase/broadphase.hpp>

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace proxima::detail {

/// LIFO stack with N entries of inline storage; spills to the heap only beyond N (never in
/// a tree whose height stays below N / 3, which the trees keep by construction).
template <class T, std::size_t N>
class TraversalStack {
 public:
  /// Pushes one entry.
  void push(const T& v) {
    if (size_ < N) {
      inline_[size_] = v;
    } else {
      spill_.push_back(v);
    }
    ++size_;
  }
  /// Pops the top entry (the stack must not be empty).
  T pop() {
    --size_;
    if (size_ < N) return inline_[size_];
    T v = spill_.back();
    spill_.pop_back();
    return v;
  }
  /// True when no entry is left.
  bool empty() const { return size_ == 0; }
  /// Number of entries.
  std::size_t size() const { return size_; }

 private:
  std::array<T, N> inline_{};
  std::vector<T> spill_;
  std::size_t size_ = 0;
};

/// Ray prepared for slab tests (zero direction components flagged in `zero`). Slabs divide
/// by the direction rather than multiply by its inverse, so that a tiny component cannot
/// make an infinite inverse and a NaN product.
struct SlabRay {
  Vec3 origin{Real(0)};
  Vec3 direction{Real(0)};
  bool zero[3] = {false, false, false};

  /// Prepares a ray.
  explicit SlabRay(const Ray& ray) : origin(ray.origin), direction(ray.direction) {
    for (int a = 0; a < 3; ++a) {
      zero[a] = ray.direction[a] == Real(0);
    }
  }

  /// Entry fraction of the ray into the closed box within [0, max_t]; false on a miss.
  /// Never produces NaN: zero direction components are handled as a slab containment test.
  bool enter(const Aabb& box, Real max_t, Real& t_enter) const {
    Real t0 = Real(0);
    Real t1 = max_t;
    for (int a = 0; a < 3; ++a) {
      if (zero[a]) {
        if (origin[a] < box.min[a] || origin[a] > box.max[a]) return false;
        continue;
      }
      Real ta = (box.min[a] - origin[a]) / direction[a];
      Real tb = (box.max[a] - origin[a]) / direction[a];
      if (ta > tb) std::swap(ta, tb);
      if (ta > t0) t0 = ta;
      if (tb < t1) t1 = tb;
      if (t0 > t1) return false;
    }
    t_enter = t0;
    return true;
  }
};

/// True when a node's slab interval [t0, t1] is empty beyond a small slack (1e-4 relative):
/// node tests only prune, the boxes themselves are tested exactly. An infinite t1 (a
/// subnormal direction component) takes no slack, since -inf + inf is an invalid operation.
inline bool slab_interval_empty(Real t0, Real t1) {
  const Real slack = std::isfinite(t1) ? std::abs(t1) * Real(1e-4) + Real(1e-30) : Real(0);
  return t0 > t1 + slack;
}

/// True when a ray query has defined, hit-capable input: finite origin and direction and
/// max_t >= 0 (max_t may be +infinity; NaN is rejected).
inline bool ray_input_ok(const Ray& ray, Real max_t) {
  for (int a = 0; a < 3; ++a) {
    if (!std::isfinite(ray.origin[a]) || !std::isfinite(ray.direction[a])) return false;
  }
  return std::isgreaterequal(max_t, Real(0));  // quiet: a NaN raises no invalid flag
}

/// Applies the ray-callback protocol: returns false when the query must stop; updates max_t.
inline bool apply_ray_result(Real result, Real& max_t) {
  if (result < Real(0)) return true;  // ignore this proxy (NaN compares false: also kept going below)
  if (result == Real(0)) {
    max_t = Real(0);
    return false;
  }
  if (result < max_t) max_t = result;
  return true;
}

}  // namespace proxima::detail
