/// @file triangle_mesh.cpp
/// TriangleMesh: creation (repair or analysis, BVH, adjacency, active edges), deformation,
/// bounds and ray casts. Point queries (contains, closest_point, mass_properties) are in
/// triangle_mesh_point_queries.cpp.
///
/// Steps of create: repair_mesh (or analyse_mesh) the input; build the binned-SAH Bvh over
/// the triangle boxes (centres = box centres); find the triangle across each edge by
/// sorting the 3n edges on their (smaller, larger) vertex pair (exactly two uses = manifold
/// neighbours, else kNoIndex); flag each edge active unless its two triangles meet within
/// flat_edge_angle of flat or concavely (the internal-edge idea of Bullet's
/// btInternalEdgeUtility and of Jolt's active edges).
///
/// Ray casts traverse by default the 4-wide hierarchy of ray_bvh.hpp (collapsed from the
/// binary BVH at creation: float child boxes rounded outward, four slab tests at once,
/// nearest child first, leaves as four-triangle blocks with a SIMD conservative rejection),
/// and otherwise (RayTraversal::Binary, or rays and meshes the float layout cannot bound)
/// the binary BVH front to back (the nearer child by slab entry first, subtrees beyond the
/// best hit so far skipped) with the robust slab test of Ize ("Robust BVH Ray Traversal",
/// JCGT 2013: the exit distance widened by 1 + 2 gamma(3) so that rounding never culls a box
/// the ray touches). Both end in the same per-triangle step (cast_triangle): an inline
/// conservative rejection (the edge functions of Woop, Benthin and Wald in Real with a
/// rounding-error bound, so it only skips triangles the exact test would miss), then the
/// watertight test of Woop, Benthin and Wald (JCGT 2013) on a TriangleRay prepared once per
/// ray, then the culling rule; so both traversals give the same hits, bit for bit. Leaves
/// read the triangle corners from copies stored in leaf order.

#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/raycast.hpp>
#include <proxima/shapes/triangle_mesh.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>

#include "shapes/ray_bvh.hpp"
#include "shapes/triangle_mesh_derived.hpp"

