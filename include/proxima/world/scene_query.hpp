#pragma once
/// @file scene_query.hpp
/// The answers of a CollisionWorld's scene queries (ray cast, line of sight, overlap, sweep,
/// closest) and how many a query collects. Every answer names the object hit, its user data
/// and, for hits and nearest points, the part of its geometry (mesh triangle, compound child).
#include <proxima/core/math.hpp>
#include <proxima/core/sub_shape_id.hpp>
#include <proxima/world/object_handle.hpp>

#include <cstdint>

namespace proxima {

/// How many answers a query collects.
enum class QueryMode : std::uint8_t {
  Closest,  ///< the nearest answer only (ray, sweep: smallest t; overlap: the lowest handle)
  Any,      ///< the first answer found, then stop (the cheapest "is there anything?")
  All,      ///< every answer (ray, sweep: sorted by t, then handle; overlap: by handle)
};

/// A ray or sweep hit on an object (world frame).
struct WorldHit {
  ObjectHandle object;          ///< the object hit
  std::uint64_t user_data = 0;  ///< its user data
  Real t = Real(0);     ///< ray: parameter (units of the direction's length); sweep: fraction of the translation
  Vec3 point{Real(0)};  ///< hit point, world frame
  Vec3 normal{Real(0), Real(0),
              Real(1)};  ///< ray: outward surface normal at the hit; sweep: unit, from the swept shape to the object
  SubShapeId sub{};      ///< part of the object hit
};

/// An object overlapping a query's geometry, box or point.
struct WorldOverlap {
  ObjectHandle object;          ///< the object
  std::uint64_t user_data = 0;  ///< its user data
};

/// One ray of a batched ray cast (CollisionWorld::raycast_batch), world frame.
struct WorldRay {
  Vec3 origin{Real(0)};                       ///< start point
  Vec3 direction{Real(1), Real(0), Real(0)};  ///< not zero; t is in units of its length
  Real max_t = Real(1);                       ///< the ray's extent in those units (>= 0)
};

/// One segment of a batched line-of-sight test (CollisionWorld::line_of_sight_batch).
struct WorldSegment {
  Vec3 from{Real(0)};  ///< world frame
  Vec3 to{Real(0)};    ///< world frame (equal to `from`: the point is tested)
};

/// The object nearest a point or a geometry, within a query's maximum distance.
struct WorldClosest {
  ObjectHandle object;                     ///< the nearest object
  std::uint64_t user_data = 0;             ///< its user data
  Real signed_distance = Real(0);          ///< > 0 gap, < 0 penetration (length units)
  Vec3 point_query{Real(0)};               ///< nearest point on the query geometry (the point itself for a point query)
  Vec3 point_object{Real(0)};              ///< nearest point on the object, world frame
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, from the query to the object
  SubShapeId sub{};                        ///< part of the object holding point_object
};

}  // namespace proxima
