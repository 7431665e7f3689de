#pragma once
// Parsing machinery shared by the workload readers (workloads.cpp, world_workloads.cpp,
// world2d_workloads.cpp): internal to proxima_support, not installed. Every reader body runs
// inside guarded(), which turns the internal ParseFailure into the Error of the Result it
// returns.
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "support/workloads.hpp"

namespace proxima::bench::detail {
// ---------------------------------------------------------------------------------
// Parsing machinery (internal exceptions, turned into Result at the API boundary)
// ---------------------------------------------------------------------------------

struct ParseFailure {
  Error error;
};

[[noreturn]] inline void fail(const std::string& path, int line, const std::string& message) {
  std::string where = path;
  if (line > 0) where += ":" + std::to_string(line);
  throw ParseFailure{make_error(ErrorCode::InvalidArgument, where, message)};
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

/// Splits a line into whitespace-separated tokens.
inline std::vector<std::string_view> split(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_space(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !is_space(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

/// The text of a file, handed out line by line with line numbers.
class Source {
 public:
  explicit Source(std::string path) : path_(std::move(path)) {
    std::ifstream in(path_, std::ios::binary);
    if (!in) fail(path_, 0, "cannot open the file");
    std::ostringstream buffer;
    buffer << in.rdbuf();
    text_ = buffer.str();
  }

  const std::string& path() const { return path_; }
  int line() const { return line_; }

  /// The next line, blank or not; false at the end.
  bool next_raw(std::string_view& out) {
    if (pos_ >= text_.size()) return false;
    const std::size_t end = text_.find('\n', pos_);
    const std::size_t stop = end == std::string::npos ? text_.size() : end;
    out = std::string_view(text_).substr(pos_, stop - pos_);
    pos_ = end == std::string::npos ? text_.size() : end + 1;
    ++line_;
    return true;
  }

  /// The next line that is neither blank nor a `#` comment; false at the end.
  bool next_record(std::string_view& out) {
    while (next_raw(out)) {
      std::size_t i = 0;
      while (i < out.size() && is_space(out[i])) ++i;
      if (i == out.size() || out[i] == '#') continue;
      return true;
    }
    return false;
  }

  [[noreturn]] void fail_here(const std::string& message) const { fail(path_, line_, message); }

  /// Bytes not read yet.
  std::size_t remaining_bytes() const { return text_.size() - pos_; }

 private:
  std::string path_;
  std::string text_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

inline std::string quoted(std::string_view s) {
  std::string out;
  out.reserve(s.size() + 2);
  out.push_back('\'');
  out.append(s);
  out.push_back('\'');
  return out;
}

inline double parse_double(const Source& src, std::string_view token) {
  std::string_view t = token;
  if (!t.empty() && t.front() == '+') t.remove_prefix(1);
  double value = 0;
  const auto [ptr, ec] = std::from_chars(t.data(), t.data() + t.size(), value);
  if (ec != std::errc() || ptr != t.data() + t.size()) src.fail_here(quoted(token) + " is not a number");
  if (!std::isfinite(value)) src.fail_here(quoted(token) + " is not a finite number");
  return value;
}

inline std::uint64_t parse_unsigned(const Source& src, std::string_view token, const std::string& what) {
  std::uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || ptr != token.data() + token.size()) {
    src.fail_here(what + " " + quoted(token) + " is not a non-negative integer");
  }
  return value;
}

/// Checks the token count of a record line.
inline void expect_tokens(const Source& src, const std::vector<std::string_view>& tokens, std::size_t n,
                          const char* layout) {
  if (tokens.size() != n) {
    src.fail_here("expected " + std::to_string(n) + " fields (" + layout + "), found " + std::to_string(tokens.size()));
  }
}

inline Vec3d parse_vec3(const Source& src, const std::vector<std::string_view>& t, std::size_t at) {
  return {parse_double(src, t[at]), parse_double(src, t[at + 1]), parse_double(src, t[at + 2])};
}

inline Vec3d parse_positive_vec3(const Source& src, const std::vector<std::string_view>& t, std::size_t at,
                                 const char* what) {
  const Vec3d v = parse_vec3(src, t, at);
  if (!(v.x > 0 && v.y > 0 && v.z > 0)) src.fail_here(std::string(what) + " must be > 0");
  return v;
}

inline double parse_positive(const Source& src, std::string_view token, const char* what) {
  const double v = parse_double(src, token);
  if (!(v > 0)) src.fail_here(std::string(what) + " must be > 0, found " + quoted(token));
  return v;
}

/// Normalises a quaternion read from the file (FORMATS.md: divide by its length).
inline Quatd normalized(const Source& src, double w, double x, double y, double z) {
  const double n = std::sqrt(w * w + x * x + y * y + z * z);
  if (!(n > 0) || !std::isfinite(n)) src.fail_here("quaternion of zero length");
  return {w / n, x / n, y / n, z / n};
}

inline Pose parse_pose(const Source& src, const std::vector<std::string_view>& t, std::size_t at) {
  Pose p;
  p.position = parse_vec3(src, t, at);
  p.rotation = normalized(src, parse_double(src, t[at + 3]), parse_double(src, t[at + 4]), parse_double(src, t[at + 5]),
                          parse_double(src, t[at + 6]));
  return p;
}

inline Header parse_header(Source& src) {
  std::string_view line;
  if (!src.next_raw(line)) fail(src.path(), 1, "empty file: expected a header line '<kind> 1 key=value ...'");
  const auto tokens = split(line);
  if (tokens.size() < 2) src.fail_here("malformed header: expected '<kind> <version> key=value ...'");
  Header h;
  h.kind = std::string(tokens[0]);
  std::uint64_t version = 0;
  const auto [ptr, ec] = std::from_chars(tokens[1].data(), tokens[1].data() + tokens[1].size(), version);
  if (ec != std::errc() || ptr != tokens[1].data() + tokens[1].size() || version > 1000000) {
    src.fail_here("malformed header: version " + quoted(tokens[1]) + " is not an integer");
  }
  h.version = static_cast<int>(version);
  for (std::size_t i = 2; i < tokens.size(); ++i) {
    const std::size_t eq = tokens[i].find('=');
    if (eq == std::string_view::npos || eq == 0) {
      src.fail_here("malformed header: " + quoted(tokens[i]) + " is not key=value");
    }
    h.keys[std::string(tokens[i].substr(0, eq))] = std::string(tokens[i].substr(eq + 1));
  }
  return h;
}

/// Every kind of FORMATS.md that these readers know (W1..W9), for "wrong kind" messages.
inline constexpr const char* kKnownKinds[] = {"broadphase",
                                              "convex_shapes",
                                              "convex_pairs",
                                              "box_pairs",
                                              "mesh_poses",
                                              "rays",
                                              "ccd_pairs",
                                              "sphere_pairs",
                                              "capsule_pairs",
                                              "world",
                                              "world_bullets_expected",
                                              "polygons2d_pairs",
                                              "sprite_masks",
                                              "sprites",
                                              "sprites_expected",
                                              "world2d"};

/// Reads the header and checks that it is `kind` version 1.
inline Header expect_header(Source& src, const char* kind) {
  Header h = parse_header(src);
  if (h.kind != kind) {
    const bool known = std::find(std::begin(kKnownKinds), std::end(kKnownKinds), h.kind) != std::end(kKnownKinds);
    src.fail_here(std::string(known ? "wrong kind " : "unknown kind ") + quoted(h.kind) + ", expected " + quoted(kind));
  }
  if (h.version != 1) {
    src.fail_here("unsupported version " + std::to_string(h.version) + " of " + quoted(kind) +
                  " (this reader knows version 1)");
  }
  return h;
}

inline const std::string& require_key(const Source& src, const Header& h, const char* key) {
  const auto it = h.keys.find(key);
  if (it == h.keys.end()) fail(src.path(), 1, std::string("header lacks the key ") + key + "=");
  return it->second;
}

/// A header value of N finite numbers joined by commas, no spaces (`lo=0,0,0`).
template <std::size_t N>
std::array<double, N> require_numbers(const Source& src, const Header& h, const char* key) {
  const std::string& text = require_key(src, h, key);
  const std::string what = std::string("header key ") + key + "=" + text + " is not " + std::to_string(N) +
                           " finite numbers joined by commas";
  std::array<double, N> v{};
  std::size_t start = 0;
  for (std::size_t a = 0; a < N; ++a) {
    const std::size_t comma = text.find(',', start);
    if ((a + 1 < N) != (comma != std::string::npos)) fail(src.path(), 1, what);
    const std::string_view part = std::string_view(text).substr(start, a + 1 < N ? comma - start : std::string::npos);
    const auto [ptr, ec] = std::from_chars(part.data(), part.data() + part.size(), v[a]);
    if (part.empty() || ec != std::errc() || ptr != part.data() + part.size() || !std::isfinite(v[a])) {
      fail(src.path(), 1, what);
    }
    start = comma + 1;
  }
  return v;
}

/// Splits a record at '|' into its fields.
inline std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t bar = line.find('|', start);
    parts.push_back(line.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start));
    if (bar == std::string_view::npos) return parts;
    start = bar + 1;
  }
}

/// The fields of a W8 / W9 world record `<id> <static|moving> <shape ...> | <pose> |
/// <velocities>`, the id checked against the record's index.
struct ObjectRecord {
  bool is_static = false;       ///< "static" (else "moving")
  std::string_view shape;       ///< the shape's tokens, from its kind name on
  std::string_view pose;        ///< the pose field
  std::string_view velocities;  ///< the velocities field
};

/// Splits record `k` of a world file into its fields (errors at the source's line).
inline ObjectRecord parse_object_record(const Source& src, std::string_view line, std::uint64_t k) {
  const auto parts = split_fields(line);
  if (parts.size() != 3) {
    src.fail_here("expected 3 fields separated by '|' (id kind shape | pose | velocities), found " +
                  std::to_string(parts.size()));
  }
  const auto head = split(parts[0]);
  if (head.size() < 3) src.fail_here("expected '<id> <static|moving> <shape ...>'");
  if (parse_unsigned(src, head[0], "object id") != k) {
    src.fail_here("object id " + std::string(head[0]) + " out of order, expected " + std::to_string(k));
  }
  ObjectRecord r;
  if (head[1] == "static") {
    r.is_static = true;
  } else if (head[1] != "moving") {
    src.fail_here("expected 'static' or 'moving', found " + quoted(head[1]));
  }
  r.shape = parts[0].substr(static_cast<std::size_t>(head[2].data() - parts[0].data()));
  r.pose = parts[1];
  r.velocities = parts[2];
  return r;
}

inline std::uint64_t require_count(const Source& src, const Header& h, const char* key) {
  const std::string& text = require_key(src, h, key);
  std::uint64_t value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size()) {
    fail(src.path(), 1, std::string("header key ") + key + "=" + text + " is not a non-negative integer");
  }
  return value;
}

inline double require_number(const Source& src, const Header& h, const char* key) {
  const std::string& text = require_key(src, h, key);
  double value = 0;
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || ptr != text.data() + text.size() || !std::isfinite(value)) {
    fail(src.path(), 1, std::string("header key ") + key + "=" + text + " is not a finite number");
  }
  return value;
}

