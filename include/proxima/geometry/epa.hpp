#pragma once
/// @file epa.hpp
/// Expanding Polytope Algorithm: penetration depth and direction of two overlapping convex
/// sets from GJK's final simplex (van den Bergen, "Proximity Queries and Penetration Depth
/// Computation on 3D Game Objects", GDC 2001; Collision Detection in Interactive 3D
/// Environments, 2004, 4.3.3).
///
/// Steps (epa::penetration; each a function of epa::detail):
///   1. build the start polytope (grow_start, build_start_polytope): grow GJK's simplex to a
///      tetrahedron around the origin: a point gets a second vertex from the six axis
///      supports, a segment a third from supports perpendicular to it, a triangle the farther
///      of the supports along its two normals, a tetrahedron is used as is; if the Minkowski
///      difference D = A - B is flat, stop (Degenerate);
///   2. expand (expand): take the face nearest the origin, query D's support along its
///      normal; when the support is within tolerance of the face, that face gives depth and
///      normal; else remove the faces that see the new vertex (carve_horizon) and fan the
///      horizon to it (add_fan, link_fan);
///   3. when rounding stops the growth (a sliver face, a pinched horizon, storage or the
///      face budget exhausted) or at the cap: the nearest face, Converged when its gap is
///      within a loose tolerance (4096 eps x scale), else MaxIterations (its distance is a
///      lower bound of the depth, the support along its normal an upper bound);
///   4. extract the answer (extract_answer): barycentric coordinates of the origin's
///      projection on the final face applied to the support points of A and B (those of
///      the face's point nearest the origin when rounding left the projection outside it).
/// No allocation (fixed storage), never NaN. On curved supports EPA converges only linearly:
/// epa::refine (epa_refine.hpp), a separate algorithm, polishes its normal.

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
  /// Status MaxIterations only: unit normals of the polytope's faces nearest the origin after
  /// the nearest, up to eight, at least 30° from `normal` and from each other (nearest first), where a
  /// refinement may start: on a curved D the support distance can have several local minima.
  std::array<Vec3, 8> other_normals{};
  int other_count = 0;  ///< entries of other_normals in use
};

namespace detail {

// The storage below is left uninitialised on purpose (no default member initialisers): a
// face slot is written whole by add_face before any read (slots < nf), its links by link()
// or link_fan, a vertex before nv counts it, a free slot before nfree counts it. Zeroing
// these arrays (about 40 KB) used to cost as much as the expansion itself.
/// A triangle of the polytope: vertices (outward order), neighbours, outward plane.
struct Face {
  std::array<std::uint16_t, 3> v;
  std::array<std::uint16_t, 3> adj;      // face across edge e (v[e] -> v[e+1])
  std::array<std::uint8_t, 3> adj_edge;  // that edge's index in the neighbour
  Vec3 n;
  Real d;
  bool alive;
};

/// A vertex of D with its support points, like gjk::Vertex but trivially constructible.
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

/// The expanding polytope: vertices, face slots (dead ones recycled) and the face budget.
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

  // Marks the face in `slot` dead and its slot free.
  void kill(int slot) {
    faces[static_cast<std::size_t>(slot)].alive = false;
    free_slots[static_cast<std::size_t>(nfree++)] = static_cast<std::uint16_t>(slot);
    --alive;
  }
};

/// Support of D = A - B along d, with the support points of A and B that make it.
template <class SupportA, class SupportB>
gjk::Vertex support_vertex(SupportA& support_a, SupportB& support_b, const Vec3& d) {
  gjk::Vertex x;
  x.a = support_a(d);
  x.b = support_b(-d);
  x.w = x.a - x.b;
  return x;
}

/// Length thresholds of one run, all proportional to the size of the problem.
struct Thresholds {
  Real scale;       ///< size of the problem (> 0)
  Real eps_len;     ///< distinct-point and off-line threshold (64 eps x scale)
  Real area_floor;  ///< least |cross product| of a face's edges (eps^2 x scale^2)
};

/// The thresholds for a problem of size `length_scale`.
inline Thresholds thresholds(Real length_scale) {
  const Real scale = std::max(length_scale, std::numeric_limits<Real>::min());
  return {scale, Real(64) * kEpsilon * scale, kEpsilon * kEpsilon * scale * scale};
}

