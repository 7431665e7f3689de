#pragma once
/// @file sprite_workloads.hpp
/// The W9 sprite workload of shared/bench/FORMATS.md: the masks (`sprite_masks.txt`, hex
/// rows), the queries (`sprites.txt`: mask A at an integer position, mask B at an integer
/// position, optionally turned by integer degrees and scaled) and the reference answers
/// (`sprites_expected.txt`).
///
/// As for W1..W8 (workloads.hpp): the header is checked (kind, version 1, the keys needed;
/// unknown keys ignored), blank and `#` lines are skipped, and a malformed file gives an
/// Error whose field is "<path>:<line>".

#include <proxima/core/result.hpp>
#include <proxima/d2/sprite_mask.hpp>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace proxima::bench {

/// One W9 query: mask A at (xa, ya); mask B at (xb, yb), turned by `angle_degrees`
/// (clockwise on screen) and scaled by `scale` about its centre when `turned`.
struct SpriteQuery {
  std::uint32_t mask_a = 0;  ///< index into SpriteWorkload::masks
  std::int64_t xa = 0;       ///< A's screen column, pixels
  std::int64_t ya = 0;       ///< A's screen row, pixels
  std::uint32_t mask_b = 0;  ///< index into SpriteWorkload::masks
  std::int64_t xb = 0;       ///< B's screen column, pixels
  std::int64_t yb = 0;       ///< B's screen row, pixels
  bool turned = false;       ///< true when the line has rot= and scale=
  double angle_degrees = 0;  ///< rot= (integer degrees as written)
  double scale = 1;          ///< scale= (> 0)
};

/// The W9 sprite workload: the masks and the `count` distinct queries repeated `repeat`
/// times (query k uses distinct[k mod count]).
struct SpriteWorkload {
  std::vector<d2::SpriteMask> masks;  ///< mask id = index
  std::vector<SpriteQuery> distinct;  ///< the queries as written, mask ids checked
  std::size_t repeat = 1;             ///< header repeat=

  /// Number of queries of the workload: count * repeat.
  std::size_t query_count() const { return distinct.size() * repeat; }
  /// Query k (0 <= k < query_count()).
  const SpriteQuery& query(std::size_t k) const { return distinct[k % distinct.size()]; }
};

/// One reference answer of `sprites_expected.txt`.
struct SpriteExpected {
  std::size_t query = 0;    ///< query index
  bool overlap = false;     ///< count > 0
  std::uint64_t count = 0;  ///< screen pixels set in both placed masks
};

/// W9 `sprite_masks` (needs count; encoding=hex when present): the masks in id order.
Result<std::vector<d2::SpriteMask>> read_sprite_masks(const std::string& path);
/// W9 `sprites` (needs count, repeat, masks) and the masks file it names (same folder),
/// every mask id checked.
Result<SpriteWorkload> read_sprite_workload(const std::string& path);
/// W9 `sprites_expected` (needs count).
Result<std::vector<SpriteExpected>> read_sprites_expected(const std::string& path);

}  // namespace proxima::bench
