#pragma once
// The project's own strict readers of the simple mesh formats (OBJ, STL, PLY, OFF). Each takes the
// whole file's bytes and returns its vertices and triangles as written (polygons fanned from
// their first vertex, identical vertices not joined), or an error naming the line, element or
// field that is wrong. They never read outside the bytes given, never allocate more than the
// bytes can describe, and always return.
#include <proxima/core/result.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <cstddef>
#include <string_view>

namespace proxima::tool {

/// Largest mesh file read, in bytes (256 MiB), by every reader and before assimp: a larger
/// file is an OutOfRange error naming "file".
inline constexpr std::size_t kMaxMeshFileBytes = std::size_t(256) << 20;

/// Wavefront OBJ: `v x y z [w | r g b]` vertices, `f a b c ...` faces (1-based indices,
/// negative ones counted back from the last vertex read so far, `a/t/n` forms accepted and
/// only the vertex index used); every other statement is ignored. Errors (InvalidArgument,
/// NotFinite, OutOfRange; field "file") name the line: a missing or malformed number, a
/// face of fewer than 3 vertices, an index of 0 or outside the vertices, a coordinate that
/// is not finite or beyond kMaxCoordinate.
Result<IndexedMesh> read_obj(std::string_view text);

/// STL, binary (80-byte header, little-endian uint32 triangle count n, then n records of
/// 50 bytes: the size must be exactly 84 + 50 n) or ASCII (`solid` ... `facet normal`,
/// `outer loop`, three `vertex x y z`, `endloop`, `endfacet` ... `endsolid`). A file that
/// starts with "solid" is ASCII unless its size is exactly that of a binary file of the
/// count it declares. Errors name the line (ASCII) or the triangle (binary).
Result<IndexedMesh> read_stl(std::string_view bytes);

/// PLY (`ascii 1.0`, `binary_little_endian 1.0`, `binary_big_endian 1.0`): a `vertex`
/// element with scalar properties x, y, z of any numeric type, an optional `face` element
/// with a list property `vertex_indices` (or `vertex_index`) of integer count and item
/// types; every other element and property is skipped by its declared type. Faces of fewer
/// than 3 vertices (points, lines) are skipped. Errors name the header line or the element,
/// its index and the property: a truncated header, a declared count that the remaining
/// bytes cannot hold (checked before anything is allocated), data ending early or continuing
/// past the declared elements, a negative or out-of-range index, a non-finite coordinate.
Result<IndexedMesh> read_ply(std::string_view bytes);

/// OFF (Geomview): the keyword `OFF` (optional `ST`, `C`, `N` prefixes; `4OFF` and `nOFF`
/// refused), the counts `vertices faces edges`, one vertex per line (its first three numbers),
/// one face per line (`n` then n 0-based indices; a colour after them is ignored), `#`
/// comments and blank lines anywhere. Faces of fewer than 3 corners are skipped. Errors name
/// the line and the vertex or face: counts that the remaining bytes cannot hold (checked
/// before anything is allocated), a malformed number, a negative or out-of-range index, data
/// ending early or continuing past the declared faces, a non-finite coordinate.
Result<IndexedMesh> read_off(std::string_view text);

}  // namespace proxima::tool
