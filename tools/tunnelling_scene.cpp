#include "tunnelling_scene.hpp"

#include <proxima/ccd/motion.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace proxima::tool {

namespace {

// SplitMix64 (Steele, Lea, Flood 2014): the same scene on every platform, unlike the
// standard library's distributions.
class Random {
 public:
  explicit Random(std::uint64_t seed) : state_(seed) {}
  // Uniform in [0, 1).
  double unit() {
    state_ += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1.0p-53;
  }
  // Uniform in [lo, hi).
  double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }

 private:
  std::uint64_t state_;
};

// The plates, in fractions of the field (x of length, y of width): two near the guns, one
// in the middle, two at the far end; half lengths in metres, spins in rad/s (both senses,
// all below 8 rad/s, so |w| dt < pi at any frame rate above 3 Hz).
struct PlateLayout {
  double x, y, half_length, spin;
};
constexpr PlateLayout kPlates[] = {
    {-0.25, 0.26, 0.25, 4.0}, {-0.25, -0.26, 0.25, -5.0}, {0.0, 0.0, 0.5, 3.0},
    {0.275, 0.24, 0.4, -6.0}, {0.275, -0.24, 0.4, 7.0},
};

constexpr double kPi = 3.14159265358979323846;

Transform at(const Vec3& position) { return Transform{position, kIdentityQuat}; }

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

Transform TunnellingPlate::pose_at(double time) const {
  const double angle = phase + spin * time;
  return Transform{centre, glm::angleAxis(static_cast<Real>(std::remainder(angle, 2.0 * kPi)), Vec3(0, 0, 1))};
}

Vec3 TunnellingBullet::position_at(double time, double frame_rate) const {
  const double flight = time - static_cast<double>(fire_frame) / frame_rate;
  return start + velocity * static_cast<Real>(flight);
}

TunnellingScene::TunnellingScene(const TunnellingConfig& config) : config_(config) {
  if (config.frames < 0 || config.bullets < 0 || !(config.frame_rate > 0.0)) {
    throw std::invalid_argument("tunnelling scene: frames and bullets must be >= 0, the frame rate > 0");
  }
  Random random(config.seed);
  const double length = static_cast<double>(config.field_length);
  const double width = static_cast<double>(config.field_width);
  const Real half_height = Real(0.3);
  for (const PlateLayout& p : kPlates) {
    TunnellingPlate plate{Box::create(Vec3(config.plate_half_thickness, Real(p.half_length), half_height)).value(),
                          Vec3(Real(p.x * length), Real(p.y * width), Real(0)), random.uniform(0.0, kPi), p.spin};
    plates_.push_back(plate);
  }
  // Bullets fired from the left edge, one lane each (y uniform over 90% of the width), aimed
  // within 0.2 rad of +x, spread evenly over the run so that the last one crosses the field.
  const int last_fire = std::max(config.frames - 8, 1);
  for (int i = 0; i < config.bullets; ++i) {
    const double radius = random.uniform(config.min_radius, config.max_radius);
    const double y = random.uniform(-0.45 * width, 0.45 * width);
    const double aim = random.uniform(-0.2, 0.2);
    const double speed = random.uniform(config.min_speed, config.max_speed);
    TunnellingBullet bullet{Sphere::create(static_cast<Real>(radius)).value(),
                            Vec3(Real(-0.5 * length + 0.05), Real(y), Real(0)),
                            Vec3(Real(speed * std::cos(aim)), Real(speed * std::sin(aim)), Real(0)),
                            static_cast<int>(static_cast<long long>(i) * last_fire / std::max(config.bullets, 1))};
    bullets_.push_back(bullet);
  }
}

bool TunnellingScene::outside_field(const Vec3& centre, Real r) const {
  return std::abs(centre.x) > Real(0.5) * config_.field_length + r ||
         std::abs(centre.y) > Real(0.5) * config_.field_width + r;
}

void TunnellingScene::run() {
  const std::size_t n = bullets_.size();
  discrete_.assign(n, BulletOutcome{});
  continuous_.assign(n, BulletOutcome{});
  discrete_stats_ = DetectorStats{};
  continuous_stats_ = DetectorStats{};
  const double dt = frame_time();
  std::vector<Motion> plate_motion(plates_.size());
  std::vector<Transform> plate_end(plates_.size());
  for (int f = 0; f < config_.frames; ++f) {
    const double t0 = static_cast<double>(f) * dt;
    for (std::size_t k = 0; k < plates_.size(); ++k) {
      // The frame's motion: constant angular velocity about z from the frame's start pose.
      plate_motion[k] =
          Motion::from_velocity(plates_[k].pose_at(t0), Vec3(Real(0)),
                                Vec3(Real(0), Real(0), static_cast<Real>(plates_[k].spin)), static_cast<Real>(dt));
      plate_end[k] = plates_[k].pose_at(t0 + dt);
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (bullets_[i].fire_frame > f) continue;
      if (bullets_[i].fire_frame == f) {
        discrete_[i].frame_positions.push_back(bullets_[i].start);
        continuous_[i].frame_positions.push_back(bullets_[i].start);
      }
      step_continuous(f, static_cast<int>(i), plate_motion);
      step_discrete(f, static_cast<int>(i), plate_end);
    }
  }
}

