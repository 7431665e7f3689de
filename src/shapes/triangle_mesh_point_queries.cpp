// Point queries on a TriangleMesh: closest point (signed for closed meshes), containment and
// mass properties.
//
// Steps:
//  1. Closest point: depth-first BVH descent, nearer child first, that enters a node only when
//     its box is within the best distance found so far (the radius shrinks as triangles are
//     tested, and is checked again when a node is popped); each leaf triangle by Ericson's
//     closest point on a triangle (geometry/closest_points.hpp). Ties keep the lower triangle
//     index.
//  2. Sign (closed meshes): the sign of (query - nearest point) . N, with N the angle-weighted
//     pseudo-normal of the feature holding the nearest point: the face normal, the sum of the
//     two face normals at an edge, the sum of incident face normals weighted by their angles at
//     a vertex (Baerentzen and Aanaes, "Signed distance computation using the angle weighted
//     pseudonormal", IEEE TVCG 2005). This is exact for a closed, oriented, manifold mesh,
//     unlike ray parity, which is fragile at edges and vertices. A nearest point whose
//     barycentric coordinates are within rounding of an edge or vertex takes that feature's
//     pseudo-normal. The vertex fan is walked through the triangle adjacency.
//  3. Containment, closed meshes: the reference answer is step 2 (points within
//     linear_tolerance(extent) of the surface count as inside). TriangleMesh::contains asks a
//     BspPolyhedron first (built on the first call under std::call_once; building it at create
//     would cost far more than the BVH), at a tolerance at least twice the reference's: its
//     Inside / Outside answers are exact there, and OnBoundary (every point within the
//     tolerance of the surface, and rare points near several splitting planes) falls back to
//     step 2, so both give the same answer.
//  4. Containment, open meshes: the generalised winding number >= 1/2 (Jacobson, Kavan,
//     Sorkine-Hornung, "Robust inside-outside segmentation using generalized winding
//     numbers", SIGGRAPH 2013; triangle solid angle by Van Oosterom and Strackee 1983). Exact:
//     a linear scan. Fast (Barill, Dickson, Schmidt, Levin, Jacobson, "Fast winding numbers
//     for soups and clouds", SIGGRAPH 2018): BVH descent, leaves exact, nodes beyond beta
//     radii whose remainder bound is below a per-node budget by the Taylor expansion of their
//     solid angle to first order (dipole plus the area-weighted normal-position moment); the
//     sum of those bounds bounds the error. When it cannot decide w >= 1/2: finer budgets,
//     then the linear scan.
//  5. Mass properties: divergence theorem over the tetrahedra joining each triangle to the
//     mean vertex (Tonon 2004; Eberly, "Polyhedral Mass Properties (Revisited)" 2009), in
//     double, as ConvexHull does.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/closest_points.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <utility>

#include "mesh_point_queries.hpp"
#include "shapes/triangle_mesh_derived.hpp"

