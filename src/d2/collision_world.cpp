/// @file collision_world.cpp
/// The 2D collision world's objects: creation, add / remove / move / teleport / filters /
/// exclusions, accessors. The step is in world_step.cpp, the queries in world_queries.cpp.

#include <proxima/core/tolerance.hpp>
#include <proxima/d2/collision_world.hpp>

#include <algorithm>
#include <string>

#include "d2/world_state.hpp"

namespace proxima::d2 {

namespace detail {

bool pose_ok(const Pose& pose) {
  return is_finite(pose.position) && max_abs_component(pose.position) <= kMaxCoordinate &&
         std::isfinite(pose.rotation.c) && std::isfinite(pose.rotation.s) &&
         std::abs(pose.rotation.c * pose.rotation.c + pose.rotation.s * pose.rotation.s - Real(1)) <= Real(1e-3);
}

void measure(Slot& s) {
  const Aabb local = s.shape.world_aabb(Pose::identity());
  s.min_extent = std::min(local.max.x - local.min.x, local.max.y - local.min.y);
  s.reach = glm::length(glm::max(glm::abs(local.min), glm::abs(local.max)));
}

}  // namespace detail

CollisionWorld::CollisionWorld(std::unique_ptr<detail::WorldState> state) : state_(std::move(state)) {}
CollisionWorld::CollisionWorld(CollisionWorld&&) noexcept = default;
CollisionWorld& CollisionWorld::operator=(CollisionWorld&&) noexcept = default;
CollisionWorld::~CollisionWorld() = default;

Result<CollisionWorld> CollisionWorld::create(const WorldSettings& settings) {
  if (auto e = validate_world_settings(settings)) return *e;
  auto broadphase = make_broadphase(settings.broadphase);
  if (!broadphase) return Error{broadphase.error().code, "settings.broadphase", broadphase.error().message};
  auto state = std::make_unique<detail::WorldState>();
  state->settings = settings;
  state->settings.max_contacts = std::min(settings.max_contacts, kMaxManifoldPoints);
  state->broadphase = std::move(broadphase).value();
  return CollisionWorld(std::move(state));
}

Result<ObjectHandle> CollisionWorld::add(const ObjectDesc& desc) {
  if (auto e = state_->busy()) return *e;
  if (!detail::pose_ok(desc.pose))
    return Error{ErrorCode::NotFinite, "desc.pose", "must be finite with a unit rotation"};
  if (!desc.shape.is_convex() && desc.kind != ObjectKind::Static) {
    return Error{ErrorCode::InvalidArgument, "desc.kind", "a chain can only be a static object"};
  }
  detail::WorldState& w = *state_;
  std::uint32_t index;
  if (!w.free_slots.empty()) {
    index = w.free_slots.back();
    w.free_slots.pop_back();
  } else {
    index = static_cast<std::uint32_t>(w.slots.size());
    w.slots.emplace_back();
  }
  detail::Slot& s = w.slots[index];
  const std::uint32_t generation = s.generation;
  s = detail::Slot{desc.shape, desc.pose,      desc.pose,  desc.kind, desc.filter, desc.sensor,
                   desc.ccd,   desc.user_data, generation, true,      false};
  detail::measure(s);
  w.broadphase->insert(index, w.proxy_box(desc.shape, desc.pose), detail::proxy_kind(desc.kind));
  ++w.live;
  return ObjectHandle{index, generation};
}

std::optional<Error> CollisionWorld::remove(ObjectHandle handle) {
  if (auto e = state_->busy()) return e;
  detail::WorldState& w = *state_;
  if (w.live_slot(handle) == nullptr)
    return Error{ErrorCode::InvalidArgument, "handle", "names no live object of this world"};
  detail::Slot& s = w.slots[handle.index];
  w.broadphase->remove(handle.index);
  std::erase_if(w.excluded, [&](std::uint64_t key) {
    return std::uint32_t(key >> 32) == handle.index || std::uint32_t(key) == handle.index;
  });
  s.alive = false;
  ++s.generation;
  w.free_slots.push_back(handle.index);
  --w.live;
  return std::nullopt;
}

std::optional<Error> CollisionWorld::move(ObjectHandle handle, const Pose& pose) {
  if (auto e = state_->busy()) return e;
  if (state_->live_slot(handle) == nullptr)
    return Error{ErrorCode::InvalidArgument, "handle", "names no live object of this world"};
  if (!detail::pose_ok(pose)) return Error{ErrorCode::NotFinite, "pose", "must be finite with a unit rotation"};
  detail::Slot& s = state_->slots[handle.index];
  s.pose = pose;
  s.moved = true;
  return std::nullopt;
}

std::optional<Error> CollisionWorld::teleport(ObjectHandle handle, const Pose& pose) {
  if (auto e = move(handle, pose)) return e;
  state_->slots[handle.index].previous = pose;
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_filter(ObjectHandle handle, const CollisionFilter& filter) {
  if (auto e = state_->busy()) return e;
  if (state_->live_slot(handle) == nullptr)
    return Error{ErrorCode::InvalidArgument, "handle", "names no live object of this world"};
  state_->slots[handle.index].filter = filter;
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_pair_excluded(ObjectHandle a, ObjectHandle b, bool excluded) {
  if (auto e = state_->busy()) return e;
  if (state_->live_slot(a) == nullptr)
    return Error{ErrorCode::InvalidArgument, "a", "names no live object of this world"};
  if (state_->live_slot(b) == nullptr)
    return Error{ErrorCode::InvalidArgument, "b", "names no live object of this world"};
  if (a == b) return Error{ErrorCode::InvalidArgument, "b", "is the same object as a"};
  const std::uint64_t key = detail::pair_key(a.index, b.index);
  if (excluded) {
    state_->excluded.insert(key);
  } else {
    state_->excluded.erase(key);
  }
  return std::nullopt;
}

bool CollisionWorld::contains(ObjectHandle handle) const { return state_->live_slot(handle) != nullptr; }

std::optional<Pose> CollisionWorld::pose(ObjectHandle handle) const {
  const detail::Slot* s = state_->live_slot(handle);
  return s == nullptr ? std::nullopt : std::optional<Pose>(s->pose);
}

std::size_t CollisionWorld::size() const { return state_->live; }

std::vector<ObjectHandle> CollisionWorld::objects() const {
  std::vector<ObjectHandle> out;
  out.reserve(state_->live);
  for (std::uint32_t i = 0; i < state_->slots.size(); ++i) {
    if (state_->slots[i].alive) out.push_back(state_->handle(i));
  }
  return out;
}

std::optional<ObjectDesc> CollisionWorld::object(ObjectHandle handle) const {
  const detail::Slot* s = state_->live_slot(handle);
  if (s == nullptr) return std::nullopt;
  return ObjectDesc{s->shape, s->pose, s->kind, s->filter, s->sensor, s->ccd, s->user_data};
}
const StepEvents& CollisionWorld::events() const { return state_->events; }
std::span<const WorldManifold> CollisionWorld::manifolds() const { return state_->manifolds; }
void CollisionWorld::set_listener(WorldListener* listener) { state_->listener = listener; }

}  // namespace proxima::d2
