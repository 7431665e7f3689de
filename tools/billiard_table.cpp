// The billiard break of `proxima demo` as a game loop on the collision world.
//
// Steps of a world step of duration h (BilliardTable::substep; a frame is `substeps` of them):
//  1. rolling resistance: every ball's speed drops by a constant deceleration times h;
//  2. motion: every ball is moved (CollisionWorld::move, one batch) to where its velocity
//     takes it in h (plus the time it owes from an impact in the previous step);
//  3. detection (CollisionWorld::step): broad phase, narrow phase and events; the balls are
//     fast objects with CcdMode::Bullet, so every moving ball's first impact with a ball
//     (both motions) or a cushion comes as an ImpactEvent at its certified time of impact;
//  4. impacts, earliest first: both objects are put back at the time of impact
//     (CollisionWorld::teleport: no motion) and the normal impulse for equal masses
//     (v_rel,n' = -e v_rel,n; Baraff, "Physically Based Modeling", impulse-based collision)
//     separates them; the rest of the step is added to those balls' next step, so no
//     ball loses time;
//  5. manifolds of the pairs touching at the new poses (balls not held in step 4): overlaps
//     are pushed apart along the normal and approaching pairs get the same impulse;
//  6. the poses go back to the world (teleport), and a scene query (CollisionWorld::overlap)
//     at every ball finds what still overlaps it (a ball held in step 4 may lie where another
//     ball's motion ended, that motion having been swept against the held ball's whole
//     motion; a push in step 5 may close on a third ball): pushed apart and given the
//     impulse, pass after pass until nothing overlaps (as in position-based projection).
// The table's listener receives the world's begin / persist / end and impact callbacks and
// keeps the set of touching pairs from them alone (the tests compare it with the world's
// contacts).
#include "billiard_table.hpp"

#include <proxima/core/assert.hpp>
#include <proxima/core/tolerance.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>

namespace proxima::tool {

namespace {

// SplitMix64 (Steele, Lea, Flood 2014): the same jitter on every platform, unlike the
// standard library's distributions.
class Jitter {
 public:
  explicit Jitter(std::uint64_t seed) : state_(seed), enabled_(seed != 0) {}
  // Uniform in [-amplitude, amplitude]; 0 when the seed is 0.
  Real next(Real amplitude) {
    state_ += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    if (!enabled_) return Real(0);
    const double unit = static_cast<double>(z >> 11) * 0x1.0p-53;  // [0, 1)
    return static_cast<Real>((2.0 * unit - 1.0) * static_cast<double>(amplitude));
  }

