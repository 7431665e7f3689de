#pragma once
/// @file ray_batch.hpp
/// Batched ray casts: many rays against one TriangleMesh in one call, split into blocks of
/// rays run by an Executor (core/executor.hpp). Each ray's answer is TriangleMesh::raycast's
/// and each block writes only its own rays' results, so the output is identical for every
/// executor and thread count (deterministic, equal to a serial loop).

#include <proxima/core/executor.hpp>
#include <proxima/core/result.hpp>
#include <proxima/geometry/ray.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <cstddef>
#include <span>

namespace proxima {

/// One ray of a batch: the ray (mesh frame) and its largest parameter.
struct BatchRay {
  Ray ray;                ///< origin and direction, local frame of the mesh
  Real max_t = kRealMax;  ///< hits with t in [0, max_t] count
};

/// How raycast_batch runs.
struct RayBatchOptions {
  FaceCulling culling = FaceCulling::None;  ///< as in TriangleMesh::raycast
  /// Smallest number of rays in one block of work handed to the executor (a hand-off costs
  /// a few microseconds); batches of fewer than twice this run inline on the caller.
  std::size_t min_rays_per_task = 256;
};

/// Closest hit of every ray: hits[i] is TriangleMesh::raycast(rays[i].ray, rays[i].max_t,
/// culling), or a RayHit with sub.triangle == kNoIndex (and t = 0) for a miss. Returns the
/// number of rays that hit. Errors: InvalidArgument ("hits") when hits is shorter than rays.
/// Blocks of contiguous rays (about 4 per thread of the executor, at least min_rays_per_task
/// rays each) run on `executor`. O(R log n / threads); allocates nothing.
Result<std::size_t> raycast_batch(const TriangleMesh& mesh, std::span<const BatchRay> rays, std::span<RayHit> hits,
                                  Executor& executor, const RayBatchOptions& options = {});

/// As above on the calling thread (serial_executor()).
Result<std::size_t> raycast_batch(const TriangleMesh& mesh, std::span<const BatchRay> rays, std::span<RayHit> hits,
                                  const RayBatchOptions& options = {});

}  // namespace proxima
