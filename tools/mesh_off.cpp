// Strict OFF (Object File Format) reader.
//
// Steps: skip blank lines and `#` comments; read the keyword (`OFF`, with the optional
// `ST`, `C` and `N` prefixes of per-vertex texture coordinates, colours and normals, whose
// values follow a vertex's three coordinates and are ignored; the 4D `4OFF` and n-dimensional
// `nOFF` are refused); read the counts `vertices faces edges` (on the keyword's line or the
// next record); check that the bytes left can hold that many records (a vertex line takes at
// least 5 bytes, a face line 7) before reserving anything; read one vertex per line (its first
// three numbers); read one face per line (`n i0 ... i(n-1)`, 0-based indices within the
// vertices, anything after them — a colour — ignored), fanned from its first corner, faces of
// fewer than 3 corners (points, lines) skipped; refuse any record after the declared faces.
// Source: the Geomview manual, "OFF Files" (geomview.org/docs/html/OFF.html).
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mesh_reader_util.hpp"
#include "mesh_readers.hpp"

namespace proxima::tool {

namespace {

using mesh_read::file_error;

std::string off_line(std::size_t line) { return "OFF line " + std::to_string(line); }

// The first token of the next record, skipping `#` comment lines; empty at the end.
std::string_view next_record(mesh_read::Tokens& tokens) {
  for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
    if (token.front() != '#') return token;
    tokens.skip_line();
  }
  return {};
}

// The keyword: [ST][C][N]OFF. False for anything else (4OFF, nOFF, another format).
bool is_off_keyword(std::string_view keyword) {
  if (keyword.size() < 3 || keyword.substr(keyword.size() - 3) != "OFF") return false;
  std::string_view prefix = keyword.substr(0, keyword.size() - 3);
  for (const std::string_view part : {"ST", "C", "N"}) {
    if (prefix.substr(0, part.size()) == part) prefix.remove_prefix(part.size());
  }
  return prefix.empty();
}

struct Counts {
  std::uint64_t vertices = 0;
  std::uint64_t faces = 0;
};

// The counts line: vertices, faces (edges, the third number, is ignored).
std::optional<Error> read_counts(mesh_read::Tokens& tokens, Counts& counts) {
  std::string_view token = tokens.next_on_line();
  if (token.empty()) token = next_record(tokens);
  std::uint64_t* targets[2] = {&counts.vertices, &counts.faces};
  for (int i = 0; i < 2; ++i, token = tokens.next_on_line()) {
    const auto value = mesh_read::parse_integer(token);
    if (!value || *value < 0) {
      return file_error(
          ErrorCode::InvalidArgument,
          off_line(tokens.line()) + ": the header needs the vertex and face counts, found " + mesh_read::quoted(token));
    }
    *targets[i] = static_cast<std::uint64_t>(*value);
  }
  tokens.skip_line();
  const std::uint64_t limit = std::numeric_limits<std::uint32_t>::max();
  const bool held = counts.vertices <= limit && counts.faces <= limit &&
                    5 * counts.vertices + 7 * counts.faces <= tokens.remaining() + 1;
  if (!held) {
    return file_error(ErrorCode::OutOfRange, off_line(tokens.line()) + ": the header declares " +
                                                 std::to_string(counts.vertices) + " vertices and " +
                                                 std::to_string(counts.faces) + " faces, more than the " +
                                                 std::to_string(tokens.remaining()) + " bytes left can hold");
  }
  return std::nullopt;
}

std::optional<Error> read_vertex(mesh_read::Tokens& tokens, IndexedMesh& mesh, std::uint64_t index) {
  double c[3] = {0.0, 0.0, 0.0};
  std::string_view token = next_record(tokens);
  for (double& value : c) {
    const auto parsed = mesh_read::parse_double(token);
    if (!parsed) {
      return file_error(ErrorCode::InvalidArgument, off_line(tokens.line()) + ": vertex " + std::to_string(index) +
                                                        " needs three numbers, found " + mesh_read::quoted(token));
    }
    value = *parsed;
    token = tokens.next_on_line();
  }
  tokens.skip_line();
  return mesh_read::push_vertex(mesh, c[0], c[1], c[2], off_line(tokens.line()));
}

std::optional<Error> read_face(mesh_read::Tokens& tokens, IndexedMesh& mesh, std::uint64_t index,
                               std::vector<std::uint32_t>& corners) {
  const std::string_view first = next_record(tokens);
  const auto n = mesh_read::parse_integer(first);
  const std::string where = off_line(tokens.line()) + ": face " + std::to_string(index);
  if (!n || *n < 0 || std::uint64_t(*n) > tokens.remaining()) {
    return file_error(first.empty() ? ErrorCode::TooFew : ErrorCode::InvalidArgument,
                      first.empty() ? "OFF: the file ends before face " + std::to_string(index)
                                    : where + " needs its corner count, found " + mesh_read::quoted(first));
  }
  corners.clear();
  for (std::int64_t k = 0; k < *n; ++k) {
    const std::string_view token = tokens.next_on_line();
    const auto corner = mesh_read::parse_integer(token);
    if (!corner) {
      return file_error(ErrorCode::InvalidArgument, where + " has " + std::to_string(k) + " of its " +
                                                        std::to_string(*n) + " corners, then " +
                                                        mesh_read::quoted(token));
    }
    if (*corner < 0 || std::uint64_t(*corner) >= mesh.vertices.size()) {
      return file_error(ErrorCode::OutOfRange, where + ": index " + std::to_string(*corner) + " is outside the " +
                                                   std::to_string(mesh.vertices.size()) + " vertices");
    }
    corners.push_back(static_cast<std::uint32_t>(*corner));
  }
  tokens.skip_line();  // a face colour
  if (corners.size() >= 3) mesh_read::push_fan(mesh, corners.data(), corners.size());
  return std::nullopt;
}

}  // namespace

Result<IndexedMesh> read_off(std::string_view text) {
  mesh_read::Tokens tokens(text);
  const std::string_view keyword = next_record(tokens);
  if (!is_off_keyword(keyword)) {
    return file_error(ErrorCode::InvalidArgument,
                      off_line(tokens.line()) + ": expected the keyword OFF (3D), found " + mesh_read::quoted(keyword));
  }
  Counts counts;
  if (auto e = read_counts(tokens, counts)) return *e;
  IndexedMesh mesh;
  mesh.vertices.reserve(counts.vertices);
  for (std::uint64_t v = 0; v < counts.vertices; ++v) {
    if (auto e = read_vertex(tokens, mesh, v)) return *e;
  }
  std::vector<std::uint32_t> corners;
  for (std::uint64_t f = 0; f < counts.faces; ++f) {
    if (auto e = read_face(tokens, mesh, f, corners)) return *e;
  }
  const std::string_view extra = next_record(tokens);
  if (!extra.empty()) {
    return file_error(ErrorCode::InvalidArgument,
                      off_line(tokens.line()) + ": data after the " + std::to_string(counts.faces) + " declared faces");
  }
  return mesh;
}

}  // namespace proxima::tool
