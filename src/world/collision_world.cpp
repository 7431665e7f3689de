// CollisionWorld: creation, objects (add, remove, move, set_*), attachment, accessors and
// the state hash. The step is in world_step.cpp, continuous detection in world_ccd.cpp,
// scene queries in world_queries.cpp.
//
// Every changing call validates everything first and changes nothing until all checks have
// passed, so a rejected call leaves the world as it was.
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "world/world_state.hpp"

namespace proxima {

using validate::is_acceptable;
using validate::is_unit;

namespace {

std::optional<Error> check_filter(const CollisionFilter& filter, const std::string& field) {
  if (filter.layer == 0)
    return make_error(ErrorCode::InvalidArgument, field + ".layer", "has no bits: it would never collide");
  if (filter.mask == 0)
    return make_error(ErrorCode::InvalidArgument, field + ".mask", "has no bits: it would never collide");
  return std::nullopt;
}

/// A geometry's fitness for an object of kind `kind` (attached or not).
std::optional<Error> check_geometry(const Shape& geometry, ObjectKind kind, bool attached, const std::string& field) {
  if (std::holds_alternative<HalfSpace>(geometry)) {
    if (kind != ObjectKind::Static)
      return make_error(ErrorCode::InvalidArgument, field,
                        "a half-space is unbounded: only a static object may hold one");
    if (attached)
      return make_error(ErrorCode::InvalidArgument, field, "a half-space cannot be attached to another object");
  }
  if (const auto* mesh = std::get_if<TriangleMesh>(&geometry); mesh != nullptr && mesh->triangle_count() == 0)
    return make_error(ErrorCode::TooFew, field, "the mesh has no triangles");
  return std::nullopt;
}

}  // namespace

/// Farthest point of the geometry from its origin and the thinnest side of its box, from
/// its local box (0 for unbounded geometry).
void measure_geometry(ObjectSlot& s) {
  const Aabb b = world_aabb(s.geometry, Transform::identity());
  if (std::holds_alternative<HalfSpace>(s.geometry)) {
    s.radius = Real(0);
    s.min_extent = Real(0);
    return;
  }
  const Vec3 far = glm::max(glm::abs(b.min), glm::abs(b.max));
  s.radius = glm::length(far);
  const Vec3 side = b.max - b.min;
  s.min_extent = std::min({side.x, side.y, side.z});
}

std::optional<Error> check_pose(const Transform& pose, const std::string& field) {
  if (!is_acceptable(pose.position))
    return make_error(ErrorCode::NotFinite, field + ".position", "must be finite and within kMaxCoordinate");
  if (!is_unit(pose.rotation))
    return make_error(ErrorCode::InvalidArgument, field + ".rotation", "must be a unit quaternion");
  return std::nullopt;
}

Aabb proxy_box(const Aabb& box, Real pad) {
  Aabb out{box.min - Vec3(pad), box.max + Vec3(pad)};
  out.min = glm::clamp(out.min, Vec3(-kMaxCoordinate), Vec3(kMaxCoordinate));
  out.max = glm::clamp(out.max, Vec3(-kMaxCoordinate), Vec3(kMaxCoordinate));
  return out;
}

Real touching_pad(const Aabb& box) {
  Real m = Real(0);
  for (int i = 0; i < 3; ++i) {
    for (const Real c : {box.min[i], box.max[i]}) {
      if (std::abs(c) < kMaxCoordinate) m = std::max(m, std::abs(c));
    }
  }
  return Real(2) * linear_tolerance(m);
}

std::string_view to_string(ObjectKind kind) { return kind == ObjectKind::Static ? "static" : "moving"; }

std::string_view to_string(CcdMode mode) {
  switch (mode) {
    case CcdMode::Off: return "off";
    case CcdMode::Auto: return "auto";
    case CcdMode::Bullet: return "bullet";
  }
  return "off";
}

std::optional<Error> validate_world_settings(const WorldSettings& s) {
  if (!std::isfinite(s.contact_distance) || s.contact_distance < 0)
    return make_error(ErrorCode::Negative, "settings.contact_distance", "must be finite and >= 0");
  if (s.max_contacts < 1 || s.max_contacts > kMaxContactPoints)
    return make_error(ErrorCode::OutOfRange, "settings.max_contacts", "must be in 1..4");
  if (!(s.ccd_safety_factor > 0 && s.ccd_safety_factor <= 1))
    return make_error(ErrorCode::OutOfRange, "settings.ccd_safety_factor", "must be in (0, 1]");
  if (!std::isfinite(s.ccd_tolerance) || s.ccd_tolerance < 0)
    return make_error(ErrorCode::Negative, "settings.ccd_tolerance", "must be finite and >= 0");
  return std::nullopt;
}

// ---- Impl helpers --------------------------------------------------------------------

void CollisionWorld::Impl::refresh_box(std::uint32_t i) {
  ObjectSlot& s = slots[i];
  s.box = proxy_box(world_aabb(s.geometry, s.pose), settings.contact_distance * Real(0.5));
}

Aabb CollisionWorld::Impl::tree_box(std::uint32_t r) const {
  Aabb box = slots[r].box;
  for_each_member(r, [&](std::uint32_t i) {
    box.min = glm::min(box.min, slots[i].box.min);
    box.max = glm::max(box.max, slots[i].box.max);
  });
  return box;
}

ProxyFilter CollisionWorld::Impl::tree_filter(std::uint32_t r) const {
  std::uint64_t layer = 0, mask = 0;
  for_each_member(r, [&](std::uint32_t i) {
    layer |= slots[i].filter.layer;
    mask |= slots[i].filter.mask;
  });
  auto fold = [](std::uint64_t bits) {
    return static_cast<std::uint32_t>(bits) | static_cast<std::uint32_t>(bits >> 32);
  };
  return ProxyFilter{fold(layer), fold(mask)};
}

void CollisionWorld::Impl::refresh_proxy(std::uint32_t r) {
  [[maybe_unused]] const BroadPhaseStatus st = broadphase->update(r, tree_box(r));
  PROXIMA_ASSERT(st == BroadPhaseStatus::Ok);
}

void CollisionWorld::Impl::reinsert_proxy(std::uint32_t r) {
  broadphase->remove(r);  // UnknownId when the tree is new
  [[maybe_unused]] const BroadPhaseStatus st = broadphase->insert(
      r, tree_box(r), slots[r].kind == ObjectKind::Static ? ProxyKind::Static : ProxyKind::Moving, tree_filter(r));
  PROXIMA_ASSERT(st == BroadPhaseStatus::Ok);
}

void CollisionWorld::Impl::propagate_pose(std::uint32_t i) {
  for (std::uint32_t c = slots[i].first_child; c != kNoSlot; c = slots[c].next_sibling) {
    slots[c].pose = slots[i].pose * local_poses.at(c);
    refresh_box(c);
    mark_moved(c);
    propagate_pose(c);
  }
}

bool CollisionWorld::Impl::may_pair(const CollisionWorld& world, std::uint32_t i, std::uint32_t j) const {
  const ObjectSlot& a = slots[i];
  const ObjectSlot& b = slots[j];
  if (a.root == b.root) return false;
  if (a.kind == ObjectKind::Static && b.kind == ObjectKind::Static) return false;
  if (!can_collide(a.filter, b.filter)) return false;
  if (a.sensor && b.sensor && !settings.sensors_sense_sensors) return false;
  if (!excluded.empty() && excluded.count(pair_key(i, j)) != 0) return false;
  if (pair_filter != nullptr) {
    const ObjectPair p = i < j ? ObjectPair{a.handle(i), b.handle(j)} : ObjectPair{b.handle(j), a.handle(i)};
    if (!pair_filter->can_collide(world, p)) return false;
  }
  return true;
}

// ---- creation --------------------------------------------------------------------------

CollisionWorld::CollisionWorld(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
CollisionWorld::CollisionWorld(CollisionWorld&&) noexcept = default;
CollisionWorld& CollisionWorld::operator=(CollisionWorld&&) noexcept = default;
CollisionWorld::~CollisionWorld() = default;

Result<CollisionWorld> CollisionWorld::create(const WorldSettings& settings) {
  if (auto e = validate_world_settings(settings)) return *e;
  auto bp = make_broadphase(settings.broadphase);
  if (!bp) {
    Error e = bp.error();
    e.field = "settings.broadphase";
    return e;
  }
  auto impl = std::make_unique<Impl>();
  impl->settings = settings;
  impl->broadphase = std::move(bp).value();
  return CollisionWorld(std::move(impl));
}

const WorldSettings& CollisionWorld::settings() const { return impl_->settings; }

// ---- objects ----------------------------------------------------------------------------

namespace {

/// Changes are refused while on_pre_contact runs.
std::optional<Error> check_not_in_pre_contact(const CollisionWorld::Impl& w) {
  if (w.in_pre_contact)
    return make_error(ErrorCode::InvalidArgument, "world", "cannot change the world from on_pre_contact");
  return std::nullopt;
}

std::optional<Error> stale(const std::string& field) {
  return make_error(ErrorCode::InvalidArgument, field, "is not a live object of this world (stale or unknown handle)");
}

}  // namespace

Result<ObjectHandle> CollisionWorld::add(const ObjectDesc& desc) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (auto e = check_not_in_pre_contact(w)) return *e;
  const ObjectSlot* parent = nullptr;
  if (desc.parent.is_set()) {
    parent = w.find(desc.parent);
    if (parent == nullptr) return *stale("desc.parent");
    if (auto e = check_pose(desc.local_pose, "desc.local_pose")) return *e;
  } else if (auto e = check_pose(desc.pose, "desc.pose")) {
    return *e;
  }
  const ObjectKind kind = parent != nullptr ? parent->kind : desc.kind;
  if (auto e = check_geometry(desc.geometry, kind, parent != nullptr, "desc.geometry")) return *e;
  if (auto e = check_filter(desc.filter, "desc.filter")) return *e;

  std::uint32_t index;
  if (!w.free_slots.empty()) {
    index = w.free_slots.back();
    w.free_slots.pop_back();
  } else {
    index = static_cast<std::uint32_t>(w.slots.size());
    w.slots.emplace_back();
  }
  ObjectSlot& s = w.slots[index];
  const std::uint32_t generation = s.generation;
  s = ObjectSlot{};
  s.generation = generation;
  s.geometry = desc.geometry;
  s.filter = desc.filter;
  s.user_data = desc.user_data;
  s.kind = kind;
  s.ccd = desc.ccd;
  s.sensor = desc.sensor;
  s.alive = true;
  measure_geometry(s);
  ++w.live;
  if (parent != nullptr) {
    const std::uint32_t p = desc.parent.index;
    s.parent = p;
    s.root = w.slots[p].root;
    s.next_sibling = w.slots[p].first_child;
    w.slots[p].first_child = index;
    w.local_poses[index] = desc.local_pose;
    s.pose = w.slots[p].pose * desc.local_pose;
    s.step_pose = s.pose;
    w.refresh_box(index);
  } else {
    s.root = index;
    s.pose = desc.pose;
    s.step_pose = desc.pose;
    w.refresh_box(index);
  }
  w.reinsert_proxy(w.slots[index].root);
  return w.slots[index].handle(index);
}

namespace {

/// Unlinks object i from its parent's child list (no-op for a root).
void unlink_from_parent(CollisionWorld::Impl& w, std::uint32_t i) {
  const std::uint32_t p = w.slots[i].parent;
  if (p == kNoSlot) return;
  std::uint32_t* link = &w.slots[p].first_child;
  while (*link != i) link = &w.slots[*link].next_sibling;
  *link = w.slots[i].next_sibling;
  w.slots[i].parent = kNoSlot;
  w.slots[i].next_sibling = kNoSlot;
  w.local_poses.erase(i);
}

/// Frees the slot of object i (its children must be handled by the caller).
void free_slot(CollisionWorld::Impl& w, std::uint32_t i) {
  ObjectSlot& s = w.slots[i];
  if (s.exclusions != 0) {
    std::erase_if(w.excluded, [&](std::uint64_t k) {
      const std::uint32_t lo = std::uint32_t(k >> 32), hi = std::uint32_t(k);
      if (lo != i && hi != i) return false;
      --w.slots[lo == i ? hi : lo].exclusions;
      return true;
    });
  }
  w.object_listeners.erase(i);
  w.local_poses.erase(i);
  const std::uint32_t generation = s.generation + 1;
  s = ObjectSlot{};
  s.generation = generation;
  w.free_slots.push_back(i);
  --w.live;
}

}  // namespace

std::optional<Error> CollisionWorld::remove(ObjectHandle object) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (auto e = check_not_in_pre_contact(w)) return e;
  if (w.find(object) == nullptr) return stale("object");
  const std::uint32_t i = object.index;
  const std::uint32_t root = w.slots[i].root;
  std::vector<std::uint32_t> doomed;
  w.for_each_member(i, [&](std::uint32_t m) { doomed.push_back(m); });
  unlink_from_parent(w, i);
  if (root == i) w.broadphase->remove(i);
  for (std::uint32_t m : doomed) free_slot(w, m);
  if (root != i) w.reinsert_proxy(root);
  return std::nullopt;
}

