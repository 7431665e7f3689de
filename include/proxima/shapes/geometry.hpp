#pragma once
/// @file geometry.hpp
/// GeometryRef: a non-owning reference to any geometry (a convex shape through ShapeRef, a
/// TriangleMesh or a Compound), and the operations every geometry answers: bounds and ray
/// casts. Pair queries over geometries are in geometry_queries.hpp.
///
/// Why a second level above ShapeRef: the narrow phase's N x N table covers convex shapes,
/// whose pair routines need nothing but the two shapes; mesh and compound queries need the
/// BVH of this (midphase) layer, which the narrow phase may not depend on. Constructors are
/// explicit so that calls with two convex shapes keep resolving to the narrow phase.

#include <proxima/shapes/compound.hpp>
#include <proxima/shapes/triangle_mesh.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <cstdint>
#include <optional>

namespace proxima {

/// Which kind of geometry a GeometryRef holds.
enum class GeometryKind : std::uint8_t {
  Convex,    ///< a convex shape (ShapeRef)
  Mesh,      ///< a TriangleMesh
  Compound,  ///< a Compound
};

/// A borrowed geometry; the referenced object must outlive the reference.
class GeometryRef {
 public:
  /// A convex shape.
  explicit GeometryRef(ShapeRef shape) noexcept : convex_(shape), kind_(GeometryKind::Convex) {}
  /// A triangle mesh.
  explicit GeometryRef(const TriangleMesh& mesh) noexcept : other_(&mesh), kind_(GeometryKind::Mesh) {}
  /// A compound.
  explicit GeometryRef(const Compound& compound) noexcept : other_(&compound), kind_(GeometryKind::Compound) {}
  /// The alternative held by an owning Geometry.
  explicit GeometryRef(const Geometry& geometry) noexcept;

  /// The kind held.
  GeometryKind kind() const noexcept { return kind_; }
  /// The convex shape (kind() == Convex only).
  ShapeRef convex() const noexcept { return *convex_; }
  /// The mesh (kind() == Mesh only).
  const TriangleMesh& mesh() const noexcept { return *static_cast<const TriangleMesh*>(other_); }
  /// The compound (kind() == Compound only).
  const Compound& compound() const noexcept { return *static_cast<const Compound*>(other_); }

 private:
  std::optional<ShapeRef> convex_;
  const void* other_ = nullptr;
  GeometryKind kind_;
};

/// Identifies the part of a geometry a result comes from: for a compound, the index of the
/// top-level child; for a mesh (directly or as that child, or deeper), the triangle index.
/// kNoIndex where it does not apply.
struct SubShapeId {
  std::uint32_t child = kNoIndex;     ///< top-level compound child
  std::uint32_t triangle = kNoIndex;  ///< triangle of the mesh hit
};

/// A ray hit on any geometry (world frame when cast through a pose).
struct GeometryRayHit {
  RayHit hit;      ///< t, point, normal
  SubShapeId sub;  ///< which child / triangle
};

/// Box of `geometry` under `pose` (world frame).
Aabb world_aabb(GeometryRef geometry, const Transform& pose);

/// Closest hit of a world-frame `ray` within [0, max_t] against `geometry` placed at `pose`.
/// Convex shapes are solid (origin inside: t = 0); meshes are surfaces (see TriangleMesh).
std::optional<GeometryRayHit> raycast(GeometryRef geometry, const Transform& pose, const Ray& ray, Real max_t);

}  // namespace proxima
