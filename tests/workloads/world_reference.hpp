#pragma once
// An independent double-precision reference for the W8 per-frame query (FORMATS.md, "W8
// collision worlds"): every pair {i, j} of objects, not both static, whose exact closed
// shapes touch or overlap, computed from the parsed records without the library.
//   - Convex shapes are a core point set (sphere: its centre; capsule: its two segment
//     ends; box: its 8 corners; hull: its points; mesh triangle: its 3 corners) plus a
//     radius; two of them touch iff the distance of the cores' hulls, by GJK in double
//     (Gilbert, Johnson, Keerthi 1988, with Ericson's closest-point-on-simplex routines,
//     Real-Time Collision Detection 5.1.2-5.1.6), is at most the sum of the radii.
//   - A half-space {n.x <= d} touches a convex shape iff min over the core of n.p minus the
//     radius is <= d (the support point).
//   - A mesh touches a shape iff one of its triangles does (triangles found through a 2D grid
//     of cells over the mesh's x, y box).
// Candidate pairs: closed world boxes in double, grown by 1e-7, swept on x (moving against
// moving, and moving against static in two sorted lists). FORMATS.md: no pair of frames 0
// and F is within 1e-9 of touching, so this margin and GJK's relative 1e-14 termination
// decide every pair exactly.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "support/world_workloads.hpp"

namespace proxima::bench::world_ref {

/// a + b, a - b, s a, a . b, a x b in double.
inline Vec3d add(const Vec3d& a, const Vec3d& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3d mul(double s, const Vec3d& a) { return {s * a.x, s * a.y, s * a.z}; }
inline double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3d cross(const Vec3d& a, const Vec3d& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}

/// A convex shape in the world: the hull of `points` grown by `radius`.
struct Convex {
  std::vector<Vec3d> points;  ///< core points, world frame
  double radius = 0;          ///< added radius

  /// The core point farthest along d.
  const Vec3d& support(const Vec3d& d) const {
    std::size_t best = 0;
    double best_dot = dot(points[0], d);
    for (std::size_t i = 1; i < points.size(); ++i) {
      const double v = dot(points[i], d);
      if (v > best_dot) {
        best_dot = v;
        best = i;
      }
    }
    return points[best];
  }
};

/// Closest point to the origin of the simplex `s` (1..4 points); `s` is reduced to the
/// smallest sub-simplex holding that point. Returns false when the origin is inside a
/// full tetrahedron.
inline bool closest_on_simplex(std::vector<Vec3d>& s, Vec3d& v) {
  // The corners are taken by value: `out` may be the simplex they come from.
  auto segment = [](const Vec3d a, const Vec3d b, std::vector<Vec3d>& out) {
    const Vec3d ab = sub(b, a);
    const double t = -dot(a, ab);
    const double len2 = dot(ab, ab);
    if (t <= 0 || len2 <= 0) {
      out = {a};
      return a;
    }
    if (t >= len2) {
      out = {b};
      return b;
    }
    out = {a, b};
    return add(a, mul(t / len2, ab));
  };
  // Ericson 5.1.5 with p = origin.
  auto triangle = [&](const Vec3d a, const Vec3d b, const Vec3d c, std::vector<Vec3d>& out) {
    const Vec3d ab = sub(b, a), ac = sub(c, a), ap = mul(-1, a);
    const double d1 = dot(ab, ap), d2 = dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) {
      out = {a};
      return a;
    }
    const Vec3d bp = mul(-1, b);
    const double d3 = dot(ab, bp), d4 = dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) {
      out = {b};
      return b;
    }
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      out = {a, b};
      return add(a, mul(d1 / (d1 - d3), ab));
    }
    const Vec3d cp = mul(-1, c);
    const double d5 = dot(ab, cp), d6 = dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) {
      out = {c};
      return c;
    }
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      out = {a, c};
      return add(a, mul(d2 / (d2 - d6), ac));
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      out = {b, c};
      return add(b, mul((d4 - d3) / ((d4 - d3) + (d5 - d6)), sub(c, b)));
    }
    const double denom = 1 / (va + vb + vc);
    out = {a, b, c};
    return add(a, add(mul(vb * denom, ab), mul(vc * denom, ac)));
  };
  switch (s.size()) {
    case 1: v = s[0]; return true;
    case 2: v = segment(s[0], s[1], s); return true;
    case 3: v = triangle(s[0], s[1], s[2], s); return true;
    default: {
      // Ericson 5.1.6: the origin is outside face (a, b, c) when it and d lie on different
      // sides of its plane; a flat tetrahedron (d on the plane) counts every face as such.
      const std::array<std::array<int, 4>, 4> faces{{{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}}};
      bool inside = true;
      double best = std::numeric_limits<double>::infinity();
      std::vector<Vec3d> best_s, tmp;
      Vec3d best_v{};
      for (const auto& f : faces) {
        const Vec3d& a = s[f[0]];
        const Vec3d n = cross(sub(s[f[1]], a), sub(s[f[2]], a));
        const double side_p = -dot(a, n), side_d = dot(sub(s[f[3]], a), n);
        if (side_p * side_d > 0) continue;
        inside = false;
        const Vec3d q = triangle(a, s[f[1]], s[f[2]], tmp);
        if (dot(q, q) < best) {
          best = dot(q, q);
          best_v = q;
          best_s = tmp;
        }
      }
      if (inside) return false;
      s = best_s;
      v = best_v;
      return true;
    }
  }
}

