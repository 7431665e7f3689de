// Analysis and repair of an indexed triangle mesh.
//
// Steps (repair_mesh; analyse_mesh runs only 1 and 7):
//  1. Validate: at least one triangle, every index inside the vertex array, every coordinate
//     finite and within kMaxCoordinate.
//  2. Weld: vertices are binned in a uniform grid of cell size weld_distance (cells as
//     sorted integer keys, so no hash table); each vertex, in index order, merges into the
//     lowest-index earlier representative within weld_distance found in the 27 surrounding
//     cells (9 key ranges). Distance zero welds exact duplicates only (lexicographic sort).
//  3. Degenerate triangles: a repeated index, or twice the area below kRelativeTolerance
//     times the longest edge squared (the same test as Triangle::create).
//  4. Duplicate triangles: the same vertex set as an earlier triangle (either winding).
//  5. Unused vertices are dropped and the indices remapped.
//  6. Orientation: an edge map (undirected edge keys sorted) links the two triangles of
//     every manifold edge; a breadth-first search flips a neighbour that traverses the shared
//     edge in the same direction. Each such patch is then turned outward by the sign of its
//     volume when it is closed, else to the winding most of its triangles had.
//  7. Report: edge map counts (boundary, non-manifold, inconsistent), edge-connected
//     components by union-find, volume by the divergence theorem (sum of signed tetrahedra
//     against a reference point, in double) and surface area.
// References: Botsch, Kobbelt, Pauly, Alliez, Levy, "Polygon Mesh Processing" (2010),
// ch. 2 (halfedge consistency) and ch. 3 (repair); Zhang & Chen, "Efficient feature
// extraction for 2D/3D objects in mesh representation" (ICIP 2001) for the volume formula.
#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/shapes/indexed_mesh.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "shapes/double_vector.hpp"

namespace proxima {
namespace {

using detail::D3;

constexpr std::uint32_t kNone = 0xffffffffu;

std::optional<Error> validate_mesh(const IndexedMesh& mesh) {
  if (mesh.triangles.empty()) return make_error(ErrorCode::TooFew, "triangles", "the mesh has no triangle");
  if (mesh.vertices.size() > std::size_t(std::numeric_limits<std::uint32_t>::max())) {
    return make_error(ErrorCode::OutOfRange, "vertices", "more vertices than 32-bit indices can address");
  }
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (auto e = validate::finite(mesh.vertices[i], "vertices[" + std::to_string(i) + "]")) return e;
  }
  const std::size_t n = mesh.vertices.size();
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (std::size_t k = 0; k < 3; ++k) {
      if (mesh.triangles[t][k] >= n) {
        return make_error(
            ErrorCode::OutOfRange, "triangles[" + std::to_string(t) + "][" + std::to_string(k) + "]",
            "index " + std::to_string(mesh.triangles[t][k]) + " is past the " + std::to_string(n) + " vertices");
      }
    }
  }
  return std::nullopt;
}

/// A repeated index, or twice the area (double) at most kRelativeTolerance times the
/// longest edge squared.
bool is_degenerate(const IndexedMesh& mesh, const TriangleIndices& t) {
  if (t[0] == t[1] || t[1] == t[2] || t[2] == t[0]) return true;
  const D3 a = detail::to_d3(mesh.vertices[t[0]]);
  const D3 b = detail::to_d3(mesh.vertices[t[1]]);
  const D3 c = detail::to_d3(mesh.vertices[t[2]]);
  const double longest =
      std::max({detail::norm(detail::sub(b, a)), detail::norm(detail::sub(c, b)), detail::norm(detail::sub(a, c))});
  const double twice_area = detail::norm(detail::cross(detail::sub(b, a), detail::sub(c, a)));
  return !(twice_area > double(kRelativeTolerance) * longest * longest);
}

std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t(a) << 32) | b : (std::uint64_t(b) << 32) | a;
}