namespace {

/// Sets object i's world pose (an attached object: its local pose follows), its subtree's
/// poses and boxes; the caller refreshes the tree's proxy.
void place(CollisionWorld::Impl& w, std::uint32_t i, const Transform& pose) {
  ObjectSlot& s = w.slots[i];
  s.pose = pose;
  if (s.parent != kNoSlot) w.local_poses[i] = relative(w.slots[s.parent].pose, pose);
  w.refresh_box(i);
  w.mark_moved(i);
  w.propagate_pose(i);
}

}  // namespace

namespace {

/// move (teleport false) or teleport: validates, places the object and its subtree, and
/// with `teleport` makes their new poses the start of the next step's motion.
std::optional<Error> set_pose(CollisionWorld::Impl& w, ObjectHandle object, const Transform& pose, bool teleport) {
  if (auto e = check_not_in_pre_contact(w)) return e;
  if (w.find(object) == nullptr) return stale("object");
  if (auto e = check_pose(pose, "pose")) return e;
  place(w, object.index, pose);
  if (teleport) w.for_each_member(object.index, [&](std::uint32_t m) { w.slots[m].step_pose = w.slots[m].pose; });
  w.refresh_proxy(w.slots[object.index].root);
  return std::nullopt;
}

}  // namespace

std::optional<Error> CollisionWorld::move(ObjectHandle object, const Transform& pose) {
  const detail::WriteScope writing(impl_->access);
  return set_pose(*impl_, object, pose, false);
}

