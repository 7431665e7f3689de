// CollisionWorld::state_hash: a 64-bit digest of everything that decides the world's future
// answers, for determinism tests and bug reports.
//
// Steps: the step count, then per slot in index order (free slots too: their generations
// decide future handles) the generation, liveness, kind, modes, filter, user data, parent,
// local pose, pose, step pose and the geometry (its type, local box and vertex count);
// the free list; the exclusions in sorted order; then every pair of the pair table with its
// touching flag and cache (a hull's cached support vertex by its position), and every contact manifold point by point.
// Each value is folded in by StateDigest (world/snapshot_stream.hpp): splitmix64 over its
// bytes, 8 at a time.
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>

#include "world/snapshot_stream.hpp"
#include "world/world_state.hpp"

namespace proxima {

namespace {

/// Running digest with the world's vectors and poses.
struct Digest : StateDigest, RealSequence<Digest> {};

std::uint64_t vertex_count(const Shape& g) {
  if (const auto* h = std::get_if<ConvexHull>(&g)) return h->vertices().size();
  if (const auto* m = std::get_if<TriangleMesh>(&g)) return m->vertices().size() * 1000003ull + m->triangle_count();
  if (const auto* c = std::get_if<Compound>(&g)) return c->children().size();
  return 0;
}

/// A cached support vertex: for a hull, the vertex itself (a hull rebuilt from a snapshot
/// may number its vertices differently), else the hint as stored.
void support_hint(Digest& d, const Shape& g, std::uint32_t hint) {
  const auto* h = std::get_if<ConvexHull>(&g);
  if (h != nullptr && hint < h->vertices().size())
    d.vec(h->vertices()[hint]);
  else
    d.word(hint);
}

}  // namespace

std::uint64_t CollisionWorld::state_hash() const {
  const detail::ReadScope reading(impl_->access);
  const Impl& w = *impl_;
  Digest d;
  d.word(w.steps);
  d.word(w.slots.size());
  for (std::uint32_t i = 0; i < w.slots.size(); ++i) {
    const ObjectSlot& s = w.slots[i];
    d.word(s.generation);
    d.word(s.alive ? 1 : 0);
    if (!s.alive) continue;
    d.word((std::uint64_t(s.kind) << 16) | (std::uint64_t(s.ccd) << 8) | (s.sensor ? 1u : 0u));
    d.word(s.filter.layer);
    d.word(s.filter.mask);
    d.word(static_cast<std::uint32_t>(s.filter.group));
    d.word(s.user_data);
    d.word(s.parent);
    if (s.parent != ObjectHandle::kNoObject) d.pose(w.local_poses.at(i));
    d.pose(s.pose);
    d.pose(s.step_pose);
    d.word(s.geometry.index());
    const Aabb local = world_aabb(s.geometry, Transform::identity());
    d.vec(local.min);
    d.vec(local.max);
    d.word(vertex_count(s.geometry));
  }
  for (std::uint32_t f : w.free_slots) d.word(f);
  std::vector<std::uint64_t> excluded(w.excluded.begin(), w.excluded.end());
  std::sort(excluded.begin(), excluded.end());
  for (std::uint64_t k : excluded) d.word(k);
  for (const PairState& p : w.pairs) {
    d.word(p.key());
    d.word((std::uint64_t(p.gen_lo) << 32) | p.gen_hi);
    d.word((std::uint64_t(p.touching) << 8) | p.sensor);
    d.word(p.next_point_id);
    d.vec(p.cache.axis);
    support_hint(d, w.slots[p.lo].geometry, p.cache.support_hint_a);
    support_hint(d, w.slots[p.hi].geometry, p.cache.support_hint_b);
    d.word((std::uint64_t(p.cache.part_a) << 32) | p.cache.part_b);
    d.word((std::uint64_t(p.cache.sat_feature) << 1) | (p.cache.valid ? 1u : 0u));
  }
  for (const WorldManifold& m : w.contacts) {
    d.word(m.pair.a.to_integer());
    d.word(m.pair.b.to_integer());
    d.vec(m.normal);
    for (int k = 0; k < m.count; ++k) {
      const WorldContactPoint& p = m.points[k];
      d.word((std::uint64_t(p.id) << 32) | p.contact.feature_id);
      d.vec(p.contact.point_a);
      d.vec(p.contact.point_b);
      d.real(p.contact.depth);
      d.real(p.user[0]);
      d.real(p.user[1]);
    }
  }
  return d.h;
}

}  // namespace proxima
