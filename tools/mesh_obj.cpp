// Strict Wavefront OBJ reader.
//
// Steps: read the text line by line; `v` lines give a vertex (the first three numbers; a
// fourth weight or three colour values are allowed and ignored); `f` lines give a polygon
// whose corners are the integers before any '/', 1-based, negative ones relative to the
// vertices read so far (-1 is the last); the polygon is fanned from its first corner; every
// other statement is ignored. Positive indices may refer to vertices defined later, so they
// are checked against the final vertex count at the end.
// Source: the Wavefront OBJ specification (Appendix B1 of the Advanced Visualizer manual),
// "Vertex data" and "Referencing vertex data".
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "mesh_reader_util.hpp"
#include "mesh_readers.hpp"

namespace proxima::tool {

namespace {

using mesh_read::file_error;

std::string obj_line(std::size_t line) { return "OBJ line " + std::to_string(line); }

std::optional<Error> read_vertex(mesh_read::Tokens& tokens, IndexedMesh& mesh) {
  double c[3] = {0.0, 0.0, 0.0};
  for (double& value : c) {
    const std::string_view token = tokens.next_on_line();
    const auto parsed = mesh_read::parse_double(token);
    if (!parsed) {
      return file_error(ErrorCode::InvalidArgument,
                        obj_line(tokens.line()) + ": a vertex needs three numbers, found " + mesh_read::quoted(token));
    }
    value = *parsed;
  }
  tokens.skip_line();
  if (mesh.vertices.size() >= std::numeric_limits<std::uint32_t>::max()) {
    return file_error(ErrorCode::OutOfRange, obj_line(tokens.line()) + ": too many vertices");
  }
  return mesh_read::push_vertex(mesh, c[0], c[1], c[2], obj_line(tokens.line()));
}

// One face corner: the index before any '/', resolved to 0-based (negative: relative).
std::optional<Error> read_corner(std::string_view token, std::size_t line, std::size_t vertex_count,
                                 std::uint32_t& corner) {
  const std::string_view index = token.substr(0, token.find('/'));
  const auto value = mesh_read::parse_integer(index);
  if (!value) {
    return file_error(ErrorCode::InvalidArgument,
                      obj_line(line) + ": malformed face index " + mesh_read::quoted(token));
  }
  if (*value == 0) return file_error(ErrorCode::OutOfRange, obj_line(line) + ": face index 0 (indices start at 1)");
  std::int64_t zero_based = *value > 0 ? *value - 1 : std::int64_t(vertex_count) + *value;
  if (zero_based < 0) {
    return file_error(ErrorCode::OutOfRange, obj_line(line) + ": relative face index " + std::to_string(*value) +
                                                 " refers before the first vertex (" + std::to_string(vertex_count) +
                                                 " read so far)");
  }
  if (zero_based >= std::int64_t(std::numeric_limits<std::uint32_t>::max())) {
    return file_error(ErrorCode::OutOfRange,
                      obj_line(line) + ": face index " + std::to_string(*value) + " is too large");
  }
  corner = static_cast<std::uint32_t>(zero_based);
  return std::nullopt;
}

std::optional<Error> read_face(mesh_read::Tokens& tokens, IndexedMesh& mesh, std::vector<std::uint32_t>& corners,
                               std::vector<std::size_t>& face_lines) {
  corners.clear();
  for (std::string_view token = tokens.next_on_line(); !token.empty(); token = tokens.next_on_line()) {
    std::uint32_t corner = 0;
    if (auto e = read_corner(token, tokens.line(), mesh.vertices.size(), corner)) return e;
    corners.push_back(corner);
  }
  if (corners.size() < 3) {
    return file_error(
        ErrorCode::InvalidArgument,
        obj_line(tokens.line()) + ": a face needs at least 3 vertices, found " + std::to_string(corners.size()));
  }
  mesh_read::push_fan(mesh, corners.data(), corners.size());
  face_lines.resize(mesh.triangles.size(), tokens.line());
  return std::nullopt;
}

}  // namespace

Result<IndexedMesh> read_obj(std::string_view text) {
  IndexedMesh mesh;
  mesh_read::Tokens tokens(text);
  std::vector<std::uint32_t> corners;
  std::vector<std::size_t> face_lines;  // the line of each triangle, for the final check
  for (std::string_view keyword = tokens.next(); !keyword.empty(); keyword = tokens.next()) {
    std::optional<Error> error;
    if (keyword == "v") {
      error = read_vertex(tokens, mesh);
    } else if (keyword == "f") {
      error = read_face(tokens, mesh, corners, face_lines);
    } else {
      tokens.skip_line();
    }
    if (error) return *error;
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (const std::uint32_t corner : mesh.triangles[t]) {
      if (corner >= mesh.vertices.size()) {
        return file_error(ErrorCode::OutOfRange, obj_line(face_lines[t]) + ": face index " +
                                                     std::to_string(corner + 1) + " is beyond the " +
                                                     std::to_string(mesh.vertices.size()) + " vertices of the file");
      }
    }
  }
  return mesh;
}

}  // namespace proxima::tool
