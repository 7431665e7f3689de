#pragma once
/// @file draw_world.hpp
/// Emitters of a CollisionWorld: every object's surface at its pose, coloured by its kind,
/// sensor flag and filter; optionally its world box and the manifolds of the touching pairs.
#include <proxima/core/debug_draw.hpp>
#include <proxima/debug/draw_contacts.hpp>
#include <proxima/debug/tessellate.hpp>
#include <proxima/world/collision_world.hpp>
#include <proxima/world/object_desc.hpp>

namespace proxima::debug {

/// The colour of an object by what it is: a sensor translucent green (alpha 96, whatever
/// its kind); a static object grey; a moving object one of 8 hues picked by the lowest set
/// bit of its filter's layer (layer 1: blue), so objects of different layers differ.
Rgba object_color(const ObjectDesc& object);

/// The colour of an object of this kind, sensor flag and filter (the rule of object_color;
/// the 2D world's objects use it too).
Rgba object_color(ObjectKind kind, bool sensor, const CollisionFilter& filter);

/// What draw_world draws.
struct WorldDrawOptions {
  bool shapes = true;                ///< every object's surface ({Shapes, 0}, object_color)
  bool bounds = false;               ///< every object's world box ({Bounds, 0})
  bool contacts = true;              ///< the manifolds of the touching pairs (draw_manifold)
  TessellationOptions tessellation;  ///< how the shapes are tessellated
  ContactDrawOptions contact;        ///< how contacts are drawn
};

/// Draws `world` as it is after its last step (objects in handle order). O(objects +
/// their tessellations + contacts).
void draw_world(DebugDraw& sink, const CollisionWorld& world, const WorldDrawOptions& options = {});

}  // namespace proxima::debug
