// The W9 sprite workload (shared/bench/FORMATS.md): every query of sprites.txt against the
// per-pixel loop of sprite_reference.hpp, and the first 2,000 against
// sprites_expected.txt exactly. Skips when the shared data folder is absent.
#include <gtest/gtest.h>

#include <proxima/d2/sprite_overlap.hpp>

#include <filesystem>

#include "d2/sprite_reference.hpp"
#include "support/sprite_workloads.hpp"
#include "support/workloads.hpp"
#include "sweep_size.hpp"

namespace proxima::d2 {
namespace {

using bench::SpriteQuery;
using bench::SpriteWorkload;

/// The W9 workload, or nothing when the data folder lacks it.
std::optional<SpriteWorkload> load_workload() {
  const std::string path = bench::workload_path(bench::workload_dir(), "sprites.txt");
  if (!std::filesystem::exists(path)) return std::nullopt;
  return bench::read_sprite_workload(path).value();
}

SpriteOverlap answer(const SpriteWorkload& w, const SpriteQuery& q) {
  const SpriteMask& a = w.masks[q.mask_a];
  const SpriteMask& b = w.masks[q.mask_b];
  if (!q.turned) return sprite_overlap(a, {q.xa, q.ya}, b, {q.xb, q.yb});
  return sprite_overlap(a, {q.xa, q.ya}, b, TurnedPlacement::create({q.xb, q.yb}, q.angle_degrees, q.scale).value());
}

SpriteOverlap reference(const SpriteWorkload& w, const SpriteQuery& q) {
  const SpriteMask& a = w.masks[q.mask_a];
  const SpriteMask& b = w.masks[q.mask_b];
  if (!q.turned) return test::reference_overlap(a, {q.xa, q.ya}, b, {q.xb, q.yb});
  return test::reference_turned(a, {q.xa, q.ya}, b, {q.xb, q.yb}, q.angle_degrees, q.scale);
}

TEST(SpriteWorkload, ReaderSeesTheHeaders) {
  const auto w = load_workload();
  if (!w) GTEST_SKIP() << "sprites.txt not found in " << bench::workload_dir();
  ASSERT_EQ(w->masks.size(), 64u);
  EXPECT_EQ(w->distinct.size(), 20000u);
  EXPECT_EQ(w->query_count(), 100000u);
  EXPECT_EQ(w->masks[2].width(), 256);
  EXPECT_EQ(w->masks[2].height(), 8);
  std::size_t turned = 0;
  for (const SpriteQuery& q : w->distinct) turned += q.turned ? 1 : 0;
  EXPECT_GT(turned, 1000u);
  EXPECT_LT(turned, 4000u);
}

TEST(SpriteWorkload, EveryQueryMatchesPerPixelLoop) {
  const auto w = load_workload();
  if (!w) GTEST_SKIP() << "sprites.txt not found in " << bench::workload_dir();
  const int queries = test::sweep_size(static_cast<int>(w->distinct.size()));
  int overlapping = 0;
  for (int k = 0; k < queries; ++k) {
    const SpriteQuery& q = w->distinct[static_cast<std::size_t>(k)];
    const SpriteOverlap want = reference(*w, q), got = answer(*w, q);
    ASSERT_EQ(got, want) << "query " << k;
    overlapping += got.overlap ? 1 : 0;
  }
  EXPECT_GT(overlapping, 0);
}

TEST(SpriteWorkload, FirstQueriesMatchExpectedFile) {
  const auto w = load_workload();
  const std::string path = bench::workload_path(bench::workload_dir(), "sprites_expected.txt");
  if (!w || !std::filesystem::exists(path)) GTEST_SKIP() << "W9 files not found in " << bench::workload_dir();
  const auto expected = bench::read_sprites_expected(path).value();
  ASSERT_EQ(expected.size(), 2000u);
  for (const bench::SpriteExpected& e : expected) {
    const SpriteOverlap got = answer(*w, w->distinct.at(e.query));
    EXPECT_EQ(got.count, e.count) << "query " << e.query;
    EXPECT_EQ(got.overlap, e.overlap) << "query " << e.query;
  }
}

}  // namespace
}  // namespace proxima::d2