namespace proxima {
namespace {

/// Box of triangle t.
inline Aabb triangle_box(const IndexedMesh& m, const TriangleIndices& t) {
  const Vec3& a = m.vertices[t[0]];
  const Vec3& b = m.vertices[t[1]];
  const Vec3& c = m.vertices[t[2]];
  return {glm::min(a, glm::min(b, c)), glm::max(a, glm::max(b, c))};
}

/// Triangle boxes and their centres.
void triangle_boxes(const IndexedMesh& m, std::vector<Aabb>& boxes, std::vector<Vec3>* centers) {
  const std::size_t n = m.triangles.size();
  boxes.resize(n);
  if (centers) centers->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    boxes[i] = triangle_box(m, m.triangles[i]);
    if (centers) (*centers)[i] = boxes[i].center();
  }
}

/// Corners of the triangles in BVH leaf order.
void gather_leaf_triangles(const IndexedMesh& m, const Bvh& bvh, std::vector<std::array<Vec3, 3>>& out) {
  const std::span<const std::uint32_t> prims = bvh.primitives();
  out.resize(prims.size());
  for (std::size_t i = 0; i < prims.size(); ++i) {
    const TriangleIndices& t = m.triangles[prims[i]];
    out[i] = {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
  }
}

/// The derived data of a mesh with these triangles and hierarchy.
std::shared_ptr<detail::MeshDerived> derive(const IndexedMesh& m, const Bvh& bvh) {
  auto d = std::make_shared<detail::MeshDerived>();
  gather_leaf_triangles(m, bvh, d->leaf_triangles);
  d->ray_bvh = detail::RayBvh::build(bvh, d->leaf_triangles);
  return d;
}

/// Triangle across each edge (kNoIndex for boundary and non-manifold edges). The 3n edge
/// uses are bucketed by their smaller vertex (counting sort, in slot order), each bucket is
/// ordered by the larger vertex (then slot), and a (smaller, larger) pair used exactly twice
/// joins two triangles. O(n + V) apart from the small per-vertex sorts.
void compute_neighbors(const IndexedMesh& m, std::vector<std::array<std::uint32_t, 3>>& neighbors) {
  const std::size_t n = m.triangles.size();
  const std::size_t nv = m.vertices.size();
  neighbors.assign(n, {kNoIndex, kNoIndex, kNoIndex});
  struct EdgeUse {
    std::uint32_t larger;  // larger vertex of the edge
    std::uint32_t slot;    // 3 * triangle + edge
  };
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (const TriangleIndices& t : m.triangles)
    for (std::size_t e = 0; e < 3; ++e) ++start[std::min(t[e], t[(e + 1) % 3]) + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<EdgeUse> uses(3 * n);
  {
    std::vector<std::uint32_t> cursor(start.begin(), start.end() - 1);
    for (std::size_t i = 0; i < n; ++i) {
      const TriangleIndices& t = m.triangles[i];
      for (std::size_t e = 0; e < 3; ++e) {
        const std::uint32_t u = t[e];
        const std::uint32_t v = t[(e + 1) % 3];
        uses[cursor[std::min(u, v)]++] = {std::max(u, v), static_cast<std::uint32_t>(3 * i + e)};
      }
    }
  }
  const auto before = [](const EdgeUse& a, const EdgeUse& b) {
    return a.larger < b.larger || (a.larger == b.larger && a.slot < b.slot);
  };
  for (std::size_t v = 0; v < nv; ++v) {
    EdgeUse* first = uses.data() + start[v];
    EdgeUse* last = uses.data() + start[v + 1];
    if (last - first <= 16) {
      for (EdgeUse* p = first + 1; p < last; ++p)  // insertion sort (buckets are tiny)
        for (EdgeUse* q = p; q > first && before(*q, *(q - 1)); --q) std::swap(*q, *(q - 1));
    } else {
      std::sort(first, last, before);
    }
    for (EdgeUse* p = first; p < last;) {
      EdgeUse* q = p + 1;
      while (q < last && q->larger == p->larger) ++q;
      if (q - p == 2) {
        const std::uint32_t s0 = p[0].slot;
        const std::uint32_t s1 = p[1].slot;
        neighbors[s0 / 3][s0 % 3] = s1 / 3;
        neighbors[s1 / 3][s1 % 3] = s0 / 3;
      }
      p = q;
    }
  }
}

/// Active-edge bits from the neighbours and the dihedral angles.
void compute_active_edges(const IndexedMesh& m, const std::vector<std::array<std::uint32_t, 3>>& neighbors,
                          Real flat_edge_angle, std::vector<std::uint8_t>& active) {
  const std::size_t n = m.triangles.size();
  active.assign(n, 0);
  const Real cos_flat = std::cos(std::clamp(flat_edge_angle, Real(0), Real(3.14159265358979)));
  for (std::size_t i = 0; i < n; ++i) {
    const TriangleIndices& t = m.triangles[i];
    const Vec3& a = m.vertices[t[0]];
    const Vec3 nt = glm::cross(m.vertices[t[1]] - a, m.vertices[t[2]] - a);
    const Real lt = glm::length(nt);
    std::uint8_t bits = 0;
    for (std::size_t e = 0; e < 3; ++e) {
      const std::uint32_t other = neighbors[i][e];
      if (other == kNoIndex) {
        bits = static_cast<std::uint8_t>(bits | (1u << e));
        continue;
      }
      const TriangleIndices& u = m.triangles[other];
      const std::uint32_t v0 = t[e];
      const std::uint32_t v1 = t[(e + 1) % 3];
      // The neighbour's vertex off the shared edge, and whether it runs the edge the other way.
      std::size_t apex = 0;
      bool opposite = false;
      for (std::size_t k = 0; k < 3; ++k) {
        if (u[k] != v0 && u[k] != v1) apex = k;
        if (u[k] == v1 && u[(k + 1) % 3] == v0) opposite = true;
      }
      const Vec3& ua = m.vertices[u[0]];
      const Vec3 nu = glm::cross(m.vertices[u[1]] - ua, m.vertices[u[2]] - ua);
      const Real lu = glm::length(nu);
      if (!opposite || !(lt > Real(0)) || !(lu > Real(0))) {  // inconsistent or degenerate: keep
        bits = static_cast<std::uint8_t>(bits | (1u << e));
        continue;
      }
      const Real cos_angle = glm::dot(nt, nu) / (lt * lu);
      if (cos_angle >= cos_flat) continue;  // flat: inactive
      // Convex when the neighbour's apex lies below this triangle's plane.
      const Real height = glm::dot(nt, m.vertices[u[apex]] - a);
      if (height < Real(0)) bits = static_cast<std::uint8_t>(bits | (1u << e));
    }
    active[i] = bits;
  }
}

/// The ray prepared for box tests: origin and inverse direction. A zero (or subnormal)
/// direction component gets inverse 1 and is flagged: the slab of that axis is then all of t
/// when the origin lies in it and none otherwise (no 0 * inf, so no NaN).
struct BoxRay {
  Vec3 origin;
  Vec3 inv;
  bool zero[3] = {false, false, false};
  bool any_zero = false;
};

inline BoxRay prepare_box_ray(const Ray& ray) {
  BoxRay r{ray.origin, Vec3(1)};
  for (int a = 0; a < 3; ++a) {
    const Real d = ray.direction[a];
    if (std::abs(d) >= std::numeric_limits<Real>::min()) {
      r.inv[a] = Real(1) / d;
    } else {
      r.zero[a] = true;
      r.any_zero = true;
    }
  }
  return r;
}

/// 1 + 2 gamma(3) of Ize 2013 (gamma(n) = n eps / (1 - n eps), eps = half an ulp of 1).
constexpr Real kSlabWiden =
    Real(1) + Real(2) * (Real(3) * kEpsilon * Real(0.5)) / (Real(1) - Real(3) * kEpsilon * Real(0.5));

/// Slab test: true when the ray's [0, t_max] meets the node box; `t_near` gets the entry.
inline bool slab(const BvhNode& node, const BoxRay& r, Real t_max, Real& t_near) {
  const Vec3 t0 = (node.min - r.origin) * r.inv;
  const Vec3 t1 = (node.max - r.origin) * r.inv;
  Vec3 lo = glm::min(t0, t1);
  Vec3 hi = glm::max(t0, t1);
  if (r.any_zero) {  // rare: axis-parallel rays
    for (int a = 0; a < 3; ++a) {
      if (!r.zero[a]) continue;
      if (r.origin[a] < node.min[a] || r.origin[a] > node.max[a]) return false;
      lo[a] = -kRealMax;
      hi[a] = kRealMax;
    }
  }
  const Real tn = std::max(std::max(lo.x, lo.y), std::max(lo.z, Real(0)));
  const Real tf = std::min(std::min(hi.x, hi.y), std::min(hi.z, t_max)) * kSlabWiden;
  t_near = tn;
  return tn <= tf;
}

/// Conservative inline rejection before the exact watertight test: the edge functions of
/// Woop et al. in Real on the sheared vertices, with a bound on their rounding error (vs
/// the exact values, and so vs the exact test's own) of 16 eps (|b_x c_y| + |b_y c_x|) in
/// magnitudes. False only when two edge functions have opposite signs beyond that bound,
/// i.e. when ray_triangle surely misses; true sends the triangle to ray_triangle.
inline bool may_hit(const geometry::TriangleRay& r, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ra = a - r.ray.origin;
  const Vec3 rb = b - r.ray.origin;
  const Vec3 rc = c - r.ray.origin;
  const int kx = r.kx, ky = r.ky, kz = r.kz;
  const Real sx = r.shear.x, sy = r.shear.y;
  const Real ax = ra[kx] - sx * ra[kz], ay = ra[ky] - sy * ra[kz];
  const Real bx = rb[kx] - sx * rb[kz], by = rb[ky] - sy * rb[kz];
  const Real cx = rc[kx] - sx * rc[kz], cy = rc[ky] - sy * rc[kz];
  const Real max_ax = std::abs(ra[kx]) + std::abs(sx * ra[kz]), max_ay = std::abs(ra[ky]) + std::abs(sy * ra[kz]);
  const Real max_bx = std::abs(rb[kx]) + std::abs(sx * rb[kz]), max_by = std::abs(rb[ky]) + std::abs(sy * rb[kz]);
  const Real max_cx = std::abs(rc[kx]) + std::abs(sx * rc[kz]), max_cy = std::abs(rc[ky]) + std::abs(sy * rc[kz]);
  const Real u = bx * cy - by * cx;
  const Real v = cx * ay - cy * ax;
  const Real w = ax * by - ay * bx;
  constexpr Real k = Real(16) * kEpsilon;
  const Real eu = k * (max_bx * max_cy + max_by * max_cx);
  const Real ev = k * (max_cx * max_ay + max_cy * max_ax);
  const Real ew = k * (max_ax * max_by + max_ay * max_bx);
  const bool some_negative = u < -eu || v < -ev || w < -ew;
  const bool some_positive = u > eu || v > ev || w > ew;
  return !(some_negative && some_positive);
}

/// may_hit's products cannot overflow when the origin, like every vertex, is within
/// kMaxCoordinate (the shear factors are at most 1 in magnitude).
inline bool filter_applies(const Ray& ray) {
  return std::abs(ray.origin.x) <= kMaxCoordinate && std::abs(ray.origin.y) <= kMaxCoordinate &&
         std::abs(ray.origin.z) <= kMaxCoordinate;
}

/// True when the hit on triangle (a, b, c) passes `culling`.
inline bool passes_culling(FaceCulling culling, const RayHit& hit, const Vec3& a, const Vec3& b, const Vec3& c) {
  if (culling == FaceCulling::None) return true;
  const Real side = glm::dot(hit.normal, glm::cross(b - a, c - a));  // > 0: hit from the front
  return culling == FaceCulling::Back ? side > Real(0) : side < Real(0);
}

/// Stack entry of the ordered traversal.
struct StackEntry {
  std::uint32_t node;
  Real t_near = Real(0);
};

}  // namespace

Result<TriangleMesh> TriangleMesh::create(IndexedMesh mesh, const MeshCreateOptions& options) {
  auto data = std::make_shared<Data>();
  if (options.repair) {
    Result<RepairedMesh> repaired = repair_mesh(mesh, options.repair_options);
    if (!repaired) return repaired.error();
    data->mesh = std::move(repaired.value().mesh);
    data->report = repaired.value().report;
  } else {
    Result<MeshReport> report = analyse_mesh(mesh);
    if (!report) return report.error();
    data->report = report.value();
    data->mesh = std::move(mesh);
  }
  if (data->mesh.triangles.empty()) return make_error(ErrorCode::TooFew, "triangles", "no triangle left after repair");
  if (data->mesh.triangles.size() >= std::size_t(kNoIndex) / 3)
    return make_error(ErrorCode::OutOfRange, "triangles", "too many triangles");
  std::vector<Aabb> boxes;
  std::vector<Vec3> centers;
  triangle_boxes(data->mesh, boxes, &centers);
  data->bvh = Bvh::build(boxes, centers, options.bvh);
  data->derived = derive(data->mesh, data->bvh);
  compute_neighbors(data->mesh, data->neighbors);
  compute_active_edges(data->mesh, data->neighbors, options.flat_edge_angle, data->active_edges);
  data->flat_edge_angle = options.flat_edge_angle;
  return TriangleMesh(std::move(data));
}

Result<TriangleMesh> TriangleMesh::deformed(std::span<const Vec3> vertices) const {
  if (vertices.size() != data_->mesh.vertices.size())
    return make_error(ErrorCode::InvalidArgument, "vertices",
                      "expected " + std::to_string(data_->mesh.vertices.size()) + " vertices, got " +
                          std::to_string(vertices.size()));
  static constexpr const char* kAxis[3] = {".x", ".y", ".z"};
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      const Real x = vertices[i][a];
      const std::string field = "vertices[" + std::to_string(i) + "]";
      if (!std::isfinite(x)) return make_error(ErrorCode::NotFinite, field + kAxis[a], "not finite");
      if (std::abs(x) > kMaxCoordinate)
        return make_error(ErrorCode::OutOfRange, field + kAxis[a], "beyond kMaxCoordinate");
    }
  }
  auto data = std::make_shared<Data>(*data_);
  data->mesh.vertices.assign(vertices.begin(), vertices.end());
  std::vector<Aabb> boxes;
  triangle_boxes(data->mesh, boxes, nullptr);
  data->bvh.refit(boxes);
  data->derived = derive(data->mesh, data->bvh);
  compute_active_edges(data->mesh, data->neighbors, data->flat_edge_angle, data->active_edges);
  // Volume and area follow the vertices (divergence theorem, as in the analysis).
  Real volume = Real(0);
  Real area = Real(0);
  for (const TriangleIndices& t : data->mesh.triangles) {
    const Vec3& a = data->mesh.vertices[t[0]];
    const Vec3& b = data->mesh.vertices[t[1]];
    const Vec3& c = data->mesh.vertices[t[2]];
    volume += glm::dot(a, glm::cross(b, c)) / Real(6);
    area += glm::length(glm::cross(b - a, c - a)) * Real(0.5);
  }
  data->report.volume = volume;
  data->report.surface_area = area;
  return TriangleMesh(std::move(data));
}