std::optional<Error> CollisionWorld::teleport(ObjectHandle object, const Transform& pose) {
  const detail::WriteScope writing(impl_->access);
  return set_pose(*impl_, object, pose, true);
}

namespace {

/// move(span)'s placing (validated entries): the new boxes of the objects that are neither
/// attached nor carry attached ones, on the executor (each entry writes its own box), then
/// every entry applied in order on the calling thread (attached ones through place(), which
/// carries their trees); the moved trees' roots into w.move_roots.
void place_all(CollisionWorld::Impl& w, std::span<const ObjectMove> moves, Executor& executor) {
  const auto simple = [&](std::uint32_t i) {
    return w.slots[i].parent == kNoSlot && w.slots[i].first_child == kNoSlot;
  };
  std::vector<Aabb>& boxes = w.move_boxes;
  boxes.resize(moves.size());
  const Real pad = w.settings.contact_distance * Real(0.5);
  const std::size_t n = moves.size();
  const std::size_t grain = std::max<std::size_t>(64, n / (executor.concurrency() * 8 + 1));
  executor.run((n + grain - 1) / grain, [&](std::size_t begin, std::size_t end) {
    for (std::size_t k = begin * grain; k < std::min(n, end * grain); ++k) {
      const std::uint32_t i = moves[k].object.index;
      if (simple(i)) boxes[k] = proxy_box(world_aabb(w.slots[i].geometry, moves[k].pose), pad);
    }
  });
  w.move_roots.clear();
  for (std::size_t k = 0; k < n; ++k) {
    const std::uint32_t i = moves[k].object.index;
    if (simple(i)) {  // place() without the tree: the same pose, box and moved mark
      w.slots[i].pose = moves[k].pose;
      w.slots[i].box = boxes[k];
      w.mark_moved(i);
    } else {
      place(w, i, moves[k].pose);
    }
    w.move_roots.push_back(w.slots[i].root);
  }
}

}  // namespace

