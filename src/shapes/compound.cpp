/// @file compound.cpp
/// Compound: validation, the BVH over the children's boxes and the aggregate queries.
///
/// Steps of create: check every child (finite unit pose, no half-space), compute each
/// child's box in the compound's frame (world_aabb of the child under its pose), build the
/// binned-SAH Bvh over those boxes. Mass properties: each child's properties are moved into
/// the compound frame (centroid by the pose, inertia rotated R I R^T), summed, and the
/// inertias shifted to the common centroid by the parallel-axis theorem (any rigid-body text,
/// e.g. Goldstein, "Classical Mechanics", ch. 5).

#include <proxima/shapes/compound.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <utility>

namespace proxima {

Result<Compound> Compound::create(std::vector<CompoundChild> children, const BvhBuildOptions& bvh) {
  if (children.empty()) return make_error(ErrorCode::TooFew, "children", "a compound needs at least one child");
  std::vector<Aabb> boxes;
  std::vector<Vec3> centers;
  boxes.reserve(children.size());
  centers.reserve(children.size());
  for (std::size_t i = 0; i < children.size(); ++i) {
    CompoundChild& child = children[i];
    const std::string prefix = "children[" + std::to_string(i) + "]";
    auto pose = Transform::create(child.pose.position, child.pose.rotation);
    if (!pose) {
      Error e = pose.error();
      e.field = prefix + ".pose." + e.field;
      return e;
    }
    child.pose = *pose;
    if (shape_type(child.shape) == ShapeType::HalfSpace)
      return make_error(ErrorCode::InvalidArgument, prefix + ".shape",
                        "a half-space is unbounded and cannot be a compound child");
    const Aabb box = proxima::world_aabb(child.shape, child.pose);
    boxes.push_back(box);
    centers.push_back(box.center());
  }
  auto data = std::make_shared<Data>();
  data->bvh = Bvh::build(boxes, centers, bvh);
  data->children = std::move(children);
  return Compound(std::move(data));
}

Aabb Compound::world_aabb(const Transform& pose) const {
  Aabb box = Aabb::empty();
  for (const CompoundChild& child : children()) box.grow(proxima::world_aabb(child.shape, pose * child.pose));
  return box;
}

namespace {

MassProperties child_mass_properties(const Shape& shape, Real density) {
  return std::visit(
      [&](const auto& s) {
        if constexpr (std::is_same_v<std::decay_t<decltype(s)>, HalfSpace>)
          return MassProperties{};  // refused by create
        else
          return s.mass_properties(density);
      },
      shape);
}

/// The answer past Real's range (a child's properties overflowed): turning and shifting an
/// infinite inertia would mix infinities of both signs into NaN, so the whole inertia is
/// +infinity, the volume and mass the children's sums, the centroid the box centre.
MassProperties overflowed(std::span<const CompoundChild> kids, Real density, const Vec3& centre) {
  MassProperties total;
  for (const CompoundChild& child : kids) {
    const MassProperties m = child_mass_properties(child.shape, density);
    total.volume += m.volume;
    total.mass += m.mass;
  }
  total.centroid = centre;
  for (int c = 0; c < 3; ++c) total.inertia[c] = Vec3(std::numeric_limits<Real>::infinity());
  return total;
}

}  // namespace

MassProperties Compound::mass_properties(Real density) const {
  MassProperties total;
  const auto kids = children();
  std::vector<MassProperties> moved;
  moved.reserve(kids.size());
  Vec3 weighted{Real(0)};
  for (const CompoundChild& child : kids) {
    MassProperties m = child_mass_properties(child.shape, density);
    if (!is_finite(m)) return overflowed(kids, density, local_aabb().center());
    const Mat3 r = child.pose.rotation_matrix();
    m.centroid = child.pose.apply(m.centroid);
    m.inertia = r * m.inertia * glm::transpose(r);
    total.volume += m.volume;
    total.mass += m.mass;
    weighted += m.volume * m.centroid;
    moved.push_back(m);
  }
  // Centroid: volume-weighted (equal to mass-weighted at uniform density, and defined for
  // density 0); a compound of zero volume (open meshes, flat shapes) uses its box centre.
  total.centroid = total.volume > Real(0) ? weighted / total.volume : local_aabb().center();
  total.inertia = Mat3(Real(0));
  for (const MassProperties& m : moved) total.inertia += shift_inertia(m.inertia, m.mass, m.centroid - total.centroid);
  return total;
}

}  // namespace proxima
