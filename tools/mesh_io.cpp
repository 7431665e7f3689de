// Mesh loading: the project's strict readers for OBJ, STL and PLY (mesh_readers.hpp), assimp
// for the other formats.
//
// Steps: check the file's size against kMaxMeshFileBytes; for .obj, .stl and .ply read the
// bytes and parse them with the strict reader, then join identical vertices. Otherwise
// import through assimp with triangulation, identical-vertex joining and primitive sorting (never a
// winding flip or normal generation); walk the node tree from the root, accumulating the
// node transforms; append the triangles of every mesh a node references, their vertices
// transformed to the root frame (reversed triangles when the transform mirrors); return the
// merged vertices and triangles as they are (repair is the caller's choice), after checking
// every index against its mesh's vertex count.
#include "mesh_io.hpp"

#include <algorithm>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <system_error>
#include <unordered_map>
#include <utility>

#include "mesh_readers.hpp"

namespace proxima::tool {
namespace {

void append_node(const aiScene& scene, const aiNode& node, const aiMatrix4x4& parent, IndexedMesh& out) {
  const aiMatrix4x4 transform = parent * node.mTransformation;
  const bool mirrored = transform.Determinant() < 0;
  for (unsigned m = 0; m < node.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[node.mMeshes[m]];
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const aiVector3D p = transform * mesh.mVertices[v];
      out.vertices.emplace_back(static_cast<Real>(p.x), static_cast<Real>(p.y), static_cast<Real>(p.z));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines
      if (face.mIndices[0] >= mesh.mNumVertices || face.mIndices[1] >= mesh.mNumVertices ||
          face.mIndices[2] >= mesh.mNumVertices) {
        continue;  // never read outside the mesh (load_mesh rejects the file: see bad_index)
      }
      TriangleIndices t{base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]};
      if (mirrored) std::swap(t[1], t[2]);
      out.triangles.push_back(t);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) append_node(scene, *node.mChildren[c], transform, out);
}

// Whether any face of the scene's meshes indexes past its mesh's vertices.
bool bad_index(const aiScene& scene) {
  for (unsigned m = 0; m < scene.mNumMeshes; ++m) {
    const aiMesh& mesh = *scene.mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      for (unsigned i = 0; i < face.mNumIndices; ++i) {
        if (face.mIndices[i] >= mesh.mNumVertices) return true;
      }
    }
  }
  return false;
}

// Identical positions (-0 and +0 alike) become one vertex, numbered in order of first use by
// the triangles; vertices no triangle uses are dropped (as assimp's import does).
IndexedMesh join_identical_vertices(IndexedMesh in) {
  struct Key {
    Real x, y, z;
    bool operator==(const Key& o) const { return x == o.x && y == o.y && z == o.z; }
  };
  struct Hash {
    std::size_t operator()(const Key& k) const {
      std::size_t h = 0;
      for (const Real c : {k.x, k.y, k.z}) {
        const Real v = c == Real(0) ? Real(0) : c;
        std::uint64_t bits = 0;
        std::memcpy(&bits, &v, sizeof v);
        h = (h ^ bits) * 1099511628211ull;
      }
      return h;
    }
  };
  std::unordered_map<Key, std::uint32_t, Hash> index;
  index.reserve(in.vertices.size());
  IndexedMesh out;
  out.triangles.reserve(in.triangles.size());
  for (const TriangleIndices& t : in.triangles) {
    TriangleIndices joined{};
    for (std::size_t k = 0; k < 3; ++k) {
      const Vec3& v = in.vertices[t[k]];
      const auto [it, added] = index.emplace(Key{v.x, v.y, v.z}, static_cast<std::uint32_t>(out.vertices.size()));
      if (added) out.vertices.push_back(v);
      joined[k] = it->second;
    }
    out.triangles.push_back(joined);
  }
  return out;
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext;
}

Result<IndexedMesh> read_with_own_reader(const std::string& path, const std::string& ext) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(std::istreambuf_iterator<char>(in), {});
  if (!in && !in.eof()) return make_error(ErrorCode::InvalidArgument, "file", "cannot read mesh file \"" + path + "\"");
  if (bytes.size() > kMaxMeshFileBytes) {
    return make_error(ErrorCode::OutOfRange, "file", "mesh file \"" + path + "\" is larger than the limit");
  }
  Result<IndexedMesh> read = ext == ".obj" ? read_obj(bytes) : ext == ".stl" ? read_stl(bytes) : read_ply(bytes);
  if (!read.ok()) {
    const Error& e = read.error();
    return make_error(e.code, "file", "mesh file \"" + path + "\": " + e.message);
  }
  return join_identical_vertices(std::move(read).value());
}

Result<IndexedMesh> read_with_assimp(const std::string& path) {
  Assimp::Importer importer;
  // Keep only what a collision mesh needs (no normals, colours, texture coordinates), so that
  // joining identical vertices merges by position.
  importer.SetPropertyInteger(AI_CONFIG_PP_RVC_FLAGS, aiComponent_NORMALS | aiComponent_TANGENTS_AND_BITANGENTS |
                                                          aiComponent_COLORS | aiComponent_TEXCOORDS |
                                                          aiComponent_BONEWEIGHTS | aiComponent_ANIMATIONS |
                                                          aiComponent_TEXTURES | aiComponent_LIGHTS |
                                                          aiComponent_CAMERAS | aiComponent_MATERIALS);
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE, aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const unsigned flags =
      aiProcess_RemoveComponent | aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_SortByPType;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (scene == nullptr || scene->mRootNode == nullptr) {
    return make_error(ErrorCode::InvalidArgument, "file",
                      "cannot read mesh file \"" + path + "\": " + importer.GetErrorString());
  }
  if (bad_index(*scene)) {
    return make_error(ErrorCode::OutOfRange, "file", "mesh file \"" + path + "\" has a face index past its vertices");
  }
  IndexedMesh mesh;
  append_node(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  return mesh;
}

}  // namespace

Result<IndexedMesh> load_mesh(const std::string& path) {
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) {
    return make_error(ErrorCode::InvalidArgument, "file",
                      "cannot read mesh file \"" + path + "\": Unable to open file \"" + path + "\".");
  }
  if (size > kMaxMeshFileBytes) {
    return make_error(ErrorCode::OutOfRange, "file",
                      "mesh file \"" + path + "\" has " + std::to_string(size) + " bytes, more than the limit of " +
                          std::to_string(kMaxMeshFileBytes) + " (256 MiB)");
  }
  const std::string ext = lower_extension(path);
  const bool own = ext == ".obj" || ext == ".stl" || ext == ".ply";
  auto loaded = own ? read_with_own_reader(path, ext) : read_with_assimp(path);
  if (!loaded.ok()) return loaded;
  const IndexedMesh& mesh = *loaded;
  if (mesh.triangles.empty()) {
    return make_error(ErrorCode::TooFew, "file", "mesh file \"" + path + "\" holds no triangle");
  }
  if (mesh.vertices.size() > std::numeric_limits<std::uint32_t>::max()) {
    return make_error(ErrorCode::OutOfRange, "file", "mesh file \"" + path + "\" has too many vertices");
  }
  return loaded;
}

std::string mesh_file_extensions() {
  Assimp::Importer importer;
  std::string list;
  importer.GetExtensionList(list);
  return list;
}

}  // namespace proxima::tool