std::optional<Error> CollisionWorld::move(std::span<const ObjectMove> moves, Executor& executor) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (auto e = check_not_in_pre_contact(w)) return e;
  for (std::size_t k = 0; k < moves.size(); ++k) {
    const bool live = w.find(moves[k].object) != nullptr;
    if (live && is_acceptable(moves[k].pose.position) && is_unit(moves[k].pose.rotation)) continue;
    const std::string field = "moves[" + std::to_string(k) + "]";  // built only for the error
    if (!live) return stale(field + ".object");
    return check_pose(moves[k].pose, field + ".pose");
  }
  place_all(w, moves, executor);
  std::vector<std::uint32_t>& roots = w.move_roots;  // scratch kept by the world: no allocation per call
  std::sort(roots.begin(), roots.end());
  roots.erase(std::unique(roots.begin(), roots.end()), roots.end());
  std::vector<ProxyUpdate>& updates = w.move_updates;
  updates.clear();
  for (std::uint32_t r : roots) updates.push_back({r, w.tree_box(r)});
  [[maybe_unused]] const BroadPhaseStatus st = w.broadphase->update(updates);
  PROXIMA_ASSERT(st == BroadPhaseStatus::Ok);
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_geometry(ObjectHandle object, const Shape& geometry) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (auto e = check_not_in_pre_contact(w)) return e;
  ObjectSlot* s = w.find(object);
  if (s == nullptr) return stale("object");
  if (auto e = check_geometry(geometry, s->kind, s->parent != kNoSlot, "geometry")) return e;
  s->geometry = geometry;
  s->geometry_changed = true;
  measure_geometry(*s);
  w.refresh_box(object.index);
  w.mark_moved(object.index);
  w.refresh_proxy(s->root);
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_filter(ObjectHandle object, const CollisionFilter& filter) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (auto e = check_not_in_pre_contact(w)) return e;
  ObjectSlot* s = w.find(object);
  if (s == nullptr) return stale("object");
  if (auto e = check_filter(filter, "filter")) return e;
  s->filter = filter;
  w.reinsert_proxy(s->root);
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_kind(ObjectHandle object, ObjectKind kind) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (auto e = check_not_in_pre_contact(w)) return e;
  ObjectSlot* s = w.find(object);
  if (s == nullptr) return stale("object");
  if (s->parent != kNoSlot)
    return make_error(ErrorCode::InvalidArgument, "kind", "an attached object takes the kind of its tree's root");
  std::optional<Error> bad;
  w.for_each_member(object.index, [&](std::uint32_t m) {
    if (!bad) bad = check_geometry(w.slots[m].geometry, kind, m != object.index, "kind");
  });
  if (bad) return bad;
  w.for_each_member(object.index, [&](std::uint32_t m) { w.slots[m].kind = kind; });
  w.reinsert_proxy(object.index);
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_ccd(ObjectHandle object, CcdMode mode) {
  const detail::WriteScope writing(impl_->access);
  ObjectSlot* s = impl_->find(object);
  if (s == nullptr) return stale("object");
  s->ccd = mode;
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_user_data(ObjectHandle object, std::uint64_t user_data) {
  const detail::WriteScope writing(impl_->access);
  ObjectSlot* s = impl_->find(object);
  if (s == nullptr) return stale("object");
  s->user_data = user_data;
  return std::nullopt;
}

std::optional<Error> CollisionWorld::attach(ObjectHandle object, ObjectHandle parent, const Transform& local_pose) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (auto e = check_not_in_pre_contact(w)) return e;
  if (w.find(object) == nullptr) return stale("object");
  const std::uint32_t i = object.index;
  const std::uint32_t old_root = w.slots[i].root;
  if (!parent.is_set()) {  // detach, keeping the world pose
    if (w.slots[i].parent == kNoSlot) return std::nullopt;
    unlink_from_parent(w, i);
    w.for_each_member(i, [&](std::uint32_t m) { w.slots[m].root = i; });
    w.reinsert_proxy(old_root);
    w.reinsert_proxy(i);
    return std::nullopt;
  }
  if (w.find(parent) == nullptr) return stale("parent");
  for (std::uint32_t a = parent.index; a != kNoSlot; a = w.slots[a].parent)
    if (a == i)
      return make_error(ErrorCode::InvalidArgument, "parent", "is the object itself or one of its descendants");
  if (auto e = check_pose(local_pose, "local_pose")) return e;
  const ObjectKind kind = w.slots[w.slots[parent.index].root].kind;
  std::optional<Error> bad;
  w.for_each_member(i, [&](std::uint32_t m) {
    if (!bad) bad = check_geometry(w.slots[m].geometry, kind, true, "object");
  });
  if (bad) return bad;

  if (w.slots[i].parent == kNoSlot)
    w.broadphase->remove(i);
  else
    unlink_from_parent(w, i);
  const std::uint32_t p = parent.index;
  const std::uint32_t new_root = w.slots[p].root;
  w.slots[i].parent = p;
  w.slots[i].next_sibling = w.slots[p].first_child;
  w.slots[p].first_child = i;
  w.local_poses[i] = local_pose;
  w.for_each_member(i, [&](std::uint32_t m) {
    w.slots[m].root = new_root;
    w.slots[m].kind = kind;
  });
  place(w, i, w.slots[p].pose * local_pose);
  if (old_root != i && old_root != new_root) w.reinsert_proxy(old_root);
  w.reinsert_proxy(new_root);
  return std::nullopt;
}

