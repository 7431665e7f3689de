#pragma once
// Writing JSON text without a JSON library (the capture format): numbers that read back to
// the same value, escaped strings, and base64 for binary blobs. Internal to the library.
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>

#include <cstdint>
#include <string>
#include <string_view>

namespace proxima::debug::json {

/// Appends `value` as the shortest decimal that reads back to the same Real (std::to_chars);
/// a non-finite value as null (JSON has no infinity or NaN).
void real(std::string& out, Real value);
/// Appends an unsigned integer.
void integer(std::string& out, std::uint64_t value);
/// Appends `text` as a JSON string: quotes, backslashes and control characters escaped
/// (\uXXXX), other bytes (UTF-8) as they are.
void string(std::string& out, std::string_view text);
/// Appends [x, y, z].
void vec3(std::string& out, const Vec3& v);
/// Appends a quaternion as [x, y, z, w] (glTF's and three.js's order).
void quat(std::string& out, const Quat& q);
/// Appends [r, g, b, a] (0..255 each).
void color(std::string& out, Rgba c);
/// Appends "key": (with the comma before it unless `first`).
void key(std::string& out, std::string_view name, bool first = false);

/// Base64 (RFC 4648, with padding) of `bytes`.
std::string base64(std::string_view bytes);

}  // namespace proxima::debug::json
