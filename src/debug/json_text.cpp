// JSON text and base64 for the capture format (json_text.hpp).
#include "debug/json_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace proxima::debug::json {

void real(std::string& out, Real value) {
  if (!std::isfinite(value)) {
    out += "null";
    return;
  }
  if (value == Real(0)) value = Real(0);  // -0 as 0
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void integer(std::string& out, std::uint64_t value) {
  char buffer[24];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

void string(std::string& out, std::string_view text) {
  out += '"';
  for (const char c : text) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
      out += escaped;
    } else {
      out += c;
    }
  }
  out += '"';
}

void vec3(std::string& out, const Vec3& v) {
  out += '[';
  real(out, v.x);
  out += ',';
  real(out, v.y);
  out += ',';
  real(out, v.z);
  out += ']';
}

void quat(std::string& out, const Quat& q) {
  out += '[';
  real(out, q.x);
  out += ',';
  real(out, q.y);
  out += ',';
  real(out, q.z);
  out += ',';
  real(out, q.w);
  out += ']';
}

void color(std::string& out, Rgba c) {
  out += '[';
  integer(out, c.r);
  out += ',';
  integer(out, c.g);
  out += ',';
  integer(out, c.b);
  out += ',';
  integer(out, c.a);
  out += ']';
}

void key(std::string& out, std::string_view name, bool first) {
  if (!first) out += ',';
  string(out, name);
  out += ':';
}

std::string base64(std::string_view bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
    std::uint32_t group = 0;
    for (std::size_t k = 0; k < 3; ++k) {
      group = (group << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
    }
    for (std::size_t k = 0; k < 4; ++k) {
      out += k <= n ? kAlphabet[(group >> (18 - 6 * k)) & 63u] : '=';
    }
  }
  return out;
}

}  // namespace proxima::debug::json
