#pragma once
// Internal: convex polytopes given as intersections of slabs {lo_i <= d_i . x <= hi_i},
// computed in double precision around a local origin (k-DOP vertices, volume, emptiness).

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <span>
#include <vector>

namespace proxima::detail {

/// Vertices of {x : lo[i] - slack <= dirs[i] . x <= hi[i] + slack}: every intersection
/// point of three planes with independent normals that satisfies all the (slackened)
/// slabs, duplicates within `merge` merged. With `stop_at_first` it returns after the first
/// vertex (emptiness test). O(n^4) for n slabs.
std::vector<glm::dvec3> slab_polytope_vertices(std::span<const glm::dvec3> dirs, std::span<const double> lo,
                                               std::span<const double> hi, double slack, double merge,
                                               bool stop_at_first);

/// Volume of the slab polytope whose vertices are `vertices` (as returned above); a vertex
/// belongs to a face plane when within `on_plane` of it. Faces are ordered by angle around
/// their centroid and summed as pyramids over the vertices' mean.
double slab_polytope_volume(std::span<const glm::dvec3> dirs, std::span<const double> lo, std::span<const double> hi,
                            std::span<const glm::dvec3> vertices, double on_plane);

}  // namespace proxima::detail
