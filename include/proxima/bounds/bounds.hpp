#pragma once
/// @file bounds.hpp
/// Every bounding-volume header: the volumes (Aabb, BoundingSphere, Obb, BoundingCapsule,
/// Kdop<K>, ConvexHull), their fitters (point sets, triangle soups, placed shapes), the
/// overlap tests between every pair, and the point/ray/segment/plane queries.

#include <proxima/bounds/bounding_capsule.hpp>
#include <proxima/bounds/bounding_sphere.hpp>
#include <proxima/bounds/convex_distance.hpp>
#include <proxima/bounds/fit_aabb.hpp>
#include <proxima/bounds/fit_capsule.hpp>
#include <proxima/bounds/fit_hull.hpp>
#include <proxima/bounds/fit_kdop.hpp>
#include <proxima/bounds/fit_obb.hpp>
#include <proxima/bounds/fit_shape.hpp>
#include <proxima/bounds/fit_shape_capsule.hpp>
#include <proxima/bounds/fit_sphere.hpp>
#include <proxima/bounds/kdop.hpp>
#include <proxima/bounds/obb.hpp>
#include <proxima/bounds/overlap.hpp>
#include <proxima/bounds/triangle_soup.hpp>
#include <proxima/bounds/volume_queries.hpp>
