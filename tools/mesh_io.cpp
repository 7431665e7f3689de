// Mesh loading: the project's strict readers for OBJ, STL, PLY and OFF (mesh_readers.hpp),
// assimp for the other formats.
//
// Steps: check the file's size against kMaxMeshFileBytes; for .obj, .stl, .ply and .off read the
// bytes and parse them with the strict reader, then join identical vertices. Otherwise
// import through assimp in a child process (fork; its address space limited unless built with
// a sanitizer), which sends the mesh or the error back through a pipe; the parent waits at
// most ImportLimits::seconds, then kills it, and a child that dies on a signal or a non-zero
// exit is an error naming the file. In the child: import with triangulation, identical-vertex
// joining and primitive sorting (never a winding flip or normal generation); walk the node
// tree from the root, accumulating the node transforms; append the triangles of every mesh a
// node references, their vertices transformed to the root frame (reversed triangles when the
// transform mirrors); return the merged vertices and triangles as they are (repair is the
// caller's choice), after checking every index against its mesh's vertex count.
#include "mesh_io.hpp"

#include <algorithm>
#include <array>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <cctype>
#include <cerrno>
#include <chrono>
#include <csignal>
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

#if defined(__unix__)
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#define PROXIMA_ISOLATED_IMPORT 1
#endif

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

using OwnReader = Result<IndexedMesh> (*)(std::string_view);

// The project's strict reader of a file extension (lower case), or null: assimp's then.
OwnReader own_reader(const std::string& ext) {
  if (ext == ".obj") return read_obj;
  if (ext == ".stl") return read_stl;
  if (ext == ".ply") return read_ply;
  if (ext == ".off") return read_off;
  return nullptr;
}

Result<IndexedMesh> read_with_own_reader(const std::string& path, OwnReader reader) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(std::istreambuf_iterator<char>(in), {});
  if (!in && !in.eof()) return make_error(ErrorCode::InvalidArgument, "file", "cannot read mesh file \"" + path + "\"");
  if (bytes.size() > kMaxMeshFileBytes) {
    return make_error(ErrorCode::OutOfRange, "file", "mesh file \"" + path + "\" is larger than the limit");
  }
  Result<IndexedMesh> read = reader(bytes);
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

#if defined(PROXIMA_ISOLATED_IMPORT)

// True in builds with AddressSanitizer, whose shadow memory needs more address space than
// any limit a mesh import should get: the child's memory is then not limited.
constexpr bool kSanitizedBuild =
#if defined(__SANITIZE_ADDRESS__)
    true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
    true;
#else
    false;
#endif
#else
    false;
#endif

// The child's answer on the pipe: 'M', vertex and triangle counts (uint64), the vertices
// (3 Real each) and the triangles (3 uint32 each); or 'E', the error code (one byte) and the
// message.
std::string encode(const Result<IndexedMesh>& r) {
  std::string out;
  if (!r.ok()) {
    out += 'E';
    out += static_cast<char>(r.error().code);
    out += r.error().message;
    return out;
  }
  const IndexedMesh& m = *r;
  const std::array<std::uint64_t, 2> counts{m.vertices.size(), m.triangles.size()};
  out += 'M';
  out.append(reinterpret_cast<const char*>(counts.data()), sizeof(counts));
  out.append(reinterpret_cast<const char*>(m.vertices.data()), m.vertices.size() * sizeof(Vec3));
  out.append(reinterpret_cast<const char*>(m.triangles.data()), m.triangles.size() * sizeof(TriangleIndices));
  return out;
}

