#pragma once
// Internal: persistent contact points. Matches a pair's new manifold (narrow phase) to its
// manifold of the previous step so that points keep their ids and user slots while the same
// features touch.
//
// Steps: for each new point, in order, the unused old points with the same feature id and
// the same parts (sub-shape ids) are candidates; the nearest of them (by point_a) is taken
// and the new point inherits its id and user slots (persisted = true); a point without a
// candidate gets the pair's next id. Source: Lin and Canny's closest-feature coherence, as
// Box2D and Bullet match manifold points by feature id.
#include <proxima/narrowphase/contact.hpp>
#include <proxima/world/world_events.hpp>

#include <cstdint>

namespace proxima::detail {

/// Fills `out` (its pair is set by the caller) from `now`, matched against `previous`
/// (nullptr: no manifold in the previous step); `next_id` hands out new point ids.
void match_contact_points(const WorldManifold* previous, const ContactManifold& now, std::uint32_t& next_id,
                          WorldManifold& out);

}  // namespace proxima::detail
