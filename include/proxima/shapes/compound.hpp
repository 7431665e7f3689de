#pragma once
/// @file compound.hpp
/// Compound: an immutable, shared set of child shapes (convex shapes, triangle meshes or
/// other compounds) at local poses, with a BVH over the children's boxes. A compound is a
/// Shape like any other (shape.hpp, which defines CompoundChild) and answers every query
/// through ShapeRef.
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/mass_properties.hpp>
#include <proxima/spatial/bvh.hpp>

#include <memory>
#include <span>
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
  /// Past Real's range (is_finite false for a child) the whole inertia is +infinity.
  MassProperties mass_properties(Real density = Real(1)) const;

 private:
  struct Data;  ///< the immutable shared data (children and BVH), defined in shape.hpp
  explicit Compound(std::shared_ptr<const Data> data) : data_(std::move(data)) {}
  std::shared_ptr<const Data> data_;
};

}  // namespace proxima

// CompoundChild and Compound::Data hold a Shape, which holds a Compound: they are defined
// in shape.hpp, included here so that including compound.hpp alone is enough.
#include <proxima/shapes/shape.hpp>
