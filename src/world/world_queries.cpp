// Scene queries of CollisionWorld: ray cast, line of sight, overlap (geometry, box, point),
// sweep and closest object.
//
// Steps of every query: validate the arguments; ask the broad phase for the proxies (one
// per attachment tree) meeting the query's box or ray; expand them to the member objects
// whose own boxes meet it and that the filter accepts; run the exact test (raycast,
// intersect, shape_cast, distance) on each; collect per mode. Closest keeps the smallest t
// or distance (ties: lower handle), Any stops at the first answer, All sorts by t (or by
// handle). A ray query clips the broad phase's ray as closer hits are found.
#include <proxima/ccd/shape_cast.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "world/world_state.hpp"

namespace proxima {

using validate::is_acceptable;
using validate::is_unit;

namespace {

using Impl = CollisionWorld::Impl;

/// Calls f(index) for every live object the filter accepts whose box meets `box`, trees in
/// index order; stops when f returns false.
template <class F>
void for_each_object_in_box(const Impl& w, const Aabb& box, const QueryFilter& filter, F&& f) {
  std::vector<std::uint32_t> roots;
  w.broadphase->query_aabb(box, [&](ProxyId id) {
    roots.push_back(id);
    return true;
  });
  std::sort(roots.begin(), roots.end());
  bool go = true;
  for (std::uint32_t r : roots) {
    w.for_each_member(r, [&](std::uint32_t j) {
      const ObjectSlot& s = w.slots[j];
      if (go && s.box.overlaps(box) && filter.accepts(s.handle(j), s.filter)) go = f(j);
    });
    if (!go) return;
  }
}

std::optional<Error> check_point(const Vec3& p, const char* field) {
  if (!is_acceptable(p)) return make_error(ErrorCode::NotFinite, field, "must be finite and within kMaxCoordinate");
  return std::nullopt;
}

std::optional<Error> check_distance(Real d, const char* field) {
  if (!std::isfinite(d) || d < 0) return make_error(ErrorCode::Negative, field, "must be finite and >= 0");
  return std::nullopt;
}

void sort_hits(std::vector<WorldHit>& hits) {
  std::sort(hits.begin(), hits.end(),
            [](const WorldHit& x, const WorldHit& y) { return x.t != y.t ? x.t < y.t : x.object < y.object; });
}

/// Keeps the closest hit only (ties: lower handle).
void keep_closest(std::vector<WorldHit>& hits) {
  sort_hits(hits);
  if (hits.size() > 1) hits.resize(1);
}

/// Overlap tests of every object in `box` by `test(index)`, collected per mode.
template <class Test>
std::vector<WorldOverlap> overlaps(const Impl& w, const Aabb& box, const QueryFilter& filter, QueryMode mode,
                                   Test&& test) {
  std::vector<WorldOverlap> out;
  for_each_object_in_box(w, box, filter, [&](std::uint32_t j) {
    if (!test(j)) return true;
    out.push_back({w.slots[j].handle(j), w.slots[j].user_data});
    return mode != QueryMode::Any;
  });
  std::sort(out.begin(), out.end(), [](const WorldOverlap& x, const WorldOverlap& y) { return x.object < y.object; });
  if (mode == QueryMode::Closest && out.size() > 1) out.resize(1);
  return out;
}

}  // namespace

Result<std::vector<WorldHit>> CollisionWorld::raycast(const Ray& ray, Real max_t, const QueryFilter& filter,
                                                      QueryMode mode) const {
  const detail::ReadScope reading(impl_->access);
  const Impl& w = *impl_;
  if (auto e = check_point(ray.origin, "ray.origin")) return *e;
  if (!is_acceptable(ray.direction) || glm::dot(ray.direction, ray.direction) == Real(0))
    return make_error(ErrorCode::InvalidArgument, "ray.direction", "must be finite and not zero");
  if (auto e = check_distance(max_t, "max_t")) return *e;
  std::vector<WorldHit> hits;
  Real limit = max_t;
  w.broadphase->query_ray(ray, max_t, [&](ProxyId root, Real) -> Real {
    bool stop = false;
    w.for_each_member(root, [&](std::uint32_t j) {
      const ObjectSlot& s = w.slots[j];
      if (stop || !filter.accepts(s.handle(j), s.filter)) return;
      const std::optional<RayHit> hit = proxima::raycast(s.geometry, s.pose, ray, limit);
      if (!hit) return;
      hits.push_back({s.handle(j), s.user_data, hit->t, hit->point, hit->normal, hit->sub});
      if (mode == QueryMode::Closest) limit = hit->t;
      if (mode == QueryMode::Any) stop = true;
    });
    return stop ? Real(0) : limit;
  });
  if (mode == QueryMode::All)
    sort_hits(hits);
  else
    keep_closest(hits);
  return hits;
}

Result<bool> CollisionWorld::line_of_sight(const Vec3& from, const Vec3& to, const QueryFilter& filter) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_point(from, "from")) return *e;
  if (auto e = check_point(to, "to")) return *e;
  if (from == to) {
    auto inside = overlap_point(from, filter, QueryMode::Any);
    return inside->empty();
  }
  auto hits = raycast(Ray{from, to - from}, Real(1), filter, QueryMode::Any);
  if (!hits) return hits.error();
  return hits->empty();
}

