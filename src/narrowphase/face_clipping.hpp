#pragma once
/// @file face_clipping.hpp
/// Contact points of two supporting features (supporting_face.hpp) along a contact normal:
/// the reference feature is the one best aligned with the normal, the incident feature is
/// clipped against the reference's side planes (Sutherland–Hodgman), and every clipped point
/// whose gap along the normal is at most the contact distance becomes a contact, projected
/// on the reference plane, with the features' core radii added on their sides.

#include <proxima/narrowphase/contact.hpp>

#include <array>

#include "supporting_face.hpp"

namespace proxima::narrow {

/// Cosine of the largest angle between the contact normal and a reference face normal (or
/// the normal of the plane through a reference segment) for which the pair gets a clipped
/// manifold; beyond it the caller keeps its one-point manifold.
inline constexpr Real kReferenceFaceCosine = Real(0.985);

/// Largest number of clipped points before reduction.
inline constexpr int kMaxClipPoints = 2 * kMaxFacePoints;

/// Clipped contact points before reduction.
struct ClippedContacts {
  std::array<ContactPoint, kMaxClipPoints> points{};  ///< world frame, convention of contact.hpp
  int count = 0;                                      ///< valid entries
};

/// Clips the features `fa` (of A, supporting along +normal) and `fb` (of B, along -normal),
/// `normal` unit from A to B. Returns false, leaving `out` empty, when neither feature can be
/// a reference (a point, a polygon tilted more than acos(kReferenceFaceCosine) from the
/// normal, a segment not perpendicular to it within that angle) or when the incident
/// feature is a single point. Otherwise writes every clipped point whose gap (surface to
/// surface, radii included) is at most `contact_distance`, and returns true (possibly with
/// no point). Feature ids: the reference face (or a side of it) and the incident vertex (or
/// edge). O(n m) for features of n and m points; allocates nothing.
bool clip_features(const SupportingFace& fa, const SupportingFace& fb, const Vec3& normal, Real contact_distance,
                   ClippedContacts& out);

/// clip_features, then the points reduced to request.max_contacts (reduce_contacts: the
/// deepest first, then the largest area) and written to `m` (points and count; normal,
/// status and method are left to the caller). Returns false, leaving `m` untouched, when
/// clip_features does or when no point survives. `witness` (optional): the pair's closest points
/// as a contact, added to the candidates when every clipped point is shallower than it (a
/// reference face tilted from the normal), so the manifold keeps the true deepest point.
bool clipped_manifold(const SupportingFace& fa, const SupportingFace& fb, const Vec3& normal,
                      const PairRequest& request, ContactManifold& m, const ContactPoint* witness = nullptr);

/// clipped_manifold when no witness of depth `witness_depth` would be added: writes the
/// manifold and returns true when clipping keeps a point at least that deep; returns false,
/// leaving `m` untouched, when the caller needs the witness (clipping failed, or every point
/// is shallower). Lets a pair skip computing its closest features.
bool deep_clipped_manifold(const SupportingFace& fa, const SupportingFace& fb, const Vec3& normal,
                           const PairRequest& request, Real witness_depth, ContactManifold& m);

}  // namespace proxima::narrow