namespace proxima {

namespace detail {

namespace {

Vec3 face_normal(const MeshView& m, std::uint32_t t) {
  const TriangleIndices& tri = m.triangles[t];
  const Vec3 a = m.vertices[tri[0]];
  const Vec3 n = glm::cross(m.vertices[tri[1]] - a, m.vertices[tri[2]] - a);
  Vec3 u;
  Real len;
  return unit_and_length(n, u, len) ? u : Vec3(Real(0));
}

Real corner_angle(const MeshView& m, std::uint32_t t, int corner) {
  const TriangleIndices& tri = m.triangles[t];
  const Vec3 v = m.vertices[tri[std::size_t(corner)]];
  const Vec3 e1 = m.vertices[tri[std::size_t((corner + 1) % 3)]] - v;
  const Vec3 e2 = m.vertices[tri[std::size_t((corner + 2) % 3)]] - v;
  return std::atan2(glm::length(glm::cross(e1, e2)), glm::dot(e1, e2));
}

int corner_of(const TriangleIndices& tri, std::uint32_t v) {
  for (int k = 0; k < 3; ++k) {
    if (tri[std::size_t(k)] == v) return k;
  }
  return -1;
}

// Angle-weighted normal sum around vertex `corner` of triangle t: walks the fan by crossing
// the edge leaving the vertex (consistent for an oriented manifold); stops at a boundary.
Vec3 vertex_pseudo_normal(const MeshView& m, std::uint32_t t, int corner) {
  const std::uint32_t v = m.triangles[t][std::size_t(corner)];
  Vec3 sum(Real(0));
  std::uint32_t cur = t;
  int k = corner;
  for (std::size_t step = 0; step <= m.triangles.size(); ++step) {
    sum += corner_angle(m, cur, k) * face_normal(m, cur);
    if (m.neighbors.empty()) break;
    const std::uint32_t next = m.neighbors[cur][std::size_t(k)];
    if (next == kNoIndex || next == t) break;
    cur = next;
    k = corner_of(m.triangles[cur], v);
    if (k < 0) break;
  }
  return sum;
}

Vec3 edge_pseudo_normal(const MeshView& m, std::uint32_t t, int edge) {
  Vec3 n = face_normal(m, t);
  if (!m.neighbors.empty()) {
    const std::uint32_t other = m.neighbors[t][std::size_t(edge)];
    if (other != kNoIndex) n += face_normal(m, other);
  }
  return n;
}

Vec3 feature_pseudo_normal(const MeshView& m, std::uint32_t t, const Vec3& bary) {
  // A coordinate within rounding of zero puts the point on the opposite edge; two of them on
  // the remaining vertex.
  const Real eps = Real(64) * kEpsilon;
  const bool z0 = bary.x <= eps;
  const bool z1 = bary.y <= eps;
  const bool z2 = bary.z <= eps;
  const int zeros = int(z0) + int(z1) + int(z2);
  if (zeros >= 2) {
    const int corner = !z0 ? 0 : (!z1 ? 1 : 2);
    return vertex_pseudo_normal(m, t, corner);
  }
  if (zeros == 1) {
    // Edge e runs from vertex e to e + 1: the zero coordinate is the opposite vertex.
    const int edge = z2 ? 0 : (z0 ? 1 : 2);
    return edge_pseudo_normal(m, t, edge);
  }
  return face_normal(m, t);
}

Real squared_distance_to_box(const Vec3& p, const BvhNode& node) {
  const Vec3 q = glm::clamp(p, node.min, node.max);
  return length_squared(q - p);
}

}  // namespace

MeshClosest mesh_closest(const MeshView& mesh, const Bvh& bvh, const Vec3& point) {
  MeshClosest best;
  best.distance_squared = std::numeric_limits<Real>::infinity();
  geometry::TrianglePoint best_tp;
  auto test = [&](std::uint32_t t) {
    const TriangleIndices& tri = mesh.triangles[t];
    const geometry::TrianglePoint tp =
        geometry::closest_point_triangle(point, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
    const Real d2 = length_squared(tp.point - point);
    if (d2 < best.distance_squared || (d2 == best.distance_squared && t < best.triangle)) {
      best.distance_squared = d2;
      best.triangle = t;
      best.point = tp.point;
      best_tp = tp;
    }
    return true;
  };
  if (bvh.empty()) {
    for (std::uint32_t t = 0; t < mesh.triangles.size(); ++t) test(t);
  } else {
    // Nearer child first; a node's box distance is checked again when it is popped, against
    // the radius found meanwhile (Bvh::traverse tests nodes when they are pushed).
    const std::span<const BvhNode> nodes = bvh.nodes();
    const std::span<const std::uint32_t> prims = bvh.primitives();
    struct Entry {
      std::uint32_t node;
      Real d2;
    };
    Entry stack[2 * Bvh::kMaxDepth + 2];
    std::uint32_t top = 0;
    stack[top++] = {0, squared_distance_to_box(point, nodes[0])};
    while (top != 0) {
      const Entry e = stack[--top];
      if (e.d2 > best.distance_squared) continue;
      const BvhNode& node = nodes[e.node];
      if (node.is_leaf()) {
        for (std::uint32_t i = node.first; i != node.first + node.count; ++i) test(prims[i]);
        continue;
      }
      const Real d0 = squared_distance_to_box(point, nodes[node.first]);
      const Real d1 = squared_distance_to_box(point, nodes[node.first + 1]);
      const bool left_first = d0 <= d1;
      const Entry near{left_first ? node.first : node.first + 1, left_first ? d0 : d1};
      const Entry far{left_first ? node.first + 1 : node.first, left_first ? d1 : d0};
      if (far.d2 <= best.distance_squared) stack[top++] = far;
      if (near.d2 <= best.distance_squared) stack[top++] = near;
    }
  }
  if (best.triangle != kNoIndex) best.pseudo_normal = feature_pseudo_normal(mesh, best.triangle, best_tp.barycentric);
  return best;
}

SurfacePoint mesh_closest_point(const MeshView& mesh, const Bvh& bvh, const Vec3& point) {
  SurfacePoint r;
  if (!is_finite(point) || mesh.triangles.empty()) {
    r.point = mesh.vertices.empty() ? Vec3(Real(0)) : mesh.vertices[0];
    r.signed_distance = std::numeric_limits<Real>::infinity();
    return r;
  }
  const MeshClosest c = mesh_closest(mesh, bvh, point);
  r.point = c.point;
  const Vec3 diff = point - c.point;
  Vec3 unit;
  Real length = Real(0);
  Vec3 pn;
  Real pn_len;
  const bool has_pn = unit_and_length(c.pseudo_normal, pn, pn_len);
  if (!has_pn) pn = Vec3(Real(0), Real(0), Real(1));
  if (unit_and_length(diff, unit, length)) {
    const bool inside = mesh.closed && glm::dot(diff, c.pseudo_normal) < Real(0);
    r.signed_distance = inside ? -length : length;
    r.normal = inside ? -unit : unit;
  } else {
    r.signed_distance = Real(0);
    r.normal = pn;
  }
  return r;
}

bool mesh_contains(const MeshView& mesh, const Bvh& bvh, const Vec3& point) {
  if (!is_finite(point) || mesh.triangles.empty()) return false;
  if (!mesh.closed) return mesh_winding_number(mesh, point) >= 0.5;
  const MeshClosest c = mesh_closest(mesh, bvh, point);
  const Real tol = linear_tolerance(mesh.scale);
  if (c.distance_squared <= tol * tol) return true;
  return glm::dot(point - c.point, c.pseudo_normal) < Real(0);
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// Signed solid angle of triangle (a, b, c) seen from p (Van Oosterom and Strackee 1983), in
// double; 0 when p is on the triangle's corner or edge (the formula is 0 / 0 there).
double solid_angle(const MeshView& mesh, const TriangleIndices& t, const double p[3]) {
  double v[3][3];
  double len[3];
  for (int k = 0; k < 3; ++k) {
    const Vec3& q = mesh.vertices[t[std::size_t(k)]];
    for (int i = 0; i < 3; ++i) v[k][i] = double(q[i]) - p[i];
    len[k] = std::sqrt(v[k][0] * v[k][0] + v[k][1] * v[k][1] + v[k][2] * v[k][2]);
  }
  auto dot = [](const double* x, const double* y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
  const double det = v[0][0] * (v[1][1] * v[2][2] - v[1][2] * v[2][1]) -
                     v[0][1] * (v[1][0] * v[2][2] - v[1][2] * v[2][0]) +
                     v[0][2] * (v[1][0] * v[2][1] - v[1][1] * v[2][0]);
  const double den =
      len[0] * len[1] * len[2] + dot(v[0], v[1]) * len[2] + dot(v[1], v[2]) * len[0] + dot(v[2], v[0]) * len[1];
  if (det == 0 && den == 0) return 0;
  return 2 * std::atan2(det, den);
}

}  // namespace

double mesh_winding_number(const MeshView& mesh, const Vec3& point) {
  const double p[3] = {double(point.x), double(point.y), double(point.z)};
  double sum = 0;
  for (const TriangleIndices& t : mesh.triangles) sum += solid_angle(mesh, t, p);
  return sum / (4 * kPi);
}

std::vector<WindingNode> build_winding_nodes(const MeshView& mesh, const Bvh& bvh) {
  const std::span<const BvhNode> nodes = bvh.nodes();
  const std::span<const std::uint32_t> prims = bvh.primitives();
  std::vector<WindingNode> out(nodes.size());
  if (nodes.empty()) return out;
  // Raw sums per node, about the origin: area, area * centroid, area * normal and
  // area * n_i * centroid_j; turned into WindingNode once the children are done.
  struct Raw {
    double area = 0;
    std::array<double, 3> first{0, 0, 0};
    std::array<double, 3> dipole{0, 0, 0};
    std::array<double, 9> second{};
  };
  std::vector<Raw> raw(nodes.size());
  auto finish = [&](std::uint32_t id) {
    const Raw& r = raw[id];
    WindingNode& w = out[id];
    w.area = r.area;
    w.dipole = r.dipole;
    for (int i = 0; i < 3; ++i) {
      w.center[std::size_t(i)] =
          r.area > 0 ? r.first[std::size_t(i)] / r.area : 0.5 * (double(nodes[id].min[i]) + double(nodes[id].max[i]));
    }
    for (std::size_t i = 0; i < 3; ++i) {
      for (std::size_t j = 0; j < 3; ++j) w.second[3 * i + j] = r.second[3 * i + j] - r.dipole[i] * w.center[j];
    }
  };
  auto distance = [](const std::array<double, 3>& a, const std::array<double, 3>& b) {
    return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
  };
  // Post-order walk with an explicit stack (entries: node, children done).
  std::vector<std::pair<std::uint32_t, bool>> stack{{0u, false}};
  while (!stack.empty()) {
    const auto [id, expanded] = stack.back();
    stack.pop_back();
    const BvhNode& node = nodes[id];
    if (node.is_leaf()) {
      Raw& r = raw[id];
      for (std::uint32_t i = node.first; i != node.first + node.count; ++i) {
        const TriangleIndices& t = mesh.triangles[prims[i]];
        double v[3][3];
        for (int k = 0; k < 3; ++k) {
          for (int a = 0; a < 3; ++a) v[k][a] = double(mesh.vertices[t[std::size_t(k)]][a]);
        }
        const double e1[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
        const double e2[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
        const double half_cross[3] = {0.5 * (e1[1] * e2[2] - e1[2] * e2[1]), 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]),
                                      0.5 * (e1[0] * e2[1] - e1[1] * e2[0])};
        const double area =
            std::sqrt(half_cross[0] * half_cross[0] + half_cross[1] * half_cross[1] + half_cross[2] * half_cross[2]);
        const double c[3] = {(v[0][0] + v[1][0] + v[2][0]) / 3, (v[0][1] + v[1][1] + v[2][1]) / 3,
                             (v[0][2] + v[1][2] + v[2][2]) / 3};
        r.area += area;
        for (std::size_t a = 0; a < 3; ++a) {
          r.first[a] += area * c[a];
          r.dipole[a] += half_cross[a];
          for (std::size_t b = 0; b < 3; ++b) r.second[3 * a + b] += half_cross[a] * c[b];
        }
      }
      finish(id);
      double radius = 0;
      for (std::uint32_t i = node.first; i != node.first + node.count; ++i) {
        for (const std::uint32_t k : mesh.triangles[prims[i]]) {
          const Vec3& q = mesh.vertices[k];
          radius = std::max(radius, distance(out[id].center, {double(q.x), double(q.y), double(q.z)}));
        }
      }
      out[id].radius = radius;
      continue;
    }
    if (!expanded) {
      stack.push_back({id, true});
      stack.push_back({node.first, false});
      stack.push_back({node.first + 1, false});
      continue;
    }
    Raw& r = raw[id];
    for (const std::uint32_t child : {node.first, node.first + 1}) {
      const Raw& cr = raw[child];
      r.area += cr.area;
      for (std::size_t a = 0; a < 9; ++a) r.second[a] += cr.second[a];
      for (std::size_t a = 0; a < 3; ++a) {
        r.first[a] += cr.first[a];
        r.dipole[a] += cr.dipole[a];
      }
    }
    finish(id);
    double radius = 0;
    for (const std::uint32_t child : {node.first, node.first + 1}) {
      radius = std::max(radius, distance(out[id].center, out[child].center) + out[child].radius);
    }
    out[id].radius = radius;
  }
  return out;
}

double mesh_fast_winding_number(const MeshView& mesh, const Bvh& bvh, std::span<const WindingNode> wnodes,
                                const Vec3& point, double beta, double node_error, double& error_bound) {
  const std::span<const BvhNode> nodes = bvh.nodes();
  const std::span<const std::uint32_t> prims = bvh.primitives();
  const double p[3] = {double(point.x), double(point.y), double(point.z)};
  double sum = 0;
  double error = 0;
  std::uint32_t stack[2 * Bvh::kMaxDepth + 2];
  std::uint32_t top = 0;
  stack[top++] = 0;
  while (top != 0) {
    const std::uint32_t id = stack[--top];
    const BvhNode& node = nodes[id];
    if (node.is_leaf()) {
      for (std::uint32_t i = node.first; i != node.first + node.count; ++i) {
        sum += solid_angle(mesh, mesh.triangles[prims[i]], p);
      }
      continue;
    }
    const WindingNode& w = wnodes[id];
    const double r[3] = {w.center[0] - p[0], w.center[1] - p[1], w.center[2] - p[2]};
    const double d2 = r[0] * r[0] + r[1] * r[1] + r[2] * r[2];
    const double d = std::sqrt(d2);
    const double gap = d - w.radius;
    const double node_bound = gap > 0 ? w.area * 3 * w.radius * w.radius / (gap * gap * gap * gap) : kRealMax;
    if (d > beta * w.radius && node_bound <= 4 * kPi * node_error) {
      // Solid angle = integral of n . (x - p) / |x - p|^3 over the triangles; expanded about
      // the centre c: N . r / d^3 + J : T with J = I / d^3 - 3 r r^T / d^5 (the Jacobian of
      // the kernel) and T = sum area n (c_t - c)^T. Remainder (Taylor, third derivatives of
      // 1 / |y| bounded by 3! / |y|^4 on lines): area * 3 radius^2 / (d - radius)^4.
      const double inv3 = 1 / (d2 * d);
      const double inv5 = inv3 / d2;
      double omega = (w.dipole[0] * r[0] + w.dipole[1] * r[1] + w.dipole[2] * r[2]) * inv3;
      omega += (w.second[0] + w.second[4] + w.second[8]) * inv3;
      double rtr = 0;
      for (std::size_t i = 0; i < 3; ++i) {
        for (std::size_t j = 0; j < 3; ++j) rtr += r[i] * w.second[3 * i + j] * r[j];
      }
      omega -= 3 * rtr * inv5;
      sum += omega;
      error += node_bound;
      continue;
    }
    stack[top++] = node.first;
    stack[top++] = node.first + 1;
  }
  error_bound = error / (4 * kPi);
  return sum / (4 * kPi);
}

bool mesh_contains_open(const MeshView& mesh, const Bvh& bvh, std::span<const WindingNode> nodes, const Vec3& point) {
  if (!is_finite(point) || mesh.triangles.empty()) return false;
  if (!bvh.empty() && nodes.size() == bvh.nodes().size()) {
    // Per-node error budgets of 1e-3, 1e-5, 1e-7 in turn (measured on the capless shared
    // icosphere: 21 us per point against 32 us for two passes and 270 us for the scan);
    // each answer stands when its error bound (plus a rounding margin) cannot move the
    // winding number across 1/2.
    for (const double node_error : {1e-3, 1e-5, 1e-7}) {
      double bound = 0;
      const double w = mesh_fast_winding_number(mesh, bvh, nodes, point, 2.0, node_error, bound);
      if (std::abs(w - 0.5) > bound + 1e-9) return w > 0.5;
    }
  }
  return mesh_winding_number(mesh, point) >= 0.5;
}

bool mesh_contains_bsp(const MeshView& mesh, const Bvh& bvh, const BspPolyhedron& bsp, const Vec3& point) {
  if (!is_finite(point) || mesh.triangles.empty()) return false;
  // Inside and Outside answers are exact away from the tree's tolerance band, which holds
  // every point within the reference's tolerance of the surface: those, and the rare
  // points near several planes, are OnBoundary and go to the reference.
  const Real tol = std::max(bsp.tolerance(), Real(2) * linear_tolerance(mesh.scale));
  switch (bsp.classify(point, tol)) {
    case PointClass::Inside: return true;
    case PointClass::Outside: return false;
    case PointClass::OnBoundary: break;
  }
  return mesh_contains(mesh, bvh, point);
}

MassProperties mesh_mass_properties(const MeshView& mesh, Real density) {
  MassProperties result;
  if (!mesh.closed || mesh.vertices.empty()) return result;
  double r[3] = {0, 0, 0};
  for (const Vec3& v : mesh.vertices) {
    for (int a = 0; a < 3; ++a) r[a] += double(v[a]);
  }
  for (double& x : r) x /= double(mesh.vertices.size());
  double volume = 0;
  double first[3] = {0, 0, 0};
  double cov[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  for (const TriangleIndices& t : mesh.triangles) {
    double q[3][3];
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < 3; ++i) q[k][i] = double(mesh.vertices[t[std::size_t(k)]][i]) - r[i];
    }
    const double* a = q[0];
    const double* b = q[1];
    const double* c = q[2];
    const double det =
        a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0]);
    const double s[3] = {a[0] + b[0] + c[0], a[1] + b[1] + c[1], a[2] + b[2] + c[2]};
    volume += det / 6.0;
    for (int i = 0; i < 3; ++i) first[i] += det / 24.0 * s[i];
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) cov[i][j] += det / 120.0 * (a[i] * a[j] + b[i] * b[j] + c[i] * c[j] + s[i] * s[j]);
    }
  }
  if (!(volume > 0)) return result;
  const double cen[3] = {first[0] / volume, first[1] / volume, first[2] / volume};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) cov[i][j] -= volume * cen[i] * cen[j];
  }
  const double trace = cov[0][0] + cov[1][1] + cov[2][2];
  const double rho = double(density);
  result.volume = Real(volume);
  result.mass = Real(rho * volume);
  result.centroid = Vec3(Real(r[0] + cen[0]), Real(r[1] + cen[1]), Real(r[2] + cen[2]));
  for (int col = 0; col < 3; ++col) {
    for (int row = 0; row < 3; ++row) {
      result.inertia[col][row] = Real(rho * ((col == row ? trace : 0.0) - cov[row][col]));
    }
  }
  return result;
}

}  // namespace detail

