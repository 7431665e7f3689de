#include <proxima/core/transform.hpp>
#include <proxima/core/validate.hpp>

namespace proxima {

Result<Transform> Transform::create(const Vec3& position, const Quat& rotation) {
  if (auto e = validate::finite(position, "position")) return *e;
  if (auto e = validate::unit_quaternion(rotation, "rotation")) return *e;
  return Transform{position, glm::normalize(rotation)};
}

}  // namespace proxima