/// Distance between the hulls of a.points and b.points (0 when they overlap), by GJK.
inline double core_distance(const Convex& a, const Convex& b) {
  Vec3d v = sub(a.points[0], b.points[0]);
  std::vector<Vec3d> s;
  double scale = 0;
  for (const Vec3d& p : a.points) scale = std::max(scale, dot(p, p));
  for (const Vec3d& p : b.points) scale = std::max(scale, dot(p, p));
  double best = std::numeric_limits<double>::infinity();  // |v|^2 of the simplex so far
  for (int iter = 0; iter < 200; ++iter) {
    const double vv = dot(v, v);
    if (vv <= 1e-30 * (1 + scale)) return 0;
    const Vec3d w = sub(a.support(mul(-1, v)), b.support(v));
    if (vv - dot(v, w) <= 1e-14 * vv) return std::sqrt(vv);
    for (const Vec3d& p : s) {
      if (p == w) return std::sqrt(vv);
    }
    s.push_back(w);
    if (!closest_on_simplex(s, v)) return 0;
    const double nv = dot(v, v);
    if (nv >= best) return std::sqrt(std::min(nv, best));  // no progress: converged
    best = nv;
  }
  return std::sqrt(best);
}

/// Signed gap of two convex shapes when their cores are apart (distance - radii); when the
/// cores overlap, -(radii) (the cores' own penetration is not measured).
inline double gap(const Convex& a, const Convex& b) { return core_distance(a, b) - a.radius - b.radius; }

/// Overlap of the two shapes' projections on the unit direction n (A's extent beyond B's
/// low side): max over A of n.x + ra - (min over B of n.x - rb). An upper bound of the
/// penetration depth for every n; <= 0 means a separating plane.
inline double overlap_along(const Convex& a, const Convex& b, const Vec3d& n) {
  return dot(a.support(n), n) + a.radius - (dot(b.support(mul(-1, n)), n) - b.radius);
}

