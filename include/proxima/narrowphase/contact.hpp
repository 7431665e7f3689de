#pragma once
/// @file contact.hpp
/// The narrow phase's value types and the sign convention every pair obeys.
///
/// Convention (docs/conventions.md): all points and normals are in the world frame (the frame
/// of the two transforms passed in). `normal` is unit length and points from A to B.
/// `signed_distance > 0` is a gap, `< 0` a penetration, and `depth = -signed_distance`.
/// `point_a` lies on A's surface, `point_b` on B's, and
///     point_b == point_a + signed_distance * normal      (within tolerance).
/// Moving B by `t * normal` changes the signed distance by `t` (for small t).
///
/// One touching rule for every query (intersect, distance, collide, collide_all; convex,
/// mesh and compound pairs alike): a pair is *in contact* when its signed distance is at
/// most max(request.contact_distance, tolerance), where `tolerance` is the pair's absolute
/// tolerance (DistanceResult::tolerance). Touching (|signed_distance| <= tolerance) is thus
/// a hit: intersect answers true and collide gives a contact of depth about 0 (in_contact).

#include <proxima/core/math.hpp>
#include <proxima/core/sub_shape_id.hpp>
#include <proxima/geometry/gjk_variant.hpp>

#include <array>
#include <cstdint>

namespace proxima {

/// What a query found. Every result carries one; none of them means "no answer".
enum class PairStatus : std::uint8_t {
  Separated,      ///< the shapes are apart by signed_distance > tolerance
  Touching,       ///< |signed_distance| <= tolerance
  Penetrating,    ///< the shapes overlap; signed_distance = -depth
  MaxIterations,  ///< the iteration cap stopped GJK/EPA; the answer is the best bound found
                  ///< (for a gap: an upper bound on the distance, exact witnesses of it)
  Degenerate,     ///< EPA could not build or grow its polytope; the answer came from the
                  ///< fall-back named by `method` (SAT for polytopes, else GJK's core contact)
  InvalidInput,   ///< a transform not finite or past kMaxPlacedCoordinate: "separated, +inf"
};

/// Which algorithm produced the answer (for diagnostics, tests and benchmarks).
enum class PairMethod : std::uint8_t {
  Analytic,      ///< a closed-form routine written for this pair
  Gjk,           ///< GJK (plain or accelerated) on the cores, radii added
  Epa,           ///< GJK, then EPA for the penetration
  Sat,           ///< separating-axis test over face normals and edge pairs
  Support,       ///< half-space against a support mapping
  ClosestPoint,  ///< the shapes' closest-point queries: a point, segment, triangle or box core against the
                 ///< other shape's, or both shapes' alternately (two curved shapes, GJK's gap open)
};

/// Options for every narrow-phase query. Defaults suit a real-time world in metres.
struct PairRequest {
  /// Largest number of contact points `collide` reports (1..4).
  int max_contacts = 4;
  /// Speculative contact distance (length units, >= 0): `collide` also reports pairs whose
  /// gap is at most this, with negative depth; `intersect` counts them as hits.
  Real contact_distance = Real(0);
  /// Absolute distance tolerance (length units); 0 picks linear_tolerance(scale of the pair).
  Real tolerance = Real(0);
  /// Iteration cap of GJK and of EPA (each).
  int max_iterations = 128;
  /// Largest number of faces EPA may create before it stops with status Degenerate.
  int max_epa_faces = 256;
  /// The GJK iteration to run for distance and boolean queries.
  gjk::Variant gjk = gjk::Variant::Plain;
};

/// Warm-start data kept by the caller between frames for one ordered pair (A, B). Pass the
/// same cache for the same pair every frame; a default-constructed cache means "cold".
/// Directions are stored in A's local frame so they survive rigid motion of the pair.
struct PairCache {
  Vec3 axis{Real(0)};              ///< last separating / penetration direction, A to B, A-local
  std::uint32_t support_hint_a{};  ///< last support vertex of A (hill-climbing start)
  std::uint32_t support_hint_b{};  ///< last support vertex of B
  std::uint32_t sat_feature{};     ///< last SAT axis (polytope pairs; pair-specific code)
  /// Pairs with a mesh or compound side: A's part (top-level compound child, mesh triangle)
  /// that answered last, tried first by the next query (kNoIndex: none).
  std::uint32_t part_a = kNoIndex;
  std::uint32_t part_b = kNoIndex;  ///< the same for B
  bool valid = false;               ///< convex pairs: false means nothing cached yet
};

/// Answer of `distance`: signed distance with witness points on each surface, and the parts
/// of A and B (mesh triangle, compound child) that hold them.
struct DistanceResult {
  Real signed_distance = Real(0);          ///< > 0 gap, < 0 penetration (= -depth), length units
  Vec3 point_a{Real(0)};                   ///< witness on A's surface, world frame
  Vec3 point_b{Real(0)};                   ///< witness on B's surface, world frame
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, A to B, world frame
  PairStatus status = PairStatus::Separated;
  PairMethod method = PairMethod::Analytic;
  int iterations = 0;  ///< GJK + EPA iterations (0 for analytic routines)
  SubShapeId sub_a{};  ///< part of A holding point_a (kNoIndex fields for a convex A)
  SubShapeId sub_b{};  ///< part of B holding point_b
  /// Absolute tolerance (length units) the answer was decided with: the request's, else
  /// linear_tolerance of the pair's scale (sizes and coordinates). |signed_distance| <=
  /// tolerance is Touching; see in_contact.
  Real tolerance = Real(0);
};

/// One contact point of a manifold.
struct ContactPoint {
  Vec3 point_a{Real(0)};                   ///< on A's surface, world frame
  Vec3 point_b{Real(0)};                   ///< on B's surface, world frame
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, A to B, world frame (same for all points of
                                           ///< a convex pair's manifold)
  Real depth = Real(0);                    ///< penetration (> 0) or speculative gap (< 0), length units
  /// Identifies the pair of features that made this point, stable from frame to frame while
  /// the same features touch, so a world can match contacts and warm-start impulses.
  /// See make_feature_id.
  std::uint32_t feature_id = 0;
  SubShapeId sub_a{};  ///< part of A this point lies on (kNoIndex fields for a convex A)
  SubShapeId sub_b{};  ///< part of B
};

/// Largest number of points in a manifold.
inline constexpr int kMaxContactPoints = 4;

/// Answer of `collide`: up to four contact points sharing one normal.
struct ContactManifold {
  std::array<ContactPoint, kMaxContactPoints> points{};
  int count = 0;                           ///< number of valid entries in `points`; 0 when the shapes are apart by more
                                           ///< than the request's contact_distance
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, A to B, world frame
  PairStatus status = PairStatus::Separated;
  PairMethod method = PairMethod::Analytic;
};

/// The kind of feature a contact comes from, for feature ids.
enum class FeatureKind : std::uint8_t { Vertex = 0, Edge = 1, Face = 2, Surface = 3 };

/// Packs the features of A and B into a contact's feature id:
/// bits 30-31 kind of A, 16-29 index on A, 14-15 kind of B, 0-13 index on B (indices are
/// taken modulo 2^14). The same features give the same id in every frame.
constexpr std::uint32_t make_feature_id(FeatureKind kind_a, std::uint32_t index_a, FeatureKind kind_b,
                                        std::uint32_t index_b) {
  return (static_cast<std::uint32_t>(kind_a) << 30) | ((index_a & 0x3FFFu) << 16) |
         (static_cast<std::uint32_t>(kind_b) << 14) | (index_b & 0x3FFFu);
}

/// The feature id seen from the other side (A and B swapped).
constexpr std::uint32_t mirror_feature_id(std::uint32_t id) { return (id >> 16) | ((id & 0xFFFFu) << 16); }

/// The status that goes with a signed distance and a tolerance.
constexpr PairStatus status_from_distance(Real signed_distance, Real tolerance) {
  return signed_distance > tolerance    ? PairStatus::Separated
         : signed_distance < -tolerance ? PairStatus::Penetrating
                                        : PairStatus::Touching;
}

/// The gap (length units) up to which a pair counts as in contact: the request's contact
/// distance, or the pair's tolerance when that is larger (touching is a hit).
constexpr Real contact_reach(Real contact_distance, Real tolerance) {
  return contact_distance > tolerance ? contact_distance : tolerance;
}

/// The touching rule shared by every query: true when the distance answer `d` is within
/// contact_reach(request.contact_distance, d.tolerance). intersect(...) answers exactly this
/// for the same request, and collide(...) gives at least one contact exactly when it holds
/// (request.max_contacts >= 1).
constexpr bool in_contact(const DistanceResult& d, const PairRequest& request) {
  return d.signed_distance <= contact_reach(request.contact_distance, d.tolerance);
}

/// The result with A and B swapped: witnesses and parts exchanged, normal negated.
inline DistanceResult mirrored(const DistanceResult& r) {
  DistanceResult m = r;
  m.point_a = r.point_b;
  m.point_b = r.point_a;
  m.normal = -r.normal;
  m.sub_a = r.sub_b;
  m.sub_b = r.sub_a;
  return m;
}

/// The contact with A and B swapped: witnesses and parts exchanged, normal negated, feature
/// id mirrored.
inline ContactPoint mirrored(const ContactPoint& c) {
  ContactPoint m = c;
  m.point_a = c.point_b;
  m.point_b = c.point_a;
  m.normal = -c.normal;
  m.feature_id = mirror_feature_id(c.feature_id);
  m.sub_a = c.sub_b;
  m.sub_b = c.sub_a;
  return m;
}

/// The manifold with A and B swapped: every point mirrored, normal negated.
inline ContactManifold mirrored(const ContactManifold& m) {
  ContactManifold f = m;
  f.normal = -m.normal;
  for (int i = 0; i < m.count; ++i) f.points[i] = mirrored(m.points[i]);
  return f;
}

}  // namespace proxima
