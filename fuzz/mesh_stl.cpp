// libFuzzer entry point of the strict STL mesh reader (tools/mesh_stl.cpp): any bytes must
// give a mesh or an error, never a crash, a hang or a read outside the input; a mesh's
// indices must all refer to its vertices, and its coordinates must be finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "mesh_readers.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  const auto mesh = proxima::tool::read_stl(bytes);
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
