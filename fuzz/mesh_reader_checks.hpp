#pragma once
// What the mesh reader targets (mesh_obj.cpp, mesh_stl.cpp, mesh_ply.cpp) check of a reader's
// answer: any bytes give a mesh or an error, never a crash, a hang or a read outside the
// input; a mesh's indices all refer to its vertices, and its coordinates are finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "mesh_readers.hpp"

namespace proxima::fuzz {

/// The fuzzer's input as the bytes of a file.
inline std::string_view file_bytes(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

/// Aborts when a mesh the reader accepted breaks the properties above; 0 otherwise.
inline int check_read_mesh(const Result<IndexedMesh>& mesh) {
  if (!mesh.ok()) return 0;
  for (const auto& t : mesh->triangles) {
    for (const auto i : t) {
      if (i >= mesh->vertices.size()) std::abort();
    }
  }
  for (const auto& v : mesh->vertices) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) std::abort();
  }
  return 0;
}

}  // namespace proxima::fuzz
