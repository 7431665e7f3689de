#pragma once
/// @file object_desc.hpp
/// ObjectDesc: everything an object of a CollisionWorld holds, given to CollisionWorld::add.
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/world/collision_filter.hpp>
#include <proxima/world/object_handle.hpp>

#include <cstdint>
#include <string_view>

namespace proxima {

/// How an object takes part in the step.
enum class ObjectKind : std::uint8_t {
  Static,  ///< level geometry, rarely moved: never tested against other static objects
  Moving,  ///< tested against every other object each step
};

/// Continuous detection of an object (a moving object's motion over a step runs from its
/// previous pose to its new one; see CollisionWorld::step).
enum class CcdMode : std::uint8_t {
  Off,     ///< discrete only: the object may pass through thin objects when fast
  Auto,    ///< when fast (WorldSettings::ccd_safety_factor), swept against static objects
  Bullet,  ///< when fast, swept against static and moving objects (both motions)
};

/// Short names: "static", "moving"; "off", "auto", "bullet".
std::string_view to_string(ObjectKind kind);
/// Short name of a continuous-detection mode.
std::string_view to_string(CcdMode mode);

/// Description of a new object (see CollisionWorld::add).
struct ObjectDesc {
  Shape geometry = *Sphere::create(Real(1));  ///< any geometry; a half-space or a mesh only as a Static object
  Transform pose;                             ///< local -> world; ignored when `parent` is set
  ObjectKind kind = ObjectKind::Moving;       ///< static or moving
  CollisionFilter filter;                     ///< which objects it may pair with
  bool sensor = false;                        ///< a sensor reports enter / exit, never contacts
  CcdMode ccd = CcdMode::Auto;                ///< continuous detection (costs nothing while the object is slow)
  std::uint64_t user_data = 0;                ///< the caller's value, returned in events and queries
  ObjectHandle parent{};                      ///< attach to this object (default: none)
  Transform local_pose;                       ///< with a parent: this object's frame in the parent's frame
};

}  // namespace proxima
