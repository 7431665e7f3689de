// The W9 sprite workload (shared/bench/FORMATS.md): every query of sprites.txt against the
// per-pixel loop of sprite_reference.hpp, and the first 2,000 against
// sprites_expected.txt exactly. Skips when the shared data folder is absent.
#include <gtest/gtest.h>

#include <proxima/d2/sprite_overlap.hpp>

#include <filesystem>
#include <fstream>

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

/// Writes `text` to a file of the test's temporary folder and returns its path.
std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = (std::filesystem::temp_directory_path() / name).string();
  std::ofstream(path) << text;
  return path;
}

TEST(SpriteWorkload, MalformedFilesNameTheLine) {
  const std::string masks =
      write_file("proxima_w9_masks.txt", "sprite_masks 1 count=2\nmask 0 5 1\nf8\nmask 1 4 2\n0\n00\n");
  const auto bad_row = bench::read_sprite_masks(masks);
  ASSERT_FALSE(bad_row.ok());
  EXPECT_EQ(bad_row.error().field, masks + ":6");
  EXPECT_NE(bad_row.error().message.find("row 1 of mask 1"), std::string::npos) << bad_row.error().message;
  write_file("proxima_w9_masks.txt", "sprite_masks 1 count=1\nmask 0 5 2\nf8\nfc\n");
  const auto bad_padding = bench::read_sprite_masks(masks);
  ASSERT_FALSE(bad_padding.ok());
  EXPECT_NE(bad_padding.error().message.find("rows[1]"), std::string::npos) << bad_padding.error().message;
  write_file("proxima_w9_masks.txt", "sprite_masks 1 count=1\nmask 0 4 1\nf\n");
  const std::string queries = write_file(
      "proxima_w9_sprites.txt", "sprites 1 count=2 repeat=5 masks=proxima_w9_masks.txt\n0 1 2 0 3 4\n0 1 2 1 3 4\n");
  const auto bad_id = bench::read_sprite_workload(queries);
  ASSERT_FALSE(bad_id.ok());
  EXPECT_EQ(bad_id.error().field, queries + ":3");
  write_file("proxima_w9_sprites.txt",
             "sprites 1 count=1 repeat=5 masks=proxima_w9_masks.txt\n0 1 2 0 3 4 rot=30 scale=-1\n");
  const auto bad_scale = bench::read_sprite_workload(queries);
  ASSERT_FALSE(bad_scale.ok());
  EXPECT_EQ(bad_scale.error().field, queries + ":2");
  write_file("proxima_w9_sprites.txt",
             "sprites 1 count=1 repeat=5 masks=proxima_w9_masks.txt\n0 1 2 0 3 4 rot=30 scale=1.5\n");
  const SpriteWorkload good = bench::read_sprite_workload(queries).value();
  ASSERT_EQ(good.query_count(), 5u);
  EXPECT_TRUE(good.query(4).turned);
  EXPECT_EQ(good.query(4).angle_degrees, 30.0);
  EXPECT_EQ(good.query(4).scale, 1.5);
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
