// Mesh loading through assimp.
//
// Steps: import with triangulation, identical-vertex joining and primitive sorting (never a
// winding flip or normal generation); walk the node tree from the root, accumulating the
// node transforms; append the triangles of every mesh a node references, their vertices
// transformed to the root frame (reversed triangles when the transform mirrors); return the
// merged vertices and triangles as they are (repair is the caller's choice).
#include "mesh_io.hpp"

#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cstdint>
#include <limits>
#include <utility>

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
      TriangleIndices t{base + face.mIndices[0], base + face.mIndices[1], base + face.mIndices[2]};
      if (mirrored) std::swap(t[1], t[2]);
      out.triangles.push_back(t);
    }
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) append_node(scene, *node.mChildren[c], transform, out);
}

}  // namespace

Result<IndexedMesh> load_mesh(const std::string& path) {
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
  IndexedMesh mesh;
  append_node(*scene, *scene->mRootNode, aiMatrix4x4(), mesh);
  if (mesh.triangles.empty()) {
    return make_error(ErrorCode::TooFew, "file", "mesh file \"" + path + "\" holds no triangle");
  }
  if (mesh.vertices.size() > std::numeric_limits<std::uint32_t>::max()) {
    return make_error(ErrorCode::OutOfRange, "file", "mesh file \"" + path + "\" has too many vertices");
  }
  return mesh;
}

std::string mesh_file_extensions() {
  Assimp::Importer importer;
  std::string list;
  importer.GetExtensionList(list);
  return list;
}

}  // namespace proxima::tool