/// GJK's simplex on its way to a tetrahedron. `apex_on_triangle`: v[3] was added to the
/// triangle v[0..2] by add_apex (the faces are then made in a different order).
struct StartSimplex {
  std::array<gjk::Vertex, 4> v{};  ///< vertices of D with their support points
  int size = 0;                    ///< vertices in use (1..4)
  bool apex_on_triangle = false;   ///< v[3] is add_apex's apex on triangle v[0..2]
};

/// Copies GJK's simplex; an empty one gets D's support along +x.
template <class SupportA, class SupportB>
StartSimplex load_start(SupportA& support_a, SupportB& support_b, const gjk::Simplex& start) {
  StartSimplex s;
  s.size = std::clamp(start.size, 0, 4);
  for (int i = 0; i < s.size; ++i) s.v[static_cast<std::size_t>(i)] = start.v[static_cast<std::size_t>(i)];
  if (s.size == 0) {
    s.v[0] = support_vertex(support_a, support_b, Vec3(Real(1), Real(0), Real(0)));
    s.size = 1;
  }
  return s;
}

/// A point becomes a segment: the first of the six axis supports away from it. False when
/// D is a point.
template <class SupportA, class SupportB>
bool grow_to_segment(SupportA& support_a, SupportB& support_b, StartSimplex& s, const Thresholds& th) {
  const Vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const Vec3& d : axes) {
    const gjk::Vertex x = support_vertex(support_a, support_b, d);
    if (glm::length(x.w - s.v[0].w) > th.eps_len) {
      s.v[1] = x;
      s.size = 2;
      return true;
    }
  }
  return false;
}

/// A segment becomes a triangle: of the supports along six directions perpendicular to it
/// (60 degrees apart), the one farthest off its line. False when D is a segment.
template <class SupportA, class SupportB>
bool grow_to_triangle(SupportA& support_a, SupportB& support_b, StartSimplex& s, const Thresholds& th) {
  const Vec3 e = s.v[1].w - s.v[0].w;
  const Vec3 eu = e / glm::length(e);
  Vec3 axis(Real(1), Real(0), Real(0));
  if (std::abs(eu.y) < std::abs(eu[0]) && std::abs(eu.y) <= std::abs(eu.z))
    axis = Vec3(0, 1, 0);
  else if (std::abs(eu.z) < std::abs(eu[0]))
    axis = Vec3(0, 0, 1);
  const Vec3 d1 = glm::normalize(glm::cross(eu, axis));
  const Vec3 d2 = glm::cross(eu, d1);
  Real best = th.eps_len;
  for (int i = 0; i < 6; ++i) {
    const Real ang = Real(i) * Real(1.0471975511965976);
    const Vec3 d = std::cos(ang) * d1 + std::sin(ang) * d2;
    const gjk::Vertex x = support_vertex(support_a, support_b, d);
    const Vec3 rel = x.w - s.v[0].w;
    const Real off = glm::length(rel - eu * glm::dot(rel, eu));
    if (off > best) {
      best = off;
      s.v[2] = x;
      s.size = 3;
    }
  }
  return s.size == 3;
}

/// A triangle becomes a tetrahedron: the farther of D's supports along its two normals (a
/// bipyramid need not be convex). The origin lies on the triangle, so on the tetrahedron's
/// boundary; the expansion goes on from it. False when the triangle or D is flat.
template <class SupportA, class SupportB>
bool add_apex(SupportA& support_a, SupportB& support_b, StartSimplex& s, const Thresholds& th) {
  Vec3 nn = glm::cross(s.v[1].w - s.v[0].w, s.v[2].w - s.v[0].w);
  const Real len = glm::length(nn);
  if (!(len > th.area_floor)) return false;
  nn /= len;
  const gjk::Vertex up = support_vertex(support_a, support_b, nn);
  const gjk::Vertex down = support_vertex(support_a, support_b, -nn);
  const Real hu = glm::dot(nn, up.w - s.v[0].w);
  const Real hd = glm::dot(nn, s.v[0].w - down.w);
  if (hu >= hd && hu > th.eps_len)
    s.v[3] = up;
  else if (hd > th.eps_len)
    s.v[3] = down;
  else
    return false;  // D is flat
  s.size = 4;
  s.apex_on_triangle = true;
  return true;
}

