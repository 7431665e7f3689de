#pragma once
/// @file epa.hpp
/// Expanding Polytope Algorithm: penetration depth and direction of two overlapping convex
/// sets from GJK's final simplex (van den Bergen, "Proximity Queries and Penetration Depth
/// Computation on 3D Game Objects", GDC 2001; Collision Detection in Interactive 3D
/// Environments, 2004, 4.3.3).
///
/// Steps:
///   1. grow GJK's simplex to a polytope around the origin: a point gets a second vertex
///      from the six axis supports, a segment a third from supports perpendicular to it, a
///      triangle the farther of the supports along its two normals (a tetrahedron), a
///      tetrahedron is used as is; if the Minkowski difference D = A - B is flat, stop (Degenerate);
///   2. repeat: take the face nearest the origin, query D's support along its normal; when
///      the support is within tolerance of the face, that face gives depth and normal;
///      else remove the faces that see the new vertex and fan the horizon to it;
///   3. when rounding stops the growth (a sliver face, a pinched horizon, storage or the
///      face budget exhausted) or at the cap: the nearest face, Converged when its gap is
///      within a loose tolerance (4096 eps x scale), else MaxIterations (its distance is a
///      lower bound of the depth, the support along its normal an upper bound).
/// Witnesses: barycentric coordinates of the origin's projection on the final face applied
/// to the support points of A and B. No allocation (fixed storage), never NaN.

#include <proxima/core/math.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/geometry/gjk.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

namespace proxima::epa {

/// How EPA stopped.
enum class Status : std::uint8_t {
  Converged,      ///< the nearest face is exact within tolerance
  MaxIterations,  ///< the cap stopped it: depth is a lower bound (nearest face so far)
  Degenerate,     ///< D is flat or the polytope could not grow: no answer (fall back)
};

/// Options of one EPA run.
struct Settings {
  int max_iterations = 128;                  ///< iteration cap
  int max_faces = 256;                       ///< largest number of faces alive at once (capped at kMaxFaces)
  Real abs_tolerance = Real(0);              ///< stop when support distance - face distance <= this
  Real rel_tolerance = Real(16) * kEpsilon;  ///< ... or <= this times the depth
};

/// Storage limits (fixed arrays on the stack).
inline constexpr int kMaxFaces = 512;
/// See kMaxFaces.
inline constexpr int kMaxVertices = 192;

/// What epa::penetration found: how it stopped, depth, normal and witnesses.
struct Outcome {
  Status status = Status::Degenerate;  ///< how the expansion stopped (Degenerate: the fields below keep their defaults)
  Real depth = Real(0);                ///< penetration depth of the sets (>= 0)
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, from A to B: moving B by depth*normal separates
  Vec3 point_a{Real(0)};                   ///< deepest point of A (common frame)
  Vec3 point_b{Real(0)};                   ///< deepest point of B: point_a - depth * normal
  Real gap = Real(0);                      ///< least support distance seen minus depth: a bound on the depth error
  Vec3 upper_normal{Real(0), Real(0), Real(1)};  ///< unit normal along which that least support distance was seen
  int iterations = 0;  ///< expansion steps, each one support query (at most Settings::max_iterations)
};

namespace detail {

// The storage below is left uninitialised on purpose (no default member initialisers): a
// face slot is written whole by add_face before any read (slots < nf), its links by link()
// or the fan step, a vertex before nv counts it, a free slot before nfree counts it. Zeroing
// these arrays (about 40 KB) used to cost as much as the expansion itself.
struct Face {
  std::array<std::uint16_t, 3> v;
  std::array<std::uint16_t, 3> adj;      // face across edge e (v[e] -> v[e+1])
  std::array<std::uint8_t, 3> adj_edge;  // that edge's index in the neighbour
  Vec3 n;
  Real d;
  bool alive;
};

// A vertex of D with its support points, like gjk::Vertex but trivially constructible.
struct PolyVertex {
  Vec3 w;
  Vec3 a;
  Vec3 b;
  PolyVertex& operator=(const gjk::Vertex& x) {
    w = x.w;
    a = x.a;
    b = x.b;
    return *this;
  }
};

struct Polytope {
  std::array<PolyVertex, kMaxVertices> verts;
  std::array<Face, kMaxFaces> faces;
  int nv = 0;
  int nf = 0;      // slots used (alive or dead)
  int alive = 0;   // faces alive
  int budget = 0;  // most faces alive at once
  std::array<std::uint16_t, kMaxFaces> free_slots;
  int nfree = 0;
  Vec3 inner{Real(0)};  // a point inside (orients new faces)

