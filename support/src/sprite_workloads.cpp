// Readers of the W9 sprite files (shared/bench/FORMATS.md):
//   1. check the header (kind, version 1, the keys needed);
//   2. sprite_masks: per mask, a `mask <id> <w> <h>` line (ids in order) and h hex rows of
//      ceil(w / 4) digits each (a row of another length fails at its line), turned into a
//      SpriteMask (its own validation names the row and digit of a bad digit or padding
//      bit, reported at the mask's last line);
//   3. sprites: `maskA xA yA maskB xB yB [rot=<deg> scale=<s>]` lines, ids checked against
//      the masks file the header names (same folder);
//   4. sprites_expected: `<query> <0|1> <count>` lines;
//   5. any problem becomes an Error whose field is "<path>:<line>".
#include "support/sprite_workloads.hpp"

#include <charconv>
#include <limits>

#include "text_parse.hpp"

namespace proxima::bench {
using namespace detail;

namespace {

std::int64_t parse_integer(const Source& src, std::string_view token, const char* what) {
  std::int64_t value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) {
    src.fail_here(std::string(what) + " " + quoted(token) + " is not an integer");
  }
  return value;
}

/// The value of a `key=value` token, or fails.
std::string_view keyed(const Source& src, std::string_view token, std::string_view key) {
  if (token.substr(0, key.size() + 1) != std::string(key) + "=") {
    src.fail_here("expected " + std::string(key) + "=<number>, not " + quoted(token));
  }
  return token.substr(key.size() + 1);
}

d2::SpriteMask read_one_mask(Source& src, std::uint64_t id) {
  std::string_view line;
  if (!src.next_record(line)) fail(src.path(), src.line(), "file ends before mask " + std::to_string(id));
  const auto t = split(line);
  if (t.size() != 4 || t[0] != "mask") src.fail_here("expected 'mask <id> <w> <h>'");
  if (parse_unsigned(src, t[1], "mask id") != id) src.fail_here("mask ids must be 0, 1, 2, ... in order");
  const std::uint64_t width = parse_unsigned(src, t[2], "width");
  const std::uint64_t height = parse_unsigned(src, t[3], "height");
  if (width > d2::kMaxSpriteSide || height > d2::kMaxSpriteSide) src.fail_here("mask larger than kMaxSpriteSide");
  std::vector<std::string> rows;
  rows.reserve(reservable(src, height));
  for (std::uint64_t y = 0; y < height; ++y) {
    if (!src.next_raw(line)) fail(src.path(), src.line(), "file ends inside mask " + std::to_string(id));
    while (!line.empty() && is_space(line.back())) line.remove_suffix(1);
    if (line.size() != (width + 3) / 4) {
      src.fail_here("row " + std::to_string(y) + " of mask " + std::to_string(id) +
                    " must have ceil(w / 4) = " + std::to_string((width + 3) / 4) + " hex digits");
    }
    rows.emplace_back(line);
  }
  auto mask = d2::SpriteMask::from_hex_rows(static_cast<std::int32_t>(width), rows);
  if (!mask) src.fail_here("mask " + std::to_string(id) + ": " + mask.error().what());
  return std::move(mask).value();
}

SpriteQuery parse_query(const Source& src, const std::vector<std::string_view>& t, std::size_t masks) {
  if (t.size() != 6 && t.size() != 8) src.fail_here("expected 'maskA xA yA maskB xB yB [rot=<deg> scale=<s>]'");
  SpriteQuery q;
  const std::uint64_t a = parse_unsigned(src, t[0], "maskA"), b = parse_unsigned(src, t[3], "maskB");
  if (a >= masks || b >= masks) src.fail_here("mask id beyond the masks file's count");
  q.mask_a = static_cast<std::uint32_t>(a);
  q.mask_b = static_cast<std::uint32_t>(b);
  q.xa = parse_integer(src, t[1], "xA");
  q.ya = parse_integer(src, t[2], "yA");
  q.xb = parse_integer(src, t[4], "xB");
  q.yb = parse_integer(src, t[5], "yB");
  if (t.size() == 8) {
    q.turned = true;
    q.angle_degrees = parse_double(src, keyed(src, t[6], "rot"));
    q.scale = parse_positive(src, keyed(src, t[7], "scale"), "scale");
  }
  return q;
}

}  // namespace

Result<std::vector<d2::SpriteMask>> read_sprite_masks(const std::string& path) {
  return guarded<std::vector<d2::SpriteMask>>([&]() {
    Source src(path);
    const Header h = expect_header(src, "sprite_masks");
    const std::uint64_t count = require_count(src, h, "count");
    const auto encoding = h.keys.find("encoding");
    if (encoding != h.keys.end() && encoding->second != "hex") fail(path, 1, "encoding= must be hex");
    std::vector<d2::SpriteMask> masks;
    masks.reserve(reservable(src, count));
    for (std::uint64_t id = 0; id < count; ++id) masks.push_back(read_one_mask(src, id));
    std::string_view line;
    if (src.next_record(line)) src.fail_here("more masks than the header's count=" + std::to_string(count));
    return masks;
  });
}

Result<SpriteWorkload> read_sprite_workload(const std::string& path) {
  const std::string masks_name = header_value(path, "masks");
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? std::string(".") : path.substr(0, slash);
  auto masks = masks_name.empty() ? Result<std::vector<d2::SpriteMask>>(std::vector<d2::SpriteMask>{})
                                  : read_sprite_masks(dir + "/" + masks_name);
  if (!masks) return masks.error();
  return guarded<SpriteWorkload>([&]() {
    Source src(path);
    const Header h = expect_header(src, "sprites");
    const std::uint64_t count = require_count(src, h, "count");
    const std::uint64_t repeat = require_count(src, h, "repeat");
    require_key(src, h, "masks");
    if (repeat == 0) fail(path, 1, "repeat= must be >= 1");
    if (count > 0 && repeat > kMaxWorkloadQueries / count) {
      fail(path, 1, "count= * repeat= is more than kMaxWorkloadQueries (2^24)");
    }
    SpriteWorkload out;
    out.masks = std::move(masks).value();
    out.repeat = repeat;
    out.distinct.reserve(reservable(src, count));
    read_records(src, count, [&](const std::vector<std::string_view>& t) {
      out.distinct.push_back(parse_query(src, t, out.masks.size()));
    });
    return out;
  });
}

Result<std::vector<SpriteExpected>> read_sprites_expected(const std::string& path) {
  return guarded<std::vector<SpriteExpected>>([&]() {
    Source src(path);
    const Header h = expect_header(src, "sprites_expected");
    const std::uint64_t count = require_count(src, h, "count");
    std::vector<SpriteExpected> out;
    out.reserve(reservable(src, count));
    read_records(src, count, [&](const std::vector<std::string_view>& t) {
      expect_tokens(src, t, 3, "<query> <0|1> <count>");
      SpriteExpected e;
      e.query = parse_unsigned(src, t[0], "query index");
      const std::uint64_t flag = parse_unsigned(src, t[1], "overlap flag");
      if (flag > 1) src.fail_here("the overlap flag must be 0 or 1");
      e.overlap = flag == 1;
      e.count = parse_unsigned(src, t[2], "count");
      out.push_back(e);
    });
    return out;
  });
}

}  // namespace proxima::bench
