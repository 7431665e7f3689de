// CollisionWorld::save / load: the versioned binary snapshot of a whole world.
//
// Layout (world/snapshot_stream.hpp's encoding, shared with the 2D world's snapshot:
// little-endian integers; every real written as an IEEE double, exact for float):
//   "PROXWRLD", version (u32 = 1), sizeof(Real) of the writer (u8);
//   settings; step count; slots (generation, liveness, and for a live object its geometry,
//   poses, filter, user data, kind, modes, attachment links and flags); free list; moved
//   list; exclusions (sorted); the pair table (keys, generations, user data, cache, manifold
//   index, next point id, flags); the manifolds; the last step's events.
// Geometry: a tag per shape kind and its parameters; hulls and meshes shared by several
//   objects (or compound children) are written once and referred to by number afterwards, so
//   a loaded world shares them as the saved one did. A hull is rebuilt from its vertices
//   (qhull may order them differently), so the caches' support hints of top-level hulls
//   are mapped from the saved vertex order to the rebuilt one.
// A compound is rebuilt by Compound::create, which normalises its children's rotations again:
//   each saved rotation is replaced by a nearby quaternion that this normalisation maps
//   exactly onto it, so the rebuilt compound equals the saved one bit for bit.
// Loading checks every count against what the stream holds, every index against the slot
// table, the attachment links (parents alive, no cycle, roots consistent), and rebuilds
// the derived state (boxes, measures, broad-phase proxies) from what it read.
#include <proxima/core/validate.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <cmath>
#include <istream>
#include <limits>
#include <map>
#include <ostream>
#include <unordered_map>

#include "world/snapshot_stream.hpp"
#include "world/world_state.hpp"

namespace proxima {

namespace {

using Impl = CollisionWorld::Impl;
constexpr char kMagic[] = "PROXWRLD";
constexpr std::uint32_t kVersion = 1;

// ---- writing -----------------------------------------------------------------------------

class Writer : public SnapshotWriter, public RealSequence<Writer> {
 public:
  explicit Writer(std::ostream& out) : SnapshotWriter(out) {}

  /// A geometry; hulls and meshes already written are referred to by number.
  void geometry(const Shape& g) {
    u8(static_cast<std::uint8_t>(g.index()));
    std::visit([this](const auto& s) { shape(s); }, g);
  }

 private:
  void shape(const Point&) {}
  void shape(const Segment& s) {
    vec(s.a());
    vec(s.b());
  }
  void shape(const Triangle& t) {
    for (int k = 0; k < 3; ++k) vec(t.vertex(k));
  }
  void shape(const Sphere& s) { real(s.radius()); }
  void shape(const Capsule& s) {
    real(s.radius());
    real(s.half_length());
  }
  void shape(const Box& s) { vec(s.half_extents()); }
  void shape(const Cylinder& s) {
    real(s.radius());
    real(s.half_length());
  }
  void shape(const Cone& s) {
    real(s.radius());
    real(s.half_length());
  }
  void shape(const Ellipsoid& s) { vec(s.radii()); }
  void shape(const HalfSpace& s) {
    vec(s.normal());
    real(s.offset());
  }
  void shape(const ConvexHull& h) {
    if (shared(h.vertices().data())) return;
    u32(static_cast<std::uint32_t>(h.vertices().size()));
    for (const Vec3& v : h.vertices()) vec(v);
  }
  void shape(const TriangleMesh& m) {
    if (shared(m.vertices().data())) return;
    u32(static_cast<std::uint32_t>(m.vertices().size()));
    for (const Vec3& v : m.vertices()) vec(v);
    u32(m.triangle_count());
    for (const TriangleIndices& t : m.triangles())
      for (std::uint32_t i : t) u32(i);
  }
  void shape(const Compound& c) {
    u32(static_cast<std::uint32_t>(c.children().size()));
    for (const CompoundChild& child : c.children()) {
      geometry(child.shape);
      pose(child.pose);
    }
  }
  /// Writes the reference number of already-written shared data (true), or marks it new.
  bool shared(const void* data) {
    const auto [it, fresh] = written_.emplace(data, static_cast<std::uint32_t>(written_.size()));
    u32(fresh ? kNoSlot : it->second);
    return !fresh;
  }