std::optional<Error> CollisionWorld::set_pair_excluded(ObjectHandle a, ObjectHandle b, bool excluded) {
  const detail::WriteScope writing(impl_->access);
  Impl& w = *impl_;
  if (w.find(a) == nullptr) return stale("a");
  if (w.find(b) == nullptr) return stale("b");
  if (a == b) return make_error(ErrorCode::InvalidArgument, "b", "is the same object as a");
  const std::uint64_t key = pair_key(a.index, b.index);
  if (excluded) {
    if (w.excluded.insert(key).second) {
      ++w.slots[a.index].exclusions;
      ++w.slots[b.index].exclusions;
    }
  } else if (w.excluded.erase(key) != 0) {
    --w.slots[a.index].exclusions;
    --w.slots[b.index].exclusions;
  }
  return std::nullopt;
}

// ---- accessors -------------------------------------------------------------------------

bool CollisionWorld::contains(ObjectHandle object) const {
  const detail::ReadScope reading(impl_->access);
  return impl_->find(object) != nullptr;
}

std::size_t CollisionWorld::size() const {
  const detail::ReadScope reading(impl_->access);
  return impl_->live;
}

std::vector<ObjectHandle> CollisionWorld::objects() const {
  const detail::ReadScope reading(impl_->access);
  std::vector<ObjectHandle> out;
  out.reserve(impl_->live);
  for (std::uint32_t i = 0; i < impl_->slots.size(); ++i)
    if (impl_->slots[i].alive) out.push_back(impl_->slots[i].handle(i));
  return out;
}

