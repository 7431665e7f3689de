#pragma once
/// @file compound.hpp
/// Compound: an immutable, shared set of child geometries (convex shapes, triangle meshes or
/// other compounds) at local poses, with a BVH over the children's boxes. A compound works
/// wherever a geometry does (midphase/geometry.hpp, midphase/geometry_queries.hpp).

#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/spatial/bvh.hpp>
#include <proxima/shapes/triangle_mesh.hpp>
#include <proxima/shapes/shape.hpp>

#include <memory>
#include <optional>
#include <span>
#include <variant>
#include <vector>

namespace proxima {

struct CompoundChild;

/// Children at local poses plus a BVH over their boxes (frame of the compound).
class Compound {
 public:
  /// Validated construction. Errors: TooFew for no child ("children"), NotFinite for a
  /// non-finite child pose ("children[3].pose"), InvalidArgument for a half-space child
  /// ("children[3].shape": unbounded, it cannot go in a BVH). O(n log n).
  static Result<Compound> create(std::vector<CompoundChild> children, const BvhBuildOptions& bvh = {});

  /// The children, in the order given.
  std::span<const CompoundChild> children() const;
  /// BVH over the children's boxes in the compound's frame (primitive i = child i).
  const Bvh& bvh() const;
  /// Box of all children (compound frame).
  Aabb local_aabb() const { return bvh().bounds(); }
  /// Box in the world frame under `pose` (union of the children's world boxes).
  Aabb world_aabb(const Transform& pose) const;
  /// Mass properties of the union of the children at `density`, children assumed disjoint
  /// (overlapping volume counts twice, as in Jolt and Bullet); open meshes contribute none.
  MassProperties mass_properties(Real density = Real(1)) const;

  struct Data;  ///< the immutable shared data (children and BVH)

 private:
  explicit Compound(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  std::shared_ptr<const Data> data_;
};

/// Any geometry, owning: a convex shape, a triangle mesh or a compound (meshes and
/// compounds share their data, so copies are cheap).
using Geometry = std::variant<Shape, TriangleMesh, Compound>;

/// One child of a compound: its geometry and its pose in the compound's frame.
struct CompoundChild {
  Geometry geometry;  ///< the child geometry
  Transform pose;     ///< child frame -> compound frame
};

/// The data behind a Compound.
struct Compound::Data {
  std::vector<CompoundChild> children;  ///< children in the order given
  Bvh bvh;                              ///< over the children's boxes, compound frame
};

inline std::span<const CompoundChild> Compound::children() const { return data_->children; }
inline const Bvh& Compound::bvh() const { return data_->bvh; }

}  // namespace proxima
