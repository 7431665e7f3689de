#include "tunnelling_scene.hpp"

#include <proxima/core/assert.hpp>
#include <proxima/world/collision_world.hpp>

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

void TunnellingScene::run(const TunnellingFrameObserver& observer) {
  run_detector(CcdMode::Off, discrete_, discrete_stats_, observer);
  run_detector(CcdMode::Bullet, continuous_, continuous_stats_, observer);
}

namespace {

constexpr std::uint64_t kPlateLayer = 1;
constexpr std::uint64_t kBulletLayer = 2;
constexpr std::uint64_t kPlateUserData = 1u << 20;  // user data of plate k: kPlateUserData + k; bullet i: i

void check(const std::optional<Error>& error) {
  PROXIMA_ASSERT(!error);
  static_cast<void>(error);
}

}  // namespace

// One detector: the whole run in a world whose bullets have continuous-detection `mode`.
// Each frame: the plates and the flying bullets are moved to their poses at the frame's end
// (a bullet fired this frame is added at its start first), the world steps, and its events
// stop the bullets: an impact (continuous) at its time of impact, else a begun contact at
// the frame's end; stopped bullets and those that left the field are removed.
void TunnellingScene::run_detector(CcdMode mode, std::vector<BulletOutcome>& outcomes, DetectorStats& stats,
                                   const TunnellingFrameObserver& observer) const {
  const std::size_t n = bullets_.size();
  outcomes.assign(n, BulletOutcome{});
  stats = DetectorStats{};
  CollisionWorld world = CollisionWorld::create().value();
  std::vector<ObjectHandle> plate(plates_.size());
  for (std::size_t k = 0; k < plates_.size(); ++k) {
    ObjectDesc desc;
    desc.geometry = plates_[k].box;
    desc.pose = plates_[k].pose_at(0.0);
    desc.ccd = CcdMode::Off;
    desc.filter = CollisionFilter{kPlateLayer, kBulletLayer, 0};
    desc.user_data = kPlateUserData + k;
    plate[k] = world.add(desc).value();
  }
  std::vector<ObjectHandle> bullet(n);
  std::vector<char> flying(n, 0);
  const double dt = frame_time();
  std::vector<ObjectMove> moves;
  for (int f = 0; f < config_.frames; ++f) {
    const double t0 = static_cast<double>(f) * dt, t1 = t0 + dt;
    moves.clear();
    for (std::size_t k = 0; k < plates_.size(); ++k) moves.push_back({plate[k], plates_[k].pose_at(t1)});
    for (std::size_t i = 0; i < n; ++i) {
      if (bullets_[i].fire_frame == f) {
        ObjectDesc desc;
        desc.geometry = bullets_[i].sphere;
        desc.pose = at(bullets_[i].start);
        desc.ccd = mode;
        desc.filter = CollisionFilter{kBulletLayer, kPlateLayer, 0};
        desc.user_data = i;
        bullet[i] = world.add(desc).value();
        flying[i] = 1;
        outcomes[i].frame_positions.push_back(bullets_[i].start);
      }
      if (flying[i]) moves.push_back({bullet[i], at(bullets_[i].position_at(t1, config_.frame_rate))});
    }
    check(world.move(moves));
    const auto clock = std::chrono::steady_clock::now();
    check(world.step(static_cast<Real>(dt)));
    stats.seconds += seconds_since(clock);
    ++stats.steps;
    if (observer) observer(mode, f, world);
    const StepEvents& events = world.events();
    stats.impacts += events.impacts.size();
    stats.begin_events += events.begin.size();
    for (const ImpactEvent& e : events.impacts) {  // a is the fast bullet, b the plate
      BulletOutcome& out = outcomes[e.user_data_a];
      out.hit = true;
      out.plate = static_cast<int>(e.user_data_b - kPlateUserData);
      out.frame = f;
      out.toi = e.toi;
      out.time = t0 + static_cast<double>(e.toi) * dt;
      out.stop = bullets_[e.user_data_a].position_at(out.time, config_.frame_rate);
      out.point = e.point;
      ++stats.hits;
    }
    for (const ContactEvent& e : events.begin) {  // (plate, bullet): plates were added first
      BulletOutcome& out = outcomes[e.user_data_b];
      if (out.hit) continue;  // its impact, or a lower plate's contact, came first
      out.hit = true;
      out.plate = static_cast<int>(e.user_data_a - kPlateUserData);
      out.frame = f;
      out.time = t1;
      out.stop = bullets_[e.user_data_b].position_at(t1, config_.frame_rate);
      out.point = out.stop;
      out.frame_positions.push_back(out.stop);
      ++stats.hits;
      if (mode != CcdMode::Off) ++stats.late_hits;
    }
    for (std::size_t i = 0; i < n; ++i) {
      if (!flying[i]) continue;
      BulletOutcome& out = outcomes[i];
      if (!out.hit) {
        out.frame = f;
        out.time = t1;
        out.stop = bullets_[i].position_at(t1, config_.frame_rate);
        out.frame_positions.push_back(out.stop);
        out.left_field = outside_field(out.stop, bullets_[i].sphere.radius());
      }
      if (out.hit || out.left_field) {
        check(world.remove(bullet[i]));
        flying[i] = 0;
      }
    }
  }
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