Aabb TriangleMesh::world_aabb(const Transform& pose) const {
  const Mat3 r = pose.rotation_matrix();
  Aabb box = Aabb::empty();
  for (const Vec3& v : data_->mesh.vertices) box.grow(r * v);
  if (!box.is_valid()) return box;
  return {box.min + pose.position, box.max + pose.position};
}

namespace {

/// A ray prepared once for the triangle tests of a mesh cast.
struct MeshRay {
  geometry::TriangleRay tri;  ///< watertight test's permutation and shear
  bool filter = false;        ///< may_hit (and filter_block) apply
  FaceCulling culling = FaceCulling::None;
  detail::BlockRay block;  ///< the same permutation and shear for filter_block
};

inline MeshRay prepare_mesh_ray(const Ray& ray, FaceCulling culling, const geometry::TriangleRay& tri) {
  MeshRay r{tri, filter_applies(ray), culling, {}};
  const int k[3] = {r.tri.kx, r.tri.ky, r.tri.kz};
  for (int i = 0; i < 3; ++i) r.block.origin[i] = ray.origin[k[i]];
  r.block.sx = r.tri.shear.x;
  r.block.sy = r.tri.shear.y;
  r.block.kx = r.tri.kx;
  r.block.ky = r.tri.ky;
  r.block.kz = r.tri.kz;
  return r;
}

inline MeshRay prepare_mesh_ray(const Ray& ray, FaceCulling culling) {
  return prepare_mesh_ray(ray, culling, geometry::TriangleRay::prepare(ray));
}

/// The exact test of one triangle in a mesh ray cast, shared by every cast and both
/// traversals: the conservative rejection (when it applies), the watertight test within
/// [0, limit], then the culling rule.
/// `filtered`: the rejection was already applied (by filter_block).
inline std::optional<RayHit> cast_triangle(const MeshRay& r, Real limit, const std::array<Vec3, 3>& t,
                                           bool filtered = false) {
  if (r.filter && !filtered && !may_hit(r.tri, t[0], t[1], t[2])) return std::nullopt;
  std::optional<RayHit> hit = geometry::ray_triangle(r.tri, limit, t[0], t[1], t[2]);
  if (hit && !passes_culling(r.culling, *hit, t[0], t[1], t[2])) return std::nullopt;
  return hit;
}

/// Closest hit so far, with the tie rule (equal t: lower triangle index).
struct ClosestHit {
  Real max_t;
  std::optional<RayHit> best;
  Real best_t;

