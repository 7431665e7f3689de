#pragma once
// What the fuzz targets share: the floating-point traps, a reader that turns the fuzzer's
// bytes into bounded values (never failing: an exhausted input reads zeros), and the report
// of a violated property (printed, then abort(), which libFuzzer and ctest both see as a
// crash).
#include <proxima/core/math.hpp>

#include <cfenv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <span>

namespace proxima::fuzz {

/// Turns on the "invalid operation" trap (glibc), as the test main does: any NaN made by the
/// code under test stops at the faulty instruction (SIGFPE, a crash to the fuzzer).
inline void enable_traps() {
#if defined(__GLIBC__) && !defined(PROXIMA_NO_FP_TRAPS)
  feenableexcept(FE_INVALID);
#endif
}

/// enable_traps() once per process: every target calls it first (libFuzzer has no main of
/// ours to call it from).
inline void start_target() {
  static const bool started = (enable_traps(), true);
  (void)started;
}

/// What fail() prints before it aborts: a target sets it to describe the input at hand
/// (shapes, poses, answers), so that a crash report says what was being checked.
inline std::function<void()>& failure_context() {
  static std::function<void()> context;
  return context;
}

/// Prints a vector as "(x, y, z)" with every digit of a Real.
inline void print_vec(const char* name, const Vec3& v) {
  std::fprintf(stderr, "  %s (%.9g, %.9g, %.9g)\n", name, double(v.x), double(v.y), double(v.z));
}

/// Reports a violated property and aborts.
[[noreturn]] inline void fail(const char* what) {
  std::fprintf(stderr, "fuzz property violated: %s\n", what);
  if (failure_context()) failure_context()();
  std::fflush(stderr);
  std::abort();
}

/// Aborts with `what` unless `condition` holds.
inline void check(bool condition, const char* what) {
  if (!condition) fail(what);
}

/// Aborts unless every component is finite.
inline void check_finite(Real x, const char* what) { check(std::isfinite(x), what); }
inline void check_finite(const Vec3& v, const char* what) {
  check(std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z), what);
}

/// Reads the fuzzer's bytes front to back; past the end every read gives zero.
class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  /// Bytes not yet read.
  std::size_t remaining() const { return size_ - offset_; }
  bool empty() const { return offset_ >= size_; }

  std::uint8_t byte() { return offset_ < size_ ? data_[offset_++] : std::uint8_t{0}; }
  std::uint16_t u16() { return static_cast<std::uint16_t>(byte() | (byte() << 8)); }
  std::uint32_t u32() { return static_cast<std::uint32_t>(u16()) | (static_cast<std::uint32_t>(u16()) << 16); }

  /// An integer in [0, count) (count >= 1).
  std::uint32_t index(std::uint32_t count) { return count <= 256 ? byte() % count : u32() % count; }
  bool flag() { return (byte() & 1) != 0; }

  /// A value in [0, 1] on a grid of 65536 steps (so that exact 0, 1 and halves occur).
  Real unit() { return static_cast<Real>(u16()) / Real(65535); }
  /// A value in [lo, hi].
  Real in_range(Real lo, Real hi) { return lo + (hi - lo) * unit(); }
  /// A positive length from `lo` to `hi` spread evenly over the decades between.
  Real log_range(Real lo, Real hi) { return lo * std::pow(hi / lo, unit()); }
  /// A point of the cube [-half, half]^3.
  Vec3 vec_in(Real half) { return {in_range(-half, half), in_range(-half, half), in_range(-half, half)}; }
  /// A unit quaternion: four components normalised (the identity when all four are 0), or,
  /// for a quarter of the inputs, a quarter turn about an axis or the identity.
  Quat rotation() {
    const std::uint8_t kind = byte();
    if (kind % 4 == 0) {
      static constexpr Real h = Real(0.70710678118654752);
      switch ((kind / 4) % 4) {
        case 0: return Quat(Real(1), Real(0), Real(0), Real(0));
        case 1: return Quat(h, h, Real(0), Real(0));
        case 2: return Quat(h, Real(0), h, Real(0));
        default: return Quat(h, Real(0), Real(0), h);
      }
    }
    Quat q(in_range(-1, 1), in_range(-1, 1), in_range(-1, 1), in_range(-1, 1));
    const Real n = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!(n > Real(1e-3))) return Quat(Real(1), Real(0), Real(0), Real(0));
    return Quat(q.w / n, q.x / n, q.y / n, q.z / n);
  }
  /// Every bit pattern of a Real: NaN, infinities, subnormals, the largest values. NaNs are
  /// made quiet: a signaling NaN raises the invalid flag in any comparison, std::isfinite
  /// included, which is what it is for; the library is asked to refuse quiet NaNs without
  /// raising it.
  Real raw_real() {
    Real x;
    if constexpr (sizeof(Real) == 4) {
      std::uint32_t bits = u32();
      if ((bits & 0x7f800000u) == 0x7f800000u && (bits & 0x007fffffu) != 0) bits |= 0x00400000u;
      std::memcpy(&x, &bits, sizeof x);
    } else {
      std::uint64_t bits = static_cast<std::uint64_t>(u32()) | (static_cast<std::uint64_t>(u32()) << 32);
      constexpr std::uint64_t exponent = 0x7ff0000000000000u, mantissa = 0x000fffffffffffffu;
      if ((bits & exponent) == exponent && (bits & mantissa) != 0) bits |= 0x0008000000000000u;
      std::memcpy(&x, &bits, sizeof x);
    }
    return x;
  }
  /// The bytes not yet read, all of them.
  std::span<const std::uint8_t> rest() {
    std::span<const std::uint8_t> tail(data_ + offset_, remaining());
    offset_ = size_;
    return tail;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t offset_ = 0;
};

}  // namespace proxima::fuzz
