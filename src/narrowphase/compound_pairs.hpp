#pragma once
/// @file compound_pairs.hpp
/// Internal: a compound (side A) against any shape (side B), and the reduction of a
/// composite pair's contacts to one manifold; reached through the dispatch table of
/// dispatch.cpp, which mirrors these for the cells with the compound on side B.
#include <proxima/narrowphase/contact.hpp>
#include <proxima/narrowphase/contact_collector.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include "part_hint.hpp"

namespace proxima::narrow {

/// True when a child of `a` is in contact with B (the touching rule of contact.hpp). `hint` (optional):
/// the child pair tried first, then the one that touched (part_hint.hpp).
bool compound_intersect(const Compound& a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                        const PairRequest& request, PartHint* hint = nullptr);

/// Minimum signed distance over the children of `a` against B, searching only for answers
/// below `cutoff` (+infinity when none is); sub_a.child names the child. `hint`
/// (optional): A's child answered first, its distance the first bound; then the answer's
/// children.
DistanceResult compound_distance(const Compound& a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                                 const PairRequest& request, Real cutoff, PartHint* hint = nullptr);

/// Every contact of the children of `a` against B, each tagged with its child in sub_a
/// (and B's child in sub_b when B is a compound too).
void compound_collide_all(const Compound& a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                          const PairRequest& request, ContactCollector& collector);

/// The manifold of a pair with a mesh or compound side: collide_all, then the contacts
/// within about 26 degrees of the deepest one's normal reduced to request.max_contacts.
ContactManifold reduced_manifold(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                                 const PairRequest& request);

/// The request of a query with a mesh or compound side, its tolerance resolved once for
/// every part (request.tolerance when set, else linear_tolerance of the largest world
/// coordinate of either shape's box; a half-space: of its position): all parts then decide
/// touching alike, so the composite answer obeys the touching rule of contact.hpp.
PairRequest composite_request(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                              const PairRequest& request);

/// distance() with a cutoff: the dispatch table's cell, for the branch and bound across the
/// parts of composite shapes.
DistanceResult distance_below(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                              const PairRequest& request, Real cutoff);

}  // namespace proxima::narrow
