#pragma once
// Helpers shared by the narrow-phase correctness suites: seeded random shapes of every type
// (sizes with extreme ratios, hulls of 8-64 random points), world-frame surface distances
// through the shapes' own closest_point (an independent reference: the shape layer, not the
// narrow phase), and the tolerance a check allows at a length scale.
#include <gtest/gtest.h>

#include <proxima/core/tolerance.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <variant>
#include <vector>

#include "narrowphase/mesh_mesh.hpp"
#include "shapes/shape_visit.hpp"
#include "support/random.hpp"

namespace proxima::test {

/// True for the float build.
inline constexpr bool kFloatBuild = sizeof(Real) == 4;

/// Relative accuracy the narrow-phase checks allow (times the pair's length scale): GJK/EPA
/// converge to about sqrt(epsilon) relative on curved shapes in float.
inline Real narrow_tolerance(Real scale) {
  const Real rel = kFloatBuild ? Real(2e-3) : Real(1e-6);
  return rel * std::max(Real(1e-30), scale);
}

/// Every convex shape type in ShapeType order (the kinds with pair routines of their own).
inline std::vector<ShapeType> all_shape_types() {
  std::vector<ShapeType> t;
  for (int i = 0; i < kConvexShapeTypeCount; ++i) t.push_back(static_cast<ShapeType>(i));
  return t;
}

/// An ordered pair of shape types: the parameter of the suites run once per pair.
struct TypePair {
  ShapeType a;
  ShapeType b;
};

/// A per-pair test's name, "<a>_<b>".
inline std::string type_pair_name(const testing::TestParamInfo<TypePair>& info) {
  return std::string(to_string(info.param.a)) + "_" + to_string(info.param.b);
}

/// Every ordered pair of the first `count` shape types (ShapeType order) that `keep(a, b)`
/// accepts.
template <class Keep>
std::vector<TypePair> type_pairs(int count, Keep keep) {
  std::vector<TypePair> pairs;
  for (int i = 0; i < count; ++i) {
    for (int j = 0; j < count; ++j) {
      const auto a = static_cast<ShapeType>(i);
      const auto b = static_cast<ShapeType>(j);
      if (keep(a, b)) pairs.push_back({a, b});
    }
  }
  return pairs;
}

/// narrow::mesh_mesh_collide_all into a vector (appended).
inline void mesh_mesh_contacts(const TriangleMesh& a, const Transform& pose_a, const TriangleMesh& b,
                               const Transform& pose_b, const PairRequest& request, std::vector<ContactPoint>& out,
                               narrow::MeshMeshNodes nodes = narrow::MeshMeshNodes::Oriented) {
  ContactVector collector;
  narrow::mesh_mesh_collide_all(a, pose_a, b, pose_b, request, collector, nodes);
  out.insert(out.end(), collector.contacts.begin(), collector.contacts.end());
}

/// collide_all into a vector (appended), through the library's ContactVector collector.
inline void collect_contacts(ShapeRef a, const Transform& pose_a, ShapeRef b, const Transform& pose_b,
                             const PairRequest& request, std::vector<ContactPoint>& out) {
  ContactVector collector;
  collide_all(a, pose_a, b, pose_b, request, collector);
  out.insert(out.end(), collector.contacts.begin(), collector.contacts.end());
}

/// True for the shapes without interior (point, segment, triangle).
inline bool is_thin(ShapeType t) {
  return t == ShapeType::Point || t == ShapeType::Segment || t == ShapeType::Triangle;
}

/// A size in [lo, hi), log-uniform.
inline Real log_uniform(Random& rng, Real lo, Real hi) { return lo * std::pow(hi / lo, rng.uniform(Real(0), Real(1))); }

/// A size vector: each component log-uniform in [0.2, 1.5) times `s`; one time in five one
/// component is squashed or stretched (ratios up to ~1:50).
inline Vec3 random_extents(Random& rng, Real s) {
  const Real ez = log_uniform(rng, Real(0.2), Real(1.5));
  const Real ey = log_uniform(rng, Real(0.2), Real(1.5));
  const Real ex = log_uniform(rng, Real(0.2), Real(1.5));
  Vec3 e(ex, ey, ez);
  if (rng.integer(0, 4) == 0) e[rng.integer(0, 2)] *= rng.integer(0, 1) == 0 ? Real(0.03) : Real(2.5);
  return e * s;
}

/// Random points for a hull: `n` points in a box of half extents `e` (a squashed cloud when
/// e is flat).
inline std::vector<Vec3> random_cloud(Random& rng, int n, const Vec3& e) {
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    const Vec3 u = rng.in_ball(Real(1));
    pts.push_back(u * e);
  }
  return pts;
}

