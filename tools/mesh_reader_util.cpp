#include "mesh_reader_util.hpp"

#include <proxima/core/tolerance.hpp>

#include <charconv>
#include <cmath>

namespace proxima::tool::mesh_read {

namespace {

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }

}  // namespace

std::string_view Tokens::next() {
  while (pos_ < text_.size() && is_space(text_[pos_])) {
    if (text_[pos_] == '\n') ++line_;
    ++pos_;
  }
  return next_on_line();
}

std::string_view Tokens::next_on_line() {
  while (pos_ < text_.size() && text_[pos_] != '\n' && is_space(text_[pos_])) ++pos_;
  const std::size_t start = pos_;
  while (pos_ < text_.size() && !is_space(text_[pos_])) ++pos_;
  token_line_ = line_;
  return text_.substr(start, pos_ - start);
}

void Tokens::skip_line() {
  while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
}

std::uint32_t quiet_nan_bits(std::uint32_t float_bits) {
  const bool nan = (float_bits & 0x7f800000u) == 0x7f800000u && (float_bits & 0x007fffffu) != 0;
  return nan ? float_bits | 0x00400000u : float_bits;
}

std::uint64_t quiet_nan_bits(std::uint64_t double_bits) {
  const bool nan =
      (double_bits & 0x7ff0000000000000ull) == 0x7ff0000000000000ull && (double_bits & 0x000fffffffffffffull) != 0;
  return nan ? double_bits | 0x0008000000000000ull : double_bits;
}

std::optional<double> parse_double(std::string_view token) {
  double value = 0.0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (token.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::optional<std::int64_t> parse_integer(std::string_view token) {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  std::int64_t value = 0;
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (token.empty() || ec != std::errc() || ptr != end) return std::nullopt;
  return value;
}

std::string quoted(std::string_view token) {
  std::string out;
  out.reserve(42);
  out += '"';
  out.append(token.substr(0, 40));
  out += '"';
  return out;
}

Error file_error(ErrorCode code, std::string message) { return make_error(code, "file", std::move(message)); }

std::optional<Error> push_vertex(IndexedMesh& mesh, double x, double y, double z, const std::string& where) {
  const double c[3] = {x, y, z};
  const char* names[3] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(c[i]))
      return file_error(ErrorCode::NotFinite, where + ": coordinate " + names[i] + " is not finite");
    if (!(std::fabs(c[i]) <= double(kMaxCoordinate))) {
      return file_error(ErrorCode::OutOfRange, where + ": coordinate " + names[i] + " is beyond the supported range");
    }
  }
  mesh.vertices.emplace_back(static_cast<Real>(x), static_cast<Real>(y), static_cast<Real>(z));
  return std::nullopt;
}

void push_fan(IndexedMesh& mesh, const std::uint32_t* corners, std::size_t count) {
  for (std::size_t i = 2; i < count; ++i) mesh.triangles.push_back({corners[0], corners[i - 1], corners[i]});
}

}  // namespace proxima::tool::mesh_read