/// How many of `count` announced records (or rows, or points) to reserve room for: no more
/// than the bytes left to read, since each takes at least one. A hostile count then reserves
/// only what the file could hold, and reading stops at the file's end with an error.
inline std::size_t reservable(const Source& src, std::uint64_t count) {
  return static_cast<std::size_t>(std::min<std::uint64_t>(count, src.remaining_bytes()));
}

/// Reads exactly `count` records with `parse(tokens)` and checks nothing follows.
template <class Parse>
inline void read_records(Source& src, std::uint64_t count, Parse parse) {
  std::string_view line;
  for (std::uint64_t k = 0; k < count; ++k) {
    if (!src.next_record(line)) {
      fail(src.path(), src.line(),
           "file ends after " + std::to_string(k) + " of the " + std::to_string(count) + " records of the header");
    }
    parse(split(line));
  }
  if (src.next_record(line)) {
    src.fail_here("more records than the header's count=" + std::to_string(count));
  }
}

/// Runs a reader body, turning a ParseFailure into an Error.
template <class T, class Body>
inline Result<T> guarded(Body body) {
  try {
    return body();
  } catch (const ParseFailure& f) {
    return f.error;
  }
}

inline std::string file_stem(const std::string& path) {
  std::size_t slash = path.find_last_of('/');
  std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = name.find_last_of('.');
  return dot == std::string::npos ? name : name.substr(0, dot);
}

/// The value of `key` in the header of `path`, or "" when the header cannot be read or
/// lacks it (the full reader then reports why).
inline std::string header_value(const std::string& path, const char* key) {
  const auto header = read_header(path);
  if (!header) return {};
  const auto it = header->keys.find(key);
  return it == header->keys.end() ? std::string() : it->second;
}

}  // namespace proxima::bench::detail