void TunnellingScene::step_continuous(int f, int i, const std::vector<Motion>& plate_motion) {
  BulletOutcome& out = continuous_[static_cast<std::size_t>(i)];
  if (out.hit || out.left_field) return;
  const TunnellingBullet& bullet = bullets_[static_cast<std::size_t>(i)];
  const double dt = frame_time();
  const double t0 = static_cast<double>(f) * dt;
  const Motion motion = Motion::from_velocity(at(bullet.position_at(t0, config_.frame_rate)), bullet.velocity,
                                              Vec3(Real(0)), static_cast<Real>(dt));
  ToiResult first;
  int first_plate = -1;
  const auto clock = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < plates_.size(); ++k) {
    const Result<ToiResult> r = time_of_impact(bullet.sphere, motion, plates_[k].box, plate_motion[k]);
    ++continuous_stats_.queries;
    if (!r) {
      ++continuous_stats_.errors;
      continue;
    }
    const ToiResult& toi = r.value();
    continuous_stats_.iterations += static_cast<std::uint64_t>(toi.iterations);
    ++continuous_stats_.statuses[static_cast<std::size_t>(toi.status)];
    const bool contact = toi.status == CcdStatus::Hit || toi.status == CcdStatus::InitiallyOverlapping;
    if (contact && (first_plate < 0 || toi.toi < first.toi)) {
      first = toi;
      first_plate = static_cast<int>(k);
    }
  }
  continuous_stats_.seconds += seconds_since(clock);
  out.frame = f;
  if (first_plate >= 0) {
    out.hit = true;
    out.plate = first_plate;
    out.toi = first.toi;
    out.time = t0 + static_cast<double>(first.toi) * dt;
    out.stop = motion.at(first.toi).position;
    out.point = first.point;
    ++continuous_stats_.hits;
    return;
  }
  out.stop = motion.end.position;
  out.time = t0 + dt;
  out.frame_positions.push_back(out.stop);
  out.left_field = outside_field(out.stop, bullet.sphere.radius());
}

void TunnellingScene::step_discrete(int f, int i, const std::vector<Transform>& plate_end) {
  BulletOutcome& out = discrete_[static_cast<std::size_t>(i)];
  if (out.hit || out.left_field) return;
  const TunnellingBullet& bullet = bullets_[static_cast<std::size_t>(i)];
  const double t1 = static_cast<double>(f + 1) * frame_time();
  const Vec3 centre = bullet.position_at(t1, config_.frame_rate);
  int plate = -1;
  const auto clock = std::chrono::steady_clock::now();
  for (std::size_t k = 0; k < plates_.size() && plate < 0; ++k) {
    ++discrete_stats_.queries;
    if (intersect(bullet.sphere, at(centre), plates_[k].box, plate_end[k])) plate = static_cast<int>(k);
  }
  discrete_stats_.seconds += seconds_since(clock);
  out.frame = f;
  out.time = t1;
  out.stop = centre;
  out.frame_positions.push_back(centre);
  if (plate >= 0) {
    out.hit = true;
    out.plate = plate;
    out.point = centre;
    ++discrete_stats_.hits;
    return;
  }
  out.left_field = outside_field(centre, bullet.sphere.radius());
}

bool TunnellingScene::tunnelled(int i) const {
  const BulletOutcome& c = continuous_[static_cast<std::size_t>(i)];
  const BulletOutcome& d = discrete_[static_cast<std::size_t>(i)];
  return c.hit && !(d.hit && d.plate == c.plate);
}

int TunnellingScene::tunnelled_count() const {
  int count = 0;
  for (std::size_t i = 0; i < continuous_.size(); ++i) count += tunnelled(static_cast<int>(i)) ? 1 : 0;
  return count;
}

int TunnellingScene::discrete_only_count() const {
  int count = 0;
  for (std::size_t i = 0; i < continuous_.size(); ++i) count += discrete_[i].hit && !continuous_[i].hit ? 1 : 0;
  return count;
}

}  // namespace proxima::tool
