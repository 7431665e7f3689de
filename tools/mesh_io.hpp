#pragma once
// Loading triangle meshes from files (OBJ, STL, PLY, glTF, ... whatever the installed assimp
// reads) into an IndexedMesh. The tool uses assimp; the library never does.
#include <proxima/core/result.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <string>

namespace proxima::tool {

/// Reads every triangle of the file at `path`. Files of more than kMaxMeshFileBytes
/// (256 MiB) are refused (OutOfRange "file") before anything is read. OBJ, STL and PLY
/// (by the extension, in any case) are read by the project's strict readers
/// (mesh_readers.hpp: their errors are those of the readers, prefixed with the path);
/// polygons are fanned from their first corner. Other formats go through assimp: all meshes of the scene, each placed
/// by the product of its node transforms (a mirroring transform keeps the outward winding by reversing its triangles),
/// polygons triangulated, points and lines ignored, the file's winding kept. Identical vertices are joined; near ones
/// are left for repair_mesh to weld. The mesh is not repaired. Errors: InvalidArgument naming "file" when the file
/// cannot be read or parsed (the reader's or assimp's message), OutOfRange "file" for an index past the vertices,
/// TooFew "file" when it holds no triangle.
Result<IndexedMesh> load_mesh(const std::string& path);

/// The file extensions the installed assimp can read ("*.3ds;*.obj;...").
std::string mesh_file_extensions();

}  // namespace proxima::tool
