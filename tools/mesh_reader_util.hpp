#pragma once
// Helpers shared by the mesh readers (mesh_obj.cpp, mesh_stl.cpp, mesh_ply.cpp): whitespace
// tokens with line numbers, strict number parsing, coordinate validation and fanning.
#include <proxima/core/result.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace proxima::tool::mesh_read {

/// Reads whitespace-separated tokens of a text, counting lines (1-based).
class Tokens {
 public:
  explicit Tokens(std::string_view text) : text_(text) {}
  /// The next token (empty at the end); `line()` is then the token's line.
  std::string_view next();
  /// The next token on the current line only (empty when the line ends first).
  std::string_view next_on_line();
  /// Skips the rest of the current line.
  void skip_line();
  /// The line of the last token returned.
  std::size_t line() const { return token_line_; }
  /// Bytes not yet read.
  std::size_t remaining() const { return text_.size() - pos_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0;
  std::size_t line_ = 1;
  std::size_t token_line_ = 1;
};

/// A binary float32 (or float64) whose bits are a signaling NaN made quiet, its payload kept:
/// converting or comparing a signaling NaN raises the invalid flag (a trap where it is on),
/// a quiet one is then refused as not finite like any other NaN.
std::uint32_t quiet_nan_bits(std::uint32_t float_bits);
std::uint64_t quiet_nan_bits(std::uint64_t double_bits);

/// The whole token as a double (std::from_chars: no leading '+', no spaces), or nothing.
std::optional<double> parse_double(std::string_view token);

/// The whole token as a signed 64-bit integer (an optional leading '+' or '-'), or nothing.
std::optional<std::int64_t> parse_integer(std::string_view token);

/// The token in double quotes, cut to its first 40 characters (for error messages).
std::string quoted(std::string_view token);

/// An error of a mesh file (field "file").
Error file_error(ErrorCode code, std::string message);

/// Appends the vertex (x, y, z) after checking each coordinate is finite and at most
/// kMaxCoordinate in magnitude once converted to Real; `where` names it in the error.
std::optional<Error> push_vertex(IndexedMesh& mesh, double x, double y, double z, const std::string& where);

/// Appends the fan (c0, c1, c2), (c0, c2, c3), ... of a polygon's corners (at least 3).
void push_fan(IndexedMesh& mesh, const std::uint32_t* corners, std::size_t count);

}  // namespace proxima::tool::mesh_read