/// Step 1a: grows the start simplex to a tetrahedron (point, segment, triangle, apex). False
/// when D is too thin to hold one.
template <class SupportA, class SupportB>
bool grow_start(SupportA& support_a, SupportB& support_b, StartSimplex& s, const Thresholds& th) {
  if (s.size == 1 && !grow_to_segment(support_a, support_b, s, th)) return false;
  if (s.size == 2 && !grow_to_triangle(support_a, support_b, s, th)) return false;
  if (s.size == 3 && !add_apex(support_a, support_b, s, th)) return false;
  return true;
}

/// The four faces of the start tetrahedron, turned outward. False when one is degenerate.
inline bool add_start_faces(Polytope& p, const StartSimplex& s, Real area_floor) {
  for (int i = 0; i < 4; ++i) p.verts[static_cast<std::size_t>(i)] = s.v[static_cast<std::size_t>(i)];
  p.nv = 4;
  if (!s.apex_on_triangle) {
    p.inner = (s.v[0].w + s.v[1].w + s.v[2].w + s.v[3].w) * Real(0.25);
    return p.add_face(0, 1, 2, area_floor) && p.add_face(0, 1, 3, area_floor) && p.add_face(0, 2, 3, area_floor) &&
           p.add_face(1, 2, 3, area_floor);
  }
  Vec3 inner = s.v[0].w + s.v[1].w + s.v[2].w;
  inner += s.v[3].w;
  p.inner = inner / Real(p.nv);
  return p.add_face(0, 1, 3, area_floor) && p.add_face(1, 2, 3, area_floor) && p.add_face(2, 0, 3, area_floor) &&
         p.add_face(0, 1, 2, area_floor);
}

/// Step 1b: the start polytope: faces, their adjacency, and the check that the origin is
/// inside (or on) it; false when it is not (the sets barely touch) or a face is degenerate.
inline bool build_start_polytope(Polytope& p, const StartSimplex& s, const Thresholds& th) {
  if (!add_start_faces(p, s, th.area_floor)) return false;
  std::array<int, 8> slots{};
  for (int f = 0; f < p.nf; ++f) slots[static_cast<std::size_t>(f)] = f;
  if (!p.link(slots.data(), p.nf)) return false;
  for (int f = 0; f < p.nf; ++f)
    if (p.faces[static_cast<std::size_t>(f)].d < -th.eps_len) return false;
  return true;
}

/// Slot of the live face nearest the origin, -1 when none is alive.
inline int nearest_face(const Polytope& p) {
  int best = -1;
  Real best_d = std::numeric_limits<Real>::infinity();
  for (int f = 0; f < p.nf; ++f) {
    const Face& face = p.faces[static_cast<std::size_t>(f)];
    if (face.alive && face.d < best_d) {
      best_d = face.d;
      best = f;
    }
  }
  return best;
}

/// The least support distance seen (an upper bound of the depth) and the normal it was seen along.
struct UpperBound {
  Real distance = std::numeric_limits<Real>::infinity();  ///< least n . s_D(n) over the normals queried
  Vec3 normal{Real(0), Real(0), Real(1)};                 ///< the n that gave it
};

/// Barycentric coordinates of the origin's projection on face f (unclamped).
inline Vec3 barycentric(const Polytope& p, const Face& f) {
  const Vec3 proj = f.n * std::max(f.d, Real(0));
  const Vec3& a = p.verts[f.v[0]].w;
  const Vec3& b = p.verts[f.v[1]].w;
  const Vec3& c = p.verts[f.v[2]].w;
  const Real den = glm::dot(f.n, glm::cross(b - a, c - a));
  const Real la = glm::dot(f.n, glm::cross(b - proj, c - proj)) / den;
  const Real lb = glm::dot(f.n, glm::cross(c - proj, a - proj)) / den;
  return Vec3(la, lb, Real(1) - la - lb);
}

