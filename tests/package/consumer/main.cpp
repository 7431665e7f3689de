// Uses the public API through the package: build a shape, place it, cast a ray; reject a
// bad shape through Result. Built without exceptions (PROXIMA_CONSUMER_NO_EXCEPTIONS), it
// also checks that value() on an error reaches the assert handler and never returns.
#include <proxima/core/assert.hpp>
#include <proxima/core/config.hpp>
#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/sphere.hpp>

#include <cstdio>
#include <cstdlib>
#include <cstring>

#if defined(PROXIMA_CONSUMER_NO_EXCEPTIONS) && PROXIMA_EXCEPTIONS
#error "the no-exceptions consumer found a library configured with exceptions"
#endif

namespace {

#if !PROXIMA_EXCEPTIONS
// value() on an error must arrive here with the error's field; exits with success.
void expect_radius_error(const char* expression, const char*, int) {
  const bool named =
      std::strstr(expression, "Result::value() on an error") != nullptr && std::strstr(expression, "radius") != nullptr;
  std::printf("consumer: value() on an error: %s\n", expression);
  std::fflush(stdout);
  std::_Exit(named ? 0 : 5);
}
#endif

}  // namespace

int main() {
  const auto sphere = proxima::Sphere::create(proxima::Real(1));
  if (!sphere) return 1;
  const proxima::Transform pose{proxima::Vec3(0, 0, 5), proxima::kIdentityQuat};
  const proxima::Ray ray{proxima::Vec3(0), proxima::Vec3(0, 0, 1)};
  const auto hit = proxima::raycast(*sphere, pose, ray, proxima::Real(100));
  if (!hit || hit->t < proxima::Real(3.999) || hit->t > proxima::Real(4.001)) return 2;
  std::printf("consumer: hit at t = %g\n", static_cast<double>(hit->t));

  const auto bad = proxima::Sphere::create(proxima::Real(-1));
  if (bad.ok() || bad.error().code != proxima::ErrorCode::NonPositive || bad.error().field != "radius") return 3;
  std::printf("consumer: rejected %s\n", bad.error().what().c_str());

#if !PROXIMA_EXCEPTIONS
  proxima::set_assert_handler(&expect_radius_error);
  (void)bad.value();
  return 4;  // value() returned on an error
#else
  return 0;
#endif
}