  explicit ClosestHit(Real max) : max_t(max), best_t(max) {}

  /// Limit of the triangle test for the next leaf: one ulp beyond the best, since the test
  /// compares its unrounded t with the limit and a hit that rounds to the same t must still
  /// reach the tie rule.
  Real limit() const { return best ? std::min(max_t, std::nextafter(best_t, kRealMax)) : max_t; }

  void visit(const MeshRay& r, Real limit, const std::array<Vec3, 3>& corners, std::uint32_t tri,
             bool filtered = false) {
    const std::optional<RayHit> hit = cast_triangle(r, limit, corners, filtered);
    if (!hit) return;
    if (best && (hit->t > best->t || (hit->t == best->t && tri > best->sub.triangle))) return;
    best = *hit;
    best->sub.triangle = tri;
    best_t = hit->t;
  }
};

/// What the ray casts read of a mesh.
struct MeshParts {
  const IndexedMesh& mesh;
  const Bvh& bvh;
  const detail::MeshDerived& derived;
};

/// The 4-wide hierarchy of `d` when `traversal` asks for it and it exists.
inline const detail::RayBvh* wide_of(const detail::MeshDerived& d, RayTraversal traversal) {
  if (traversal != RayTraversal::Wide || d.ray_bvh.nodes.empty()) return nullptr;
  return &d.ray_bvh;
}

/// Calls `visit(slot, corners) -> bool` (false stops) for each triangle of the wide leaf starting at
/// block `first` with `count` triangles that filter_block keeps (all of them when the
/// rejection does not apply). Returns false when stopped.
template <class Visit>
bool visit_wide_leaf(const detail::RayBvh& wide, std::uint32_t first, std::uint32_t count, const MeshRay& r,
                     Visit&& visit) {
  for (std::uint32_t b = first; count != 0; ++b) {
    const detail::TriangleBlock4& block = wide.blocks[b];
    count -= block.count;
    unsigned mask = r.filter ? detail::filter_block(block, r.block) : (1u << block.count) - 1u;
    for (; mask != 0; mask &= mask - 1) {
      const auto lane = static_cast<std::uint32_t>(std::countr_zero(mask));
      const std::array<Vec3, 3> corners{Vec3(block.v[0][0][lane], block.v[0][1][lane], block.v[0][2][lane]),
                                        Vec3(block.v[1][0][lane], block.v[1][1][lane], block.v[1][2][lane]),
                                        Vec3(block.v[2][0][lane], block.v[2][1][lane], block.v[2][2][lane])};
      if (!visit(block.slot + lane, corners)) return false;
    }
  }
  return true;
}

/// Calls `visit(corners, triangle, filtered) -> bool` (false stops) for every triangle of every leaf
/// whose box the ray meets within [0, max_t], through the chosen hierarchy, in no
/// particular order. Returns false when stopped.
template <class Visit>
bool for_each_candidate(const MeshParts& d, const Ray& ray, const MeshRay& r, Real max_t, RayTraversal traversal,
                        Visit&& visit) {
  if (const detail::RayBvh* wide = wide_of(d.derived, traversal)) {
    const detail::WideRay w = detail::prepare_wide_ray(ray);
    if (w.valid) {
      const std::span<const std::uint32_t> prims = d.bvh.primitives();
      bool go_on = true;
      detail::traverse_wide(
          *wide, w, detail::round_up_float(max_t), [&](std::uint32_t first, std::uint32_t count, float&) {
            go_on = visit_wide_leaf(*wide, first, count, r, [&](std::uint32_t i, const std::array<Vec3, 3>& corners) {
              return visit(corners, prims[i], true);
            });
            return go_on;
          });
      return go_on;
    }
  }
  const BoxRay box_ray = prepare_box_ray(ray);
  Real t_near = Real(0);
  const std::vector<Vec3>& verts = d.mesh.vertices;
  return d.bvh.traverse([&](const BvhNode& node) { return slab(node, box_ray, max_t, t_near); },
                        [&](std::uint32_t tri) {
                          const TriangleIndices& t = d.mesh.triangles[tri];
                          return visit(std::array<Vec3, 3>{verts[t[0]], verts[t[1]], verts[t[2]]}, tri, false);
                        });
}

/// Closest hit through the binary hierarchy, front to back (the reference traversal).
void closest_binary(const MeshParts& d, const Ray& ray, const MeshRay& r, ClosestHit& closest) {
  const BoxRay box_ray = prepare_box_ray(ray);
  const std::span<const BvhNode> nodes = d.bvh.nodes();
  const std::span<const std::uint32_t> prims = d.bvh.primitives();
  StackEntry stack[Bvh::kMaxDepth + 1];
  std::uint32_t top = 0;
  Real t_root = Real(0);
  if (!slab(nodes[0], box_ray, closest.best_t, t_root)) return;
  std::uint32_t current = 0;
  while (true) {
    const BvhNode& node = nodes[current];
    if (node.is_leaf()) {
      const Real limit = closest.limit();
      for (std::uint32_t i = node.first; i != node.first + node.count; ++i)
        closest.visit(r, limit, d.derived.leaf_triangles[i], prims[i]);
    } else {
      Real t_left = Real(0), t_right = Real(0);
      const bool hit_left = slab(nodes[node.first], box_ray, closest.best_t, t_left);
      const bool hit_right = slab(nodes[node.first + 1], box_ray, closest.best_t, t_right);
      if (hit_left && hit_right) {
        if (t_right < t_left) {
          stack[top++] = {node.first, t_left};
          current = node.first + 1;
        } else {
          stack[top++] = {node.first + 1, t_right};
          current = node.first;
        }
        continue;
      }
      if (hit_left) {
        current = node.first;
        continue;
      }
      if (hit_right) {
        current = node.first + 1;
        continue;
      }
    }
    // Pop the next subtree that may still hold a hit no farther than the best.
    bool found = false;
    while (top != 0) {
      const StackEntry& e = stack[--top];
      if (e.t_near <= closest.best_t * kSlabWiden) {
        current = e.node;
        found = true;
        break;
      }
    }
    if (!found) break;
  }
}

}  // namespace