/// The Minkowski difference of polytopes has flat faces that the polytope splits into
/// coplanar triangles: when the origin's projection falls outside `nearest`, the live face
/// within `slack` of it whose coordinates are least negative. Writes that face and its
/// coordinates. The other face must also be turned from `nearest` by no more than the
/// larger of `slack` and sqrt(eps) times D's radius (about `extent`) moves a plane across
/// D: a face merely close to the origin but turned away (a curved pair far from the world
/// origin, whose slack is loose) would answer with a normal that nothing certified.
inline void face_holding_projection(const Polytope& p, const Face& nearest, Real slack, Real extent, Face& f,
                                    Vec3& lam) {
  f = nearest;
  lam = barycentric(p, f);
  const Real inside = -Real(64) * kEpsilon;
  if (!(std::min({lam.x, lam.y, lam.z}) < inside)) return;
  for (int g = 0; g < p.nf; ++g) {
    const Face& other = p.faces[static_cast<std::size_t>(g)];
    if (!other.alive || other.d > nearest.d + slack) continue;
    if (Real(2) * extent * glm::length(other.n - nearest.n) > std::max(slack, kSqrtEpsilon * extent)) continue;
    const Vec3 l = barycentric(p, other);
    if (std::min({l.x, l.y, l.z}) > std::min({lam.x, lam.y, lam.z})) {
      lam = l;
      f = other;
    }
  }
}

/// Coordinates of the point of face f nearest the origin (gjk's triangle solver in
/// gjk::Wide on the exact vertices a - b): the witnesses of a face that does not hold the
/// origin's projection. Clamping the projection's coordinates instead would slide the point
/// along a sliver face (a cylinder's generator against a short chord) by up to the
/// sliver's length, though the projection lies a rounding-sized step outside it.
inline Vec3 nearest_point_coordinates(const Polytope& p, const Face& f) {
  std::array<gjk::BasicVertex<gjk::Wide>, 3> v;
  for (std::size_t i = 0; i < 3; ++i) {
    const PolyVertex& x = p.verts[f.v[i]];
    v[i].w = gjk::WideVec3(x.a) - gjk::WideVec3(x.b);
    v[i].a = Vec3(Real(i));  // a tag: which face vertex the solver kept
  }
  gjk::WideSimplex s;
  gjk::detail::solve_2d(v[0], v[1], v[2], s);
  Vec3 lam(Real(0));
  for (int k = 0; k < s.size; ++k) {
    const auto i = static_cast<int>(s.v[static_cast<std::size_t>(k)].a.x);
    lam[i] = Real(s.lambda[static_cast<std::size_t>(k)]);
  }
  return lam;
}

/// At the cap: the normals of the faces nearest the origin, each at least 30° from the answer's
/// normal and from those taken before (Outcome::other_normals), nearest first.
inline void collect_other_normals(const Polytope& p, Outcome& r) {
  const Real cos30 = Real(0.8660254);
  while (r.other_count < static_cast<int>(r.other_normals.size())) {
    int best = -1;
    for (int i = 0; i < p.nf; ++i) {
      const Face& f = p.faces[static_cast<std::size_t>(i)];
      if (!f.alive || (best >= 0 && !(f.d < p.faces[static_cast<std::size_t>(best)].d))) continue;
      bool apart = glm::dot(f.n, r.normal) < cos30;
      for (int k = 0; k < r.other_count && apart; ++k)
        apart = glm::dot(f.n, r.other_normals[static_cast<std::size_t>(k)]) < cos30;
      if (apart) best = i;
    }
    if (best < 0) return;
    r.other_normals[static_cast<std::size_t>(r.other_count++)] = p.faces[static_cast<std::size_t>(best)].n;
  }
}

