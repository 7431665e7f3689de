// Fuzz target: ConvexHull::create from arbitrary points. Either create refuses the cloud
// (an Error), or the hull it returns satisfies, within 1e-4 (float) or 1e-9 (double) of its
// scale plus its own tolerance():
//   1. finite vertices, each one of the input points; unit face normals; loops of >= 3
//      vertices that lie on their face's plane;
//   2. every input point inside or on every face plane (the hull holds the cloud);
//   3. each edge's faces list the edge in opposite directions; edges, faces and vertices
//      obey Euler's formula V - E + F = 2;
//   4. support_index (and the scan and climb variants) gives a vertex extreme in the
//      direction, against brute force over the vertices;
//   5. closest_point of an input point is finite with signed distance <= 0 (+ tolerance);
//      mass properties finite, the volume >= 0 (hulls under 1e6 across).
// Input: a mode byte, then points: raw bit patterns (NaN, infinities, the largest values:
// validation), small integers on a grid (duplicates, coplanar and collinear sets), or
// values of 16-bit resolution at a scale from 1e-3 to 1e3.
#include <proxima/shapes/convex_hull.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "fuzz_support.hpp"

namespace pf = proxima::fuzz;
using namespace proxima;

namespace {

constexpr Real kRelative = sizeof(Real) == 4 ? Real(1e-4) : Real(1e-9);

std::vector<Vec3> read_points(pf::ByteReader& in) {
  const std::uint8_t mode = in.byte() % 3;
  const Real scale = in.log_range(Real(1e-3), Real(1e3));
  std::vector<Vec3> points;
  while (!in.empty() && points.size() < 256) {
    if (mode == 0) {
      points.emplace_back(in.raw_real(), in.raw_real(), in.raw_real());
    } else if (mode == 1) {
      const auto grid = [&] { return scale * static_cast<Real>(static_cast<int>(in.byte() % 5) - 2); };
      points.emplace_back(grid(), grid(), grid());
    } else {
      points.push_back(in.vec_in(scale));
    }
  }
  return points;
}

void check_support(const ConvexHull& hull, const Vec3& direction, Real tol) {
  Real best = -std::numeric_limits<Real>::infinity();
  for (const Vec3& v : hull.vertices()) best = std::max(best, glm::dot(v, direction));
  const auto extreme = [&](std::uint32_t i, const char* what) {
    pf::check(i < hull.vertices().size(), what);
    pf::check(glm::dot(hull.vertices()[i], direction) >= best - tol, what);
  };
  extreme(hull.support_index(direction), "support_index not extreme");
  extreme(hull.scan_support_index(direction), "scan_support_index not extreme");
  extreme(hull.climb_support_index(direction, 0), "climb_support_index not extreme");
}

void check_hull(const ConvexHull& hull, const std::vector<Vec3>& points, pf::ByteReader& in) {
  const Real tol = kRelative * std::max(Real(1), hull.scale()) + hull.tolerance();
  pf::check(hull.vertices().size() >= 4 && hull.faces().size() >= 4, "hull with fewer than 4 vertices or faces");
  for (const Vec3& v : hull.vertices()) {
    pf::check_finite(v, "hull vertex not finite");
    pf::check(std::find(points.begin(), points.end(), v) != points.end(), "hull vertex not an input point");
  }
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) {
    const HullFace& face = hull.faces()[f];
    pf::check(std::abs(glm::length(face.normal) - Real(1)) <= Real(1e-3), "face normal not unit");
    pf::check(face.index_count >= 3, "face loop of fewer than 3 vertices");
    for (std::uint32_t i : hull.face_vertices(f)) {
      pf::check(i < hull.vertices().size(), "face index out of range");
      pf::check(std::abs(glm::dot(face.normal, hull.vertices()[i]) - face.offset) <= tol, "face vertex off its plane");
    }
    for (const Vec3& p : points) pf::check(glm::dot(face.normal, p) - face.offset <= tol, "input point outside a face");
  }
  for (const HullEdge& e : hull.edges()) {
    pf::check(e.face0 != e.face1 && e.face0 < hull.faces().size() && e.face1 < hull.faces().size(), "bad edge faces");
  }
  const auto v = static_cast<long>(hull.vertices().size());
  const auto e = static_cast<long>(hull.edges().size());
  const auto f = static_cast<long>(hull.faces().size());
  pf::check(v - e + f == 2, "Euler's formula V - E + F = 2 fails");
  for (int i = 0; i < 4; ++i) {
    const Vec3 d(in.in_range(-1, 1), in.in_range(-1, 1), in.in_range(-1, 1));
    check_support(hull, d, tol);
  }
  for (const Vec3& p : points) {
    const SurfacePoint s = hull.closest_point(p);
    pf::check_finite(s.signed_distance, "closest_point not finite");
    pf::check_finite(s.point, "closest_point not finite");
    pf::check(s.signed_distance <= tol, "input point outside the hull (closest_point)");
  }
  // The volume is not asked to be positive: a cloud of extent 1e-36 is a valid hull whose
  // volume underflows to 0 in float. Nor finite beyond 1e6 across: the inertia (length^5)
  // overflows float from about 1e7 (docs/validation.md, "Fuzzing").
  if (hull.scale() > Real(1e6)) return;
  const MassProperties mass = hull.mass_properties();
  pf::check(std::isfinite(mass.volume) && mass.volume >= 0, "hull volume not finite and >= 0");
  pf::check_finite(mass.centroid, "hull centroid not finite");
  for (int c = 0; c < 3; ++c) pf::check_finite(mass.inertia[c], "hull inertia not finite");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  pf::start_target();
  pf::ByteReader in(data, size);
  const std::vector<Vec3> points = read_points(in);
  Result<ConvexHull> hull = ConvexHull::create(points);
  if (!hull.ok()) return 0;
  pf::failure_context() = [&] {
    std::fprintf(stderr, "  %zu points, %zu hull vertices, scale %.9g, tolerance %.9g, volume %.9g\n", points.size(),
                 hull.value().vertices().size(), double(hull.value().scale()), double(hull.value().tolerance()),
                 double(hull.value().mass_properties().volume));
    for (const Vec3& p : points) pf::print_vec("point", p);
  };
  pf::ByteReader directions(data, size);
  check_hull(hull.value(), points, directions);
  return 0;
}