  std::unordered_map<const void*, std::uint32_t> written_;
};

void write_cache(Writer& w, const PairCache& c) {
  w.vec(c.axis);
  w.u32(c.support_hint_a);
  w.u32(c.support_hint_b);
  w.u32(c.sat_feature);
  w.u32(c.part_a);
  w.u32(c.part_b);
  w.u8(c.valid ? 1 : 0);
}

void write_contact_point(Writer& w, const ContactPoint& c) {
  w.vec(c.point_a);
  w.vec(c.point_b);
  w.vec(c.normal);
  w.real(c.depth);
  w.u32(c.feature_id);
  w.u32(c.sub_a.child);
  w.u32(c.sub_a.triangle);
  w.u32(c.sub_b.child);
  w.u32(c.sub_b.triangle);
}

void write_events(Writer& w, const StepEvents& ev) {
  for (const auto* list : {&ev.begin, &ev.persist, &ev.end}) write_contact_events(w, *list);
  for (const auto* list : {&ev.sensor_enter, &ev.sensor_exit}) write_sensor_events(w, *list);
  w.u32(static_cast<std::uint32_t>(ev.impacts.size()));
  for (const ImpactEvent& e : ev.impacts) {
    write_handle(w, e.a);
    write_handle(w, e.b);
    w.real(e.toi);
    w.vec(e.point);
    w.vec(e.normal);
    w.u32(e.sub_a.child);
    w.u32(e.sub_a.triangle);
    w.u32(e.sub_b.child);
    w.u32(e.sub_b.triangle);
    w.u64(e.user_data_a);
    w.u64(e.user_data_b);
  }
}

}  // namespace

std::optional<Error> CollisionWorld::save(std::ostream& out) const {
  const detail::ReadScope reading(impl_->access);
  const Impl& m = *impl_;
  Writer w(out);
  write_snapshot_header(w, kMagic, kVersion);
  write_settings(w, m.settings);
  w.u64(m.steps);
  w.u32(static_cast<std::uint32_t>(m.slots.size()));
  for (std::uint32_t i = 0; i < m.slots.size(); ++i) {
    const ObjectSlot& o = m.slots[i];
    w.u32(o.generation);
    w.u8(o.alive ? 1 : 0);
    if (!o.alive) continue;
    w.geometry(o.geometry);
    w.pose(o.pose);
    w.pose(o.step_pose);
    w.u64(o.filter.layer);
    w.u64(o.filter.mask);
    w.u32(static_cast<std::uint32_t>(o.filter.group));
    w.u64(o.user_data);
    for (std::uint32_t link : {o.parent, o.first_child, o.next_sibling, o.root}) w.u32(link);
    if (o.parent != kNoSlot) w.pose(m.local_poses.at(i));
    w.u8(static_cast<std::uint8_t>(o.kind));
    w.u8(static_cast<std::uint8_t>(o.ccd));
    w.u8(static_cast<std::uint8_t>((o.sensor ? 1 : 0) | (o.moved ? 2 : 0) | (o.geometry_changed ? 4 : 0)));
  }
  w.u32(static_cast<std::uint32_t>(m.free_slots.size()));
  for (std::uint32_t f : m.free_slots) w.u32(f);
  w.u32(static_cast<std::uint32_t>(m.moved.size()));
  for (std::uint32_t i : m.moved) w.u32(i);
  std::vector<std::uint64_t> excluded(m.excluded.begin(), m.excluded.end());
  std::sort(excluded.begin(), excluded.end());
  w.u32(static_cast<std::uint32_t>(excluded.size()));
  for (std::uint64_t k : excluded) w.u64(k);
  w.u32(static_cast<std::uint32_t>(m.pairs.size()));
  for (const PairState& p : m.pairs) {
    w.u32(p.lo);
    w.u32(p.hi);
    w.u32(p.gen_lo);
    w.u32(p.gen_hi);
    w.u64(p.user_lo);
    w.u64(p.user_hi);
    write_cache(w, p.cache);
    w.u32(static_cast<std::uint32_t>(p.contact));
    w.u32(p.next_point_id);
    w.u8(p.sensor);
    w.u8(static_cast<std::uint8_t>((p.touching ? 1 : 0) | (p.was_touching ? 2 : 0)));
  }
  w.u32(static_cast<std::uint32_t>(m.contacts.size()));
  for (const WorldManifold& c : m.contacts) {
    write_handle(w, c.pair.a);
    write_handle(w, c.pair.b);
    w.vec(c.normal);
    w.u32(static_cast<std::uint32_t>(c.count));
    for (int k = 0; k < c.count; ++k) {
      write_contact_point(w, c.points[k].contact);
      w.u32(c.points[k].id);
      w.u8(c.points[k].persisted ? 1 : 0);
      w.real(c.points[k].user[0]);
      w.real(c.points[k].user[1]);
    }
  }
  write_events(w, m.events);
  out.flush();
  if (!out) return make_error(ErrorCode::InvalidArgument, "out", "the stream failed while the snapshot was written");
  return std::nullopt;
}

// ---- reading -----------------------------------------------------------------------------

namespace {

/// The snapshot reader with 3D vectors, poses and geometry.
class Reader : public SnapshotReader {
 public:
  using SnapshotReader::SnapshotReader;

