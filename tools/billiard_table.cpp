// The billiard break of `proxima demo`: event-driven rigid balls on a table with cushions.
//
// Steps of a frame (BilliardTable::step):
//  1. rolling resistance: every ball's speed drops by a constant deceleration times dt;
//  2. broad phase: each ball's world AABB swept over the rest of the frame; the library's
//     incremental sweep-and-prune (SweepAndPrune) pairs the balls, and each box is tested against the cushions'
//     world AABBs (HalfSpace::world_aabb: bounded on the cushion's axis only);
//  3. narrow phase with time of impact: for a candidate ball pair the relative motion of one
//     centre is a ray cast against a Sphere of radius 2r at the other centre; for a cushion the
//     ball's centre is cast against the cushion's HalfSpace pushed out by r (Minkowski sums,
//     Ericson, Real-Time Collision Detection, 5.5.7 and 5.5.3). A ray starting inside counts
//     only while the bodies approach;
//  4. the earliest impact is advanced to, resolved with a normal impulse for equal masses
//     (v_rel,n' = -e v_rel,n; Baraff, "Physically Based Modeling", impulse-based collision),
//     the boxes are swept again from there, and 3-4 repeat until the frame holds no impact.
// Straight-line motion within the frame makes the times of impact exact, so balls never
// tunnel, whatever their speed.
#include "billiard_table.hpp"

#include <proxima/core/assert.hpp>
#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <cmath>

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

}  // namespace

BilliardTable::BilliardTable(const BilliardConfig& config)
    : config_(config),
      ball_(Sphere::create(config.ball_radius).value()),
      contact_ball_(Sphere::create(Real(2) * config.ball_radius).value()),
      cushion_{HalfSpace::create(Vec3(1, 0, 0), Real(-0.5) * config.table_length).value(),
               HalfSpace::create(Vec3(-1, 0, 0), Real(-0.5) * config.table_length).value(),
               HalfSpace::create(Vec3(0, 1, 0), Real(-0.5) * config.table_width).value(),
               HalfSpace::create(Vec3(0, -1, 0), Real(-0.5) * config.table_width).value()},
      contact_cushion_{cushion_} {
  const Real r = config.ball_radius;
  for (int c = 0; c < kCushionCount; ++c) {
    contact_cushion_[c] = HalfSpace::create(cushion_[c].normal(), cushion_[c].offset() + r).value();
    cushion_box_[c] = cushion_[c].world_aabb(Transform::identity());
  }

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
      position_[static_cast<std::size_t>(kRackOrder[slot])] = Vec3(x, y, r);
    }
  }

  // Cue ball on the head spot, aimed at the apex ball (a few millimetres and a fraction of
  // a degree off with a non-zero seed).
  const Vec3 cue(Real(-0.25) * config.table_length, jitter.next(Real(0.004)), r);
  position_[0] = cue;
  const Real aim = std::atan2(position_[1].y - cue.y, position_[1].x - cue.x) + jitter.next(Real(0.004));
  velocity_[0] = Vec3(std::cos(aim), std::sin(aim), Real(0)) * config.cue_speed;

  for (int i = 0; i < kBallCount; ++i) trajectory_[i].push_back(position_[i]);
}

double BilliardTable::kinetic_energy() const {
  double sum = 0.0;
  for (const Vec3& v : velocity_) sum += 0.5 * static_cast<double>(glm::dot(v, v));
  return sum;
}

void BilliardTable::sweep_boxes(Real duration) {
  for (int i = 0; i < kBallCount; ++i) {
    swept_box_[i] =
        merge(ball_.world_aabb(at(position_[i])), ball_.world_aabb(at(position_[i] + velocity_[i] * duration)));
  }
}

void BilliardTable::place_ball(int ball, const Vec3& position, const Vec3& velocity) {
  position_[ball] = Vec3(position.x, position.y, config_.ball_radius);
  velocity_[ball] = Vec3(velocity.x, velocity.y, Real(0));
  trajectory_[ball].assign(1, position_[ball]);
}

void BilliardTable::find_candidates(std::vector<char>& ball_seen, std::vector<char>& cushion_seen) {
  ++stats_.broad_phase_passes;
  if (config_.brute_force_pairs) {
    ball_pairs_.clear();
    for (std::uint32_t i = 0; i < kBallCount; ++i) {
      for (std::uint32_t j = i + 1; j < kBallCount; ++j) ball_pairs_.emplace_back(i, j);
    }
  } else {
    for (std::uint32_t i = 0; i < kBallCount; ++i) {
      const BroadPhaseStatus status =
          sweep_filled_ ? sweep_.update(i, swept_box_[i]) : sweep_.insert(i, swept_box_[i], ProxyKind::Moving);
      PROXIMA_ASSERT(status == BroadPhaseStatus::Ok);
      static_cast<void>(status);
    }
    sweep_filled_ = true;
    sweep_.find_pairs(proxy_pairs_);
    ball_pairs_.clear();
    for (const ProxyPair& p : proxy_pairs_) ball_pairs_.emplace_back(p.lo, p.hi);
  }
  for (const IndexPair& p : ball_pairs_) ball_seen[p.first * kBallCount + p.second] = 1;
  cushion_pairs_.clear();
  for (std::uint32_t i = 0; i < kBallCount; ++i) {
    for (std::uint32_t c = 0; c < kCushionCount; ++c) {
      if (config_.brute_force_pairs || swept_box_[i].overlaps(cushion_box_[c])) {
        cushion_pairs_.emplace_back(i, c);
        cushion_seen[i * kCushionCount + c] = 1;
      }
    }
  }
}