/// One use of an undirected edge: triangle, slot (edge from vertex slot to slot+1) and
/// whether it runs from the lower to the higher vertex index.
struct EdgeUse {
  std::uint64_t key;
  std::uint32_t triangle;
  std::uint8_t slot;
  bool forward;
};

/// Every edge use of the non-repeated-index triangles, sorted by key.
std::vector<EdgeUse> edge_uses(const std::vector<TriangleIndices>& triangles) {
  std::vector<EdgeUse> uses;
  uses.reserve(triangles.size() * 3);
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const TriangleIndices& tri = triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) continue;
    for (std::uint8_t e = 0; e < 3; ++e) {
      const std::uint32_t a = tri[e];
      const std::uint32_t b = tri[(e + 1) % 3];
      uses.push_back({edge_key(a, b), static_cast<std::uint32_t>(t), e, a < b});
    }
  }
  std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
    return x.key != y.key ? x.key < y.key : x.triangle < y.triangle;
  });
  return uses;
}

/// Disjoint sets with path halving and union by index.
struct UnionFind {
  std::vector<std::uint32_t> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  std::uint32_t find(std::uint32_t x) {
    while (parent[x] != x) {
      parent[x] = parent[parent[x]];
      x = parent[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

/// Step 7: the report of `mesh` (input_* and repair counters left at zero).
MeshReport analyse(const IndexedMesh& mesh) {
  MeshReport r;
  const auto& tris = mesh.triangles;
  for (const TriangleIndices& t : tris) {
    if (is_degenerate(mesh, t)) ++r.degenerate_triangles;
  }

  const std::vector<EdgeUse> uses = edge_uses(tris);
  UnionFind sets(tris.size());
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    const std::size_t count = j - i;
    if (count == 1) ++r.boundary_edges;
    if (count > 2) ++r.non_manifold_edges;
    if (count == 2 && uses[i].forward == uses[i + 1].forward) ++r.inconsistent_edges;
    for (std::size_t k = i + 1; k < j; ++k) sets.unite(uses[i].triangle, uses[k].triangle);
    i = j;
  }
  for (std::uint32_t t = 0; t < tris.size(); ++t) {
    if (sets.find(t) == t) ++r.components;
  }
  r.closed = !tris.empty() && !uses.empty() && r.boundary_edges == 0 && r.non_manifold_edges == 0;
  r.oriented = r.inconsistent_edges == 0;

  // Volume and area in double, against the first vertex of the first triangle as the
  // reference point (keeps the tetrahedra small for meshes far from the origin).
  double volume6 = 0;
  double area2 = 0;
  if (!tris.empty()) {
    const D3 o = detail::to_d3(mesh.vertices[tris[0][0]]);
    for (const TriangleIndices& t : tris) {
      const D3 a = detail::sub(detail::to_d3(mesh.vertices[t[0]]), o);
      const D3 b = detail::sub(detail::to_d3(mesh.vertices[t[1]]), o);
      const D3 c = detail::sub(detail::to_d3(mesh.vertices[t[2]]), o);
      volume6 += detail::dot(a, detail::cross(b, c));
      area2 += detail::norm(detail::cross(detail::sub(b, a), detail::sub(c, a)));
    }
  }
  r.volume = static_cast<Real>(volume6 / 6.0);
  r.surface_area = static_cast<Real>(area2 / 2.0);
  return r;
}

/// Step 2: representative of every vertex (rep[i] <= i) for welding within `distance`.
std::vector<std::uint32_t> weld(const std::vector<Vec3>& v, double distance) {
  const std::size_t n = v.size();
  std::vector<std::uint32_t> rep(n);
  std::iota(rep.begin(), rep.end(), 0u);
  if (n < 2) return rep;
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);

  if (!(distance > 0)) {
    // Exact duplicates: sort lexicographically, each run maps to its lowest index.
    auto less = [&](std::uint32_t a, std::uint32_t b) {
      const Vec3& p = v[a];
      const Vec3& q = v[b];
      if (p.x != q.x) return p.x < q.x;
      if (p.y != q.y) return p.y < q.y;
      if (p.z != q.z) return p.z < q.z;
      return a < b;
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 1; i < n; ++i) {
      const std::uint32_t a = order[i - 1];
      const std::uint32_t b = order[i];
      if (v[a] == v[b]) rep[b] = rep[a];
    }
    return rep;
  }

  // Grid cells keyed by clamped integer coordinates (clamping keeps neighbours adjacent).
  D3 lo = detail::to_d3(v[0]);
  D3 hi = lo;
  for (const Vec3& p : v) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], double(p[a]));
      hi[a] = std::max(hi[a], double(p[a]));
    }
  }
  constexpr double kMaxCell = double(1 << 20) - 2;  // 21 bits per axis in a 64-bit key
  // Cells no smaller than the weld distance (neighbours within it are in the 27 cells around)
  // and no more than kMaxCell per axis: a tiny distance (double's default tolerance) would
  // otherwise clamp most vertices into the last cell and make the search quadratic.
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  const double cell_size = std::max(distance, extent / (kMaxCell - 1));
  using Cell = std::array<std::int64_t, 3>;
  auto cell_of = [&](const Vec3& p) {
    Cell c;
    for (int a = 0; a < 3; ++a) {
      const double x = std::floor((double(p[a]) - lo[a]) / cell_size);
      c[a] = static_cast<std::int64_t>(std::clamp(x, 0.0, kMaxCell)) + 1;  // +1: room for -1
    }
    return c;
  };
  auto key_of = [](const Cell& c) {
    return (std::uint64_t(c[0]) << 42) | (std::uint64_t(c[1]) << 21) | std::uint64_t(c[2]);
  };
  std::vector<Cell> cells(n);
  std::vector<std::uint64_t> keys(n);
  for (std::size_t i = 0; i < n; ++i) {
    cells[i] = cell_of(v[i]);
    keys[i] = key_of(cells[i]);
  }
  std::sort(order.begin(), order.end(),
            [&](std::uint32_t a, std::uint32_t b) { return keys[a] != keys[b] ? keys[a] < keys[b] : a < b; });
  std::vector<std::uint64_t> sorted_keys(n);
  for (std::size_t i = 0; i < n; ++i) sorted_keys[i] = keys[order[i]];

  const double d2 = distance * distance;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Cell& c = cells[i];
    const D3 p = detail::to_d3(v[i]);
    std::uint32_t best = i;
    // Cells (x, y, z - 1..z + 1) are one contiguous key range (z is the low field).
    for (std::int64_t dx = -1; dx <= 1; ++dx) {
      for (std::int64_t dy = -1; dy <= 1; ++dy) {
        const std::uint64_t k_lo = key_of({c[0] + dx, c[1] + dy, c[2] - 1});
        const std::uint64_t k_hi = k_lo + 2;
        auto it = std::lower_bound(sorted_keys.begin(), sorted_keys.end(), k_lo);
        for (; it != sorted_keys.end() && *it <= k_hi; ++it) {
          const std::uint32_t j = order[static_cast<std::size_t>(it - sorted_keys.begin())];
          if (j >= best || rep[j] != j) continue;
          const D3 q = detail::to_d3(v[j]);
          const D3 d = detail::sub(p, q);
          if (detail::dot(d, d) <= d2) best = j;
        }
      }
    }
    rep[i] = best;
  }
  return rep;
}