/// Step 3: the answer from the nearest face: depth and normal, and witnesses from the
/// coordinates of the origin's projection applied to A's and B's support points: clamped
/// and normalised when the projection is inside the face within rounding, else those of
/// the face's point nearest the origin.
inline Outcome extract_answer(const Polytope& p, const Face& nearest, Status status, int iterations,
                              const UpperBound& upper, const Thresholds& th, const Settings& settings) {
  Face f;
  Vec3 lam;
  face_holding_projection(p, nearest, std::max(Real(64) * kEpsilon * th.scale, settings.abs_tolerance), th.scale, f,
                          lam);
  if (std::min({lam.x, lam.y, lam.z}) < -Real(64) * kEpsilon) lam = nearest_point_coordinates(p, f);
  Real la = std::clamp(lam.x, Real(0), Real(1));
  Real lb = std::clamp(lam.y, Real(0), Real(1));
  Real lc = std::clamp(lam.z, Real(0), Real(1));
  const PolyVertex& a = p.verts[f.v[0]];
  const PolyVertex& b = p.verts[f.v[1]];
  const PolyVertex& c = p.verts[f.v[2]];
  const Real sum = la + lb + lc;
  if (sum > Real(0)) {
    la /= sum;
    lb /= sum;
    lc /= sum;
  } else {
    la = Real(1);
  }
  Outcome r;
  r.status = status;
  r.depth = std::max(f.d, Real(0));
  r.normal = f.n;
  r.point_a = la * a.a + lb * b.a + lc * c.a;
  r.point_b = la * a.b + lb * b.b + lc * c.b;
  r.iterations = iterations;
  r.gap = upper.distance - nearest.d;
  r.upper_normal = std::isfinite(upper.distance) ? upper.normal : f.n;
  if (status == Status::MaxIterations) collect_other_normals(p, r);
  return r;
}

/// Work arrays of one expansion step, written before read (entries below `count` / the
/// stack top): left uninitialised, like the polytope's storage.
struct HorizonWork {
  std::array<std::array<std::uint16_t, 2>, kMaxFaces> horizon;  // (unseen face, its edge), in walk order
  std::array<std::array<std::uint16_t, 2>, kMaxFaces> stack;    // (face, edge entered by)
  std::array<int, kMaxFaces> fan;                               // slot of the new face on each horizon edge
  int count;                                                    // horizon edges
};

/// Step 2a: removes `nearest` (slot `slot`) and every face that sees `w`, by a depth-first walk
/// across edges; the horizon is the ordered list of (unseen face, edge) where the walk
/// stopped. False when the work arrays overflow or the horizon has fewer than three edges.
inline bool carve_horizon(Polytope& p, int slot, const Face& nearest, const Vec3& w, HorizonWork& work) {
  const auto sees = [&](const Face& face) { return glm::dot(face.n, w - p.verts[face.v[0]].w) > Real(0); };
  int nh = 0;
  int top = 0;
  p.kill(slot);
  for (int e = 2; e >= 0; --e) {
    work.stack[static_cast<std::size_t>(top++)] = {nearest.adj[static_cast<std::size_t>(e)],
                                                   nearest.adj_edge[static_cast<std::size_t>(e)]};
  }
  while (top > 0) {
    const auto item = work.stack[static_cast<std::size_t>(--top)];
    Face& face = p.faces[item[0]];
    if (!face.alive) continue;
    if (!sees(face)) {
      if (nh >= kMaxFaces) return false;
      work.horizon[static_cast<std::size_t>(nh++)] = item;
      continue;
    }
    p.kill(item[0]);
    for (int k = 2; k >= 1; --k) {
      const std::size_t e = (item[1] + static_cast<std::size_t>(k)) % 3;
      if (top >= kMaxFaces) return false;
      work.stack[static_cast<std::size_t>(top++)] = {face.adj[e], face.adj_edge[e]};
    }
  }
  work.count = nh;
  return nh >= 3;
}

/// Step 2b: one new face from each horizon edge to vertex `wi`. False when one is
/// degenerate or over budget.
inline bool add_fan(Polytope& p, HorizonWork& work, int wi, Real area_floor) {
  for (int h = 0; h < work.count; ++h) {
    const auto& item = work.horizon[static_cast<std::size_t>(h)];
    const Face& g = p.faces[item[0]];
    const std::uint16_t a = g.v[(item[1] + 1u) % 3u];
    const std::uint16_t b = g.v[item[1]];
    if (!p.add_face(a, b, wi, area_floor, false)) return false;
    work.fan[static_cast<std::size_t>(h)] = p.last;
  }
  return true;
}