BilliardTable::Impact BilliardTable::earliest_impact(Real duration) const {
  Impact best;
  for (const auto& [i, j] : ball_pairs_) {
    const Vec3 relative_motion = (velocity_[i] - velocity_[j]) * duration;
    const auto hit = raycast(contact_ball_, at(position_[j]), Ray{position_[i], relative_motion}, Real(1));
    if (!hit || hit->t >= best.fraction) continue;
    // Starting in contact (or overlapping by rounding): an impact only while approaching.
    if (hit->t <= Real(0) && !(glm::dot(position_[i] - position_[j], relative_motion) < Real(0))) continue;
    best = Impact{hit->t, static_cast<int>(i), static_cast<int>(j)};
  }
  for (const auto& [i, c] : cushion_pairs_) {
    const Vec3 motion = velocity_[i] * duration;
    const auto hit = raycast(contact_cushion_[c], Transform::identity(), Ray{position_[i], motion}, Real(1));
    if (!hit || hit->t >= best.fraction) continue;
    if (hit->t <= Real(0) && !(glm::dot(cushion_[c].normal(), motion) < Real(0))) continue;
    best = Impact{hit->t, static_cast<int>(i), -1 - static_cast<int>(c)};
  }
  return best;
}

void BilliardTable::resolve(const Impact& impact) {
  const int i = impact.a;
  const Real r = config_.ball_radius;
  if (impact.b >= 0) {
    const int j = impact.b;
    Vec3 n = position_[j] - position_[i];
    const Real len = glm::length(n);
    n = len > Real(0) ? n / len : Vec3(1, 0, 0);
    const Real approach = glm::dot(velocity_[j] - velocity_[i], n);
    if (approach < Real(0)) {
      // Equal masses: the impulse per unit mass splits the normal velocity change evenly.
      const Real impulse = Real(-0.5) * (Real(1) + config_.ball_restitution) * approach;
      velocity_[i] -= impulse * n;
      velocity_[j] += impulse * n;
    }
    contacts_.push_back({position_[i] + n * r, frame_, i, j});
    ++stats_.ball_collisions;
    record_point(i);
    record_point(j);
  } else {
    const int c = -1 - impact.b;
    const Vec3& n = cushion_[c].normal();
    const Real approach = glm::dot(velocity_[i], n);
    if (approach < Real(0)) velocity_[i] -= (Real(1) + config_.cushion_restitution) * approach * n;
    contacts_.push_back({position_[i] - n * r, frame_, i, impact.b});
    ++stats_.cushion_collisions;
    record_point(i);
  }
}

void BilliardTable::record_point(int ball) {
  std::vector<Vec3>& path = trajectory_[ball];
  if (path.empty() || path.back() != position_[ball]) path.push_back(position_[ball]);
}

void BilliardTable::step() {
  const Real dt = static_cast<Real>(1.0 / config_.frame_rate);
  const Real slow_down = config_.rolling_deceleration * dt;
  for (Vec3& v : velocity_) {
    const Real speed = glm::length(v);
    v = speed > slow_down ? v * ((speed - slow_down) / speed) : Vec3(Real(0));
  }

  std::vector<char> ball_seen(static_cast<std::size_t>(kBallCount) * kBallCount, 0);
  std::vector<char> cushion_seen(static_cast<std::size_t>(kBallCount) * kCushionCount, 0);
  Real remaining = dt;
  sweep_boxes(remaining);
  find_candidates(ball_seen, cushion_seen);
  for (int events = 0;; ++events) {
    if (events >= config_.max_events_per_frame) {
      ++stats_.capped_frames;
      break;
    }
    const Impact impact = earliest_impact(remaining);
    if (impact.fraction > Real(1)) break;
    const Real h = impact.fraction * remaining;
    for (int i = 0; i < kBallCount; ++i) position_[i] += velocity_[i] * h;
    remaining = std::max(Real(0), remaining - h);
    resolve(impact);
    sweep_boxes(remaining);
    find_candidates(ball_seen, cushion_seen);
  }
  for (int i = 0; i < kBallCount; ++i) {
    position_[i] += velocity_[i] * remaining;
    record_point(i);
  }

  stats_.frames += 1;
  stats_.brute_ball_pairs += kBallCount * (kBallCount - 1) / 2;
  stats_.brute_cushion_pairs += static_cast<std::uint64_t>(kBallCount) * kCushionCount;
  stats_.candidate_ball_pairs += static_cast<std::uint64_t>(std::count(ball_seen.begin(), ball_seen.end(), 1));
  stats_.candidate_cushion_pairs += static_cast<std::uint64_t>(std::count(cushion_seen.begin(), cushion_seen.end(), 1));
  ++frame_;
}

}  // namespace proxima::tool
