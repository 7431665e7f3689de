// Uses the public API through the package: build a shape, place it, cast a ray.
#include <proxima/core/transform.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/sphere.hpp>

#include <cstdio>

int main() {
  const auto sphere = proxima::Sphere::create(proxima::Real(1));
  if (!sphere) return 1;
  const proxima::Transform pose{proxima::Vec3(0, 0, 5), proxima::kIdentityQuat};
  const proxima::Ray ray{proxima::Vec3(0), proxima::Vec3(0, 0, 1)};
  const auto hit = proxima::raycast(*sphere, pose, ray, proxima::Real(100));
  if (!hit || hit->t < proxima::Real(3.999) || hit->t > proxima::Real(4.001)) return 2;
  std::printf("consumer: hit at t = %g\n", static_cast<double>(hit->t));
  return 0;
}