/// Step 2c: links each fan face to its horizon neighbour (edge 0) and to the fan faces
/// beside it. False when the horizon is pinched (a vertex met twice).
inline bool link_fan(Polytope& p, const HorizonWork& work) {
  const int nh = work.count;
  for (int h = 0; h < nh; ++h) {
    const auto& item = work.horizon[static_cast<std::size_t>(h)];
    const int slot = work.fan[static_cast<std::size_t>(h)];
    Face& f = p.faces[static_cast<std::size_t>(slot)];
    Face& g = p.faces[item[0]];
    f.adj[0] = item[0];
    f.adj_edge[0] = static_cast<std::uint8_t>(item[1]);
    g.adj[item[1]] = static_cast<std::uint16_t>(slot);
    g.adj_edge[item[1]] = 0;
    int next = -1;
    int count = 0;
    for (int x = 0; x < nh; ++x) {
      if (p.faces[static_cast<std::size_t>(work.fan[static_cast<std::size_t>(x)])].v[0] == f.v[1]) {
        next = x;
        ++count;
      }
    }
    if (count != 1) return false;
    const int nslot = work.fan[static_cast<std::size_t>(next)];
    f.adj[1] = static_cast<std::uint16_t>(nslot);
    f.adj_edge[1] = 2;
    p.faces[static_cast<std::size_t>(nslot)].adj[2] = static_cast<std::uint16_t>(slot);
    p.faces[static_cast<std::size_t>(nslot)].adj_edge[2] = 1;
  }
  return true;
}

/// Step 2: expands the polytope until the nearest face's support gap is within tolerance,
/// the cap, or rounding stops the growth (see the file comment), then extracts the answer.
template <class SupportA, class SupportB>
Outcome expand(Polytope& p, SupportA& support_a, SupportB& support_b, const Thresholds& th, const Settings& settings) {
  UpperBound upper;
  HorizonWork work;
  for (int it = 0;; ++it) {
    const int best = nearest_face(p);
    if (best < 0) return Outcome{};
    const Face closest = p.faces[static_cast<std::size_t>(best)];
    if (it >= settings.max_iterations)
      return extract_answer(p, closest, Status::MaxIterations, it, upper, th, settings);
    const gjk::Vertex w = support_vertex(support_a, support_b, closest.n);
    const Real dw = glm::dot(closest.n, w.w);
    const Real tol = std::max(
        {settings.abs_tolerance, settings.rel_tolerance * std::max(closest.d, Real(0)), Real(8) * kEpsilon * th.scale});
    if (dw < upper.distance) upper = {dw, closest.n};
    if (dw - closest.d <= tol) return extract_answer(p, closest, Status::Converged, it + 1, upper, th, settings);
    // Rounding can leave the polytope unable to grow (a sliver face, a pinched horizon, full
    // storage): answer with the nearest face, Converged when its gap is within a loose tolerance.
    const Real loose_tol = std::max(Real(32) * tol, Real(4096) * kEpsilon * th.scale);
    const auto stuck = [&]() {
      const Status status = dw - closest.d <= loose_tol ? Status::Converged : Status::MaxIterations;
      return extract_answer(p, closest, status, it + 1, upper, th, settings);
    };
    if (p.nv >= kMaxVertices) return stuck();
    const int wi = p.nv;
    p.verts[static_cast<std::size_t>(wi)] = w;
    ++p.nv;
    if (!carve_horizon(p, best, closest, w.w, work) || !add_fan(p, work, wi, th.area_floor) || !link_fan(p, work))
      return stuck();
  }
}

}  // namespace detail

/// Penetration depth of A and B (overlapping) from GJK's final simplex, with support
/// functors in a common frame as for gjk::distance. `length_scale` (> 0) is the size of
/// the problem, for the degeneracy thresholds. O(iterations x (faces + support cost)).
template <class SupportA, class SupportB>
Outcome penetration(SupportA& support_a, SupportB& support_b, const gjk::Simplex& start, Real length_scale,
                    const Settings& settings) {
  const detail::Thresholds th = detail::thresholds(length_scale);
  detail::StartSimplex s = detail::load_start(support_a, support_b, start);
  if (!detail::grow_start(support_a, support_b, s, th)) return Outcome{};
  detail::Polytope p;
  p.budget = std::clamp(settings.max_faces, 4, kMaxFaces);
  if (!detail::build_start_polytope(p, s, th)) return Outcome{};
  return detail::expand(p, support_a, support_b, th, settings);
}

}  // namespace proxima::epa