  // Adds face (i, j, k), turned away from `inner` when `orient` (the initial faces) or else
  // kept in the given order (horizon edge, new vertex: outward by construction); false when
  // it is degenerate or over budget.
  bool add_face(int i, int j, int k, Real area_floor, bool orient = true) {
    if (alive >= budget) return false;
    if (nfree == 0 && nf >= kMaxFaces) return false;
    const Vec3& a = verts[static_cast<std::size_t>(i)].w;
    const Vec3& b = verts[static_cast<std::size_t>(j)].w;
    const Vec3& c = verts[static_cast<std::size_t>(k)].w;
    Vec3 n = glm::cross(b - a, c - a);
    const Real len = std::sqrt(glm::dot(n, n));
    if (!(len > area_floor)) return false;
    n /= len;
    const int slot = nfree > 0 ? free_slots[static_cast<std::size_t>(--nfree)] : nf++;
    Face& f = faces[static_cast<std::size_t>(slot)];
    f.v = {static_cast<std::uint16_t>(i), static_cast<std::uint16_t>(j), static_cast<std::uint16_t>(k)};
    if (orient && glm::dot(n, a - inner) < Real(0)) {
      n = -n;
      std::swap(f.v[1], f.v[2]);
    }
    f.n = n;
    f.d = glm::dot(n, a);
    f.alive = true;
    ++alive;
    last = slot;
    return true;
  }
  int last = -1;  // slot of the face added last

  // Links faces slots[0..count) to each other and to themselves by matching reversed edges.
  bool link(const int* slots, int count) {
    for (int x = 0; x < count; ++x) {
      Face& f = faces[static_cast<std::size_t>(slots[x])];
      for (std::size_t e = 0; e < 3; ++e) {
        const std::uint16_t i = f.v[e];
        const std::uint16_t j = f.v[(e + 1) % 3];
        bool found = false;
        for (int y = 0; y < count && !found; ++y) {
          const Face& g = faces[static_cast<std::size_t>(slots[y])];
          for (std::size_t k = 0; k < 3; ++k) {
            if (g.v[k] == j && g.v[(k + 1) % 3] == i) {
              f.adj[e] = static_cast<std::uint16_t>(slots[y]);
              f.adj_edge[e] = static_cast<std::uint8_t>(k);
              found = true;
              break;
            }
          }
        }
        if (!found) return false;
      }
    }
    return true;
  }

