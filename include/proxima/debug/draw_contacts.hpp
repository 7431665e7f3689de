#pragma once
/// @file draw_contacts.hpp
/// Emitters of contact manifolds: for each point, markers at its two witnesses, the segment
/// between them (its length is the depth), the normal from the midpoint, and a label with
/// the depth. World frame, the narrow phase's conventions (normal from A to B, depth > 0 a
/// penetration).
#include <proxima/core/debug_draw.hpp>
#include <proxima/narrowphase/contact.hpp>
#include <proxima/world/world_events.hpp>

#include <span>

namespace proxima::debug {

/// How contacts are drawn.
struct ContactDrawOptions {
  Real normal_length = Real(0.25);      ///< length of the drawn normals (length units)
  Rgba point_color{255, 40, 40, 255};   ///< witness markers and the segment between them
  Rgba normal_color{255, 220, 0, 255};  ///< normals
  Real point_size = Real(6);            ///< marker diameter, pixels
  bool labels = true;                   ///< a "depth=..." label per point
};

/// Draws each point: markers at point_a and point_b and the segment between them
/// ({Contacts, 0}), the normal from their midpoint ({Normals, 0}), a depth label
/// ({Contacts, 0}). Emits 2 markers, 2 lines and (with labels) 1 label per point.
void draw_contact_points(DebugDraw& sink, std::span<const ContactPoint> points, const ContactDrawOptions& options = {});

/// The first `count` points of a narrow-phase manifold, as draw_contact_points.
void draw_manifold(DebugDraw& sink, const ContactManifold& manifold, const ContactDrawOptions& options = {});

/// The points of a world manifold, as draw_contact_points.
void draw_manifold(DebugDraw& sink, const WorldManifold& manifold, const ContactDrawOptions& options = {});

}  // namespace proxima::debug
