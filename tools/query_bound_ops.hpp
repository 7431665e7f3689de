#pragma once
// Query operations on bounding volumes: bound (the volume of a placed shape) and fit (the
// volume of a point set).
#include "json_values.hpp"

namespace proxima::tool {

/// {"target", "volume"} -> the bounding volume of the placed shape in the world frame
/// (aabb, sphere, obb, capsule, kdop6, kdop14, kdop18, kdop26).
Json op_bound(const Json& request);
/// {"points", "volume"} -> the volume fitted to the points and "volume_m3" (its volume):
/// aabb, sphere (minimal), sphere_centroid, sphere_aabb, sphere_ritter, obb, obb_pca,
/// capsule, kdop6 .. kdop26, hull.
Json op_fit(const Json& request);

}  // namespace proxima::tool
