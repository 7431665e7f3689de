// Batched scene queries of CollisionWorld: rays, line-of-sight segments and closest points,
// spans in and spans out.
//
// Steps of every batch:
//  1. validate the output span's size and every item, in item order; the first bad one is
//     named ("rays[3].direction") and nothing is written;
//  2. spread the items over the executor (Executor::run: disjoint ranges); each item runs the
//     single query (world_queries.cpp; a ray its closest-hit walk without the hit list), which
//     only reads the world, and writes its own slot, so the answers equal the serial loop's
//     whatever the executor and its thread count;
//  3. count the answers, serially.
#include <proxima/core/validate.hpp>
#include <proxima/shapes/shape_queries.hpp>
#include <proxima/world/collision_world.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "world/world_state.hpp"

namespace proxima {

namespace {

using validate::is_acceptable;
using Impl = CollisionWorld::Impl;

std::string item_field(const char* span, std::size_t i, const char* member) {
  std::string field = std::string(span) + "[" + std::to_string(i) + "]";
  if (member != nullptr) field += std::string(".") + member;
  return field;
}

std::optional<Error> check_sizes(std::size_t items, std::size_t answers, const char* answers_field,
                                 const char* items_field) {
  if (items == answers) return std::nullopt;
  return make_error(ErrorCode::InvalidArgument, answers_field,
                    "must hold one entry per entry of " + std::string(items_field) + " (" + std::to_string(items) +
                        "), not " + std::to_string(answers));
}

std::optional<Error> check_point(const Vec3& p, const char* span, std::size_t i, const char* member) {
  if (is_acceptable(p)) return std::nullopt;
  return make_error(ErrorCode::NotFinite, item_field(span, i, member), "must be finite and within kMaxCoordinate");
}

/// Runs item(i) for every i in [0, count) on the executor.
template <class Item>
void for_each_item(Executor& executor, std::size_t count, Item&& item) {
  executor.run(count, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) item(i);
  });
}

}  // namespace

Result<std::size_t> CollisionWorld::raycast_batch(std::span<const WorldRay> rays, std::span<WorldHit> hits,
                                                  const QueryFilter& filter, Executor& executor) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_sizes(rays.size(), hits.size(), "hits", "rays")) return *e;
  for (std::size_t i = 0; i < rays.size(); ++i) {
    const WorldRay& r = rays[i];
    if (auto e = check_point(r.origin, "rays", i, "origin")) return *e;
    if (!is_acceptable(r.direction) || glm::dot(r.direction, r.direction) == Real(0)) {
      return make_error(ErrorCode::InvalidArgument, item_field("rays", i, "direction"), "must be finite and not zero");
    }
    if (!std::isfinite(r.max_t) || r.max_t < Real(0)) {
      return make_error(ErrorCode::Negative, item_field("rays", i, "max_t"), "must be finite and >= 0");
    }
  }
  // The closest hit of raycast(..., QueryMode::Closest) without its list: the same clipped
  // ray and the same order (t, then handle).
  const Impl& w = *impl_;
  for_each_item(executor, rays.size(), [&](std::size_t i) {
    const Ray ray{rays[i].origin, rays[i].direction};
    WorldHit best;
    Real limit = rays[i].max_t;
    w.broadphase->query_ray(ray, limit, [&](ProxyId root, Real) -> Real {
      w.for_each_member(root, [&](std::uint32_t j) {
        const ObjectSlot& s = w.slots[j];
        if (!filter.accepts(s.handle(j), s.filter)) return;
        const std::optional<RayHit> hit = proxima::raycast(s.geometry, s.pose, ray, limit);
        if (!hit) return;
        const ObjectHandle h = s.handle(j);
        if (!best.object.is_set() || hit->t < best.t || (hit->t == best.t && h < best.object)) {
          best = WorldHit{h, s.user_data, hit->t, hit->point, hit->normal, hit->sub};
        }
        limit = hit->t;
      });
      return limit;
    });
    hits[i] = best;
  });
  return static_cast<std::size_t>(
      std::count_if(hits.begin(), hits.end(), [](const WorldHit& h) { return h.object.is_set(); }));
}

Result<std::size_t> CollisionWorld::line_of_sight_batch(std::span<const WorldSegment> segments,
                                                        std::span<std::uint8_t> visible, const QueryFilter& filter,
                                                        Executor& executor) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_sizes(segments.size(), visible.size(), "visible", "segments")) return *e;
  for (std::size_t i = 0; i < segments.size(); ++i) {
    if (auto e = check_point(segments[i].from, "segments", i, "from")) return *e;
    if (auto e = check_point(segments[i].to, "segments", i, "to")) return *e;
  }
  for_each_item(executor, segments.size(), [&](std::size_t i) {
    const Result<bool> clear = line_of_sight(segments[i].from, segments[i].to, filter);
    visible[i] = clear.ok() && *clear ? 1 : 0;
  });
  return static_cast<std::size_t>(std::count(visible.begin(), visible.end(), std::uint8_t(1)));
}

Result<std::size_t> CollisionWorld::closest_point_batch(std::span<const Vec3> points, Real max_distance,
                                                        std::span<WorldClosest> nearest, const QueryFilter& filter,
                                                        Executor& executor) const {
  const detail::ReadScope reading(impl_->access);
  if (auto e = check_sizes(points.size(), nearest.size(), "nearest", "points")) return *e;
  if (!std::isfinite(max_distance) || max_distance < Real(0)) {
    return make_error(ErrorCode::Negative, "max_distance", "must be finite and >= 0");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (auto e = check_point(points[i], "points", i, nullptr)) return *e;
  }
  for_each_item(executor, points.size(), [&](std::size_t i) {
    const Result<std::optional<WorldClosest>> found = closest_point(points[i], max_distance, filter);
    nearest[i] = found.ok() && found->has_value() ? **found : WorldClosest{};
  });
  return static_cast<std::size_t>(
      std::count_if(nearest.begin(), nearest.end(), [](const WorldClosest& c) { return c.object.is_set(); }));
}

}  // namespace proxima