std::optional<RayHit> TriangleMesh::raycast(const Ray& ray, Real max_t, FaceCulling culling,
                                            RayTraversal traversal) const {
  const MeshParts d{data_->mesh, data_->bvh, *data_->derived};
  if (d.bvh.empty() || !(max_t >= Real(0))) return std::nullopt;
  ClosestHit closest(max_t);
  if (const detail::RayBvh* wide = wide_of(d.derived, traversal)) {
    const detail::WideRay w = detail::prepare_wide_ray(ray);
    if (w.valid) {  // then the triangle ray is valid too (finite origin, non-zero direction)
      const std::span<const std::uint32_t> prims = d.bvh.primitives();
      MeshRay r{};
      bool prepared = false;  // prepared at the first leaf: many rays reach none
      detail::traverse_wide(
          *wide, w, detail::round_up_float(max_t), [&](std::uint32_t first, std::uint32_t count, float& t_max) {
            if (!prepared) {
              r = prepare_mesh_ray(ray, culling, geometry::TriangleRay::prepare(ray));
              prepared = true;
            }
            const Real limit = closest.limit();
            visit_wide_leaf(*wide, first, count, r, [&](std::uint32_t i, const std::array<Vec3, 3>& corners) {
              closest.visit(r, limit, corners, prims[i], true);
              return true;
            });
            if (closest.best) t_max = detail::round_up_float(closest.best_t);
            return true;
          });
      return closest.best;
    }
  }
  const MeshRay r = prepare_mesh_ray(ray, culling);
  if (!r.tri.valid) return std::nullopt;
  closest_binary(d, ray, r, closest);
  return closest.best;
}