std::optional<ObjectDesc> CollisionWorld::object(ObjectHandle object) const {
  const detail::ReadScope reading(impl_->access);
  const ObjectSlot* s = impl_->find(object);
  if (s == nullptr) return std::nullopt;
  ObjectDesc d;
  d.geometry = s->geometry;
  d.pose = s->pose;
  d.kind = s->kind;
  d.filter = s->filter;
  d.sensor = s->sensor;
  d.ccd = s->ccd;
  d.user_data = s->user_data;
  if (s->parent != kNoSlot) {
    d.parent = impl_->slots[s->parent].handle(s->parent);
    d.local_pose = impl_->local_poses.at(object.index);
  }
  return d;
}

Transform CollisionWorld::pose(ObjectHandle object) const {
  const detail::ReadScope reading(impl_->access);
  const ObjectSlot* s = impl_->find(object);
  return s != nullptr ? s->pose : Transform::identity();
}

Aabb CollisionWorld::bounds(ObjectHandle object) const {
  const detail::ReadScope reading(impl_->access);
  const ObjectSlot* s = impl_->find(object);
  return s != nullptr ? s->box : Aabb{};
}

void CollisionWorld::set_listener(WorldListener* listener) {
  const detail::WriteScope writing(impl_->access);
  impl_->listener = listener;
}

std::optional<Error> CollisionWorld::set_object_listener(ObjectHandle object, WorldListener* listener) {
  const detail::WriteScope writing(impl_->access);
  if (impl_->find(object) == nullptr) return stale("object");
  if (listener == nullptr)
    impl_->object_listeners.erase(object.index);
  else
    impl_->object_listeners[object.index] = listener;
  return std::nullopt;
}

void CollisionWorld::set_pair_filter(PairFilterCallback* filter) {
  const detail::WriteScope writing(impl_->access);
  impl_->pair_filter = filter;
}

}  // namespace proxima