 private:
  std::uint64_t state_;
  bool enabled_;
};

Transform at(const Vec3& position) { return Transform{position, kIdentityQuat}; }

constexpr std::uint64_t kCushionUserData = 100;  // user data of cushion c: 100 + c
constexpr std::uint64_t kCushionLayer = 1;
constexpr std::uint64_t kBallLayer = 2;

CollisionWorld make_world(const BilliardConfig& config) {
  if (!(config.frame_rate > 0.0) || config.substeps < 1 || config.frames < 0) {
    throw std::invalid_argument("billiards: frames >= 0, frame_rate > 0 and substeps >= 1 are required");
  }
  WorldSettings settings;
  settings.broadphase = config.broadphase;
  settings.contact_distance = config.contact_distance;
  settings.max_contacts = 1;
  settings.ccd_safety_factor = Real(0.001);  // every moving ball is swept
  settings.ccd_tolerance = Real(1e-5);
  Result<CollisionWorld> world = CollisionWorld::create(settings);
  if (!world) throw std::invalid_argument("billiards: " + world.error().message);
  return std::move(world).value();
}

}  // namespace

BilliardStart rack_break(const BilliardConfig& config) {
  BilliardStart start;
  const Real r = config.ball_radius;
  // Triangle rack, apex on the foot spot (x = L/4), rows of 1..5 balls towards the foot
  // cushion; neighbours `rack_gap` apart so that the break is a sequence of impacts.
  Jitter jitter(config.seed);
  const Real spacing = Real(2) * r + config.rack_gap;
  const Real row_step = spacing * std::sqrt(Real(3)) / Real(2);
  const Real foot_spot = Real(0.25) * config.table_length;
  // Ball numbers by rack position (row by row): 1 at the apex, 8 in the middle of row 3.
  static constexpr int kRackOrder[15] = {1, 9, 2, 10, 8, 3, 11, 7, 14, 4, 5, 13, 15, 6, 12};
  const Real wiggle = Real(0.25) * config.rack_gap;  // neighbours close by at most 0.71 gap
  int slot = 0;
  for (int row = 0; row < 5; ++row) {
    for (int k = 0; k <= row; ++k, ++slot) {
      const Real x = foot_spot + static_cast<Real>(row) * row_step + jitter.next(wiggle);
      const Real y = (static_cast<Real>(k) - Real(0.5) * static_cast<Real>(row)) * spacing + jitter.next(wiggle);
      start.position[static_cast<std::size_t>(kRackOrder[slot])] = Vec3(x, y, r);
    }
  }
  // Cue ball on the head spot, aimed at the apex ball (a few millimetres and a fraction of
  // a degree off with a non-zero seed).
  const Vec3 cue(Real(-0.25) * config.table_length, jitter.next(Real(0.004)), r);
  start.position[0] = cue;
  const Real aim = std::atan2(start.position[1].y - cue.y, start.position[1].x - cue.x) + jitter.next(Real(0.004));
  start.velocity[0] = Vec3(std::cos(aim), std::sin(aim), Real(0)) * config.cue_speed;
  return start;
}

std::array<HalfSpace, 4> table_cushions(const BilliardConfig& config) {
  return {HalfSpace::create(Vec3(1, 0, 0), Real(-0.5) * config.table_length).value(),
          HalfSpace::create(Vec3(-1, 0, 0), Real(-0.5) * config.table_length).value(),
          HalfSpace::create(Vec3(0, 1, 0), Real(-0.5) * config.table_width).value(),
          HalfSpace::create(Vec3(0, -1, 0), Real(-0.5) * config.table_width).value()};
}

/// Receives the world's callbacks: counts them and keeps the touching pairs.
class BilliardTable::Listener final : public WorldListener {
 public:
  explicit Listener(BilliardStats& stats) : stats_(stats) {}
  void on_contact_begin(CollisionWorld&, const ContactEvent& event) override {
    ++stats_.callbacks;
    touching_.insert(key(event.pair));
  }
  void on_contact_persist(CollisionWorld&, const ContactEvent&) override { ++stats_.callbacks; }
  void on_contact_end(CollisionWorld&, const ContactEvent& event) override {
    ++stats_.callbacks;
    touching_.erase(key(event.pair));
  }
  void on_impact(CollisionWorld&, const ImpactEvent&) override { ++stats_.callbacks; }
  const std::set<std::pair<std::uint64_t, std::uint64_t>>& touching() const { return touching_; }

