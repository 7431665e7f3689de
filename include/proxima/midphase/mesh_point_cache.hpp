#pragma once
/// @file mesh_point_cache.hpp
/// MeshPointCache: the acceleration data of a TriangleMesh's containment queries (the BSP
/// tree of a closed mesh, the far-field winding-number data of an open one), built on the
/// first query that needs it.

#include <memory>

namespace proxima {

namespace detail {
struct MeshPointCacheState;  // src/midphase/mesh_point_queries.hpp
}  // namespace detail

/// A slot for data derived from a mesh's vertices and triangles, built at most once, on
/// first use, under std::call_once: safe when one immutable mesh is queried from many
/// threads. Copying gives an empty (unbuilt) slot, never the source's data: a copy is made
/// for a mesh whose vertices then change (TriangleMesh::deformed).
class MeshPointCache {
 public:
  /// An empty slot.
  MeshPointCache();
  /// An empty slot (the source's data is not copied).
  MeshPointCache(const MeshPointCache& /*unused*/);
  /// Empties the slot (the source's data is not copied).
  MeshPointCache& operator=(const MeshPointCache& /*unused*/);
  ~MeshPointCache();

  /// The slot's state (internal).
  detail::MeshPointCacheState& state() const { return *state_; }

 private:
  std::unique_ptr<detail::MeshPointCacheState> state_;
};

}  // namespace proxima