Result<IndexedMesh> decode(const std::string& bytes, const std::string& path) {
  const Error broken =
      make_error(ErrorCode::InvalidArgument, "file", "mesh file \"" + path + "\": the import's answer was cut short");
  if (bytes.size() >= 2 && bytes[0] == 'E') {
    return make_error(static_cast<ErrorCode>(static_cast<unsigned char>(bytes[1])), "file", bytes.substr(2));
  }
  std::array<std::uint64_t, 2> counts{};
  if (bytes.size() < 1 + sizeof(counts) || bytes[0] != 'M') return broken;
  std::memcpy(counts.data(), bytes.data() + 1, sizeof(counts));
  const std::size_t body = bytes.size() - 1 - sizeof(counts);
  if (counts[0] > body / sizeof(Vec3) || counts[1] > body / sizeof(TriangleIndices) ||
      counts[0] * sizeof(Vec3) + counts[1] * sizeof(TriangleIndices) != body) {
    return broken;
  }
  IndexedMesh m;
  m.vertices.resize(counts[0]);
  m.triangles.resize(counts[1]);
  const char* at = bytes.data() + 1 + sizeof(counts);
  std::memcpy(m.vertices.data(), at, counts[0] * sizeof(Vec3));
  std::memcpy(m.triangles.data(), at + counts[0] * sizeof(Vec3), counts[1] * sizeof(TriangleIndices));
  return m;
}

// The child: import, answer on `fd`, leave without running the parent's exit handlers.
[[noreturn]] void import_in_child(const std::string& path, const ImportLimits& limits, int fd) {
  if (!kSanitizedBuild) {
    const rlimit memory{static_cast<rlim_t>(limits.memory_bytes), static_cast<rlim_t>(limits.memory_bytes)};
    setrlimit(RLIMIT_AS, &memory);
  }
  std::string answer;
  try {
    answer = encode(read_with_assimp(path));
  } catch (const std::exception& e) {
    answer = encode(make_error(ErrorCode::InvalidArgument, "file",
                               "cannot read mesh file \"" + path + "\": assimp failed (" + e.what() + ")"));
  }
  for (std::size_t done = 0; done < answer.size();) {
    const ssize_t n = ::write(fd, answer.data() + done, answer.size() - done);
    if (n <= 0) break;
    done += static_cast<std::size_t>(n);
  }
  ::_exit(0);
}

// The parent: everything the child writes until it closes the pipe, or false past the deadline.
bool read_answer(int fd, int seconds, std::string& out) {
  using Clock = std::chrono::steady_clock;
  const Clock::time_point deadline = Clock::now() + std::chrono::seconds(seconds);
  char buffer[1 << 16];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(std::min<long long>(left, 1 << 30)));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) return false;
    const ssize_t n = ::read(fd, buffer, sizeof(buffer));
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return true;
    out.append(buffer, static_cast<std::size_t>(n));
  }
}

Result<IndexedMesh> read_with_assimp_isolated(const std::string& path, const ImportLimits& limits) {
  const std::string name = "mesh file \"" + path + "\"";
  int fds[2];
  if (::pipe(fds) != 0)
    return make_error(ErrorCode::InvalidArgument, "file", name + ": cannot start the import (pipe)");
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    return make_error(ErrorCode::InvalidArgument, "file", name + ": cannot start the import (fork)");
  }
  if (pid == 0) {
    ::close(fds[0]);
    import_in_child(path, limits, fds[1]);
  }
  ::close(fds[1]);
  std::string answer;
  const bool finished = read_answer(fds[0], limits.seconds, answer);
  ::close(fds[0]);
  if (!finished) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!finished) {
    return make_error(
        ErrorCode::OutOfRange, "file",
        name + ": assimp's import took more than " + std::to_string(limits.seconds) + " s and was stopped");
  }
  if (WIFSIGNALED(status)) {
    return make_error(ErrorCode::InvalidArgument, "file",
                      name + ": assimp's import died on signal " + std::to_string(WTERMSIG(status)) + " (" +
                          ::strsignal(WTERMSIG(status)) + ")");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    return make_error(ErrorCode::InvalidArgument, "file",
                      name + ": assimp's import failed (exit status " + std::to_string(WEXITSTATUS(status)) + ")");
  }
  return decode(answer, path);
}

#endif

}  // namespace

Result<IndexedMesh> import_with_assimp(const std::string& path, const ImportLimits& limits) {
#if defined(PROXIMA_ISOLATED_IMPORT)
  return read_with_assimp_isolated(path, limits);
#else
  (void)limits;
  return read_with_assimp(path);
#endif
}

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
  const OwnReader reader = own_reader(lower_extension(path));
  auto loaded = reader != nullptr ? read_with_own_reader(path, reader) : import_with_assimp(path);
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