 private:
  static std::pair<std::uint64_t, std::uint64_t> key(const ObjectPair& p) {
    return {p.a.to_integer(), p.b.to_integer()};
  }
  BilliardStats& stats_;
  std::set<std::pair<std::uint64_t, std::uint64_t>> touching_;
};

BilliardTable::BilliardTable(const BilliardConfig& config)
    : config_(config),
      world_(make_world(config)),
      listener_(std::make_unique<Listener>(stats_)),
      ball_shape_(Sphere::create(config.ball_radius).value()) {
  world_.set_listener(listener_.get());
  const std::array<HalfSpace, 4> cushions = table_cushions(config);
  for (int c = 0; c < kCushionCount; ++c) {
    ObjectDesc desc;
    desc.geometry = cushions[static_cast<std::size_t>(c)];
    desc.kind = ObjectKind::Static;
    desc.filter.layer = kCushionLayer;
    desc.user_data = kCushionUserData + static_cast<std::uint64_t>(c);
    cushion_[static_cast<std::size_t>(c)] = world_.add(desc).value();
  }
  const BilliardStart start = rack_break(config);
  for (int b = 0; b < kBallCount; ++b) {
    position_[b] = start.position[b];
    velocity_[b] = start.velocity[b];
    ObjectDesc desc;
    desc.geometry = ball_shape_;
    desc.pose = at(position_[b]);
    desc.ccd = CcdMode::Bullet;
    desc.filter.layer = kBallLayer;
    desc.user_data = static_cast<std::uint64_t>(b);
    ball_[b] = world_.add(desc).value();
    trajectory_[b].push_back(position_[b]);
  }
}

BilliardTable::~BilliardTable() = default;

std::vector<ObjectPair> BilliardTable::touching_from_callbacks() const {
  std::vector<ObjectPair> pairs;
  for (const auto& [a, b] : listener_->touching())
    pairs.push_back({ObjectHandle::from_integer(a), ObjectHandle::from_integer(b)});
  return pairs;
}

double BilliardTable::kinetic_energy() const {
  double sum = 0.0;
  for (const Vec3& v : velocity_) sum += 0.5 * static_cast<double>(glm::dot(v, v));
  return sum;
}

void BilliardTable::place_ball(int ball, const Vec3& position, const Vec3& velocity) {
  position_[ball] = Vec3(position.x, position.y, config_.ball_radius);
  velocity_[ball] = Vec3(velocity.x, velocity.y, Real(0));
  owed_[ball] = Real(0);
  trajectory_[ball].assign(1, position_[ball]);
  const auto error = world_.teleport(ball_[ball], at(position_[ball]));
  PROXIMA_ASSERT(!error);
  static_cast<void>(error);
}

int BilliardTable::body(ObjectHandle handle) const {
  for (int b = 0; b < kBallCount; ++b) {
    if (ball_[b] == handle) return b;
  }
  for (int c = 0; c < kCushionCount; ++c) {
    if (cushion_[c] == handle) return -1 - c;
  }
  PROXIMA_ASSERT(false);
  return -1;
}

void BilliardTable::record_point(int ball) {
  std::vector<Vec3>& path = trajectory_[ball];
  if (path.empty() || path.back() != position_[ball]) path.push_back(position_[ball]);
}

void BilliardTable::collide(int ball, int other, const Vec3& normal, const Vec3& point, bool continuous) {
  // `normal` points from `ball` into `other`; approach < 0 while they close in.
  const Vec3 other_velocity = other >= 0 ? velocity_[other] : Vec3(Real(0));
  const Real approach = glm::dot(other_velocity - velocity_[ball], normal);
  if (!(approach < Real(0))) return;
  if (other >= 0) {
    // Equal masses: the impulse per unit mass splits the normal velocity change evenly.
    const Real impulse = Real(-0.5) * (Real(1) + config_.ball_restitution) * approach;
    velocity_[ball] -= impulse * normal;
    velocity_[other] += impulse * normal;
    ++stats_.ball_collisions;
  } else {
    velocity_[ball] += (Real(1) + config_.cushion_restitution) * approach * normal;
    ++stats_.cushion_collisions;
  }
  contacts_.push_back({point, frame_, ball, other, continuous});
  record_point(ball);
  if (other >= 0) record_point(other);
}

void BilliardTable::resolve_impacts(Real h, const std::array<Vec3, kBallCount>& start,
                                    std::array<bool, kBallCount>& held) {
  std::vector<const ImpactEvent*> order;
  for (const ImpactEvent& e : world_.events().impacts) order.push_back(&e);
  std::stable_sort(order.begin(), order.end(),
                   [](const ImpactEvent* x, const ImpactEvent* y) { return x->toi < y->toi; });
  for (const ImpactEvent* e : order) {
    const int a = body(e->a);
    const int b = body(e->b);
    if (held[a] || (b >= 0 && held[b])) continue;  // an earlier impact changed its motion
    const Real rest = (Real(1) - e->toi) * h;      // time the held balls owe to their next step
    position_[a] = start[a] + (position_[a] - start[a]) * e->toi;
    held[a] = true;
    owed_[a] = rest;
    if (b >= 0) {
      position_[b] = start[b] + (position_[b] - start[b]) * e->toi;
      held[b] = true;
      owed_[b] = rest;
    }
    collide(a, b, e->normal, e->point, true);
  }
}

void BilliardTable::resolve_touching(const std::array<bool, kBallCount>& held) {
  for (const WorldManifold& m : world_.contacts()) {
    int ball = body(m.pair.a);
    int other = body(m.pair.b);
    Vec3 n = m.normal;  // from pair.a to pair.b
    if (ball < 0) {     // a cushion has the lower handle: turn the pair
      std::swap(ball, other);
      n = -n;
    }
    if (held[ball] || (other >= 0 && held[other])) continue;  // the manifold predates the impact
    const ContactPoint& p = m.points[0].contact;
    if (p.depth > Real(0)) {
      if (other >= 0) {
        position_[ball] -= n * (Real(0.5) * p.depth);
        position_[other] += n * (Real(0.5) * p.depth);
      } else {
        position_[ball] -= n * p.depth;
      }
    }
    collide(ball, other, n, (p.point_a + p.point_b) * Real(0.5), false);
  }
}

void BilliardTable::substep(Real h) {
  const Real slow_down = config_.rolling_deceleration * h;
  for (Vec3& v : velocity_) {
    const Real speed = glm::length(v);
    v = speed > slow_down ? v * ((speed - slow_down) / speed) : Vec3(Real(0));
  }
  const std::array<Vec3, kBallCount> start = position_;
  moves_.clear();
  for (int b = 0; b < kBallCount; ++b) {
    position_[b] = start[b] + velocity_[b] * (h + owed_[b]);
    owed_[b] = Real(0);
    moves_.push_back({ball_[b], at(position_[b])});
  }
  const auto moved = world_.move(moves_);
  PROXIMA_ASSERT(!moved);
  static_cast<void>(moved);

  const auto clock = std::chrono::steady_clock::now();
  const auto stepped = world_.step(h);
  stats_.step_seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
  PROXIMA_ASSERT(!stepped);
  static_cast<void>(stepped);
  const StepEvents& events = world_.events();
  ++stats_.steps;
  stats_.impacts += events.impacts.size();
  stats_.begin_events += events.begin.size();
  stats_.persist_events += events.persist.size();
  stats_.end_events += events.end.size();

  std::array<bool, kBallCount> held{};
  resolve_impacts(h, start, held);
  resolve_touching(held);
  sync_world();
  separate_overlaps();
}

void BilliardTable::sync_world() {
  for (int b = 0; b < kBallCount; ++b) {
    if (position_[b] == world_.pose(ball_[b]).position) continue;
    const auto error = world_.teleport(ball_[b], at(position_[b]));
    PROXIMA_ASSERT(!error);
    static_cast<void>(error);
  }
}

void BilliardTable::separate_overlaps() {
  const Real r = config_.ball_radius;
  const std::array<HalfSpace, 4> cushions = table_cushions(config_);
  // Overlaps at the rounding of the positions are left alone: halving them moves nothing, and
  // the passes would chase them to their cap.
  const Real slop = Real(16) * kEpsilon * config_.table_length;
  constexpr int kPasses = 4 * kBallCount;
  for (int pass = 0; pass < kPasses; ++pass) {
    bool pushed = false;
    for (int b = 0; b < kBallCount; ++b) {
      QueryFilter others;
      others.ignore = ball_[b];
      const auto found = world_.overlap(ball_shape_, at(position_[b]), others);
      PROXIMA_ASSERT(found.ok());
      for (const WorldOverlap& o : found.value()) {
        const int other = body(o.object);
        Vec3 n;  // from ball b into the other
        Real depth;
        if (other >= 0) {
          const Vec3 d = position_[other] - position_[b];
          const Real distance = glm::length(d);
          n = distance > Real(0) ? d / distance : Vec3(1, 0, 0);
          depth = Real(2) * r - distance;
          if (depth > slop) {
            position_[b] -= n * (Real(0.5) * depth);
            position_[other] += n * (Real(0.5) * depth);
          }
        } else {
          const HalfSpace& cushion = cushions[static_cast<std::size_t>(-1 - other)];
          n = -cushion.normal();
          depth = r - (glm::dot(cushion.normal(), position_[b]) - cushion.offset());
          if (depth > slop) position_[b] -= n * depth;
        }
        pushed = pushed || depth > slop;
        sync_world();
        collide(b, other, n, position_[b] + n * r, false);
      }
    }
    if (!pushed) return;
  }
  ++stats_.capped_steps;  // overlaps may remain: the tests require none
}

void BilliardTable::step() {
  const Real h = static_cast<Real>(1.0 / (config_.frame_rate * config_.substeps));
  for (int s = 0; s < config_.substeps; ++s) substep(h);
  for (int b = 0; b < kBallCount; ++b) record_point(b);
  ++stats_.frames;
  ++frame_;
}

}  // namespace proxima::tool
