// Sphere against cone (Ericson, Real-Time Collision Detection, 5.1: closest point of a convex
// solid; the cone reduced to its meridian triangle, as in Eberly's point-to-cone distance).
//
// Steps:
//  1. the sphere centre c in the cone frame; its height z and its distance rho from the
//     axis, with the radial unit u = (c.x, c.y) / rho (the local +x axis when rho is 0);
//  2. in the (rho, z) half-plane the cone is the triangle apex (0, h), rim (R, -h), base
//     centre (0, -h); its two boundary edges there are the base [0, R] at z = -h (outward
//     normal -z) and the slant from the rim to the apex (outward unit normal
//     s = (2h, R) / sqrt(4h^2 + R^2) in (rho, z));
//  3. the signed distances of (rho, z) to the base line (-h - z) and to the slant line
//     (s . (rho, z - h)); c is inside when both are <= 0, and then the nearer face (the larger
//     of the two; ties go to the base) gives the depth and the normal (base: +z; slant:
//     -(2h u + R z) / sqrt(4h^2 + R^2));
//  4. outside: the nearer closest point of the edges whose outer side holds (rho, z) (a
//     convex polygon's closest point lies on such an edge); an edge's inside gives the
//     line's distance and the same normal as in step 3 (from the cone's geometry, not from a
//     difference of points); an end (apex or rim) gives the 2D difference, its length and
//     its direction mapped onto (u, z);
//  5. signed distance: core distance minus r; witnesses c + r n on the sphere and the cone's
//     surface point c + core n (turned to world).
// Manifold: that single point; feature id: the sphere's surface against the base (face 0),
// the lateral surface (surface 0), the rim (edge 0) or the apex (vertex 0). intersect applies
// the touching rule (contact.hpp) to the same distance: O(1).
#include <limits>

#include "narrowphase/pairs_rounded.hpp"
#include "narrowphase/rounded_common.hpp"

namespace proxima::narrow {

namespace {

struct SphereCone {
  DistanceResult result;
  std::uint32_t feature = 0;
};

/// The answer in the cone's (rho, z) half-plane: core distance (< 0 inside), the normal's
/// components along u and z (from the sphere to the cone), and the cone's feature.
struct MeridianAnswer {
  Real core = Real(0);
  Real n_rho = Real(0);
  Real n_z = Real(0);
  FeatureKind kind = FeatureKind::Surface;
};

/// A cone end (the apex or the rim) at (pr, pz) seen from (rho, z) outside the cone.
MeridianAnswer from_end(Real rho, Real z, Real pr, Real pz, FeatureKind kind) {
  const Real dr = pr - rho;
  const Real dz = pz - z;
  MeridianAnswer m;
  m.core = std::sqrt(dr * dr + dz * dz);
  m.kind = kind;
  if (m.core > Real(0)) {
    m.n_rho = dr / m.core;
    m.n_z = dz / m.core;
  } else {
    m.n_z = Real(1);  // on the end itself: any direction into the cone (never used: core 0)
  }
  return m;
}

/// Steps 2 to 4 for (rho, z), rho >= 0.
MeridianAnswer meridian(Real rho, Real z, Real R, Real h) {
  const Real L = std::sqrt(Real(4) * h * h + R * R);
  const Real sr = Real(2) * h / L;  // slant's outward normal (sr, sz)
  const Real sz = R / L;
  const Real base = -h - z;                    // signed distance to the base line
  const Real slant = sr * rho + sz * (z - h);  // signed distance to the slant line
  if (base <= Real(0) && slant <= Real(0)) {   // inside: the nearer face
    if (slant > base) return {slant, -sr, -sz, FeatureKind::Surface};
    return {base, Real(0), Real(1), FeatureKind::Face};
  }
  // Outside: the closest point lies on an edge whose outer side holds (rho, z).
  MeridianAnswer best;
  best.core = std::numeric_limits<Real>::infinity();
  if (base > Real(0)) {  // the base edge, (0, -h) to (R, -h)
    best = rho <= R ? MeridianAnswer{base, Real(0), Real(1), FeatureKind::Face}
                    : from_end(rho, z, R, -h, FeatureKind::Edge);
  }
  if (slant > Real(0)) {  // the slant edge, rim (R, -h) to apex (0, h); t = 0 at the rim
    const Real t = ((rho - R) * -R + (z + h) * (Real(2) * h)) / (L * L);
    MeridianAnswer on_slant;
    if (t <= Real(0)) {
      on_slant = from_end(rho, z, R, -h, FeatureKind::Edge);
    } else if (t >= Real(1)) {
      on_slant = from_end(rho, z, Real(0), h, FeatureKind::Vertex);
    } else {
      on_slant = {slant, -sr, -sz, FeatureKind::Surface};
    }
    if (on_slant.core < best.core) best = on_slant;
  }
  return best;
}

SphereCone sphere_cone(const Sphere& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                       const PairRequest& request) {
  const Vec3 c = pose_b.inverse_apply(pose_a.position);
  const Real rho = std::sqrt(c.x * c.x + c.y * c.y);
  const Vec3 u = rho > Real(0) ? Vec3(c.x / rho, c.y / rho, Real(0)) : Vec3(Real(1), Real(0), Real(0));
  const MeridianAnswer m = meridian(rho, c.z, b.radius(), b.half_length());
  const Vec3 n_local = m.n_rho * u + Vec3(Real(0), Real(0), m.n_z);
  const Vec3 q_local = c + m.core * n_local;
  const Real tol = resolve_tolerance(
      request, detail::pair_scale(pose_a, pose_b, a.radius() + std::max(b.radius(), b.half_length())));
  SphereCone sc;
  sc.result = detail::rounded_result(pose_a.position, pose_b.apply(q_local), pose_b.apply_vector(n_local), m.core,
                                     a.radius(), Real(0), tol);
  sc.feature = make_feature_id(FeatureKind::Surface, 0, m.kind, 0);
  return sc;
}

}  // namespace

DistanceResult pair_distance(const Sphere& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  return sphere_cone(a, pose_a, b, pose_b, request).result;
}

bool pair_intersect(const Sphere& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  return in_contact(sphere_cone(a, pose_a, b, pose_b, request).result, request);
}

ContactManifold pair_collide(const Sphere& a, const Transform& pose_a, const Cone& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* /*cache*/) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const SphereCone sc = sphere_cone(a, pose_a, b, pose_b, request);
  return manifold_from_distance(sc.result, request, sc.feature);
}

}  // namespace proxima::narrow