bool TriangleMesh::raycast_any(const Ray& ray, Real max_t, FaceCulling culling, RayTraversal traversal) const {
  const MeshParts d{data_->mesh, data_->bvh, *data_->derived};
  if (d.bvh.empty() || !(max_t >= Real(0))) return false;
  const MeshRay r = prepare_mesh_ray(ray, culling);
  if (!r.tri.valid) return false;
  return !for_each_candidate(d, ray, r, max_t, traversal,
                             [&](const std::array<Vec3, 3>& corners, std::uint32_t, bool filtered) {
                               return !cast_triangle(r, max_t, corners, filtered).has_value();
                             });
}

void TriangleMesh::raycast_all(const Ray& ray, Real max_t, std::vector<RayHit>& hits, FaceCulling culling,
                               RayTraversal traversal) const {
  const MeshParts d{data_->mesh, data_->bvh, *data_->derived};
  if (d.bvh.empty() || !(max_t >= Real(0))) return;
  const MeshRay r = prepare_mesh_ray(ray, culling);
  if (!r.tri.valid) return;
  const std::size_t start = hits.size();
  for_each_candidate(d, ray, r, max_t, traversal,
                     [&](const std::array<Vec3, 3>& corners, std::uint32_t tri, bool filtered) {
                       if (std::optional<RayHit> hit = cast_triangle(r, max_t, corners, filtered)) {
                         hit->sub.triangle = tri;
                         hits.push_back(*hit);
                       }
                       return true;
                     });
  std::sort(hits.begin() + static_cast<std::ptrdiff_t>(start), hits.end(), [](const RayHit& x, const RayHit& y) {
    return x.t < y.t || (x.t == y.t && x.sub.triangle < y.sub.triangle);
  });
}

}  // namespace proxima