Result<std::vector<WorldOverlap>> CollisionWorld::overlap(ShapeRef geometry, const Transform& pose,
                                                          const QueryFilter& filter, QueryMode mode) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_pose(pose, "pose")) return *e;
  const Impl& w = *impl_;
  const Aabb shape_box = world_aabb(geometry, pose);
  const Aabb box = proxy_box(shape_box, touching_pad(shape_box));  // touching counts (narrow phase)
  return overlaps(w, box, filter, mode,
                  [&](std::uint32_t j) { return intersect(geometry, pose, w.slots[j].geometry, w.slots[j].pose); });
}

Result<std::vector<WorldOverlap>> CollisionWorld::overlap_box(const Aabb& box, const QueryFilter& filter,
                                                              QueryMode mode) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_point(box.min, "box.min")) return *e;
  if (auto e = check_point(box.max, "box.max")) return *e;
  if (box.min.x > box.max.x || box.min.y > box.max.y || box.min.z > box.max.z)
    return make_error(ErrorCode::InvalidArgument, "box", "min exceeds max on some axis");
  const Impl& w = *impl_;
  // A flat box (zero extent on an axis) is a box of the smallest positive half extent.
  const Box shape = *Box::create(glm::max((box.max - box.min) * Real(0.5), Vec3(std::numeric_limits<Real>::min())));
  const Transform pose{(box.max + box.min) * Real(0.5), kIdentityQuat};
  return overlaps(w, proxy_box(box, touching_pad(box)), filter, mode,
                  [&](std::uint32_t j) { return intersect(shape, pose, w.slots[j].geometry, w.slots[j].pose); });
}

Result<std::vector<WorldOverlap>> CollisionWorld::overlap_point(const Vec3& point, const QueryFilter& filter,
                                                                QueryMode mode) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_point(point, "point")) return *e;
  const Impl& w = *impl_;
  const Point shape = *Point::create();
  const Transform pose{point, kIdentityQuat};
  return overlaps(w, proxy_box(Aabb{point, point}, touching_pad(Aabb{point, point})), filter, mode,
                  [&](std::uint32_t j) { return intersect(shape, pose, w.slots[j].geometry, w.slots[j].pose); });
}

Result<std::vector<WorldHit>> CollisionWorld::sweep(ShapeRef geometry, const Transform& pose, const Vec3& translation,
                                                    const QueryFilter& filter, QueryMode mode) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_pose(pose, "pose")) return *e;
  if (auto e = check_point(translation, "translation")) return *e;
  if (!is_convex(geometry.type()))
    return make_error(ErrorCode::InvalidArgument, "geometry", "a sweep needs a convex geometry");
  const Impl& w = *impl_;
  const Aabb start = world_aabb(geometry, pose);
  const Aabb swept{glm::min(start.min, start.min + translation), glm::max(start.max, start.max + translation)};
  std::vector<WorldHit> hits;
  for_each_object_in_box(w, proxy_box(swept, Real(0)), filter, [&](std::uint32_t j) {
    const ObjectSlot& s = w.slots[j];
    const Result<CastResult> r = shape_cast(geometry, pose, translation, s.geometry, s.pose);
    if (!r.ok() || (r->status != CcdStatus::Hit && r->status != CcdStatus::InitiallyOverlapping)) return true;
    hits.push_back({s.handle(j), s.user_data, r->t, r->point, r->normal, r->sub_b});
    return mode != QueryMode::Any;
  });
  if (mode == QueryMode::All)
    sort_hits(hits);
  else
    keep_closest(hits);
  return hits;
}

Result<std::optional<WorldClosest>> CollisionWorld::closest(ShapeRef geometry, const Transform& pose, Real max_distance,
                                                            const QueryFilter& filter) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_pose(pose, "pose")) return *e;
  if (auto e = check_distance(max_distance, "max_distance")) return *e;
  const Impl& w = *impl_;
  std::optional<WorldClosest> best;
  const Aabb box = proxy_box(world_aabb(geometry, pose), max_distance);
  for_each_object_in_box(w, box, filter, [&](std::uint32_t j) {
    const ObjectSlot& s = w.slots[j];
    const DistanceResult d = distance(geometry, pose, s.geometry, s.pose);
    if (d.signed_distance > max_distance) return true;
    if (best && d.signed_distance >= best->signed_distance) return true;
    best = WorldClosest{s.handle(j), s.user_data, d.signed_distance, d.point_a, d.point_b, d.normal, d.sub_b};
    return true;
  });
  return best;
}

Result<std::optional<WorldClosest>> CollisionWorld::closest_point(const Vec3& point, Real max_distance,
                                                                  const QueryFilter& filter) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_point(point, "point")) return *e;
  return closest(*Point::create(), Transform{point, kIdentityQuat}, max_distance, filter);
}

}  // namespace proxima
