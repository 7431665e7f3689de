// The exact event-driven reference of the billiard break (see exact_billiards.hpp).
//
// Steps of a frame: rolling resistance; then, over every pair, the times of impact by ray
// casts of the relative motion against the Minkowski sums (a Sphere of radius 2r for a ball
// pair, the cushion's HalfSpace pushed out by r; Ericson, Real-Time Collision Detection,
// 5.5.7 and 5.5.3; a ray starting inside counts only while the bodies approach); the
// earliest is advanced to and resolved with the impulse for equal masses, and again until
// the frame holds no impact. Straight-line motion makes the times exact.
#include "exact_billiards.hpp"

#include <proxima/shapes/placed.hpp>

#include <algorithm>
#include <cmath>

namespace proxima::test_billiards {

namespace {
Transform at(const Vec3& position) { return Transform{position, kIdentityQuat}; }
}  // namespace

ExactBilliards::ExactBilliards(const BilliardConfig& config)
    : config_(config),
      contact_ball_(Sphere::create(Real(2) * config.ball_radius).value()),
      cushion_(tool::table_cushions(config)),
      contact_cushion_(cushion_) {
  for (int c = 0; c < kCushionCount; ++c) {
    contact_cushion_[c] = HalfSpace::create(cushion_[c].normal(), cushion_[c].offset() + config.ball_radius).value();
  }
  const tool::BilliardStart start = tool::rack_break(config);
  position_ = start.position;
  velocity_ = start.velocity;
}

double ExactBilliards::kinetic_energy() const {
  double sum = 0.0;
  for (const Vec3& v : velocity_) sum += 0.5 * static_cast<double>(glm::dot(v, v));
  return sum;
}

void ExactBilliards::place_ball(int ball, const Vec3& position, const Vec3& velocity) {
  position_[ball] = Vec3(position.x, position.y, config_.ball_radius);
  velocity_[ball] = Vec3(velocity.x, velocity.y, Real(0));
}

ExactBilliards::Impact ExactBilliards::earliest_impact(Real duration) const {
  Impact best;
  for (int i = 0; i < kBallCount; ++i) {
    for (int j = i + 1; j < kBallCount; ++j) {
      const Vec3 relative_motion = (velocity_[i] - velocity_[j]) * duration;
      const auto hit = raycast(contact_ball_, at(position_[j]), Ray{position_[i], relative_motion}, Real(1));
      if (!hit || hit->t >= best.fraction) continue;
      if (hit->t <= Real(0) && !(glm::dot(position_[i] - position_[j], relative_motion) < Real(0))) continue;
      best = Impact{hit->t, i, j};
    }
    for (int c = 0; c < kCushionCount; ++c) {
      const Vec3 motion = velocity_[i] * duration;
      const auto hit = raycast(contact_cushion_[c], Transform::identity(), Ray{position_[i], motion}, Real(1));
      if (!hit || hit->t >= best.fraction) continue;
      if (hit->t <= Real(0) && !(glm::dot(cushion_[c].normal(), motion) < Real(0))) continue;
      best = Impact{hit->t, i, -1 - c};
    }
  }
  return best;
}

void ExactBilliards::resolve(const Impact& impact) {
  const int i = impact.a;
  const Real r = config_.ball_radius;
  if (impact.b >= 0) {
    const int j = impact.b;
    Vec3 n = position_[j] - position_[i];
    const Real len = glm::length(n);
    n = len > Real(0) ? n / len : Vec3(1, 0, 0);
    const Real approach = glm::dot(velocity_[j] - velocity_[i], n);
    if (approach < Real(0)) {
      const Real impulse = Real(-0.5) * (Real(1) + config_.ball_restitution) * approach;
      velocity_[i] -= impulse * n;
      velocity_[j] += impulse * n;
    }
    contacts_.push_back({position_[i] + n * r, frame_, i, j, true});
  } else {
    const int c = -1 - impact.b;
    const Vec3& n = cushion_[c].normal();
    const Real approach = glm::dot(velocity_[i], n);
    if (approach < Real(0)) velocity_[i] -= (Real(1) + config_.cushion_restitution) * approach * n;
    contacts_.push_back({position_[i] - n * r, frame_, i, impact.b, true});
  }
}

void ExactBilliards::step() {
  const Real dt = static_cast<Real>(1.0 / config_.frame_rate);
  const Real slow_down = config_.rolling_deceleration * dt;
  for (Vec3& v : velocity_) {
    const Real speed = glm::length(v);
    v = speed > slow_down ? v * ((speed - slow_down) / speed) : Vec3(Real(0));
  }
  Real remaining = dt;
  for (int events = 0; events < 1000; ++events) {
    const Impact impact = earliest_impact(remaining);
    if (impact.fraction > Real(1)) break;
    const Real h = impact.fraction * remaining;
    for (int i = 0; i < kBallCount; ++i) position_[i] += velocity_[i] * h;
    remaining = std::max(Real(0), remaining - h);
    resolve(impact);
  }
  for (int i = 0; i < kBallCount; ++i) position_[i] += velocity_[i] * remaining;
  ++frame_;
}

}  // namespace proxima::test_billiards
