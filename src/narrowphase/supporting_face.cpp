// Supporting features of every shape in a world direction.
//
// Steps: the direction is turned into the shape's local frame and normalised; polyhedra
// pick the face whose outward normal has the largest dot product with it (a box by its
// largest component, a hull by a scan of its faces); curved shapes report a flat piece of
// their surface (cylinder cap or side line, cone base or slant line) only when that piece's
// normal is within acos(kCurvedFaceCosine) of the direction, else their support point.
// The points are mapped to the world frame. This is the "supporting face" step of the
// clipping manifolds of Box2D (b2ClipPolygons) and Jolt (GetSupportingFace).
#include "supporting_face.hpp"

#include <cmath>

namespace proxima::narrow {
namespace {

// Unit local direction (+z for zero or non-finite input).
Vec3 local_unit(const Transform& pose, const Vec3& direction) {
  Vec3 unit(Real(0), Real(0), Real(1));
  Real length = Real(0);
  static_cast<void>(unit_and_length(pose.inverse_apply_vector(direction), unit, length));
  return unit;
}

SupportingFace single_point(const Vec3& world_point, const Vec3& world_normal, Real radius) {
  SupportingFace f;
  f.count = 1;
  f.points[0] = world_point;
  f.ids[0] = 0;
  f.normal = world_normal;
  f.radius = radius;
  return f;
}

// The segment world_p0 -> world_p1 (ids 0 and 1) as the feature `index` with its normal
// and radius.
SupportingFace two_points(const Vec3& world_p0, const Vec3& world_p1, const Vec3& world_normal, std::uint32_t index,
                          Real radius) {
  SupportingFace f;
  f.count = 2;
  f.points[0] = world_p0;
  f.points[1] = world_p1;
  f.ids[0] = 0;
  f.ids[1] = 1;
  f.index = index;
  f.normal = world_normal;
  f.radius = radius;
  return f;
}

Vec3 world_unit(const Transform& pose, const Vec3& local) { return pose.apply_vector(local); }

// Regular polygon of kRimPoints points on the circle of radius r at height z, CCW seen
// from +z when `up`, from -z otherwise.
void rim(SupportingFace& f, const Transform& pose, Real r, Real z, bool up) {
  f.count = kRimPoints;
  for (int k = 0; k < kRimPoints; ++k) {
    const int i = up ? k : (kRimPoints - k) % kRimPoints;
    const Real angle = Real(2) * kPi * static_cast<Real>(i) / static_cast<Real>(kRimPoints);
    f.points[k] = pose.apply(Vec3(r * std::cos(angle), r * std::sin(angle), z));
    f.ids[k] = static_cast<std::uint32_t>(i);
  }
}

}  // namespace

SupportingFace supporting_face(const Point& /*shape*/, const Transform& pose, const Vec3& direction) {
  return single_point(pose.position, world_unit(pose, local_unit(pose, direction)), Real(0));
}

SupportingFace supporting_face(const Segment& shape, const Transform& pose, const Vec3& direction) {
  return two_points(pose.apply(shape.a()), pose.apply(shape.b()), world_unit(pose, local_unit(pose, direction)), 0,
                    Real(0));
}

SupportingFace supporting_face(const Triangle& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 d = local_unit(pose, direction);
  SupportingFace f;
  f.count = 3;
  const bool front = glm::dot(shape.normal(), d) >= Real(0);
  f.points[0] = pose.apply(shape.a());
  f.points[1] = pose.apply(front ? shape.b() : shape.c());
  f.points[2] = pose.apply(front ? shape.c() : shape.b());

  f.ids[0] = 0;
  f.ids[1] = front ? 1u : 2u;
  f.ids[2] = front ? 2u : 1u;
  f.normal = world_unit(pose, front ? shape.normal() : -shape.normal());
  f.index = front ? 0u : 1u;
  return f;
}

SupportingFace supporting_face(const Sphere& shape, const Transform& pose, const Vec3& direction) {
  return single_point(pose.position, world_unit(pose, local_unit(pose, direction)), shape.radius());
}

SupportingFace supporting_face(const Capsule& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 normal = world_unit(pose, local_unit(pose, direction));
  if (!(shape.half_length() > Real(0))) return single_point(pose.position, normal, shape.radius());
  return two_points(pose.apply(shape.bottom()), pose.apply(shape.top()), normal, 0, shape.radius());
}

SupportingFace supporting_face(const Box& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 d = local_unit(pose, direction);
  const Vec3 ad = glm::abs(d);
  int i = 0;
  if (ad.y > ad.x) i = 1;
  if (ad.z > ad[i]) i = 2;
  const bool plus = d[i] >= Real(0);
  const int j = (i + 1) % 3;
  const int k = (i + 2) % 3;
  // Corners of the face in the (j, k) plane, CCW seen from +e_i; reversed for the - face.
  static constexpr int kSj[4] = {1, 1, -1, -1};
  static constexpr int kSk[4] = {-1, 1, 1, -1};
  const Vec3& h = shape.half_extents();
  SupportingFace f;
  f.count = 4;
  f.index = static_cast<std::uint32_t>(2 * i + (plus ? 1 : 0));
  for (int v = 0; v < 4; ++v) {
    const int q = plus ? v : 3 - v;
    Vec3 p(Real(0));
    p[i] = plus ? h[i] : -h[i];
    p[j] = kSj[q] > 0 ? h[j] : -h[j];
    p[k] = kSk[q] > 0 ? h[k] : -h[k];
    f.points[v] = pose.apply(p);
    f.ids[v] = (p.x > Real(0) ? 1u : 0u) | (p.y > Real(0) ? 2u : 0u) | (p.z > Real(0) ? 4u : 0u);
  }
  Vec3 n(Real(0));
  n[i] = plus ? Real(1) : Real(-1);
  f.normal = world_unit(pose, n);
  return f;
}

SupportingFace supporting_face(const Cylinder& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 d = local_unit(pose, direction);
  const Real r = shape.radius();
  const Real h = shape.half_length();
  SupportingFace f;
  if (std::abs(d.z) >= kCurvedFaceCosine) {
    const bool up = d.z > Real(0);
    rim(f, pose, r, up ? h : -h, up);
    f.index = up ? 1u : 0u;
    f.normal = world_unit(pose, Vec3(Real(0), Real(0), up ? Real(1) : Real(-1)));
    return f;
  }
  const Real radial = std::sqrt(d.x * d.x + d.y * d.y);
  if (radial >= kCurvedFaceCosine) {
    const Vec3 u(d.x / radial, d.y / radial, Real(0));
    return two_points(pose.apply(Vec3(r * u.x, r * u.y, -h)), pose.apply(Vec3(r * u.x, r * u.y, h)),
                      world_unit(pose, u), 2, Real(0));
  }
  return single_point(pose.apply(shape.support(d)), world_unit(pose, d), Real(0));
}

SupportingFace supporting_face(const Cone& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 d = local_unit(pose, direction);
  const Real r = shape.radius();
  const Real h = shape.half_length();
  SupportingFace f;
  if (d.z <= -kCurvedFaceCosine) {
    rim(f, pose, r, -h, false);
    f.index = 0;
    f.normal = world_unit(pose, Vec3(Real(0), Real(0), Real(-1)));
    return f;
  }
  const Real radial = std::sqrt(d.x * d.x + d.y * d.y);
  if (radial > Real(0)) {
    // Outward normal of the slant line at the direction's azimuth: (2h u, r) / |(2h, r)|.
    Vec3 unit;
    Real length = Real(0);
    if (unit_and_length(Vec3(Real(2) * h, r, Real(0)), unit, length)) {
      const Vec3 u(d.x / radial, d.y / radial, Real(0));
      const Vec3 n(unit.x * u.x, unit.x * u.y, unit.y);
      if (glm::dot(n, d) >= kCurvedFaceCosine) {
        return two_points(pose.apply(Vec3(r * u.x, r * u.y, -h)), pose.apply(Vec3(Real(0), Real(0), h)),
                          world_unit(pose, n), 1, Real(0));
      }
    }
  }
  return single_point(pose.apply(shape.support(d)), world_unit(pose, d), Real(0));
}

SupportingFace supporting_face(const Ellipsoid& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 d = local_unit(pose, direction);
  return single_point(pose.apply(shape.support(d)), world_unit(pose, d), Real(0));
}

SupportingFace supporting_face(const ConvexHull& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 d = local_unit(pose, direction);
  const auto faces = shape.faces();
  std::uint32_t best = 0;
  Real best_dot = -std::numeric_limits<Real>::infinity();
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    const Real dot = glm::dot(faces[i].normal, d);
    if (dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  const auto loop = shape.face_vertices(best);
  if (loop.size() > static_cast<std::size_t>(kMaxFacePoints)) {
    return single_point(pose.apply(shape.support(d)), world_unit(pose, d), Real(0));
  }
  SupportingFace f;
  f.count = static_cast<int>(loop.size());
  const auto vertices = shape.vertices();
  for (int v = 0; v < f.count; ++v) {
    f.points[v] = pose.apply(vertices[loop[v]]);
    f.ids[v] = loop[v];
  }
  f.index = best;
  f.normal = world_unit(pose, faces[best].normal);
  return f;
}

SupportingFace supporting_face(const HalfSpace& shape, const Transform& pose, const Vec3& direction) {
  const Vec3 d = local_unit(pose, direction);
  return single_point(pose.apply(shape.normal() * shape.offset()), world_unit(pose, d), Real(0));
}

}  // namespace proxima::narrow
