/// @file world_snapshot.cpp
/// d2::CollisionWorld::save / load / state_hash: the 2D world's versioned binary snapshot.
///
/// Layout (world/snapshot_stream.hpp's encoding: little-endian integers, reals as doubles):
///   1. "PROXWR2D", version 1, the writer's sizeof(Real); the settings;
///   2. the slots: generation and flags (alive, moved, sensor), and for a live object its
///      shape (its kind, then its parameters; a polygon's vertices in its own order), pose,
///      previous pose, filter, kind, continuous mode and user data;
///   3. the free list, then the exclusions (sorted pair keys);
///   4. the touching and the sensing pairs of the last step: what the next step's
///      begin / persist / end and enter / exit are measured against;
///   5. the manifolds and the events of the last step (what manifolds() and events() give).
/// Loading checks each list's count against the rest of the stream before reading it element
/// by element, rebuilds each shape through its validated create (a polygon through
/// Polygon::restore, which keeps its vertex numbers and so the contacts' feature ids),
/// checks every index, handle and order, then derives the rest (extents, broad-phase
/// proxies). The snapshot is canonical, so state_hash() is the digest of its bytes.

#include <proxima/d2/collision_world.hpp>

#include <sstream>
#include <string>

#include "d2/world_state.hpp"
#include "world/snapshot_stream.hpp"

namespace proxima::d2 {
namespace {

constexpr char kMagic[] = "PROXWR2D";
constexpr std::uint32_t kVersion = 1;
// The fewest bytes of each list's element, to check its count against the stream's rest.
constexpr std::size_t kVecBytes = 16;       ///< two reals
constexpr std::size_t kSlotBytes = 5;       ///< a dead slot: generation, flags
constexpr std::size_t kPointBytes = 44;     ///< a manifold point: two points, depth, feature id
constexpr std::size_t kManifoldBytes = 45;  ///< a manifold with no point: pair, normal, method, parts, count
constexpr std::size_t kImpactBytes = 76;    ///< two handles, toi, point, normal, part, two user data

// ---- writing -----------------------------------------------------------------------------

/// The snapshot writer with the plane's vectors, poses and shapes.
class Writer : public SnapshotWriter {
 public:
  using SnapshotWriter::SnapshotWriter;
  void vec(const Vec2& v) {
    real(v.x);
    real(v.y);
  }
  void pose(const Pose& p) {
    vec(p.position);
    real(p.rotation.c);
    real(p.rotation.s);
  }
  void shape(const Shape& s) {
    u8(static_cast<std::uint8_t>(s.type()));
    std::visit([this](const auto& alternative) { parameters(alternative); }, s.variant());
  }