  Vec3 vec() {
    const Real x = real(), y = real(), z = real();
    return {x, y, z};
  }
  Transform pose() {
    Transform t;
    t.position = vec();
    const Real w = real(), x = real(), y = real(), z = real();
    t.rotation = Quat(w, x, y, z);
    return t;
  }
  /// A geometry (field names the object for errors); `hull_ref` gets the shared-hull number
  /// of a top-level hull (kNoSlot otherwise).
  Shape geometry(const std::string& field, std::uint32_t& hull_ref, int depth = 0) {
    hull_ref = kNoSlot;
    const std::uint8_t tag = u8();
    if (!ok()) return *Point::create();
    if (tag >= kShapeTypeCount || depth > 32) {
      fail(field, "unknown geometry tag or compound nesting deeper than 32");
      return *Point::create();
    }
    switch (static_cast<ShapeType>(tag)) {
      case ShapeType::Point: return *Point::create();
      case ShapeType::Segment: {
        const Vec3 a = vec(), b = vec();
        return made(Segment::create(a, b), field);
      }
      case ShapeType::Triangle: {
        const Vec3 a = vec(), b = vec(), c = vec();
        return made(Triangle::create(a, b, c), field);
      }
      case ShapeType::Sphere: return made(Sphere::create(real()), field);
      case ShapeType::Capsule: {
        const Real r = real(), h = real();
        return made(Capsule::create(r, h), field);
      }
      case ShapeType::Box: return made(Box::create(vec()), field);
      case ShapeType::Cylinder: {
        const Real r = real(), h = real();
        return made(Cylinder::create(r, h), field);
      }
      case ShapeType::Cone: {
        const Real r = real(), h = real();
        return made(Cone::create(r, h), field);
      }
      case ShapeType::Ellipsoid: return made(Ellipsoid::create(vec()), field);
      case ShapeType::HalfSpace: {
        const Vec3 n = vec();
        return made(HalfSpace::create(n, real()), field);
      }
      case ShapeType::ConvexHull: return hull(field, hull_ref);
      case ShapeType::TriangleMesh: return mesh(field);
      case ShapeType::Compound: return compound(field, depth);
      case ShapeType::Count: break;
    }
    return *Point::create();
  }

  /// For the shared hull `ref`: the rebuilt hull's index of each saved vertex.
  const std::vector<std::uint32_t>& hull_order(std::uint32_t ref) const { return hull_order_.at(ref); }

 private:
  template <class S>
  Shape made(Result<S> r, const std::string& field) {
    if (!ok()) return *Point::create();
    if (!r.ok()) {
      fail(field, "the saved geometry does not validate: " + r.error().what());
      return *Point::create();
    }
    return *r;
  }

  /// A reference to shared data already read, or kNoSlot for new data.
  std::uint32_t reference(const std::string& field) {
    const std::uint32_t ref = u32();
    if (ok() && ref != kNoSlot && ref >= shared_.size()) fail(field, "refers to shared geometry not yet read");
    return ref;
  }

  Shape hull(const std::string& field, std::uint32_t& hull_ref) {
    const std::uint32_t ref = reference(field);
    if (!ok()) return *Point::create();
    if (ref != kNoSlot) {
      if (!std::holds_alternative<ConvexHull>(shared_[ref])) fail(field, "refers to shared geometry of another kind");
      hull_ref = ref;
      return shared_[ref];
    }
    std::vector<Vec3> points;
    for (std::uint32_t n = count(), k = 0; k < n && ok(); ++k) points.push_back(vec());
    Shape s = made(ConvexHull::create(points), field);
    if (!ok()) return s;
    const ConvexHull& h = std::get<ConvexHull>(s);
    std::map<std::array<Real, 3>, std::uint32_t> index;
    for (std::uint32_t k = 0; k < h.vertices().size(); ++k)
      index.emplace(std::array<Real, 3>{h.vertices()[k].x, h.vertices()[k].y, h.vertices()[k].z}, k);
    std::vector<std::uint32_t> order;
    for (const Vec3& p : points) {
      const auto it = index.find({p.x, p.y, p.z});
      order.push_back(it == index.end() ? 0u : it->second);
    }
    hull_ref = static_cast<std::uint32_t>(shared_.size());
    hull_order_[hull_ref] = std::move(order);
    shared_.push_back(s);
    return s;
  }

