#pragma once
// RFC 4648 base64 decoding for the capture tests, written here from the standard (the
// library only encodes).
#include <cstdint>
#include <string>

namespace proxima::test {

/// The bytes of base64 `text` (stops at the first '=').
inline std::string decode_base64(const std::string& text) {
  const std::string alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::uint32_t bits = 0;
  int count = 0;
  for (const char c : text) {
    if (c == '=') break;
    bits = (bits << 6) | static_cast<std::uint32_t>(alphabet.find(c));
    count += 6;
    if (count >= 8) {
      count -= 8;
      out += static_cast<char>((bits >> count) & 0xffu);
    }
  }
  return out;
}

}  // namespace proxima::test
