#pragma once
/// @file draw_world_2d.hpp
/// Emitters of a d2::CollisionWorld at z = 0: every object's shape at its pose, coloured by
/// its kind, sensor flag and filter as the 3D world's objects are (sensors translucent green,
/// static grey, moving by layer); optionally its bounds; the manifolds of the touching pairs
/// and the last step's continuous-detection impacts.
///
/// The 2D world gives poses, manifolds and events but not its objects' descriptions, so the
/// caller passes the objects it added (handle and description); poses are read from the
/// world, so an object moved since it was added is drawn where it is, and one removed is
/// skipped.
#include <proxima/core/debug_draw.hpp>
#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/draw_contacts.hpp>
#include <proxima/debug/draw_shapes_2d.hpp>

#include <span>

namespace proxima::debug {

/// The colour of a 2D object, by the rule of the 3D world's objects (object_color).
Rgba object_color(const d2::ObjectDesc& object);

/// What draw_world_2d draws.
struct World2DDrawOptions {
  bool shapes = true;          ///< every object's shape (draw_shape_2d, object_color)
  bool bounds = false;         ///< every object's world rectangle ({Bounds, 0})
  bool contacts = true;        ///< the manifolds of the touching pairs (draw_manifold_2d)
  bool impacts = true;         ///< the last step's impacts (draw_impact_2d)
  Shape2DDrawOptions shape;    ///< how shapes are drawn
  ContactDrawOptions contact;  ///< how manifolds and impacts are drawn
};

/// Draws `world` as it is after its last step: its objects in slot order
/// (d2::CollisionWorld::objects), then its manifolds and impacts. O(objects + their outlines
/// + contacts).
void draw_world_2d(DebugDraw& sink, const d2::CollisionWorld& world, const World2DDrawOptions& options = {});

}  // namespace proxima::debug
