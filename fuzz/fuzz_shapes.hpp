#pragma once
// Convex shapes and poses decoded from fuzzer bytes through the validated constructors
// (create): a shape the library refuses is no input (nullopt). Sizes lie in
// [kMinSize, kMaxSize] and positions in [-kMaxOffset, kMaxOffset]: a ratio of 400 between
// the smallest and the largest length, the range in which the float build's tolerances are
// stated (docs/conventions.md).
#include <proxima/core/transform.hpp>
#include <proxima/shapes/shape.hpp>

#include <optional>
#include <variant>
#include <vector>

#include "fuzz_support.hpp"

namespace proxima::fuzz {

inline constexpr Real kMinSize = Real(0.05);
inline constexpr Real kMaxSize = Real(20);
inline constexpr Real kMaxOffset = Real(20);

/// A convex shape and the radius of a ball about its local origin that holds it.
struct FuzzShape {
  Shape shape;
  Real reach = Real(0);
};

template <class S>
std::optional<FuzzShape> made(Result<S> result, Real reach) {
  if (!result.ok()) return std::nullopt;
  return FuzzShape{Shape(std::move(result).value()), reach};
}

/// One of the ten convex kinds (Point .. ConvexHull, ShapeType order).
inline std::optional<FuzzShape> read_convex(ByteReader& in) {
  const std::uint32_t kind = in.index(10);
  const Real s = in.log_range(kMinSize, kMaxSize);
  const Real t = in.log_range(kMinSize, kMaxSize);
  switch (kind) {
    case 0: return made(Point::create(), Real(0));
    case 1: return made(Segment::create(in.vec_in(s), in.vec_in(s)), s * Real(1.8));
    case 2: return made(Triangle::create(in.vec_in(s), in.vec_in(s), in.vec_in(s)), s * Real(1.8));
    case 3: return made(Sphere::create(s), s);
    case 4: return made(Capsule::create(s, t), s + t);
    case 5: {
      const Vec3 h(s, t, in.log_range(kMinSize, kMaxSize));
      return made(Box::create(h), glm::length(h));
    }
    case 6: return made(Cylinder::create(s, t), s + t);
    case 7: return made(Cone::create(s, t), s + t);
    case 8: {
      const Vec3 r(s, t, in.log_range(kMinSize, kMaxSize));
      return made(Ellipsoid::create(r), std::max({r.x, r.y, r.z}));
    }
    default: {
      std::vector<Vec3> points(4 + in.index(29));
      for (Vec3& p : points) p = in.vec_in(s);
      return made(ConvexHull::create(points), s * Real(1.8));
    }
  }
}

/// A pose: position in the cube of half side kMaxOffset, a unit rotation.
inline std::optional<Transform> read_pose(ByteReader& in) {
  const Vec3 position = in.vec_in(kMaxOffset);
  return Transform::from_values(position, in.rotation());
}

/// Nearest surface point of any shape of the Shape variant, in its local frame.
inline SurfacePoint closest_on(const Shape& shape, const Vec3& local) {
  return std::visit(
      [&](const auto& s) -> SurfacePoint {
        if constexpr (requires { s.closest_point(local); }) {
          return s.closest_point(local);
        } else {
          return SurfacePoint{local, Vec3(0, 0, 1), Real(0)};
        }
      },
      shape);
}

}  // namespace proxima::fuzz