/// Step 6: flips triangles so that each manifold patch is consistent (and outward when
/// closed). Returns how many triangles were flipped.
std::size_t orient(IndexedMesh& mesh) {
  auto& tris = mesh.triangles;
  const std::size_t nt = tris.size();
  const std::vector<EdgeUse> uses = edge_uses(tris);
  // Neighbour across each slot (manifold edges only) and whether that neighbour traverses the
  // edge in the same direction (then one of the two must flip).
  std::vector<std::array<std::uint32_t, 3>> neighbor(nt, {kNone, kNone, kNone});
  std::vector<std::array<bool, 3>> same(nt, {false, false, false});
  std::vector<bool> open(nt, false);  // touches a boundary or non-manifold edge
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i + 1;
    while (j < uses.size() && uses[j].key == uses[i].key) ++j;
    if (j - i == 2) {
      const EdgeUse& x = uses[i];
      const EdgeUse& y = uses[i + 1];
      neighbor[x.triangle][x.slot] = y.triangle;
      neighbor[y.triangle][y.slot] = x.triangle;
      same[x.triangle][x.slot] = same[y.triangle][y.slot] = x.forward == y.forward;
    } else {
      for (std::size_t k = i; k < j; ++k) open[uses[k].triangle] = true;
    }
    i = j;
  }
  for (std::size_t t = 0; t < nt; ++t) {
    const TriangleIndices& tri = tris[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0]) open[t] = true;
  }

  std::vector<std::int8_t> flip(nt, -1);  // -1 unvisited, 0 keep, 1 flip
  std::vector<std::uint32_t> patch;
  std::size_t flipped = 0;
  for (std::uint32_t seed = 0; seed < nt; ++seed) {
    if (flip[seed] >= 0) continue;
    patch.clear();
    patch.push_back(seed);
    flip[seed] = 0;
    bool closed = true;
    for (std::size_t head = 0; head < patch.size(); ++head) {
      const std::uint32_t t = patch[head];
      closed = closed && !open[t];
      for (int e = 0; e < 3; ++e) {
        const std::uint32_t u = neighbor[t][static_cast<std::size_t>(e)];
        if (u == kNone) {
          closed = false;
          continue;
        }
        if (flip[u] >= 0) continue;
        // Same direction in the input means opposite flip decisions are needed.
        const bool s = same[t][static_cast<std::size_t>(e)];
        flip[u] = static_cast<std::int8_t>(s ? 1 - flip[t] : flip[t]);
        patch.push_back(u);
      }
    }
    std::size_t count = 0;
    for (std::uint32_t t : patch) count += static_cast<std::size_t>(flip[t]);
    bool invert = 2 * count > patch.size();  // open patch: keep the majority winding
    if (closed) {
      double volume6 = 0;
      const D3 o = detail::to_d3(mesh.vertices[tris[seed][0]]);
      for (std::uint32_t t : patch) {
        const D3 a = detail::sub(detail::to_d3(mesh.vertices[tris[t][0]]), o);
        const D3 b = detail::sub(detail::to_d3(mesh.vertices[tris[t][1]]), o);
        const D3 c = detail::sub(detail::to_d3(mesh.vertices[tris[t][2]]), o);
        const double v = detail::dot(a, detail::cross(b, c));
        volume6 += flip[t] ? -v : v;
      }
      if (volume6 != 0) invert = volume6 < 0;
    }
    for (std::uint32_t t : patch) {
      const bool f = (flip[t] != 0) != invert;
      if (f) {
        std::swap(tris[t][1], tris[t][2]);
        ++flipped;
      }
    }
  }
  return flipped;
}

}  // namespace

