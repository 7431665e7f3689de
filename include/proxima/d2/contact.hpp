#pragma once
/// @file contact.hpp
/// The 2D narrow phase's value types. The sign convention is the 3D one
/// (narrowphase/contact.hpp): points and normals in the world frame, `normal` unit from A
/// to B, `signed_distance > 0` a gap and `< 0` a penetration (`depth = -signed_distance`),
/// `point_a` on A's surface, `point_b` on B's, and
///     point_b == point_a + signed_distance * normal      (within tolerance).

#include <proxima/d2/math.hpp>
#include <proxima/narrowphase/contact.hpp>

#include <array>
#include <cstdint>

namespace proxima::d2 {

using proxima::FeatureKind;
using proxima::make_feature_id;
using proxima::mirror_feature_id;
using proxima::PairMethod;
using proxima::PairStatus;

/// A part of a shape that holds a witness or a contact: the chain segment index, or -1 for a
/// convex shape.
using PartIndex = std::int32_t;

/// Answer of `distance`: signed distance with witness points on each surface.
struct DistanceResult {
  Real signed_distance = Real(0);             ///< > 0 gap, < 0 penetration (= -depth), length units
  Vec2 point_a{Real(0)};                      ///< witness on A's surface, world frame
  Vec2 point_b{Real(0)};                      ///< witness on B's surface, world frame
  Vec2 normal{Real(1), Real(0)};              ///< unit, A to B, world frame
  PairStatus status = PairStatus::Separated;  ///< separated, touching, penetrating or invalid input
  PairMethod method = PairMethod::Gjk;        ///< Gjk (cores apart) or Sat (cores overlapping)
  int iterations = 0;                         ///< 0: the 2D cores are measured in closed form
  PartIndex part_a = -1;                      ///< chain segment of A holding point_a (-1: convex A)
  PartIndex part_b = -1;                      ///< chain segment of B holding point_b (-1: convex B)
};

/// One contact point of a 2D manifold.
struct ContactPoint {
  Vec2 point_a{Real(0)};  ///< on A's surface, world frame
  Vec2 point_b{Real(0)};  ///< on B's surface, world frame
  Real depth = Real(0);   ///< penetration (> 0) or speculative gap (< 0), length units
  /// The features of A and B that made the point (make_feature_id: vertex or edge indices
  /// of the cores), the same from frame to frame while the same features touch.
  std::uint32_t feature_id = 0;
};

/// Largest number of points in a 2D manifold.
inline constexpr int kMaxManifoldPoints = 2;

/// Answer of `collide`: up to two contact points sharing one normal.
struct Manifold {
  std::array<ContactPoint, kMaxManifoldPoints> points{};  ///< the points (first `count`)
  int count = 0;                        ///< valid entries; 0 when apart by more than the contact distance
  Vec2 normal{Real(1), Real(0)};        ///< unit, A to B, world frame
  PairMethod method = PairMethod::Sat;  ///< Sat (clipped edges) or Gjk (one point from the distance)
  PartIndex part_a = -1;                ///< chain segment of A (-1: convex A)
  PartIndex part_b = -1;                ///< chain segment of B (-1: convex B)
};

/// A ray: the points origin + t direction for t in [0, max_t] (t in units of the
/// direction's length).
struct Ray {
  Vec2 origin{Real(0)};     ///< start point
  Vec2 direction{Real(0)};  ///< direction (need not be unit)
  /// The point at parameter t.
  Vec2 at(Real t) const { return origin + t * direction; }
};

/// First hit of a ray with a shape.
struct RayHit {
  Real t = Real(0);               ///< ray parameter of the hit
  Vec2 point{Real(0)};            ///< hit point, world frame
  Vec2 normal{Real(1), Real(0)};  ///< unit outward normal at the hit, world frame
  PartIndex part = -1;            ///< chain segment hit (-1: convex shape)
};

/// The result with A and B swapped.
inline DistanceResult mirrored(const DistanceResult& r) {
  DistanceResult m = r;
  m.point_a = r.point_b;
  m.point_b = r.point_a;
  m.normal = -r.normal;
  m.part_a = r.part_b;
  m.part_b = r.part_a;
  return m;
}

/// The manifold with A and B swapped: witnesses exchanged, normal negated, ids mirrored.
inline Manifold mirrored(const Manifold& m) {
  Manifold f = m;
  f.normal = -m.normal;
  f.part_a = m.part_b;
  f.part_b = m.part_a;
  for (int i = 0; i < m.count; ++i) {
    f.points[i].point_a = m.points[i].point_b;
    f.points[i].point_b = m.points[i].point_a;
    f.points[i].feature_id = mirror_feature_id(m.points[i].feature_id);
  }
  return f;
}

}  // namespace proxima::d2
