#pragma once
// The brute-force support of a point set: the reference for the hull support searches.
#include <proxima/core/math.hpp>

#include <cstdint>
#include <span>

namespace proxima::test {

/// First index of the largest dot product with `d` over `v` (non-empty), and that product.
inline std::uint32_t brute_support(std::span<const Vec3> v, const Vec3& d, Real& best_dot) {
  std::uint32_t best = 0;
  best_dot = glm::dot(v[0], d);
  for (std::uint32_t i = 1; i < v.size(); ++i) {
    const Real x = glm::dot(v[i], d);
    if (x > best_dot) {
      best_dot = x;
      best = i;
    }
  }
  return best;
}

}  // namespace proxima::test