 private:
  void parameters(const Point& p) { vec(p.position()); }
  void parameters(const Circle& c) {
    real(c.radius());
    vec(c.center());
  }
  void parameters(const Segment& s) {
    vec(s.a());
    vec(s.b());
  }
  void parameters(const Capsule& c) {
    vec(c.a());
    vec(c.b());
    real(c.radius());
  }
  void parameters(const Polygon& p) {
    count(static_cast<std::size_t>(p.count()));
    for (int i = 0; i < p.count(); ++i) vec(p.vertex(i));
    real(p.radius());
  }
  void parameters(const Chain& c) {
    u8(c.loop() ? 1 : 0);
    count(c.points().size());
    for (const Vec2& p : c.points()) vec(p);
  }
};

void write_slot(Writer& w, const detail::Slot& s) {
  w.u32(s.generation);
  w.u8(static_cast<std::uint8_t>((s.alive ? 1 : 0) | (s.moved ? 2 : 0) | (s.alive && s.sensor ? 4 : 0)));
  if (!s.alive) return;
  w.shape(s.shape);
  w.pose(s.pose);
  w.pose(s.previous);
  w.u64(s.filter.layer);
  w.u64(s.filter.mask);
  w.u32(static_cast<std::uint32_t>(s.filter.group));
  w.u8(static_cast<std::uint8_t>(s.kind));
  w.u8(static_cast<std::uint8_t>(s.ccd));
  w.u64(s.user_data);
}

void write_manifolds(Writer& w, const std::vector<WorldManifold>& list) {
  w.count(list.size());
  for (const WorldManifold& m : list) {
    write_handle(w, m.pair.a);
    write_handle(w, m.pair.b);
    w.vec(m.manifold.normal);
    w.u8(static_cast<std::uint8_t>(m.manifold.method));
    w.u32(static_cast<std::uint32_t>(m.manifold.part_a));
    w.u32(static_cast<std::uint32_t>(m.manifold.part_b));
    w.count(static_cast<std::size_t>(m.manifold.count));
    for (int k = 0; k < m.manifold.count; ++k) {
      const ContactPoint& p = m.manifold.points[static_cast<std::size_t>(k)];
      w.vec(p.point_a);
      w.vec(p.point_b);
      w.real(p.depth);
      w.u32(p.feature_id);
    }
  }
}

void write_events(Writer& w, const StepEvents& ev) {
  write_contact_events(w, ev.begin);
  write_contact_events(w, ev.persist);
  write_contact_events(w, ev.end);
  write_sensor_events(w, ev.sensor_enter);
  write_sensor_events(w, ev.sensor_exit);
  w.count(ev.impacts.size());
  for (const ImpactEvent& e : ev.impacts) {
    write_handle(w, e.a);
    write_handle(w, e.b);
    w.real(e.toi);
    w.vec(e.point);
    w.vec(e.normal);
    w.u32(static_cast<std::uint32_t>(e.part_b));
    w.u64(e.user_data_a);
    w.u64(e.user_data_b);
  }
}

void write_world(Writer& w, const detail::WorldState& m) {
  write_snapshot_header(w, kMagic, kVersion);
  write_settings(w, m.settings);
  w.count(m.slots.size());
  for (const detail::Slot& s : m.slots) write_slot(w, s);
  w.count(m.free_slots.size());
  for (std::uint32_t f : m.free_slots) w.u32(f);
  w.count(m.excluded.size());
  for (std::uint64_t key : m.excluded) w.u64(key);
  write_contact_events(w, m.touching);
  write_sensor_events(w, m.sensing);
  write_manifolds(w, m.manifolds);
  write_events(w, m.events);
}

}  // namespace

std::optional<Error> CollisionWorld::save(std::ostream& out) const {
  Writer w(out);
  write_world(w, *state_);
  out.flush();
  if (!out) return Error{ErrorCode::InvalidArgument, "out", "the stream failed while the snapshot was written"};
  return std::nullopt;
}

std::uint64_t CollisionWorld::state_hash() const {
  std::ostringstream bytes(std::ios::binary);
  Writer w(bytes);
  write_world(w, *state_);
  const std::string text = bytes.str();
  StateDigest d;
  d.bytes(text.data(), text.size());
  return d.h;
}

// ---- reading -----------------------------------------------------------------------------

namespace {

/// The snapshot reader with the plane's vectors, poses and shapes.
class Reader : public SnapshotReader {
 public:
  using SnapshotReader::SnapshotReader;
  Vec2 vec() {
    const Real x = real();
    const Real y = real();
    return {x, y};
  }
  Pose pose() {
    Pose p;
    p.position = vec();
    p.rotation.c = real();
    p.rotation.s = real();
    return p;
  }
  /// A 0 / 1 byte; any other value fails naming `field`.
  bool flag(const std::string& field) {
    const std::uint8_t b = u8();
    if (b > 1) fail(field, "a flag that is neither 0 nor 1");
    return b == 1;
  }
  /// A shape rebuilt by its validated create; nothing (and a failure naming `field`) when it
  /// does not validate.
  std::optional<Shape> shape(const std::string& field) {
    const std::uint8_t tag = u8();
    switch (tag) {
      case std::uint8_t(ShapeType::Point): return made(Point::create(vec()), field);
      case std::uint8_t(ShapeType::Circle): {
        const Real r = real();
        return made(Circle::create(r, vec()), field);
      }
      case std::uint8_t(ShapeType::Segment): {
        const Vec2 a = vec();
        return made(Segment::create(a, vec()), field);
      }
      case std::uint8_t(ShapeType::Capsule): {
        const Vec2 a = vec(), b = vec();
        return made(Capsule::create(a, b, real()), field);
      }
      case std::uint8_t(ShapeType::Polygon): {
        const std::vector<Vec2> p = points();
        return made(Polygon::restore(p, real()), field);
      }
      case std::uint8_t(ShapeType::Chain): {
        const bool loop = flag(field);
        const std::vector<Vec2> p = points();
        return made(Chain::create(p, loop), field);
      }
      default: fail(field, "unknown shape kind " + std::to_string(tag)); return std::nullopt;
    }
  }

