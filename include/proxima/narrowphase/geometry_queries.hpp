#pragma once
/// @file geometry_queries.hpp
/// Pair queries over any two geometries (convex, mesh, compound): intersect, distance,
/// collide (reduced manifold) and collide_all (every contact with its sub-shapes). Convex
/// pairs go straight to the narrow phase's table; a mesh or compound side descends its BVH
/// and calls the narrow phase per triangle / child. Conventions as in narrowphase/contact.hpp:
/// normal from A to B, depth > 0 for penetration, point_b = point_a + signed_distance * normal.

#include <proxima/shapes/geometry.hpp>
#include <proxima/narrowphase/contact.hpp>

#include <vector>

namespace proxima {

/// A distance answer with the sub-shapes that realise it.
struct GeometryDistance {
  DistanceResult result;  ///< as for convex pairs (world frame)
  SubShapeId a;           ///< part of A holding point_a
  SubShapeId b;           ///< part of B holding point_b
};

/// One contact with the sub-shapes that made it.
struct GeometryContact {
  ContactPoint contact;  ///< world frame, normal A to B
  SubShapeId a;          ///< part of A
  SubShapeId b;          ///< part of B
};

/// True when A and B overlap (or are within request.contact_distance); stops at the first
/// overlapping pair of parts.
bool intersect(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
               const PairRequest& request = {});

/// Signed distance and witnesses between A and B: the minimum over all pairs of parts
/// (pruned by the BVHs). A mesh against a convex shape or a compound part: the deepest
/// triangle pair gives the penetration. Mesh against mesh: the meshes are surfaces, so
/// crossing surfaces give signed distance 0 (status Touching, witnesses at a common point);
/// no penetration depth is computed between two meshes.
GeometryDistance distance(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
                          const PairRequest& request = {});

/// Every contact between parts of A and B within request.contact_distance, appended to
/// `contacts`. Mesh triangles get internal-edge handling: contacts whose normal would come
/// from an inactive (flat or concave) edge are corrected to the face normal or dropped, so
/// a box sliding over a flat mesh gets no ghost contacts.
void collide_all(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
                 const PairRequest& request, std::vector<GeometryContact>& contacts);

/// The contacts of collide_all reduced to at most request.max_contacts points (deepest
/// first, then the largest area), as one manifold for a world to use.
ContactManifold collide(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
                        const PairRequest& request = {});

}  // namespace proxima