namespace {

detail::MeshView view_of(const TriangleMesh& mesh) {
  detail::MeshView v;
  v.vertices = mesh.vertices();
  v.triangles = mesh.triangles();
  v.closed = mesh.is_closed();
  v.scale = max_abs_component(mesh.local_aabb().extents());
  return v;
}

}  // namespace

bool TriangleMesh::contains(const Vec3& point) const {
  detail::MeshView v = view_of(*this);
  v.neighbors = data_->neighbors;
  const detail::MeshPointCacheState& cache = data_->derived->point_cache.get([&] {
    detail::MeshPointCacheState built;
    if (v.closed) {
      Result<BspPolyhedron> bsp = BspPolyhedron::create(data_->mesh);
      if (bsp) built.bsp = std::move(bsp.value());
    } else {
      built.winding = detail::build_winding_nodes(v, data_->bvh);
    }
    return built;
  });
  if (v.closed) {
    return cache.bsp ? detail::mesh_contains_bsp(v, data_->bvh, *cache.bsp, point)
                     : detail::mesh_contains(v, data_->bvh, point);
  }
  return detail::mesh_contains_open(v, data_->bvh, cache.winding, point);
}

SurfacePoint TriangleMesh::closest_point(const Vec3& point) const {
  detail::MeshView v = view_of(*this);
  v.neighbors = data_->neighbors;
  return detail::mesh_closest_point(v, data_->bvh, point);
}

MassProperties TriangleMesh::mass_properties(Real density) const {
  detail::MeshView v = view_of(*this);
  v.neighbors = data_->neighbors;
  return detail::mesh_mass_properties(v, density);
}

}  // namespace proxima