  void kill(int slot) {
    faces[static_cast<std::size_t>(slot)].alive = false;
    free_slots[static_cast<std::size_t>(nfree++)] = static_cast<std::uint16_t>(slot);
    --alive;
  }
};

}  // namespace detail

/// Penetration depth of A and B (overlapping) from GJK's final simplex, with support
/// functors in a common frame as for gjk::distance. `length_scale` (> 0) is the size of
/// the problem, for the degeneracy thresholds. O(iterations x (faces + support cost)).
template <class SupportA, class SupportB>
Outcome penetration(SupportA& support_a, SupportB& support_b, const gjk::Simplex& start, Real length_scale,
                    const Settings& settings) {
  Outcome r;
  const auto make_vertex = [&](const Vec3& d) {
    gjk::Vertex x;
    x.a = support_a(d);
    x.b = support_b(-d);
    x.w = x.a - x.b;
    return x;
  };
  detail::Polytope p;
  p.budget = std::clamp(settings.max_faces, 4, kMaxFaces);
  const Real scale = std::max(length_scale, std::numeric_limits<Real>::min());
  const Real eps_len = Real(64) * kEpsilon * scale;  // distinct-point / off-line threshold
  const Real area_floor = kEpsilon * kEpsilon * scale * scale;

  std::array<gjk::Vertex, 4> s{};
  int n = std::clamp(start.size, 0, 4);
  for (int i = 0; i < n; ++i) s[static_cast<std::size_t>(i)] = start.v[static_cast<std::size_t>(i)];
  if (n == 0) {
    s[0] = make_vertex(Vec3(Real(1), Real(0), Real(0)));
    n = 1;
  }
  // Step 1: grow to a segment, a triangle, then a tetrahedron or bipyramid.
  if (n == 1) {
    const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    for (const Vec3& d : axes) {
      const gjk::Vertex x = make_vertex(d);
      if (glm::length(x.w - s[0].w) > eps_len) {
        s[1] = x;
        n = 2;
        break;
      }
    }
    if (n == 1) return r;  // D is a point
  }
  if (n == 2) {
    const Vec3 e = s[1].w - s[0].w;
    const Vec3 eu = e / glm::length(e);
    Vec3 axis(Real(1), Real(0), Real(0));
    if (std::abs(eu.y) < std::abs(eu[0]) && std::abs(eu.y) <= std::abs(eu.z))
      axis = Vec3(0, 1, 0);
    else if (std::abs(eu.z) < std::abs(eu[0]))
      axis = Vec3(0, 0, 1);
    const Vec3 d1 = glm::normalize(glm::cross(eu, axis));
    const Vec3 d2 = glm::cross(eu, d1);
    Real best = eps_len;
    for (int i = 0; i < 6; ++i) {
      const Real ang = Real(i) * Real(1.0471975511965976);
      const Vec3 d = std::cos(ang) * d1 + std::sin(ang) * d2;
      const gjk::Vertex x = make_vertex(d);
      const Vec3 rel = x.w - s[0].w;
      const Real off = glm::length(rel - eu * glm::dot(rel, eu));
      if (off > best) {
        best = off;
        s[2] = x;
        n = 3;
      }
    }
    if (n == 2) return r;  // D is a segment
  }
  int apex_count = 0;
  gjk::Vertex apex[2];
  if (n == 3) {
    Vec3 nn = glm::cross(s[1].w - s[0].w, s[2].w - s[0].w);
    const Real len = glm::length(nn);
    if (!(len > area_floor)) return r;
    nn /= len;
    const gjk::Vertex up = make_vertex(nn);
    const gjk::Vertex down = make_vertex(-nn);
    // One apex, the farther one: a tetrahedron (a bipyramid need not be convex). The origin
    // lies on the triangle, so on the tetrahedron's boundary; the expansion goes on from it.
    const Real hu = glm::dot(nn, up.w - s[0].w);
    const Real hd = glm::dot(nn, s[0].w - down.w);
    if (hu >= hd && hu > eps_len)
      apex[apex_count++] = up;
    else if (hd > eps_len)
      apex[apex_count++] = down;
    if (apex_count == 0) return r;  // D is flat
  }
  if (n == 4) {
    for (int i = 0; i < 4; ++i) p.verts[static_cast<std::size_t>(i)] = s[static_cast<std::size_t>(i)];
    p.nv = 4;
    p.inner = (s[0].w + s[1].w + s[2].w + s[3].w) * Real(0.25);
    if (!p.add_face(0, 1, 2, area_floor) || !p.add_face(0, 1, 3, area_floor) || !p.add_face(0, 2, 3, area_floor) ||
        !p.add_face(1, 2, 3, area_floor))
      return r;
  } else {
    for (int i = 0; i < 3; ++i) p.verts[static_cast<std::size_t>(i)] = s[static_cast<std::size_t>(i)];
    Vec3 inner = s[0].w + s[1].w + s[2].w;
    for (int i = 0; i < apex_count; ++i) {
      p.verts[static_cast<std::size_t>(3 + i)] = apex[i];
      inner += apex[i].w;
    }
    p.nv = 3 + apex_count;
    p.inner = inner / Real(p.nv);
    for (int i = 0; i < apex_count; ++i) {
      const int t = 3 + i;
      if (!p.add_face(0, 1, t, area_floor) || !p.add_face(1, 2, t, area_floor) || !p.add_face(2, 0, t, area_floor))
        return r;
    }
    if (apex_count == 1 && !p.add_face(0, 1, 2, area_floor)) return r;
  }
  {
    std::array<int, 8> slots{};
    for (int f = 0; f < p.nf; ++f) slots[static_cast<std::size_t>(f)] = f;
    if (!p.link(slots.data(), p.nf)) return r;
  }
  // The origin must be inside (or on) the initial polytope; else the sets barely touch.
  for (int f = 0; f < p.nf; ++f)
    if (p.faces[static_cast<std::size_t>(f)].d < -eps_len) return r;

  // Step 2: expand.
  // Barycentric coordinates of the origin's projection on face f (unclamped).
  const auto barycentric = [&](const detail::Face& f) {
    const Vec3 proj = f.n * std::max(f.d, Real(0));
    const Vec3& a = p.verts[f.v[0]].w;
    const Vec3& b = p.verts[f.v[1]].w;
    const Vec3& c = p.verts[f.v[2]].w;
    const Real den = glm::dot(f.n, glm::cross(b - a, c - a));
    const Real la = glm::dot(f.n, glm::cross(b - proj, c - proj)) / den;
    const Real lb = glm::dot(f.n, glm::cross(c - proj, a - proj)) / den;
    return Vec3(la, lb, Real(1) - la - lb);
  };
  Real upper = std::numeric_limits<Real>::infinity();  // least support distance seen: depth <= it
  Vec3 upper_normal(Real(0), Real(0), Real(1));        // ... seen along this normal
  const auto finish = [&](const detail::Face& nearest, Status status, int iterations, Real gap) {
    // The Minkowski difference of polytopes has flat faces that the polytope splits into
    // coplanar triangles: the witness comes from the one that holds the projection.
    detail::Face f = nearest;
    Vec3 lam = barycentric(f);
    const Real inside = -Real(64) * kEpsilon;
    if (std::min({lam.x, lam.y, lam.z}) < inside) {
      const Real slack = std::max(Real(64) * kEpsilon * scale, settings.abs_tolerance);
      for (int g = 0; g < p.nf; ++g) {
        const detail::Face& other = p.faces[static_cast<std::size_t>(g)];
        if (!other.alive || other.d > nearest.d + slack) continue;
        const Vec3 l = barycentric(other);
        if (std::min({l.x, l.y, l.z}) > std::min({lam.x, lam.y, lam.z})) {
          lam = l;
          f = other;
        }
      }
    }
    Real la = std::clamp(lam.x, Real(0), Real(1));
    Real lb = std::clamp(lam.y, Real(0), Real(1));
    Real lc = std::clamp(lam.z, Real(0), Real(1));
    const detail::PolyVertex& a = p.verts[f.v[0]];
    const detail::PolyVertex& b = p.verts[f.v[1]];
    const detail::PolyVertex& c = p.verts[f.v[2]];
    const Real sum = la + lb + lc;
    if (sum > Real(0)) {
      la /= sum;
      lb /= sum;
      lc /= sum;
    } else {
      la = Real(1);
    }
    r.status = status;
    r.depth = std::max(f.d, Real(0));
    r.normal = f.n;
    r.point_a = la * a.a + lb * b.a + lc * c.a;
    r.point_b = la * a.b + lb * b.b + lc * c.b;
    r.iterations = iterations;
    r.gap = gap;
    r.upper_normal = std::isfinite(upper) ? upper_normal : f.n;
    return r;
  };

  // Work arrays, written before read (entries below nh / top): left uninitialised.
  std::array<std::array<std::uint16_t, 2>, kMaxFaces> horizon;
  std::array<std::array<std::uint16_t, 2>, kMaxFaces> stack;
  std::array<int, kMaxFaces> fan;
  for (int it = 0;; ++it) {
    int best = -1;
    Real best_d = std::numeric_limits<Real>::infinity();
    for (int f = 0; f < p.nf; ++f) {
      const detail::Face& face = p.faces[static_cast<std::size_t>(f)];
      if (face.alive && face.d < best_d) {
        best_d = face.d;
        best = f;
      }
    }
    if (best < 0) return r;
    const detail::Face closest = p.faces[static_cast<std::size_t>(best)];
    if (it >= settings.max_iterations) return finish(closest, Status::MaxIterations, it, upper - closest.d);
    const gjk::Vertex w = make_vertex(closest.n);
    const Real dw = glm::dot(closest.n, w.w);
    const Real tol = std::max(
        {settings.abs_tolerance, settings.rel_tolerance * std::max(closest.d, Real(0)), Real(8) * kEpsilon * scale});
    if (dw < upper) {
      upper = dw;
      upper_normal = closest.n;
    }
    if (dw - closest.d <= tol) return finish(closest, Status::Converged, it + 1, upper - closest.d);
    const Real loose_tol = std::max(Real(32) * tol, Real(4096) * kEpsilon * scale);
    if (p.nv >= kMaxVertices)
      return finish(closest, dw - closest.d <= loose_tol ? Status::Converged : Status::MaxIterations, it + 1,
                    upper - closest.d);
    const int wi = p.nv;
    p.verts[static_cast<std::size_t>(wi)] = w;
    ++p.nv;
    // Faces that see w: a depth-first walk from the nearest face across its edges; the
    // horizon is the ordered list of (unseen face, edge) where the walk stopped.
    int nh = 0;
    bool overflow = false;
    const auto sees = [&](const detail::Face& face) { return glm::dot(face.n, w.w - p.verts[face.v[0]].w) > Real(0); };
    // Explicit stack of (face, edge entered by).
    int top = 0;
    p.kill(best);
    for (int e = 2; e >= 0; --e) {
      stack[static_cast<std::size_t>(top++)] = {closest.adj[static_cast<std::size_t>(e)],
                                                closest.adj_edge[static_cast<std::size_t>(e)]};
    }
    while (top > 0 && !overflow) {
      const auto item = stack[static_cast<std::size_t>(--top)];
      detail::Face& face = p.faces[item[0]];
      if (!face.alive) continue;
      if (!sees(face)) {
        if (nh >= kMaxFaces) {
          overflow = true;
          break;
        }
        horizon[static_cast<std::size_t>(nh++)] = item;
        continue;
      }
      p.kill(item[0]);
      for (int k = 2; k >= 1; --k) {
        const std::size_t e = (item[1] + static_cast<std::size_t>(k)) % 3;
        if (top >= kMaxFaces) {
          overflow = true;
          break;
        }
        stack[static_cast<std::size_t>(top++)] = {face.adj[e], face.adj_edge[e]};
      }
    }
    // Rounding can leave the polytope unable to grow (a sliver face, a pinched horizon):
    // answer with the nearest face when its gap is within the loose tolerance.
    const auto stuck = [&]() {
      return finish(closest, dw - closest.d <= loose_tol ? Status::Converged : Status::MaxIterations, it + 1,
                    upper - closest.d);
    };
    if (overflow || nh < 3) return stuck();
    for (int h = 0; h < nh; ++h) {
      const auto& item = horizon[static_cast<std::size_t>(h)];
      const detail::Face& g = p.faces[item[0]];
      const std::uint16_t a = g.v[(item[1] + 1u) % 3u];
      const std::uint16_t b = g.v[item[1]];
      if (!p.add_face(a, b, wi, area_floor, false)) return stuck();
      fan[static_cast<std::size_t>(h)] = p.last;
    }
    // Link each fan face to its horizon neighbour (edge 0) and to the fan faces beside it.
    for (int h = 0; h < nh; ++h) {
      const auto& item = horizon[static_cast<std::size_t>(h)];
      detail::Face& f = p.faces[static_cast<std::size_t>(fan[static_cast<std::size_t>(h)])];
      detail::Face& g = p.faces[item[0]];
      f.adj[0] = item[0];
      f.adj_edge[0] = static_cast<std::uint8_t>(item[1]);
      g.adj[item[1]] = static_cast<std::uint16_t>(fan[static_cast<std::size_t>(h)]);
      g.adj_edge[item[1]] = 0;
      int next = -1;
      int count = 0;
      for (int x = 0; x < nh; ++x) {
        if (p.faces[static_cast<std::size_t>(fan[static_cast<std::size_t>(x)])].v[0] == f.v[1]) {
          next = x;
          ++count;
        }
      }
      if (count != 1) return stuck();  // pinched horizon
      const int nslot = fan[static_cast<std::size_t>(next)];
      f.adj[1] = static_cast<std::uint16_t>(nslot);
      f.adj_edge[1] = 2;
      p.faces[static_cast<std::size_t>(nslot)].adj[2] = static_cast<std::uint16_t>(fan[static_cast<std::size_t>(h)]);
      p.faces[static_cast<std::size_t>(nslot)].adj_edge[2] = 1;
    }
  }
}

/// Outcome of epa::refine.
struct Refinement {
  bool improved = false;                   ///< a normal with a smaller support distance than the start was found
  bool converged = false;                  ///< the last Newton step changed the support distance by rounding only
  Real depth = Real(0);                    ///< support distance of D along `normal`: an upper bound of the depth
  Vec3 normal{Real(0), Real(0), Real(1)};  ///< unit, from A to B
  Vec3 support_a{Real(0)};                 ///< witness on A: support points of A along normal (tipped), combined
  Vec3 support_b{Real(0)};     ///< witness on B: the same for B along -normal; support_a - support_b = depth normal
  Vec3 tangential{Real(0)};    ///< D's support along normal minus depth * normal: 0 at a smooth minimum
  Real witness_gap = Real(0);  ///< distance of the combined witnesses from the exact relation before it was enforced
  int iterations = 0;          ///< support-pair queries made
};

/// Refines a penetration normal on the support function of D = A - B: the depth is the
/// minimum over unit n of h(n) = n . s_D(n), a smooth function of n where D is strictly
/// convex, whose gradient on the sphere is the part of s_D(n) across n and whose Hessian is
/// the support map's Jacobian minus h(n) (estimated by forward differences of the support).
/// Trust-region Newton iterations from `start_normal`; a step is kept only when it lowers h,
/// so the answer is an upper bound of the depth no worse than the start. EPA converges only
/// linearly on curved supports; a few of these steps reach the precision's accuracy. Never
/// NaN (a start of zero length uses +z). O(max_steps x 3 support queries).
template <class SupportA, class SupportB>
Refinement refine(SupportA& support_a, SupportB& support_b, const Vec3& start_normal, Real length_scale,
                  int max_steps = 96) {
  Refinement r;
  const Real scale = std::max(length_scale, std::numeric_limits<Real>::min());
  const Real l2 = glm::dot(start_normal, start_normal);
  Vec3 n = l2 > Real(0) && std::isfinite(l2) ? start_normal / std::sqrt(l2) : Vec3(Real(0), Real(0), Real(1));
  Vec3 a = support_a(n);
  Vec3 b = support_b(-n);
  Vec3 p = a - b;
  Real h = glm::dot(n, p);
  r.iterations = 1;
  const Real h_start = h;
  // Forward-difference step (radians): truncation ~eta against rounding ~eps/eta.
  const Real eta = Real(4) * std::cbrt(kEpsilon);
  const Real flat = Real(8) * kEpsilon * scale;  // a change of h within rounding
  // Stop when no step within the trust radius can lower h by more than this (a kink of h,
  // where D has an edge or a ruled side, is approached by shrinking the radius).
  const Real settle = std::sqrt(kEpsilon) * std::sqrt(std::sqrt(kEpsilon)) * scale;
  Real radius = Real(0.25);  // trust radius (radians)
  const auto unit = [](const Vec3& v) { return v / std::sqrt(glm::dot(v, v)); };
  Vec3 t1(Real(0));
  Vec3 t2(Real(0));
  Real g1 = Real(0);
  Real g2 = Real(0);
  Real h11 = Real(0);
  Real h12 = Real(0);
  Real h22 = Real(0);
  bool fresh = false;     // gradient and Hessian belong to the current n
  bool steepest = false;  // the next trial is a gradient step (the Newton one failed)
  for (int step = 0; step < max_steps; ++step) {
    if (!fresh) {
      // Tangent basis (Duff et al., "Building an orthonormal basis, revisited", JCGT 2017).
      const Real sign = std::copysign(Real(1), n.z);
      const Real q = Real(-1) / (sign + n.z);
      const Real m = n.x * n.y * q;
      t1 = Vec3(Real(1) + sign * n.x * n.x * q, sign * m, -sign * n.x);
      t2 = Vec3(m, sign + n.y * n.y * q, -n.y);
      g1 = glm::dot(t1, p);
      g2 = glm::dot(t2, p);
      if (std::sqrt(g1 * g1 + g2 * g2) <= flat) {
        r.converged = true;
        break;
      }
      const Vec3 n1 = unit(n + eta * t1);
      const Vec3 n2 = unit(n + eta * t2);
      const Vec3 p1 = support_a(n1) - support_b(-n1);
      const Vec3 p2 = support_a(n2) - support_b(-n2);
      r.iterations += 2;
      h11 = glm::dot(t1, p1 - p) / eta - h;
      h22 = glm::dot(t2, p2 - p) / eta - h;
      h12 = Real(0.5) * (glm::dot(t2, p1 - p) + glm::dot(t1, p2 - p)) / eta;
      fresh = true;
    }
    // Shift the Hessian to positive definite (Levenberg-Marquardt), solve, clip to the radius.
    const Real tr = Real(0.5) * (h11 + h22);
    const Real disc = std::sqrt(Real(0.25) * (h11 - h22) * (h11 - h22) + h12 * h12);
    const Real lambda_min = tr - disc;
    const Real floor = Real(1e-3) * std::max(std::abs(tr) + disc, flat);
    const Real mu = lambda_min < floor ? floor - lambda_min : Real(0);
    const Real k11 = h11 + mu;
    const Real k22 = h22 + mu;
    const Real det = k11 * k22 - h12 * h12;
    Real d1 = Real(0);
    Real d2 = Real(0);
    if (det > Real(0) && std::isfinite(det)) {
      d1 = -(k22 * g1 - h12 * g2) / det;
      d2 = -(k11 * g2 - h12 * g1) / det;
    }
    const Real gl = std::sqrt(g1 * g1 + g2 * g2);
    Real len = std::sqrt(d1 * d1 + d2 * d2);
    // A full Newton step on a positive definite Hessian that predicts no gain beyond
    // rounding: the smooth minimum is reached.
    const bool newton_exact = mu == Real(0) && len <= radius && Real(-0.5) * (g1 * d1 + g2 * d2) <= flat;
    if (steepest || !(len > Real(0)) || !std::isfinite(len)) {  // a gradient step
      d1 = -g1 / gl * radius;
      d2 = -g2 / gl * radius;
      len = radius;
    } else if (len > radius) {
      d1 *= radius / len;
      d2 *= radius / len;
      len = radius;
    }
    const Vec3 n_try = unit(n + d1 * t1 + d2 * t2);
    const Vec3 a_try = support_a(n_try);
    const Vec3 b_try = support_b(-n_try);
    ++r.iterations;
    const Vec3 p_try = a_try - b_try;
    const Real h_try = glm::dot(n_try, p_try);
    if (h_try < h - flat) {  // a gain beyond rounding (on a flat stretch of h, stay put)
      n = n_try;
      a = a_try;
      b = b_try;
      p = p_try;
      h = h_try;
      fresh = false;
      steepest = false;
      radius = std::min(Real(0.5), std::max(radius, Real(2) * len));
    } else if (newton_exact && !steepest) {
      r.converged = true;
      break;
    } else if (!steepest) {
      steepest = true;  // at a kink of h the Newton model misleads: try the plain gradient
    } else {
      steepest = false;
      radius = Real(0.25) * len;
      if (radius * scale <= settle) {  // no step within reach can gain more than `settle`
        r.converged = true;
        break;
      }
    }
  }
  r.improved = h < h_start;
  r.depth = h;
  r.normal = n;
  r.tangential = p - h * n;
  // Witnesses. Where D's support along n is not unique (a face or edge of D: a cylinder's
  // cap or side against a point), one support point can be anywhere on that feature. The
  // feature's own support in a tangent direction e is D's support along n tipped by
  // sqrt(eps) towards e, so a small GJK in the tangent plane finds the feature's point
  // nearest the line along n; the same convex weights give points of A and B.
  {
    const Real sign = std::copysign(Real(1), n.z);
    const Real q = Real(-1) / (sign + n.z);
    const Real m = n.x * n.y * q;
    t1 = Vec3(Real(1) + sign * n.x * n.x * q, sign * m, -sign * n.x);
    t2 = Vec3(m, sign + n.y * n.y * q, -n.y);
    const Real tip = std::sqrt(kEpsilon);
    // Up to three kept points plus one new: support points and tangent coordinates.
    std::array<Vec3, 4> pa{};
    std::array<Vec3, 4> pb{};
    std::array<Real, 4> u{};
    std::array<Real, 4> v{};
    std::array<Real, 4> lam{};
    pa[0] = a;
    pb[0] = b;
    u[0] = glm::dot(t1, p);
    v[0] = glm::dot(t2, p);
    lam[0] = Real(1);
    int count = 1;
    Real mu = u[0];
    Real mv = v[0];
    const Real close = Real(4) * kEpsilon * scale;
    for (int it = 0; it < 16; ++it) {
      const Real mm = mu * mu + mv * mv;
      if (std::sqrt(mm) <= close) break;
      const Real ml = std::sqrt(mm);
      const Vec3 d = unit(n - tip * (mu / ml * t1 + mv / ml * t2));
      const Vec3 na = support_a(d);
      const Vec3 nb = support_b(-d);
      ++r.iterations;
      const Vec3 w = na - nb;
      const Real nu = glm::dot(t1, w);
      const Real nv = glm::dot(t2, w);
      if (mm - (mu * nu + mv * nv) <= close * ml) break;  // no progress towards the line
      const auto k = static_cast<std::size_t>(count);
      pa[k] = na;
      pb[k] = nb;
      u[k] = nu;
      v[k] = nv;
      const int total = count + 1;
      // Smallest-norm point of the hull of the points: vertices, segments, triangles.
      std::array<Real, 4> best{};
      Real best_norm = std::numeric_limits<Real>::infinity();
      const auto consider = [&](const std::array<Real, 4>& l) {
        Real x = Real(0);
        Real y = Real(0);
        for (std::size_t c = 0; c < 4; ++c) {
          x += l[c] * u[c];
          y += l[c] * v[c];
        }
        const Real nn = x * x + y * y;
        if (nn < best_norm) {
          best_norm = nn;
          best = l;
        }
      };
      for (std::size_t i0 = 0; i0 < static_cast<std::size_t>(total); ++i0) {
        std::array<Real, 4> w1{};
        w1[i0] = Real(1);
        consider(w1);
        for (std::size_t j0 = i0 + 1; j0 < static_cast<std::size_t>(total); ++j0) {
          const Real eu = u[j0] - u[i0];
          const Real ev = v[j0] - v[i0];
          const Real ee = eu * eu + ev * ev;
          if (ee > Real(0)) {
            const Real t = -(u[i0] * eu + v[i0] * ev) / ee;
            if (t > Real(0) && t < Real(1)) {
              std::array<Real, 4> w2{};
              w2[i0] = Real(1) - t;
              w2[j0] = t;
              consider(w2);
            }
          }
          for (std::size_t k0 = j0 + 1; k0 < static_cast<std::size_t>(total); ++k0) {
            const Real den = (u[j0] - u[i0]) * (v[k0] - v[i0]) - (v[j0] - v[i0]) * (u[k0] - u[i0]);
            if (!(std::abs(den) > Real(0))) continue;
            const Real li = (u[j0] * v[k0] - v[j0] * u[k0]) / den;
            const Real lj = (u[k0] * v[i0] - v[k0] * u[i0]) / den;
            const Real lk = Real(1) - li - lj;
            if (li >= Real(0) && lj >= Real(0) && lk >= Real(0)) {
              std::array<Real, 4> w3{};
              w3[i0] = li;
              w3[j0] = lj;
              w3[k0] = lk;
              consider(w3);
            }
          }
        }
      }
      // Keep the points with weight (at most three).
      count = 0;
      mu = Real(0);
      mv = Real(0);
      for (std::size_t c = 0; c < static_cast<std::size_t>(total); ++c) {
        if (!(best[c] > Real(0))) continue;
        const auto o = static_cast<std::size_t>(count++);
        pa[o] = pa[c];
        pb[o] = pb[c];
        u[o] = u[c];
        v[o] = v[c];
        lam[o] = best[c];
        mu += best[c] * u[c];
        mv += best[c] * v[c];
      }
      for (auto c = static_cast<std::size_t>(count); c < 4; ++c) lam[c] = Real(0);
      if (count >= 3) break;  // the origin's projection is inside a triangle: done
    }
    Vec3 wa(Real(0));
    Vec3 wb(Real(0));
    for (std::size_t c = 0; c < static_cast<std::size_t>(count); ++c) {
      wa += lam[c] * pa[c];
      wb += lam[c] * pb[c];
    }
    const Vec3 residual = (wa - wb) - h * n;
    r.witness_gap = glm::length(residual);
    r.support_a = wa - Real(0.5) * residual;
    r.support_b = wb + Real(0.5) * residual;
  }
  return r;
}

}  // namespace proxima::epa
