/// @file world_queries.cpp
/// The 2D world's scene queries: through the broad phase (flat boxes), then the narrow
/// phase on each candidate the filter accepts; answers sorted by handle where several.

#include <proxima/d2/collision_world.hpp>
#include <proxima/d2/narrowphase.hpp>

#include <algorithm>

#include "d2/world_state.hpp"

namespace proxima::d2 {

std::optional<WorldRayHit> CollisionWorld::raycast(const Ray& ray, Real max_t, const QueryFilter& filter) const {
  const detail::WorldState& w = *state_;
  if (!is_finite(ray.origin) || !is_finite(ray.direction) || !(max_t >= Real(0))) return std::nullopt;
  std::optional<WorldRayHit> best;
  const proxima::Ray flat{Vec3(ray.origin.x, ray.origin.y, Real(0)), Vec3(ray.direction.x, ray.direction.y, Real(0))};
  w.broadphase->query_ray(flat, max_t, [&](ProxyId id, Real) -> Real {
    const detail::Slot& s = w.slots[id];
    const ObjectHandle h = w.handle(id);
    if (!filter.accepts(h, s.filter)) return best ? best->hit.t : max_t;
    const auto hit = d2::raycast(s.shape, s.pose, ray, best ? best->hit.t : max_t);
    if (hit && (!best || hit->t < best->hit.t || (hit->t == best->hit.t && h < best->object)))
      best = WorldRayHit{h, *hit};
    return best ? best->hit.t : max_t;
  });
  return best;
}

int CollisionWorld::overlap(const Shape& shape, const Pose& pose, const QueryFilter& filter,
                            std::vector<ObjectHandle>& out) const {
  const detail::WorldState& w = *state_;
  const std::size_t first = out.size();
  w.broadphase->query_aabb(detail::flat_box(shape.world_aabb(pose)), [&](ProxyId id) {
    const detail::Slot& s = w.slots[id];
    const ObjectHandle h = w.handle(id);
    if (filter.accepts(h, s.filter) && intersect(shape, pose, s.shape, s.pose)) out.push_back(h);
    return true;
  });
  std::sort(out.begin() + static_cast<std::ptrdiff_t>(first), out.end());
  return static_cast<int>(out.size() - first);
}

}  // namespace proxima::d2