Result<MeshReport> analyse_mesh(const IndexedMesh& mesh) {
  if (auto e = validate_mesh(mesh)) return *e;
  MeshReport r = analyse(mesh);
  r.input_vertices = mesh.vertices.size();
  r.input_triangles = mesh.triangles.size();
  return r;
}

Result<RepairedMesh> repair_mesh(const IndexedMesh& input, const MeshRepairOptions& options) {
  if (auto e = validate_mesh(input)) return *e;
  if (auto e = validate::finite(options.weld_distance, "weld_distance")) return *e;

  IndexedMesh mesh = input;
  std::size_t welded = 0;
  std::size_t degenerate_removed = 0;
  std::size_t duplicates_removed = 0;
  std::size_t unused_removed = 0;

  // 2. Weld.
  double distance = double(options.weld_distance);
  if (distance < 0) {
    D3 lo = detail::to_d3(mesh.vertices.empty() ? Vec3(0) : mesh.vertices[0]);
    D3 hi = lo;
    for (const Vec3& p : mesh.vertices) {
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], double(p[a]));
        hi[a] = std::max(hi[a], double(p[a]));
      }
    }
    distance = double(kRelativeTolerance) * detail::norm(detail::sub(hi, lo));
  }
  const std::vector<std::uint32_t> rep = weld(mesh.vertices, distance);
  std::vector<bool> welded_away(mesh.vertices.size(), false);
  for (std::size_t i = 0; i < rep.size(); ++i) {
    if (rep[i] != i) {
      ++welded;
      welded_away[i] = true;
    }
  }
  for (TriangleIndices& t : mesh.triangles) {
    for (std::uint32_t& k : t) k = rep[k];
  }

  // 3. Degenerate triangles.
  if (options.remove_degenerate) {
    const std::size_t before = mesh.triangles.size();
    std::erase_if(mesh.triangles, [&](const TriangleIndices& t) { return is_degenerate(mesh, t); });
    degenerate_removed = before - mesh.triangles.size();
  }

  // 4. Duplicates (same vertex set, either winding): keep the first occurrence.
  if (options.remove_duplicates && !mesh.triangles.empty()) {
    // (sorted vertex set, triangle index) pairs sorted together: equal sets end up adjacent,
    // lowest index first.
    std::vector<std::pair<TriangleIndices, std::uint32_t>> sorted(mesh.triangles.size());
    for (std::size_t t = 0; t < sorted.size(); ++t) {
      sorted[t] = {mesh.triangles[t], static_cast<std::uint32_t>(t)};
      std::sort(sorted[t].first.begin(), sorted[t].first.end());
    }
    std::sort(sorted.begin(), sorted.end());
    std::vector<bool> drop(mesh.triangles.size(), false);
    for (std::size_t i = 1; i < sorted.size(); ++i) {
      if (sorted[i].first == sorted[i - 1].first) drop[sorted[i].second] = true;
    }
    std::vector<TriangleIndices> kept;
    kept.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      if (!drop[t]) kept.push_back(mesh.triangles[t]);
    }
    duplicates_removed = mesh.triangles.size() - kept.size();
    mesh.triangles = std::move(kept);
  }

  // 5. Unused vertices (welded-away ones are counted as welded, not as unused).
  if (options.remove_unused) {
    std::vector<bool> used(mesh.vertices.size(), false);
    for (const TriangleIndices& t : mesh.triangles) {
      for (std::uint32_t k : t) used[k] = true;
    }
    std::vector<std::uint32_t> remap(mesh.vertices.size(), kNone);
    std::vector<Vec3> kept;
    kept.reserve(mesh.vertices.size());
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
      if (used[i]) {
        remap[i] = static_cast<std::uint32_t>(kept.size());
        kept.push_back(mesh.vertices[i]);
      } else if (!welded_away[i]) {
        ++unused_removed;
      }
    }
    for (TriangleIndices& t : mesh.triangles) {
      for (std::uint32_t& k : t) k = remap[k];
    }
    mesh.vertices = std::move(kept);
  }

  // 6. Orientation.
  std::size_t flipped = 0;
  if (options.orient_consistently) flipped = orient(mesh);

  // 7. Report.
  RepairedMesh out;
  out.report = analyse(mesh);
  out.report.input_vertices = input.vertices.size();
  out.report.input_triangles = input.triangles.size();
  out.report.welded_vertices = welded;
  out.report.unused_vertices_removed = unused_removed;
  out.report.degenerate_triangles_removed = degenerate_removed;
  out.report.duplicate_triangles_removed = duplicates_removed;
  out.report.flipped_triangles = flipped;
  out.mesh = std::move(mesh);
  return out;
}

}  // namespace proxima
