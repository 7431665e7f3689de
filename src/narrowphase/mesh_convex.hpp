#pragma once
/// @file mesh_convex.hpp
/// A triangle mesh (side A) against a convex shape (side B), internal, reached through the
/// dispatch table of dispatch.cpp. Results are in the world frame with the mesh as A;
/// sub.triangle is set on A's side, sub.child left at kNoIndex for the caller.

#include <proxima/narrowphase/contact.hpp>
#include <proxima/narrowphase/contact_collector.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <vector>

#include "part_hint.hpp"

namespace proxima::narrow {

/// True when some triangle of the mesh is within request.contact_distance of `convex`.
/// `hint` (optional): the triangle tried first (hint->a), then the one that touched.
bool mesh_convex_intersect(const TriangleMesh& mesh, const Transform& pose_mesh, ShapeRef convex,
                           const Transform& pose_convex, const PairRequest& request, PartHint* hint = nullptr);

/// Minimum signed distance over the triangles; only answers below `cutoff` are searched
/// for (signed_distance = +infinity when none is). Ties go to the lower triangle index.
/// `hint` (optional): the triangle answered first, its distance the first bound; then the
/// answer's triangle.
DistanceResult mesh_convex_distance(const TriangleMesh& mesh, const Transform& pose_mesh, ShapeRef convex,
                                    const Transform& pose_convex, const PairRequest& request, Real cutoff,
                                    PartHint* hint = nullptr);

/// Adds the contacts of every triangle within request.contact_distance to `collector` (the
/// triangle in sub_a), with internal-edge handling (see the .cpp file); stops when it is done.
void mesh_convex_collide_all(const TriangleMesh& mesh, const Transform& pose_mesh, ShapeRef convex,
                             const Transform& pose_convex, const PairRequest& request, ContactCollector& collector);

}  // namespace proxima::narrow
