#pragma once
// Bounding volumes as JSON answers of the query protocol: each volume's defining fields,
// in the frame it was computed in (the world frame for `bound`, the points' frame for `fit`).
#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/kdop.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include "json_values.hpp"

namespace proxima::tool {

/// Adds {"min": [x,y,z], "max": [x,y,z]} to `out`.
void put_volume(Json& out, const Aabb& box);
/// Adds {"center": [x,y,z], "radius": r}.
void put_volume(Json& out, const BoundingSphere& sphere);
/// Adds {"center", "axes": [[axis 0], [axis 1], [axis 2]] (unit vectors), "half_extents"}.
void put_volume(Json& out, const Obb& box);
/// Adds {"p0", "p1", "radius"}: the points within radius of the segment p0p1.
void put_volume(Json& out, const BoundingCapsule& capsule);
/// Adds {"directions": [[dx,dy,dz], ...] (the integer slab directions), "min": [...],
/// "max": [...]}: the k-DOP is {x : min[i] <= directions[i] . x <= max[i]}.
template <int K>
void put_volume(Json& out, const Kdop<K>& kdop);
/// Adds {"vertices": [[x,y,z], ...], "faces": [[i, j, k, ...], ...]}: faces are vertex index
/// loops, counter-clockwise seen from outside.
void put_volume(Json& out, const ConvexHull& hull);

extern template void put_volume<6>(Json&, const Kdop<6>&);
extern template void put_volume<14>(Json&, const Kdop<14>&);
extern template void put_volume<18>(Json&, const Kdop<18>&);
extern template void put_volume<26>(Json&, const Kdop<26>&);

}  // namespace proxima::tool