/// One object at one frame, in the world frame.
struct Placed {
  WorldShapeKind kind = WorldShapeKind::Sphere;
  bool is_static = false;
  Convex convex;                                  ///< convex shapes
  Vec3d normal;                                   ///< half-space
  double offset = 0;                              ///< half-space
  std::vector<std::array<Vec3d, 3>> triangles;    ///< mesh, world frame
  std::vector<std::vector<std::uint32_t>> cells;  ///< mesh: triangle lists of a 2D grid
  double cell_lo_x = 0, cell_lo_y = 0, cell = 1;  ///< mesh: grid origin and cell size
  int cells_x = 0, cells_y = 0;                   ///< mesh: grid size
  Vec3d lo, hi;                                   ///< world box, grown by 1e-7
};

/// The box corners of a W8 box shape.
inline std::vector<Vec3d> box_corners(const Vec3d& h) {
  std::vector<Vec3d> out;
  for (int i = 0; i < 8; ++i) out.push_back({(i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z});
  return out;
}

/// Object `index` of `w` placed at `pose`.
inline Placed place(const WorldWorkload& w, std::size_t index, const Pose& pose) {
  const WorldObject& o = w.world.objects[index];
  Placed p;
  p.kind = o.shape.kind;
  p.is_static = o.is_static;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  constexpr double kGrow = 1e-7;
  std::vector<Vec3d> local;
  switch (o.shape.kind) {
    case WorldShapeKind::Sphere:
      local = {{0, 0, 0}};
      p.convex.radius = o.shape.radius;
      break;
    case WorldShapeKind::Capsule:
      local = {{0, 0, -o.shape.half_length}, {0, 0, o.shape.half_length}};
      p.convex.radius = o.shape.radius;
      break;
    case WorldShapeKind::Box: local = box_corners(o.shape.half_extents); break;
    case WorldShapeKind::Hull: local = w.hulls.shapes[o.shape.hull].points; break;
    case WorldShapeKind::HalfSpace: {
      p.normal = o.shape.normal;
      p.offset = o.shape.offset;
      p.lo = {-kInf, -kInf, -kInf};
      p.hi = {kInf, kInf, kInf};
      // Bounded on an axis only when the normal is that axis (as the library's box).
      for (int a = 0; a < 3; ++a) {
        const Vec3d e{a == 0 ? 1.0 : 0.0, a == 1 ? 1.0 : 0.0, a == 2 ? 1.0 : 0.0};
        if (p.normal == e) p.hi[a] = p.offset + kGrow;
        if (p.normal == mul(-1, e)) p.lo[a] = -p.offset - kGrow;
      }
      return p;
    }
    case WorldShapeKind::Mesh: {
      const ObjMesh& m = w.meshes.at(o.shape.mesh);
      std::vector<Vec3d> v;
      v.reserve(m.vertices.size());
      for (const Vec3d& l : m.vertices) v.push_back(apply(pose, l));
      p.lo = {kInf, kInf, kInf};
      p.hi = {-kInf, -kInf, -kInf};
      for (const Vec3d& x : v) {
        for (int a = 0; a < 3; ++a) {
          p.lo[a] = std::min(p.lo[a], x[a] - kGrow);
          p.hi[a] = std::max(p.hi[a], x[a] + kGrow);
        }
      }
      double extent = 0;
      for (const auto& t : m.triangles) {
        p.triangles.push_back({v[t[0]], v[t[1]], v[t[2]]});
        for (int a = 0; a < 2; ++a) {
          extent += std::max({v[t[0]][a], v[t[1]][a], v[t[2]][a]}) - std::min({v[t[0]][a], v[t[1]][a], v[t[2]][a]});
        }
      }
      p.cell = std::max(2 * extent / (2.0 * static_cast<double>(m.triangles.size())), 1e-6);
      p.cell_lo_x = p.lo.x;
      p.cell_lo_y = p.lo.y;
      p.cells_x = std::max(1, std::min(4096, static_cast<int>((p.hi.x - p.lo.x) / p.cell) + 1));
      p.cells_y = std::max(1, std::min(4096, static_cast<int>((p.hi.y - p.lo.y) / p.cell) + 1));
      p.cell = std::max((p.hi.x - p.lo.x) / p.cells_x, (p.hi.y - p.lo.y) / p.cells_y) * (1 + 1e-12);
      p.cells.resize(static_cast<std::size_t>(p.cells_x) * p.cells_y);
      for (std::uint32_t t = 0; t < p.triangles.size(); ++t) {
        const auto& tri = p.triangles[t];
        const double x0 = std::min({tri[0].x, tri[1].x, tri[2].x}), x1 = std::max({tri[0].x, tri[1].x, tri[2].x});
        const double y0 = std::min({tri[0].y, tri[1].y, tri[2].y}), y1 = std::max({tri[0].y, tri[1].y, tri[2].y});
        for (int cy = std::max(0, static_cast<int>((y0 - p.cell_lo_y) / p.cell) - 1);
             cy <= std::min(p.cells_y - 1, static_cast<int>((y1 - p.cell_lo_y) / p.cell) + 1); ++cy) {
          for (int cx = std::max(0, static_cast<int>((x0 - p.cell_lo_x) / p.cell) - 1);
               cx <= std::min(p.cells_x - 1, static_cast<int>((x1 - p.cell_lo_x) / p.cell) + 1); ++cx) {
            p.cells[static_cast<std::size_t>(cy) * p.cells_x + cx].push_back(t);
          }
        }
      }
      return p;
    }
  }
  for (const Vec3d& l : local) p.convex.points.push_back(apply(pose, l));
  p.lo = {kInf, kInf, kInf};
  p.hi = {-kInf, -kInf, -kInf};
  for (const Vec3d& x : p.convex.points) {
    for (int a = 0; a < 3; ++a) {
      p.lo[a] = std::min(p.lo[a], x[a] - p.convex.radius - kGrow);
      p.hi[a] = std::max(p.hi[a], x[a] + p.convex.radius + kGrow);
    }
  }
  return p;
}

/// Whether two closed boxes overlap.
inline bool boxes_meet(const Vec3d& alo, const Vec3d& ahi, const Vec3d& blo, const Vec3d& bhi) {
  return alo.x <= bhi.x && blo.x <= ahi.x && alo.y <= bhi.y && blo.y <= ahi.y && alo.z <= bhi.z && blo.z <= ahi.z;
}

/// The triangles of mesh `m` whose cells meet the box [lo, hi] in x, y (deduplicated).
inline std::vector<std::uint32_t> mesh_candidates(const Placed& m, const Vec3d& lo, const Vec3d& hi) {
  std::vector<std::uint32_t> out;
  const int cx0 = std::max(0, static_cast<int>(std::floor((lo.x - m.cell_lo_x) / m.cell)));
  const int cx1 = std::min(m.cells_x - 1, static_cast<int>(std::floor((hi.x - m.cell_lo_x) / m.cell)));
  const int cy0 = std::max(0, static_cast<int>(std::floor((lo.y - m.cell_lo_y) / m.cell)));
  const int cy1 = std::min(m.cells_y - 1, static_cast<int>(std::floor((hi.y - m.cell_lo_y) / m.cell)));
  for (int cy = cy0; cy <= cy1; ++cy) {
    for (int cx = cx0; cx <= cx1; ++cx) {
      const auto& cell = m.cells[static_cast<std::size_t>(cy) * m.cells_x + cx];
      out.insert(out.end(), cell.begin(), cell.end());
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// The convex piece of a mesh triangle.
inline Convex triangle_convex(const std::array<Vec3d, 3>& t) { return Convex{{t[0], t[1], t[2]}, 0}; }

/// Whether a and b (not both static, not both non-convex) touch or overlap.
inline bool touch(const Placed& a, const Placed& b) {
  if (b.kind == WorldShapeKind::HalfSpace || b.kind == WorldShapeKind::Mesh) return touch(b, a);
  if (a.kind == WorldShapeKind::HalfSpace) {
    return dot(b.convex.support(mul(-1, a.normal)), a.normal) - b.convex.radius <= a.offset;
  }
  if (a.kind == WorldShapeKind::Mesh) {
    for (const std::uint32_t t : mesh_candidates(a, b.lo, b.hi)) {
      const auto& tri = a.triangles[t];
      Vec3d lo = tri[0], hi = tri[0];
      for (int k = 1; k < 3; ++k) {
        for (int ax = 0; ax < 3; ++ax) {
          lo[ax] = std::min(lo[ax], tri[k][ax]);
          hi[ax] = std::max(hi[ax], tri[k][ax]);
        }
      }
      if (boxes_meet(lo, hi, b.lo, b.hi) && gap(triangle_convex(tri), b.convex) <= 0) return true;
    }
    return false;
  }
  return gap(a.convex, b.convex) <= 0;
}

/// A candidate or touching pair of object ids, lo < hi.
using IdPair = std::pair<std::uint32_t, std::uint32_t>;

/// Every pair of objects, not both static, whose grown world boxes overlap: a sweep on x of
/// the moving objects among themselves, then moving against static in two sorted lists.
inline std::vector<IdPair> candidate_pairs(const std::vector<Placed>& objects) {
  std::vector<std::uint32_t> moving, fixed;
  for (std::uint32_t i = 0; i < objects.size(); ++i) (objects[i].is_static ? fixed : moving).push_back(i);
  auto by_min_x = [&](std::uint32_t a, std::uint32_t b) {
    return objects[a].lo.x < objects[b].lo.x || (objects[a].lo.x == objects[b].lo.x && a < b);
  };
  std::sort(moving.begin(), moving.end(), by_min_x);
  std::sort(fixed.begin(), fixed.end(), by_min_x);
  std::vector<IdPair> out;
  auto emit = [&](std::uint32_t i, std::uint32_t j) {
    if (boxes_meet(objects[i].lo, objects[i].hi, objects[j].lo, objects[j].hi)) {
      out.emplace_back(std::min(i, j), std::max(i, j));
    }
  };
  for (std::size_t k = 0; k < moving.size(); ++k) {
    for (std::size_t m = k + 1; m < moving.size() && objects[moving[m]].lo.x <= objects[moving[k]].hi.x; ++m) {
      emit(moving[k], moving[m]);
    }
  }
  // Moving i against static j: j starting at or after i's min x is found from i; j starting
  // before it is found from j (each pair once).
  std::size_t f = 0;
  for (const std::uint32_t i : moving) {
    while (f < fixed.size() && objects[fixed[f]].lo.x < objects[i].lo.x) ++f;
    for (std::size_t m = f; m < fixed.size() && objects[fixed[m]].lo.x <= objects[i].hi.x; ++m) emit(i, fixed[m]);
  }
  std::size_t mv = 0;
  for (const std::uint32_t j : fixed) {
    while (mv < moving.size() && objects[moving[mv]].lo.x <= objects[j].lo.x) ++mv;
    for (std::size_t m = mv; m < moving.size() && objects[moving[m]].lo.x <= objects[j].hi.x; ++m) emit(moving[m], j);
  }
  std::sort(out.begin(), out.end());
  return out;
}

/// Every object of the world placed at frame k.
inline std::vector<Placed> place_all(const WorldWorkload& w, int frame) {
  std::vector<Placed> out;
  out.reserve(w.world.objects.size());
  for (std::size_t i = 0; i < w.world.objects.size(); ++i) out.push_back(place(w, i, pose_at_frame(w.world, i, frame)));
  return out;
}

/// The reference pairs of frame k (sorted).
inline std::vector<IdPair> touching_pairs(const std::vector<Placed>& objects) {
  std::vector<IdPair> out;
  for (const IdPair& p : candidate_pairs(objects)) {
    if (touch(objects[p.first], objects[p.second])) out.push_back(p);
  }
  return out;
}

}  // namespace proxima::bench::world_ref