  Shape mesh(const std::string& field) {
    const std::uint32_t ref = reference(field);
    if (!ok()) return *Point::create();
    if (ref != kNoSlot) {
      if (!std::holds_alternative<TriangleMesh>(shared_[ref])) fail(field, "refers to shared geometry of another kind");
      return shared_[ref];
    }
    IndexedMesh m;
    for (std::uint32_t n = count(), k = 0; k < n && ok(); ++k) m.vertices.push_back(vec());
    for (std::uint32_t n = count(), k = 0; k < n && ok(); ++k) {
      const std::uint32_t a = u32(), b = u32(), c = u32();
      m.triangles.push_back({a, b, c});
    }
    Shape s = made(TriangleMesh::create(std::move(m)), field);
    shared_.push_back(s);
    return s;
  }

  Shape compound(const std::string& field, int depth) {
    std::vector<CompoundChild> children;
    for (std::uint32_t n = count(), k = 0; k < n && ok(); ++k) {
      std::uint32_t ignored;
      Shape child = geometry(field, ignored, depth + 1);
      Transform pose_saved = pose();
      pose_saved.rotation = normalisation_preimage(pose_saved.rotation);
      children.push_back({std::move(child), pose_saved});
    }
    return made(Compound::create(std::move(children)), field);
  }

  /// A quaternion that Compound::create's normalisation maps exactly onto the saved (already
  /// normalised) rotation `saved`: `saved` itself when normalising it changes nothing, else
  /// the first of its neighbours within two units in the last place per component that does;
  /// `saved` when none does (the rebuilt child then differs in the last bits).
  static Quat normalisation_preimage(const Quat& saved) {
    auto maps_onto = [&](const Quat& q) {
      const Quat n = glm::normalize(q);
      return n.w == saved.w && n.x == saved.x && n.y == saved.y && n.z == saved.z;
    };
    if (!std::isfinite(glm::dot(saved, saved)) || maps_onto(saved)) return saved;
    auto step = [](Real x, int k) {
      for (; k > 0; --k) x = std::nextafter(x, std::numeric_limits<Real>::infinity());
      for (; k < 0; ++k) x = std::nextafter(x, -std::numeric_limits<Real>::infinity());
      return x;
    };
    for (int a = -2; a <= 2; ++a)
      for (int b = -2; b <= 2; ++b)
        for (int c = -2; c <= 2; ++c)
          for (int d = -2; d <= 2; ++d) {
            const Quat q(step(saved.w, a), step(saved.x, b), step(saved.y, c), step(saved.z, d));
            if (maps_onto(q)) return q;
          }
    return saved;
  }

