// Fuzz target: the narrow phase on every pair of convex shapes (ten kinds each side) at
// arbitrary poses, with the conventions of docs/conventions.md checked on every answer:
//   1. distance: finite signed distance, witnesses and normal; unit normal; status not
//      InvalidInput (the poses are valid);
//   2. point_b = point_a + signed_distance * normal;
//   3. the witnesses lie on their surfaces (closest_point of each shape);
//   4. symmetry: distance(B, A) has the same signed distance;
//   5. intersect agrees with distance <= 0 outside the band |distance| <= tolerance (inside
//      it, touching, the rule is the touching convention's and is not checked here);
//   6. collide: finite points and unit normals, a manifold exactly when the shapes are closer
//      than the contact distance (outside the same band).
// Tolerance: 1e-3 (float) or 1e-6 (double) of the pair's scale (sizes plus distance apart).
// Input: shape A, shape B (fuzz_shapes.hpp), pose A, pose B, then the request's options.
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fuzz_shapes.hpp"

namespace pf = proxima::fuzz;
using namespace proxima;

namespace {

constexpr Real kRelative = sizeof(Real) == 4 ? Real(1e-3) : Real(1e-6);

void check_distance(const DistanceResult& d, Real tol) {
  pf::check_finite(d.signed_distance, "distance: signed_distance not finite");
  pf::check_finite(d.point_a, "distance: point_a not finite");
  pf::check_finite(d.point_b, "distance: point_b not finite");
  pf::check_finite(d.normal, "distance: normal not finite");
  pf::check(d.status != PairStatus::InvalidInput, "distance: valid poses answered InvalidInput");
  pf::check(std::abs(glm::length(d.normal) - Real(1)) <= Real(1e-3), "distance: normal not unit");
  pf::check(glm::length(d.point_b - (d.point_a + d.signed_distance * d.normal)) <= tol,
            "distance: point_b != point_a + signed_distance * normal");
}

void check_on_surface(const pf::FuzzShape& s, const Transform& pose, const Vec3& world_point, Real tol,
                      const char* what) {
  const SurfacePoint p = pf::closest_on(s.shape, pose.inverse_apply(world_point));
  pf::check_finite(p.signed_distance, what);
  pf::check(std::abs(p.signed_distance) <= tol, what);
}

void check_manifold(const ContactManifold& m, Real signed_distance, Real contact_distance, Real tol) {
  pf::check(m.count >= 0 && m.count <= kMaxContactPoints, "collide: count out of range");
  pf::check_finite(m.normal, "collide: normal not finite");
  if (m.count > 0) {
    pf::check(std::abs(glm::length(m.normal) - Real(1)) <= Real(1e-3), "collide: normal not unit");
  }
  for (int i = 0; i < m.count; ++i) {
    const ContactPoint& p = m.points[static_cast<std::size_t>(i)];
    pf::check_finite(p.point_a, "collide: point_a not finite");
    pf::check_finite(p.point_b, "collide: point_b not finite");
    pf::check_finite(p.depth, "collide: depth not finite");
  }
  if (signed_distance < contact_distance - tol) pf::check(m.count > 0, "collide: no manifold for a contact");
  if (signed_distance > contact_distance + tol) pf::check(m.count == 0, "collide: manifold for shapes apart");
}

void describe(const pf::FuzzShape& a, const Transform& pa, const pf::FuzzShape& b, const Transform& pb,
              const DistanceResult& d, Real tol) {
  for (const auto* s : {&a, &b}) {
    const Aabb box = world_aabb(s->shape, Transform::identity());
    std::fprintf(stderr, "  shape type %d, reach %.9g\n", static_cast<int>(s->shape.index()), double(s->reach));
    pf::print_vec("local box min", box.min);
    pf::print_vec("local box max", box.max);
  }
  pf::print_vec("pose_a.position", pa.position);
  std::fprintf(stderr, "  pose_a.rotation (w %.9g, %.9g, %.9g, %.9g)\n", double(pa.rotation.w), double(pa.rotation.x),
               double(pa.rotation.y), double(pa.rotation.z));
  pf::print_vec("pose_b.position", pb.position);
  std::fprintf(stderr, "  pose_b.rotation (w %.9g, %.9g, %.9g, %.9g)\n", double(pb.rotation.w), double(pb.rotation.x),
               double(pb.rotation.y), double(pb.rotation.z));
  std::fprintf(stderr, "  distance %.9g status %d method %d iterations %d tolerance %.9g\n", double(d.signed_distance),
               static_cast<int>(d.status), static_cast<int>(d.method), d.iterations, double(tol));
  pf::print_vec("point_a", d.point_a);
  pf::print_vec("point_b", d.point_b);
  pf::print_vec("normal", d.normal);
  std::fprintf(stderr, "  point_a off A's surface by %.9g, point_b off B's by %.9g\n",
               double(pf::closest_on(a.shape, pa.inverse_apply(d.point_a)).signed_distance),
               double(pf::closest_on(b.shape, pb.inverse_apply(d.point_b)).signed_distance));
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pf::start_target();
  pf::ByteReader in(data, size);
  const std::optional<pf::FuzzShape> a = pf::read_convex(in);
  const std::optional<pf::FuzzShape> b = pf::read_convex(in);
  const std::optional<Transform> pa = pf::read_pose(in);
  const std::optional<Transform> pb = pf::read_pose(in);
  if (!a || !b || !pa || !pb) return 0;
  PairRequest request;
  request.max_contacts = 1 + static_cast<int>(in.index(4));
  request.gjk = in.flag() ? gjk::Variant::Nesterov : gjk::Variant::Plain;
  const Real contact_distance = in.flag() ? in.in_range(0, pf::kMaxSize) : Real(0);

  const Real scale = a->reach + b->reach + glm::length(pa->position - pb->position);
  const Real tol = kRelative * std::max(Real(1), scale);

  const DistanceResult d = distance(a->shape, *pa, b->shape, *pb, request);
  pf::failure_context() = [&] { describe(*a, *pa, *b, *pb, d, tol); };
  check_distance(d, tol);
  check_on_surface(*a, *pa, d.point_a, tol, "distance: point_a not on A's surface");
  check_on_surface(*b, *pb, d.point_b, tol, "distance: point_b not on B's surface");

  const DistanceResult swapped = distance(b->shape, *pb, a->shape, *pa, request);
  check_distance(swapped, tol);
  pf::check(std::abs(swapped.signed_distance - d.signed_distance) <= tol, "distance: not symmetric under swapping");

  const bool hit = intersect(a->shape, *pa, b->shape, *pb, request);
  if (d.signed_distance < -tol) pf::check(hit, "intersect false for penetrating shapes");
  if (d.signed_distance > tol) pf::check(!hit, "intersect true for separated shapes");

  const ContactManifold m = collide(a->shape, *pa, b->shape, *pb, request);
  check_manifold(m, d.signed_distance, Real(0), tol);
  if (contact_distance > 0) {
    request.contact_distance = contact_distance;
    check_manifold(collide(a->shape, *pa, b->shape, *pb, request), d.signed_distance, contact_distance, tol);
    const bool near = intersect(a->shape, *pa, b->shape, *pb, request);
    if (d.signed_distance < contact_distance - tol) pf::check(near, "intersect false within contact_distance");
    if (d.signed_distance > contact_distance + tol) pf::check(!near, "intersect true beyond contact_distance");
  }
  return 0;
}
