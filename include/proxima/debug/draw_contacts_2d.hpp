#pragma once
/// @file draw_contacts_2d.hpp
/// Emitters of 2D contacts at z = 0: a d2::Manifold drawn as the 3D manifolds are
/// (draw_contacts.hpp: markers at both witnesses, the segment between them, the normal from
/// their midpoint, a depth label), and a continuous-detection impact (its point and normal).
/// World frame, the 2D narrow phase's conventions (normal from A to B, depth > 0 a
/// penetration).
#include <proxima/core/debug_draw.hpp>
#include <proxima/d2/collision_world.hpp>
#include <proxima/d2/contact.hpp>
#include <proxima/debug/draw_contacts.hpp>

namespace proxima::debug {

/// The first `count` points of `manifold` (clamped to [0, d2::kMaxManifoldPoints]), as
/// draw_contact_points draws them: per point 2 markers and the witness segment
/// ({Contacts, 0}), the manifold's normal from the witnesses' midpoint ({Normals, 0}) and,
/// with labels, a "depth=..." label.
void draw_manifold_2d(DebugDraw& sink, const d2::Manifold& manifold, const ContactDrawOptions& options = {});

/// An impact of the 2D world's continuous detection: a marker at its point ({Contacts, 0},
/// options.point_color) and its normal from there ({Normals, 0}, options.normal_length long).
void draw_impact_2d(DebugDraw& sink, const d2::ImpactEvent& impact, const ContactDrawOptions& options = {});

}  // namespace proxima::debug