  std::vector<Shape> shared_;
  std::map<std::uint32_t, std::vector<std::uint32_t>> hull_order_;
};

PairCache read_cache(Reader& r) {
  PairCache c;
  c.axis = r.vec();
  c.support_hint_a = r.u32();
  c.support_hint_b = r.u32();
  c.sat_feature = r.u32();
  c.part_a = r.u32();
  c.part_b = r.u32();
  c.valid = r.u8() != 0;
  return c;
}

ContactPoint read_contact_point(Reader& r) {
  ContactPoint c;
  c.point_a = r.vec();
  c.point_b = r.vec();
  c.normal = r.vec();
  c.depth = r.real();
  c.feature_id = r.u32();
  c.sub_a.child = r.u32();
  c.sub_a.triangle = r.u32();
  c.sub_b.child = r.u32();
  c.sub_b.triangle = r.u32();
  return c;
}

void read_events(Reader& r, StepEvents& ev) {
  for (auto* list : {&ev.begin, &ev.persist, &ev.end}) read_contact_events(r, *list);
  for (auto* list : {&ev.sensor_enter, &ev.sensor_exit}) read_sensor_events(r, *list);
  for (std::uint32_t n = r.count(), k = 0; k < n && r.ok(); ++k) {
    ImpactEvent e;
    e.a = read_handle(r);
    e.b = read_handle(r);
    e.toi = r.real();
    e.point = r.vec();
    e.normal = r.vec();
    e.sub_a.child = r.u32();
    e.sub_a.triangle = r.u32();
    e.sub_b.child = r.u32();
    e.sub_b.triangle = r.u32();
    e.user_data_a = r.u64();
    e.user_data_b = r.u64();
    ev.impacts.push_back(e);
  }
}

/// The attachment links of the live objects: parents alive, children lists naming exactly
/// the objects whose parent they are, no cycle, each root the top of its chain.
bool links_consistent(const Impl& m) {
  const std::uint32_t n = static_cast<std::uint32_t>(m.slots.size());
  auto live = [&](std::uint32_t i) { return i < n && m.slots[i].alive; };
  std::vector<std::uint32_t> seen_as_child(n, 0);
  for (std::uint32_t i = 0; i < n; ++i) {
    const ObjectSlot& s = m.slots[i];
    if (!s.alive) continue;
    if (s.parent != kNoSlot && !live(s.parent)) return false;
    std::uint32_t top = i;
    for (std::uint32_t steps = 0; m.slots[top].parent != kNoSlot; ++steps) {
      if (steps > n) return false;  // a cycle
      top = m.slots[top].parent;
    }
    if (s.root != top) return false;
    std::uint32_t children = 0;
    for (std::uint32_t c = s.first_child; c != kNoSlot; c = m.slots[c].next_sibling) {
      if (!live(c) || m.slots[c].parent != i || ++children > n) return false;
      ++seen_as_child[c];
    }
  }
  for (std::uint32_t i = 0; i < n; ++i)
    if (live(i) && (m.slots[i].parent != kNoSlot) != (seen_as_child[i] == 1)) return false;
  return true;
}

}  // namespace

Result<CollisionWorld> CollisionWorld::load(std::istream& in) {
  Reader r(in);
  Result<CollisionWorld> created = create_from_snapshot<CollisionWorld>(r, kMagic, kVersion);
  if (!created.ok()) return created.error();
  CollisionWorld world = std::move(created).value();
  Impl& m = *world.impl_;
  m.steps = r.u64();

  std::vector<std::uint32_t> hull_refs;
  for (std::uint32_t n = r.count(), i = 0; i < n && r.ok(); ++i) {
    ObjectSlot s;
    s.generation = r.u32();
    s.alive = r.u8() != 0;
    hull_refs.push_back(kNoSlot);
    if (s.alive) {
      const std::string field = "snapshot.objects[" + std::to_string(i) + "]";
      s.geometry = r.geometry(field + ".geometry", hull_refs.back());
      s.pose = r.pose();
      s.step_pose = r.pose();
      s.filter.layer = r.u64();
      s.filter.mask = r.u64();
      s.filter.group = static_cast<std::int32_t>(r.u32());
      s.user_data = r.u64();
      s.parent = r.u32();
      s.first_child = r.u32();
      s.next_sibling = r.u32();
      s.root = r.u32();
      if (s.parent != kNoSlot) m.local_poses[i] = r.pose();
      const std::uint8_t kind = r.u8(), ccd = r.u8(), bits = r.u8();
      if (kind > 1 || ccd > 2) r.fail(field, "unknown kind or continuous-detection mode");
      s.kind = static_cast<ObjectKind>(kind);
      s.ccd = static_cast<CcdMode>(ccd);
      s.sensor = (bits & 1) != 0;
      s.moved = (bits & 2) != 0;
      s.geometry_changed = (bits & 4) != 0;
      const bool poses_ok = validate::is_acceptable(s.pose.position) && validate::is_unit(s.pose.rotation) &&
                            validate::is_acceptable(s.step_pose.position) && validate::is_unit(s.step_pose.rotation);
      if (r.ok() && (!poses_ok || s.filter.layer == 0 || s.filter.mask == 0))
        r.fail(field, "a pose that is not finite and unit, or a filter with no bits");
      if (r.ok() && std::holds_alternative<HalfSpace>(s.geometry) &&
          (s.kind != ObjectKind::Static || s.parent != kNoSlot))
        r.fail(field, "a half-space that is not a static, unattached object");
      ++m.live;
    }
    m.slots.push_back(std::move(s));
  }
  const std::uint32_t slot_count = static_cast<std::uint32_t>(m.slots.size());
  auto live = [&](std::uint32_t i) { return i < slot_count && m.slots[i].alive; };
  for (std::uint32_t n = r.count(), k = 0; k < n && r.ok(); ++k) {
    const std::uint32_t f = r.u32();
    if (f >= slot_count || m.slots[f].alive) r.fail("snapshot.free_slots", "names a live or unknown slot");
    m.free_slots.push_back(f);
  }
  for (std::uint32_t n = r.count(), k = 0; k < n && r.ok(); ++k) {
    const std::uint32_t i = r.u32();
    if (!live(i) || !m.slots[i].moved) r.fail("snapshot.moved", "names an object that is not marked moved");
    m.moved.push_back(i);
  }
  for (std::uint32_t n = r.count(), k = 0; k < n && r.ok(); ++k) {
    const std::uint64_t key = r.u64();
    const std::uint32_t a = std::uint32_t(key >> 32), b = std::uint32_t(key);
    if (!live(a) || !live(b) || a >= b) r.fail("snapshot.exclusions", "names objects that are not live");
    if (!r.ok()) break;
    m.excluded.insert(key);
    ++m.slots[a].exclusions;
    ++m.slots[b].exclusions;
  }
  for (std::uint32_t n = r.count(), k = 0; k < n && r.ok(); ++k) {
    PairState p;
    p.lo = r.u32();
    p.hi = r.u32();
    p.gen_lo = r.u32();
    p.gen_hi = r.u32();
    p.user_lo = r.u64();
    p.user_hi = r.u64();
    p.cache = read_cache(r);
    p.contact = static_cast<std::int32_t>(r.u32());
    p.next_point_id = r.u32();
    p.sensor = r.u8();
    const std::uint8_t bits = r.u8();
    p.touching = (bits & 1) != 0;
    p.was_touching = (bits & 2) != 0;
    if (p.lo >= p.hi || p.hi >= slot_count || p.sensor > 3 || (!m.pairs.empty() && m.pairs.back().key() >= p.key()))
      r.fail("snapshot.pairs", "pairs out of order or naming unknown slots");
    m.pairs.push_back(p);
  }
  for (std::uint32_t n = r.count(), k = 0; k < n && r.ok(); ++k) {
    WorldManifold c;
    c.pair.a = read_handle(r);
    c.pair.b = read_handle(r);
    c.normal = r.vec();
    c.count = static_cast<int>(r.u32());
    if (c.count < 0 || c.count > kMaxContactPoints) {
      r.fail("snapshot.contacts", "a manifold with more than four points");
      break;
    }
    for (int j = 0; j < c.count; ++j) {
      c.points[j].contact = read_contact_point(r);
      c.points[j].id = r.u32();
      c.points[j].persisted = r.u8() != 0;
      c.points[j].user[0] = r.real();
      c.points[j].user[1] = r.real();
    }
    m.contacts.push_back(c);
  }
  for (const PairState& p : m.pairs)
    if (p.contact != -1 && (p.contact < 0 || std::size_t(p.contact) >= m.contacts.size()))
      r.fail("snapshot.pairs", "a pair names a manifold that is not there");
  read_events(r, m.events);
  if (!r.ok()) return *r.error();
  if (!links_consistent(m)) return make_error(ErrorCode::InvalidArgument, "snapshot", "inconsistent attachment links");

  // Derived state: measures, boxes, proxies; hull support hints in the rebuilt vertex order.
  for (std::uint32_t i = 0; i < slot_count; ++i) {
    if (!m.slots[i].alive) continue;
    measure_geometry(m.slots[i]);
    m.refresh_box(i);
  }
  for (std::uint32_t i = 0; i < slot_count; ++i)
    if (m.slots[i].alive && m.slots[i].parent == kNoSlot) m.reinsert_proxy(i);
  auto remap = [&](std::uint32_t slot, std::uint32_t& hint) {
    if (hull_refs[slot] == kNoSlot) return;
    const std::vector<std::uint32_t>& order = r.hull_order(hull_refs[slot]);
    if (hint < order.size()) hint = order[hint];
  };
  for (PairState& p : m.pairs) {
    remap(p.lo, p.cache.support_hint_a);
    remap(p.hi, p.cache.support_hint_b);
  }
  return world;
}

}  // namespace proxima
