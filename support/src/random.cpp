#include "support/random.hpp"

namespace proxima::test {

Real Random::uniform(Real lo, Real hi) {
  std::uniform_real_distribution<double> d(static_cast<double>(lo), static_cast<double>(hi));
  return static_cast<Real>(d(engine_));
}

int Random::integer(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine_); }

Vec3 Random::vec3(Real lo, Real hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }

Vec3 Random::in_box(const Vec3& lo, const Vec3& hi) {
  const Real z = uniform(lo.z, hi.z);
  const Real y = uniform(lo.y, hi.y);
  const Real x = uniform(lo.x, hi.x);
  return {x, y, z};
}

Vec3 Random::vector_of_length(Real lo, Real hi) {
  const Real length = uniform(lo, hi);
  return unit_vector() * length;
}

Vec3 Random::in_ball(Real r) {
  for (;;) {
    const Vec3 v = vec3(Real(-1), Real(1));
    if (glm::dot(v, v) <= Real(1)) return v * r;
  }
}

Vec3 Random::unit_vector() {
  for (;;) {
    const Vec3 v = vec3(Real(-1), Real(1));
    const Real l2 = glm::dot(v, v);
    if (l2 > Real(1e-4) && l2 <= Real(1)) return v / std::sqrt(l2);
  }
}

Quat Random::rotation() {
  const double u1 = std::uniform_real_distribution<double>(0.0, 1.0)(engine_);
  const double u2 = std::uniform_real_distribution<double>(0.0, 2.0 * 3.14159265358979323846)(engine_);
  const double u3 = std::uniform_real_distribution<double>(0.0, 2.0 * 3.14159265358979323846)(engine_);
  const double a = std::sqrt(1.0 - u1);
  const double b = std::sqrt(u1);
  const Quat q(static_cast<Real>(b * std::cos(u3)), static_cast<Real>(a * std::sin(u2)),
               static_cast<Real>(a * std::cos(u2)), static_cast<Real>(b * std::sin(u3)));
  return glm::normalize(q);
}

Transform Random::pose(Real extent) { return Transform{vec3(-extent, extent), rotation()}; }

}  // namespace proxima::test
