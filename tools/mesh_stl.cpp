// Strict STL reader (binary and ASCII).
//
// Steps: a file whose size is exactly 84 + 50 n, n being the little-endian uint32 at byte
// 80, is binary; otherwise a file starting (after white space) with "solid" is ASCII, and
// anything else is an error (a binary file of the wrong size). Binary: each 50-byte record
// is a normal (ignored), three little-endian float32 vertices and a 2-byte attribute
// (ignored). ASCII: the keywords `solid name`, then facets `facet normal nx ny nz`,
// `outer loop`, three `vertex x y z`, `endloop`, `endfacet`, up to `endsolid [name]`;
// several solids may follow one another. Every facet gives three new vertices.
// Source: the StereoLithography Interface Specification (3D Systems, 1989).
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include "mesh_reader_util.hpp"
#include "mesh_readers.hpp"

namespace proxima::tool {

namespace {

using mesh_read::file_error;

std::uint32_t little_u32(const unsigned char* p) {
  return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
}

float little_f32(const unsigned char* p) {
  const std::uint32_t bits = mesh_read::quiet_nan_bits(little_u32(p));
  float value = 0.0f;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

Result<IndexedMesh> read_binary(std::string_view bytes, std::uint32_t count) {
  IndexedMesh mesh;
  mesh.vertices.reserve(std::size_t(count) * 3);  // the size was checked: 50 bytes each
  mesh.triangles.reserve(count);
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data()) + 84;
  for (std::uint32_t t = 0; t < count; ++t) {
    const unsigned char* record = data + std::size_t(t) * 50;
    const std::string where = "STL triangle " + std::to_string(t);
    for (int corner = 0; corner < 3; ++corner) {
      const unsigned char* p = record + 12 + 12 * corner;
      if (auto e = mesh_read::push_vertex(mesh, little_f32(p), little_f32(p + 4), little_f32(p + 8), where)) return *e;
    }
    const auto base = static_cast<std::uint32_t>(3 * t);
    mesh.triangles.push_back({base, base + 1, base + 2});
  }
  return mesh;
}

std::string stl_line(std::size_t line) { return "STL line " + std::to_string(line); }

std::optional<Error> expect(mesh_read::Tokens& tokens, std::string_view keyword) {
  const std::string_view token = tokens.next();
  if (token == keyword) return std::nullopt;
  const std::string found = token.empty() ? "the end of the file" : mesh_read::quoted(token);
  return file_error(ErrorCode::InvalidArgument,
                    stl_line(tokens.line()) + ": expected " + mesh_read::quoted(keyword) + ", found " + found);
}

std::optional<Error> read_numbers(mesh_read::Tokens& tokens, double (&out)[3]) {
  for (double& value : out) {
    const std::string_view token = tokens.next();
    const auto parsed = mesh_read::parse_double(token);
    if (!parsed) {
      return file_error(ErrorCode::InvalidArgument,
                        stl_line(tokens.line()) + ": expected a number, found " + mesh_read::quoted(token));
    }
    value = *parsed;
  }
  return std::nullopt;
}

std::optional<Error> read_facet(mesh_read::Tokens& tokens, IndexedMesh& mesh) {
  double c[3];
  if (auto e = expect(tokens, "normal")) return e;
  if (auto e = read_numbers(tokens, c)) return e;
  if (auto e = expect(tokens, "outer")) return e;
  if (auto e = expect(tokens, "loop")) return e;
  if (mesh.vertices.size() + 3 >= std::numeric_limits<std::uint32_t>::max()) {
    return file_error(ErrorCode::OutOfRange, stl_line(tokens.line()) + ": too many vertices");
  }
  const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
  for (int corner = 0; corner < 3; ++corner) {
    if (auto e = expect(tokens, "vertex")) return e;
    if (auto e = read_numbers(tokens, c)) return e;
    if (auto e = mesh_read::push_vertex(mesh, c[0], c[1], c[2], stl_line(tokens.line()))) return e;
  }
  mesh.triangles.push_back({base, base + 1, base + 2});
  if (auto e = expect(tokens, "endloop")) return e;
  return expect(tokens, "endfacet");
}

Result<IndexedMesh> read_ascii(std::string_view text) {
  IndexedMesh mesh;
  mesh_read::Tokens tokens(text);
  for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
    if (token != "solid") {
      return file_error(ErrorCode::InvalidArgument,
                        stl_line(tokens.line()) + ": expected \"solid\", found " + mesh_read::quoted(token));
    }
    tokens.skip_line();  // the solid's name
    for (token = tokens.next(); token != "endsolid"; token = tokens.next()) {
      if (token != "facet") {
        const std::string found = token.empty() ? "the end of the file" : mesh_read::quoted(token);
        return file_error(ErrorCode::InvalidArgument,
                          stl_line(tokens.line()) + ": expected \"facet\" or \"endsolid\", found " + found);
      }
      if (auto e = read_facet(tokens, mesh)) return *e;
    }
    tokens.skip_line();  // the name after endsolid
  }
  return mesh;
}

}  // namespace

Result<IndexedMesh> read_stl(std::string_view bytes) {
  if (bytes.size() >= 84) {
    const std::uint32_t count = little_u32(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
    if (std::uint64_t(bytes.size()) == 84 + 50 * std::uint64_t(count)) return read_binary(bytes, count);
  }
  const std::size_t start = bytes.find_first_not_of(" \t\r\n");
  if (start != std::string_view::npos && bytes.substr(start, 5) == "solid") return read_ascii(bytes);
  if (bytes.size() < 84) {
    return file_error(ErrorCode::InvalidArgument, "STL: " + std::to_string(bytes.size()) +
                                                      " bytes are too few for a binary STL (84 at least) and the "
                                                      "file does not start with \"solid\"");
  }
  const std::uint32_t count = little_u32(reinterpret_cast<const unsigned char*>(bytes.data()) + 80);
  return file_error(ErrorCode::InvalidArgument, "STL: binary file of " + std::to_string(bytes.size()) +
                                                    " bytes declares " + std::to_string(count) +
                                                    " triangles, which take 84 + 50 x " + std::to_string(count) +
                                                    " = " + std::to_string(84 + 50 * std::uint64_t(count)) + " bytes");
}

}  // namespace proxima::tool