 private:
  std::vector<Vec2> points() {
    std::vector<Vec2> p;
    for (std::uint32_t n = count(kVecBytes), k = 0; k < n && ok(); ++k) p.push_back(vec());
    return p;
  }
  template <class S>
  std::optional<Shape> made(Result<S> r, const std::string& field) {
    if (!ok()) return std::nullopt;
    if (!r.ok()) {
      fail(field, "the saved shape does not validate: " + r.error().what());
      return std::nullopt;
    }
    return Shape(std::move(r).value());
  }
};

bool finite(const Vec2& v) { return is_finite(v); }
bool finite(Real x) { return std::isfinite(x); }

/// A live object's fields into `s`, each checked (field names the object).
void read_object(Reader& r, const std::string& field, detail::Slot& s) {
  std::optional<Shape> shape = r.shape(field + ".shape");
  s.pose = r.pose();
  s.previous = r.pose();
  s.filter.layer = r.u64();
  s.filter.mask = r.u64();
  s.filter.group = static_cast<std::int32_t>(r.u32());
  const std::uint8_t kind = r.u8(), ccd = r.u8();
  s.user_data = r.u64();
  if (!r.ok()) return;
  if (!detail::pose_ok(s.pose)) r.fail(field + ".pose", "must be finite with a unit rotation");
  if (!detail::pose_ok(s.previous)) r.fail(field + ".previous_pose", "must be finite with a unit rotation");
  if (kind > std::uint8_t(ObjectKind::Moving)) r.fail(field + ".kind", "unknown kind");
  if (ccd > std::uint8_t(CcdMode::Bullet)) r.fail(field + ".ccd", "unknown continuous-detection mode");
  s.kind = static_cast<ObjectKind>(kind);
  s.ccd = static_cast<CcdMode>(ccd);
  if (shape && !shape->is_convex() && s.kind != ObjectKind::Static)
    r.fail(field + ".kind", "a chain can only be a static object");
  if (shape) s.shape = std::move(*shape);
}

void read_slots(Reader& r, detail::WorldState& w) {
  for (std::uint32_t n = r.count(kSlotBytes), i = 0; i < n && r.ok(); ++i) {
    const std::string field = "snapshot.objects[" + std::to_string(i) + "]";
    detail::Slot s;
    s.generation = r.u32();
    const std::uint8_t flags = r.u8();
    const bool dead_sensor = (flags & 1) == 0 && (flags & 4) != 0;
    if (flags > 7 || dead_sensor) r.fail(field, "unknown slot flags");
    s.alive = (flags & 1) != 0;
    s.moved = (flags & 2) != 0;
    s.sensor = (flags & 4) != 0;
    if (s.alive) read_object(r, field, s);
    w.slots.push_back(std::move(s));
  }
}

/// The free list: exactly the dead slots, each once.
void read_free_slots(Reader& r, detail::WorldState& w) {
  std::vector<bool> listed(w.slots.size(), false);
  for (std::uint32_t n = r.count(sizeof(std::uint32_t)), k = 0; k < n && r.ok(); ++k) {
    const std::uint32_t f = r.u32();
    if (f >= w.slots.size() || w.slots[f].alive || listed[f]) {
      r.fail("snapshot.free_slots", "names a live, unknown or repeated slot");
      return;
    }
    listed[f] = true;
    w.free_slots.push_back(f);
  }
  if (r.ok() && w.free_slots.size() != w.slots.size() - w.live)
    r.fail("snapshot.free_slots", "does not list every free slot");
}

void read_exclusions(Reader& r, detail::WorldState& w) {
  const auto live = [&](std::uint32_t i) { return i < w.slots.size() && w.slots[i].alive; };
  for (std::uint32_t n = r.count(sizeof(std::uint64_t)), k = 0; k < n && r.ok(); ++k) {
    const std::uint64_t key = r.u64();
    const std::uint32_t lo = std::uint32_t(key >> 32), hi = std::uint32_t(key);
    if (lo >= hi || !live(lo) || !live(hi) || (!w.excluded.empty() && key <= *w.excluded.rbegin())) {
      r.fail("snapshot.exclusions", "pairs out of order or naming objects that are not live");
      return;
    }
    w.excluded.insert(key);
  }
}

/// A handle this world has given out: its slot exists and has reached its generation.
bool known(const detail::WorldState& w, ObjectHandle h) {
  return h.index < w.slots.size() && h.generation <= w.slots[h.index].generation;
}

void check_contact_events(Reader& r, const detail::WorldState& w, const std::vector<ContactEvent>& list,
                          const std::string& field) {
  for (std::size_t k = 0; k < list.size() && r.ok(); ++k) {
    const ObjectPair p = list[k].pair;
    if (!known(w, p.a) || !known(w, p.b) || !(p.a < p.b) || (k > 0 && !(list[k - 1].pair < p)))
      r.fail(field, "pairs out of order or naming unknown objects");
  }
}

void check_sensor_events(Reader& r, const detail::WorldState& w, const std::vector<SensorEvent>& list,
                         const std::string& field) {
  const auto key = [](const SensorEvent& e) { return std::pair(e.sensor, e.other); };
  for (std::size_t k = 0; k < list.size() && r.ok(); ++k) {
    const SensorEvent& e = list[k];
    if (!known(w, e.sensor) || !known(w, e.other) || e.sensor.index == e.other.index ||
        (k > 0 && !(key(list[k - 1]) < key(e))))
      r.fail(field, "pairs out of order or naming unknown objects");
  }
}

void read_manifold(Reader& r, const detail::WorldState& w, WorldManifold& m) {
  m.pair.a = read_handle(r);
  m.pair.b = read_handle(r);
  Manifold& f = m.manifold;
  f.normal = r.vec();
  const std::uint8_t method = r.u8();
  f.method = static_cast<PairMethod>(method);
  f.part_a = static_cast<PartIndex>(r.u32());
  f.part_b = static_cast<PartIndex>(r.u32());
  f.count = static_cast<int>(r.count(kPointBytes));
  bool good = method <= std::uint8_t(PairMethod::ClosestPoint) && f.count >= 1 && f.count <= kMaxManifoldPoints &&
              f.part_a >= -1 && f.part_b >= -1 && finite(f.normal) && known(w, m.pair.a) && known(w, m.pair.b) &&
              m.pair.a < m.pair.b;
  for (int k = 0; k < f.count && k < kMaxManifoldPoints && r.ok(); ++k) {
    ContactPoint& p = f.points[static_cast<std::size_t>(k)];
    p.point_a = r.vec();
    p.point_b = r.vec();
    p.depth = r.real();
    p.feature_id = r.u32();
    good = good && finite(p.point_a) && finite(p.point_b) && finite(p.depth);
  }
  if (r.ok() && !good) r.fail("snapshot.manifolds", "a manifold that is not a contact of two known objects");
}

void read_manifolds(Reader& r, detail::WorldState& w) {
  for (std::uint32_t n = r.count(kManifoldBytes), k = 0; k < n && r.ok(); ++k) {
    WorldManifold m;
    read_manifold(r, w, m);
    if (r.ok() && !w.manifolds.empty() && m.pair < w.manifolds.back().pair)
      r.fail("snapshot.manifolds", "manifolds out of order");
    w.manifolds.push_back(m);
  }
}

void read_impacts(Reader& r, const detail::WorldState& w, std::vector<ImpactEvent>& list) {
  for (std::uint32_t n = r.count(kImpactBytes), k = 0; k < n && r.ok(); ++k) {
    ImpactEvent e;
    e.a = read_handle(r);
    e.b = read_handle(r);
    e.toi = r.real();
    e.point = r.vec();
    e.normal = r.vec();
    e.part_b = static_cast<PartIndex>(r.u32());
    e.user_data_a = r.u64();
    e.user_data_b = r.u64();
    if (r.ok() && (!known(w, e.a) || !known(w, e.b) || !(e.toi >= Real(0) && e.toi <= Real(1)) || !finite(e.point) ||
                   !finite(e.normal) || e.part_b < -1))
      r.fail("snapshot.events.impacts", "an impact that is not in the step or names unknown objects");
    list.push_back(e);
  }
}

void read_events(Reader& r, detail::WorldState& w) {
  StepEvents& ev = w.events;
  read_contact_events(r, ev.begin);
  read_contact_events(r, ev.persist);
  read_contact_events(r, ev.end);
  read_sensor_events(r, ev.sensor_enter);
  read_sensor_events(r, ev.sensor_exit);
  check_contact_events(r, w, ev.begin, "snapshot.events.begin");
  check_contact_events(r, w, ev.persist, "snapshot.events.persist");
  check_contact_events(r, w, ev.end, "snapshot.events.end");
  check_sensor_events(r, w, ev.sensor_enter, "snapshot.events.sensor_enter");
  check_sensor_events(r, w, ev.sensor_exit, "snapshot.events.sensor_exit");
  read_impacts(r, w, ev.impacts);
}

/// Everything after the settings, into `w`.
void read_state(Reader& r, detail::WorldState& w) {
  read_slots(r, w);
  for (const detail::Slot& s : w.slots) w.live += s.alive ? 1 : 0;
  read_free_slots(r, w);
  read_exclusions(r, w);
  read_contact_events(r, w.touching);
  check_contact_events(r, w, w.touching, "snapshot.touching");
  read_sensor_events(r, w.sensing);
  check_sensor_events(r, w, w.sensing, "snapshot.sensing");
  read_manifolds(r, w);
  read_events(r, w);
}

}  // namespace

Result<CollisionWorld> CollisionWorld::load(std::istream& in) {
  Reader r(in);
  Result<CollisionWorld> created = create_from_snapshot<CollisionWorld>(r, kMagic, kVersion);
  if (!created.ok()) return created.error();
  CollisionWorld world = std::move(created).value();
  detail::WorldState& w = *world.state_;
  read_state(r, w);
  if (!r.ok()) return *r.error();
  for (std::uint32_t i = 0; i < w.slots.size(); ++i) {
    detail::Slot& s = w.slots[i];
    if (!s.alive) continue;
    detail::measure(s);
    w.broadphase->insert(i, w.proxy_box(s.shape, s.pose), detail::proxy_kind(s.kind));
  }
  return world;
}

}  // namespace proxima::d2
