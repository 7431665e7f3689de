#include <proxima/core/transform.hpp>
#include <proxima/core/validate.hpp>

namespace proxima {

Result<Transform> Transform::create(const Vec3& position, const Quat& rotation) {
  if (std::optional<Transform> t = from_values(position, rotation)) return *t;
  if (auto e = validate::finite(position, "position")) return *e;
  if (auto e = validate::unit_quaternion(rotation, "rotation")) return *e;
  return make_error(ErrorCode::InvalidArgument, "rotation",
                    "was rejected");  // unreachable: from_values' checks are these
}

}  // namespace proxima