/// A random convex shape of type `t` whose size is about `s` (length units); a half-space for
/// the composite kinds, which have generators of their own where tests need them.
inline Shape random_shape(Random& rng, ShapeType t, Real s = Real(1)) {
  switch (t) {
    case ShapeType::Point: return Point::create().value();
    case ShapeType::Segment:
      for (;;) {
        const Vec3 p1 = rng.in_ball(s);
        const Vec3 p0 = rng.in_ball(s);
        auto r = Segment::create(p0, p1);
        if (r.ok() && r.value().length() > Real(0.05) * s) return r.value();
      }
    case ShapeType::Triangle:
      for (;;) {
        const Vec3 p2 = rng.in_ball(s);
        const Vec3 p1 = rng.in_ball(s);
        const Vec3 p0 = rng.in_ball(s);
        auto r = Triangle::create(p0, p1, p2);
        if (r.ok() && r.value().area() > Real(0.01) * s * s) return r.value();
      }
    case ShapeType::Sphere: return Sphere::create(log_uniform(rng, Real(0.1), Real(1.2)) * s).value();
    case ShapeType::Capsule: {
      const Vec3 e = random_extents(rng, s);
      return Capsule::create(e.x * Real(0.6), rng.integer(0, 6) == 0 ? Real(0) : e.z).value();
    }
    case ShapeType::Box: return Box::create(random_extents(rng, s)).value();
    case ShapeType::Cylinder: {
      const Vec3 e = random_extents(rng, s);
      return Cylinder::create(e.x, e.z).value();
    }
    case ShapeType::Cone: {
      const Vec3 e = random_extents(rng, s);
      return Cone::create(e.x, e.z).value();
    }
    case ShapeType::Ellipsoid: return Ellipsoid::create(random_extents(rng, s)).value();
    case ShapeType::ConvexHull:
      for (;;) {
        const Vec3 e = random_extents(rng, s);
        const int n = rng.integer(8, 64);
        auto r = ConvexHull::create(random_cloud(rng, n, e));
        if (r.ok()) return r.value();
      }
    case ShapeType::HalfSpace:
    case ShapeType::TriangleMesh:
    case ShapeType::Compound:
    case ShapeType::Count: break;
  }
  const Real offset = rng.uniform(Real(-0.5), Real(0.5)) * s;
  return HalfSpace::create(rng.unit_vector(), offset).value();
}

/// Length scale of a shape (half-spaces: 0, they have none).
inline Real shape_scale(const Shape& shape) {
  if (std::holds_alternative<HalfSpace>(shape) || std::holds_alternative<Point>(shape)) return Real(0);
  const Aabb box = std::visit([](const auto& s) { return s.local_aabb(); }, shape);
  return glm::length(box.max - box.min) * Real(0.5) + max_abs_component(box.max) + max_abs_component(box.min);
}

/// A point from the 17 digits the sweeps print (named regressions), in the build's Real.
inline Vec3 printed(double x, double y, double z) { return Vec3(Real(x), Real(y), Real(z)); }

/// World signed distance of `point` from the surface of `shape` placed at `pose` (the
/// shape layer's closest_point, not the narrow phase).
inline Real surface_distance(const Shape& shape, const Transform& pose, const Vec3& point) {
  return detail::visit_convex(shape, [&](const auto& s) { return closest_point(s, pose, point).signed_distance; });
}

/// Describes a shape and a pose for failure messages (enough to rebuild a reproducer).
inline std::string describe(const Shape& shape, const Transform& pose) {
  std::ostringstream o;
  o.precision(17);
  o << to_string(shape_type(shape)) << "{";
  std::visit(
      [&](const auto& s) {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, Sphere>) o << "r=" << s.radius();
        if constexpr (std::is_same_v<S, Capsule> || std::is_same_v<S, Cylinder> || std::is_same_v<S, Cone>)
          o << "r=" << s.radius() << " h=" << s.half_length();
        if constexpr (std::is_same_v<S, Box>)
          o << "h=" << s.half_extents().x << "," << s.half_extents().y << "," << s.half_extents().z;
        if constexpr (std::is_same_v<S, Ellipsoid>)
          o << "r=" << s.radii().x << "," << s.radii().y << "," << s.radii().z;
        if constexpr (std::is_same_v<S, Segment>)
          o << "a=" << s.a().x << "," << s.a().y << "," << s.a().z << " b=" << s.b().x << "," << s.b().y << ","
            << s.b().z;
        if constexpr (std::is_same_v<S, Triangle>)
          for (int i = 0; i < 3; ++i)
            o << " v" << i << "=" << s.vertex(i).x << "," << s.vertex(i).y << "," << s.vertex(i).z;
        if constexpr (std::is_same_v<S, HalfSpace>)
          o << "n=" << s.normal().x << "," << s.normal().y << "," << s.normal().z << " d=" << s.offset();
        if constexpr (std::is_same_v<S, ConvexHull>) {
          o << "pts=";
          for (const Vec3& v : s.vertices()) o << "(" << v.x << "," << v.y << "," << v.z << ")";
        }
      },
      shape);
  o << "} at p=(" << pose.position.x << "," << pose.position.y << "," << pose.position.z << ") q(xyzw)=("
    << pose.rotation.x << "," << pose.rotation.y << "," << pose.rotation.z << "," << pose.rotation.w << ")";
  return o.str();
}

/// True when every component is finite.
inline bool finite3(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

/// The lower-case name of a status (for messages).
inline const char* status_name(PairStatus s) {
  switch (s) {
    case PairStatus::Separated: return "separated";
    case PairStatus::Touching: return "touching";
    case PairStatus::Penetrating: return "penetrating";
    case PairStatus::MaxIterations: return "max_iterations";
    case PairStatus::Degenerate: return "degenerate";
    case PairStatus::InvalidInput: return "invalid_input";
  }
  return "?";
}

}  // namespace proxima::test
