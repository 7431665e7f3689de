#pragma once
/// @file sha256.hpp
/// A small SHA-256 (FIPS 180-4) for checking the workload files against SHA256SUMS.
/// Not constant-time and not meant for anything but file integrity checks.

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace proxima::bench {

/// Incremental SHA-256: update() any number of times, then finish() once.
class Sha256 {
 public:
  /// A 32-byte digest.
  using Digest = std::array<std::uint8_t, 32>;

  /// Starts a new hash (the FIPS 180-4 initial state).
  Sha256();
  /// Hashes `size` more bytes from `data`.
  void update(const void* data, std::size_t size);
  /// Hashes more bytes.
  void update(std::string_view bytes) { update(bytes.data(), bytes.size()); }
  /// Pads, finishes and returns the digest; the object must not be updated afterwards.
  Digest finish();

  /// A digest as 64 lower-case hex digits.
  static std::string to_hex(const Digest& digest);

 private:
  void compress(const std::uint8_t* block);

  std::array<std::uint32_t, 8> state_{};
  std::array<std::uint8_t, 64> buffer_{};
  std::size_t buffered_ = 0;
  std::uint64_t total_bytes_ = 0;
};

/// SHA-256 of `bytes` as 64 lower-case hex digits.
std::string sha256_hex(std::string_view bytes);

}  // namespace proxima::bench
