#pragma once
// Loading triangle meshes from files (OBJ, STL, PLY, glTF, ... whatever the installed assimp
// reads) into an IndexedMesh. The tool uses assimp; the library never does.
#include <proxima/core/result.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <cstddef>
#include <string>

namespace proxima::tool {

/// Reads every triangle of the file at `path`. Files of more than kMaxMeshFileBytes
/// (256 MiB) are refused (OutOfRange "file") before anything is read. OBJ, STL, PLY and OFF
/// (by the extension, in any case) are read by the project's strict readers
/// (mesh_readers.hpp: their errors are those of the readers, prefixed with the path);
/// polygons are fanned from their first corner. Other formats go through assimp, in a child
/// process (import_with_assimp, default limits): all meshes of the scene, each placed
/// by the product of its node transforms (a mirroring transform keeps the outward winding by reversing its triangles),
/// polygons triangulated, points and lines ignored, the file's winding kept. Identical vertices are joined; near ones
/// are left for repair_mesh to weld. The mesh is not repaired. Errors: InvalidArgument naming "file" when the file
/// cannot be read or parsed (the reader's or assimp's message), OutOfRange "file" for an index past the vertices,
/// TooFew "file" when it holds no triangle.
Result<IndexedMesh> load_mesh(const std::string& path);

/// Limits of an import through assimp, which runs in a child process: a file on which assimp
/// crashes, runs past `seconds` or allocates past `memory_bytes` is an error naming "file",
/// never the end of the calling process.
struct ImportLimits {
  int seconds = 120;                                ///< wall-clock time of the import (s)
  std::size_t memory_bytes = std::size_t(8) << 30;  ///< the child's address space (bytes; not limited under ASan)
};

/// The file at `path` read by assimp in a child process (load_mesh's path for the formats
/// without a reader of the project's own), within `limits`. Errors: those of load_mesh;
/// OutOfRange "file" past the time limit; InvalidArgument "file" when the import dies (a
/// signal, a failed allocation, a non-zero exit). Without fork (not a POSIX system), assimp
/// runs in the calling process.
Result<IndexedMesh> import_with_assimp(const std::string& path, const ImportLimits& limits = {});

/// The file extensions the installed assimp can read ("*.3ds;*.obj;...").
std::string mesh_file_extensions();

}  // namespace proxima::tool
