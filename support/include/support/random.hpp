#pragma once
// Seeded random generators for the randomized sweeps: every sweep names its seed so a
// failure reproduces exactly.
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>

#include <cfenv>
#include <cstdint>
#include <random>

namespace proxima::test {

/// Deterministic source of random geometry for tests (std::mt19937_64 with a fixed seed).
class Random {
 public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}

  /// Uniform in [lo, hi).
  Real uniform(Real lo, Real hi);
  /// Uniform integer in [lo, hi].
  int integer(int lo, int hi);
  /// Each coordinate uniform in [lo, hi).
  Vec3 vec3(Real lo, Real hi);
  /// Each coordinate uniform in [lo[i], hi[i]), drawn z first, then y, then x (the order of
  /// the three-argument form `Vec3(uniform(..x..), uniform(..y..), uniform(..z..))` under GCC,
  /// which the sweeps' seeds were chosen with).
  Vec3 in_box(const Vec3& lo, const Vec3& hi);
  /// A uniform direction times a length uniform in [lo, hi); the length is drawn first.
  Vec3 vector_of_length(Real lo, Real hi);
  /// Uniform in the ball of radius r.
  Vec3 in_ball(Real r);
  /// Uniform on the unit sphere.
  Vec3 unit_vector();
  /// Uniform random rotation (Shoemake's method).
  Quat rotation();
  /// Position in the cube [-extent, extent]^3 and a uniform rotation.
  Transform pose(Real extent);

  /// The underlying engine, for std distributions.
  std::mt19937_64& engine() { return engine_; }

 private:
  std::mt19937_64 engine_;
};

/// Disables the floating-point invalid-operation trap for the scope (for tests that feed
/// NaN on purpose and compare it).
class ScopedNoFpTraps {
 public:
  ScopedNoFpTraps() {
#if defined(__GLIBC__)
    saved_ = fedisableexcept(FE_ALL_EXCEPT);
#endif
  }
  ~ScopedNoFpTraps() {
#if defined(__GLIBC__)
    std::feclearexcept(FE_ALL_EXCEPT);
    if (saved_ >= 0) feenableexcept(saved_);
#endif
  }
  ScopedNoFpTraps(const ScopedNoFpTraps&) = delete;
  ScopedNoFpTraps& operator=(const ScopedNoFpTraps&) = delete;

 private:
  int saved_ = -1;
};

}  // namespace proxima::test
