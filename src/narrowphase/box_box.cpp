// Box-box: separating axes, exact distance and clipped contact manifold, all in the frame of
// one box with fixed-size stack buffers (no general-purpose face structures).
//
// Steps (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996, for the 15 axes; Ericson,
// Real-Time Collision Detection 4.4.1; Box2D / Dirk Gregorius for the clipping):
//  1. Work in A's frame: R = A^T B (from the relative rotation, once), t = A^T (cB - cA).
//     The 15 candidate axes are A's 3 face normals, B's 3 and the 9 cross products
//     A_i x B_j; a cross product of nearly parallel edges is skipped (its direction is
//     noise, and a parallel edge pair adds no face to the Minkowski difference). Each axis
//     is normalised so its separation is a length.
//  2. The largest separation over the axes decides: > 0 separated, <= 0 overlapping with
//     depth = -(largest separation), which is exact for polytopes (every face of the
//     Minkowski difference has one of these normals).
//  3. Separated: the exact distance is the smallest over the 16 corners clamped against the
//     other box and the edge pairs A_i, B_j whose axis separates the boxes by less than the
//     best distance so far (the separation along an axis bounds every distance from below;
//     the supporting edges along the separating side are the only candidates of a pair).
//  4. Manifold: the chosen axis (a face axis unless an edge axis is clearly shallower, for
//     stable manifolds); face axis: the reference face is a rectangle in its box's frame,
//     the incident face's 4 corners are projected along the normal onto its plane and
//     clipped against it in 2D (at most 8 points, gaps interpolated linearly), reduced to 4
//     by area (manifold_reduction.hpp) before anything is mapped to the world; edge axis:
//     the closest points of the two supporting edges. Separated pairs within the contact
//     distance clip the faces supporting the exact distance normal the same way.
//  5. The last separating axis is kept in PairCache::sat_feature and tried first.
#include <proxima/geometry/closest_points.hpp>

#include <array>
#include <cmath>
#include <limits>

#include "face_clipping.hpp"
#include "manifold_reduction.hpp"
#include "pairs_polyhedral.hpp"

namespace proxima::narrow {
namespace {

// Edge axes whose |A_i x B_j| (the sine of the angle) is below this are skipped.
const Real kParallelSine = Real(4) * kSqrtEpsilon;
// An edge axis replaces the best face axis in manifolds only when its separation exceeds
// kEdgeRelative * face separation (separations are negative when overlapping).
constexpr Real kEdgeRelative = Real(0.98);
// B's face axis replaces A's only when its separation exceeds kFaceRelative * A's.
constexpr Real kFaceRelative = Real(0.98);
constexpr int kAxes = 15;
constexpr Real kInfinity = std::numeric_limits<Real>::infinity();

// The pair in A's frame.
struct BoxPair {
  Vec3 a;         // A's half extents
  Vec3 b;         // B's half extents
  Real r[3][3];   // r[i][j] = A_i . B_j
  Real ar[3][3];  // |r|
  Vec3 t;         // B's centre in A's frame
  Real ha[3];     // a, b and t as plain arrays (glm's operator[] is a switch)
  Real hb[3];
  Real tt[3];
  Real tol;       // distance tolerance of the pair
  Real rounding;  // a few rounding errors at the pair's own size (not clamped to 1)
};

BoxPair make_pair(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                  const PairRequest& request) {
  BoxPair p;
  p.a = a.half_extents();
  p.b = b.half_extents();
  const Quat qa_inv = glm::conjugate(pose_a.rotation);
  const Mat3 rel = glm::mat3_cast(qa_inv * pose_b.rotation);  // column j = B_j in A's frame
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      p.r[i][j] = rel[j][i];
      p.ar[i][j] = std::abs(p.r[i][j]);
    }
  }
  p.t = qa_inv * (pose_b.position - pose_a.position);
  for (int i = 0; i < 3; ++i) {
    p.ha[i] = p.a[i];
    p.hb[i] = p.b[i];
    p.tt[i] = p.t[i];
  }
  const Real scale = std::max({max_abs_component(p.a), max_abs_component(p.b), max_abs_component(p.t)});
  p.tol = resolve_tolerance(request, scale);
  p.rounding = kRelativeTolerance * scale;
  return p;
}

Vec3 b_axis(const BoxPair& p, int j) { return Vec3(p.r[0][j], p.r[1][j], p.r[2][j]); }

// Separation of the boxes along axis k (0-2 A's faces, 3-5 B's, 6-14 A_i x B_j with
// i = (k-6)/3, j = (k-6)%3), and the unit axis in A's frame pointing from A to B. Returns
// false for a skipped (parallel) edge axis.
bool axis_separation(const BoxPair& p, int k, Real& sep, Vec3& axis) {
  Real l[3] = {Real(0), Real(0), Real(0)};
  if (k < 3) {
    const int i = k;
    const Real rb = p.hb[0] * p.ar[i][0] + p.hb[1] * p.ar[i][1] + p.hb[2] * p.ar[i][2];
    sep = std::abs(p.tt[i]) - (p.ha[i] + rb);
    l[i] = p.tt[i] >= Real(0) ? Real(1) : Real(-1);
    axis = Vec3(l[0], l[1], l[2]);
    return true;
  }
  if (k < 6) {
    const int j = k - 3;
    const Real ra = p.ha[0] * p.ar[0][j] + p.ha[1] * p.ar[1][j] + p.ha[2] * p.ar[2][j];
    const Real tj = p.tt[0] * p.r[0][j] + p.tt[1] * p.r[1][j] + p.tt[2] * p.r[2][j];
    sep = std::abs(tj) - (ra + p.hb[j]);
    const Real s = tj >= Real(0) ? Real(1) : Real(-1);
    axis = s * b_axis(p, j);
    return true;
  }
  const int i = (k - 6) / 3;
  const int j = (k - 6) % 3;
  const int i1 = (i + 1) % 3;
  const int i2 = (i + 2) % 3;
  const int j1 = (j + 1) % 3;
  const int j2 = (j + 2) % 3;
  const Real len = std::sqrt(p.r[i1][j] * p.r[i1][j] + p.r[i2][j] * p.r[i2][j]);
  if (!(len > kParallelSine)) return false;
  const Real ra = p.ha[i1] * p.ar[i2][j] + p.ha[i2] * p.ar[i1][j];
  const Real rb = p.hb[j1] * p.ar[i][j2] + p.hb[j2] * p.ar[i][j1];
  const Real tl = p.tt[i2] * p.r[i1][j] - p.tt[i1] * p.r[i2][j];
  sep = (std::abs(tl) - (ra + rb)) / len;
  const Real sign = tl < Real(0) ? Real(-1) : Real(1);
  l[i1] = -sign * p.r[i2][j] / len;
  l[i2] = sign * p.r[i1][j] / len;
  axis = Vec3(l[0], l[1], l[2]);
  return true;
}

struct SatResult {
  Real max_sep = -kInfinity;  // over all axes (exact)
  int max_axis = 0;
  Vec3 max_normal{Real(0), Real(0), Real(1)};
  Real face_a_sep = -kInfinity;
  int face_a_axis = 0;
  Real face_b_sep = -kInfinity;
  int face_b_axis = 3;
  Real edge_sep = -kInfinity;
  int edge_axis = -1;
  bool early_out = false;  // stopped at an axis separating by more than the limit
  // Separation of each edge axis (-infinity when skipped); complete only without early out.
  std::array<Real, 9> edge_seps;
};

// Separations along all 15 axes, straight-line (no axis vectors): sep[k] as in
// axis_separation, -infinity for a skipped edge axis. Returns the largest face separation
// (the 6 face axes are computed first so a caller may stop there).
void face_separations(const BoxPair& p, Real* sep) {
  for (int i = 0; i < 3; ++i) {
    sep[i] = std::abs(p.tt[i]) - (p.ha[i] + p.hb[0] * p.ar[i][0] + p.hb[1] * p.ar[i][1] + p.hb[2] * p.ar[i][2]);
  }
  for (int j = 0; j < 3; ++j) {
    const Real tj = p.tt[0] * p.r[0][j] + p.tt[1] * p.r[1][j] + p.tt[2] * p.r[2][j];
    sep[3 + j] = std::abs(tj) - (p.ha[0] * p.ar[0][j] + p.ha[1] * p.ar[1][j] + p.ha[2] * p.ar[2][j] + p.hb[j]);
  }
}

void edge_separations(const BoxPair& p, Real* sep) {
  static constexpr int kNext[3] = {1, 2, 0};
  static constexpr int kPrev[3] = {2, 0, 1};
  for (int i = 0; i < 3; ++i) {
    const int i1 = kNext[i];
    const int i2 = kPrev[i];
    for (int j = 0; j < 3; ++j) {
      const int j1 = kNext[j];
      const int j2 = kPrev[j];
      const Real len = std::sqrt(p.r[i1][j] * p.r[i1][j] + p.r[i2][j] * p.r[i2][j]);
      const Real ra = p.ha[i1] * p.ar[i2][j] + p.ha[i2] * p.ar[i1][j];
      const Real rb = p.hb[j1] * p.ar[i][j2] + p.hb[j2] * p.ar[i][j1];
      const Real tl = p.tt[i2] * p.r[i1][j] - p.tt[i1] * p.r[i2][j];
      sep[6 + 3 * i + j] = len > kParallelSine ? (std::abs(tl) - (ra + rb)) / len : -kInfinity;
    }
  }
}

// Runs the 15 axes; stops after the face axes when one separates by more than `limit`.
SatResult run_sat(const BoxPair& p, Real limit, const PairCache* cache) {
  SatResult s;
  if (cache != nullptr && cache->valid && cache->sat_feature < static_cast<std::uint32_t>(kAxes)) {
    Real sep = Real(0);
    Vec3 axis(Real(0), Real(0), Real(1));
    const int k = static_cast<int>(cache->sat_feature);
    if (axis_separation(p, k, sep, axis) && sep > limit) {
      s.max_sep = sep;
      s.max_axis = k;
      s.max_normal = axis;
      s.early_out = true;
      return s;
    }
  }
  Real sep[kAxes];
  face_separations(p, sep);
  s.face_a_axis = sep[1] > sep[0] ? 1 : 0;
  if (sep[2] > sep[s.face_a_axis]) s.face_a_axis = 2;
  s.face_a_sep = sep[s.face_a_axis];
  s.face_b_axis = sep[4] > sep[3] ? 4 : 3;
  if (sep[5] > sep[s.face_b_axis]) s.face_b_axis = 5;
  s.face_b_sep = sep[s.face_b_axis];
  // Largest face axis, A's first on ties.
  s.max_axis = s.face_b_sep > s.face_a_sep ? s.face_b_axis : s.face_a_axis;
  s.max_sep = sep[s.max_axis];
  if (s.max_sep > limit) {
    s.early_out = true;
  } else {
    edge_separations(p, sep);
    for (int k = 6; k < kAxes; ++k) {
      const Real e = sep[k];
      s.edge_seps[static_cast<std::size_t>(k - 6)] = e;
      if (e > s.edge_sep) {
        s.edge_sep = e;
        s.edge_axis = k;
      }
      // An edge axis must beat the face axes by more than the rounding: nearly parallel
      // edges give an axis next to a face normal with the same separation up to rounding,
      // and its supporting edges would not witness it.
      if (e > s.max_sep + (s.max_axis < 6 ? p.rounding : Real(0))) {
        s.max_sep = e;
        s.max_axis = k;
      }
    }
    s.early_out = s.max_sep > limit;
  }
  Real check = Real(0);
  static_cast<void>(axis_separation(p, s.max_axis, check, s.max_normal));
  return s;
}

void store_cache(PairCache* cache, const SatResult& s) {
  if (cache == nullptr) return;
  cache->sat_feature = static_cast<std::uint32_t>(s.max_axis);
  cache->axis = s.max_normal;
  cache->valid = true;
}

// Supporting edge of A (index i) and B (index j) along the A-frame normal n, as segments.
void supporting_edges(const BoxPair& p, int i, int j, const Vec3& n, Vec3& a0, Vec3& a1, Vec3& b0, Vec3& b1) {
  const Real nn[3] = {n.x, n.y, n.z};
  Real ca[3];
  Real ea[3] = {Real(0), Real(0), Real(0)};
  for (int m = 0; m < 3; ++m) ca[m] = m == i ? Real(0) : (nn[m] >= Real(0) ? p.ha[m] : -p.ha[m]);
  ea[i] = p.ha[i];
  a0 = Vec3(ca[0] - ea[0], ca[1] - ea[1], ca[2] - ea[2]);
  a1 = Vec3(ca[0] + ea[0], ca[1] + ea[1], ca[2] + ea[2]);
  Vec3 cb = p.t;
  Vec3 eb(Real(0));
  for (int m = 0; m < 3; ++m) {
    const Vec3 bm = b_axis(p, m);
    if (m == j) {
      eb = p.hb[m] * bm;
    } else {
      cb += (glm::dot(n, bm) <= Real(0) ? p.hb[m] : -p.hb[m]) * bm;
    }
  }
  b0 = cb - eb;
  b1 = cb + eb;
}

// Closest points of two boxes in A's frame and their squared distance.
struct ClosestFeatures {
  Real d2 = kInfinity;
  Vec3 on_a{Real(0)};
  Vec3 on_b{Real(0)};
};

// Exact closest points of two separated boxes, in A's frame (step 3). `s` must come from a
// full SAT run (no early out).
ClosestFeatures closest_features(const BoxPair& p, const SatResult& s) {
  ClosestFeatures best;
  const Vec3 bx = b_axis(p, 0);
  const Vec3 by = b_axis(p, 1);
  const Vec3 bz = b_axis(p, 2);
  // B's corners against A.
  for (int c = 0; c < 8; ++c) {
    const Vec3 v =
        p.t + ((c & 1) ? p.b.x : -p.b.x) * bx + ((c & 2) ? p.b.y : -p.b.y) * by + ((c & 4) ? p.b.z : -p.b.z) * bz;
    const Vec3 q = glm::clamp(v, -p.a, p.a);
    const Real d2 = length_squared(v - q);
    if (d2 < best.d2) best = {d2, q, v};
  }
  // A's corners against B (in B's frame, centred on B).
  for (int c = 0; c < 8; ++c) {
    const Vec3 v((c & 1) ? p.a.x : -p.a.x, (c & 2) ? p.a.y : -p.a.y, (c & 4) ? p.a.z : -p.a.z);
    const Vec3 w = v - p.t;
    const Vec3 local(glm::dot(w, bx), glm::dot(w, by), glm::dot(w, bz));
    const Vec3 q = glm::clamp(local, -p.b, p.b);
    const Real d2 = length_squared(local - q);
    if (d2 < best.d2) best = {d2, v, p.t + q.x * bx + q.y * by + q.z * bz};
  }
  // Edge pairs: the closest points of edges A_i, B_j (inner points of both) differ along
  // +-(A_i x B_j), on the side where that axis separates the boxes, by at least its
  // separation; a pair whose axis does not separate, or separates by more than the best
  // distance so far, cannot improve it.
  for (int k = 0; k < 9; ++k) {
    const Real sep = s.edge_seps[static_cast<std::size_t>(k)];
    if (!(sep > Real(0)) || sep * sep >= best.d2) continue;
    Real check = Real(0);
    Vec3 n(Real(0), Real(0), Real(1));
    if (!axis_separation(p, 6 + k, check, n)) continue;
    Vec3 a0;
    Vec3 a1;
    Vec3 b0;
    Vec3 b1;
    supporting_edges(p, k / 3, k % 3, n, a0, a1, b0, b1);
    const geometry::SegmentPair sp = geometry::closest_points_segment_segment(a0, a1, b0, b1);
    if (sp.distance_squared < best.d2) best = {sp.distance_squared, sp.on_a, sp.on_b};
  }
  return best;
}

// ---- Face clipping in the reference box's frame -------------------------------------------

// The incident box seen from the reference box: half extents, axes and centre in the
// reference frame.
struct RefFrame {
  Vec3 h;         // reference half extents
  Vec3 g;         // incident half extents
  Vec3 axes[3];   // incident axes in the reference frame
  Vec3 c;         // incident centre in the reference frame
  bool ref_is_a;  // the reference box is A
};

RefFrame frame_of_a(const BoxPair& p) {
  RefFrame f;
  f.h = p.a;
  f.g = p.b;
  for (int j = 0; j < 3; ++j) f.axes[j] = b_axis(p, j);
  f.c = p.t;
  f.ref_is_a = true;
  return f;
}

RefFrame frame_of_b(const BoxPair& p) {
  RefFrame f;
  f.h = p.b;
  f.g = p.a;
  for (int i = 0; i < 3; ++i) f.axes[i] = Vec3(p.r[i][0], p.r[i][1], p.r[i][2]);
  const Vec3 bx = b_axis(p, 0);
  const Vec3 by = b_axis(p, 1);
  const Vec3 bz = b_axis(p, 2);
  f.c = -Vec3(glm::dot(p.t, bx), glm::dot(p.t, by), glm::dot(p.t, bz));
  f.ref_is_a = false;
  return f;
}

// A clipped point: 2D position on the reference plane, gap along the projection direction,
// feature ids. Deliberately without default member initialisers (stack buffers stay raw).
struct ClipPoint {
  Real u;
  Real v;
  Real gap;
  std::uint32_t id;    // incident corner (sign bits) or crossing hash
  std::uint32_t side;  // side plane that made a crossing
  bool crossing;
};

constexpr std::uint32_t edge_hash(std::uint32_t a, std::uint32_t b, std::uint32_t side) {
  const std::uint32_t lo = std::min(a, b);
  const std::uint32_t hi = std::max(a, b);
  return (lo * 131u + hi * 7u + side * 977u) & 0x3FFFu;
}

// Keeps the part of polygon `in` (n points) where sign * coordinate <= limit (coordinate u
// when `along_u`, else v); writes to `out`, returns the new count (<= n + 1).
int clip_side(const ClipPoint* in, int n, ClipPoint* out, bool along_u, Real sign, Real limit, std::uint32_t side) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const ClipPoint& c = in[i];
    const ClipPoint& x = in[i + 1 == n ? 0 : i + 1];
    const Real dc = sign * (along_u ? c.u : c.v) - limit;
    const Real dx = sign * (along_u ? x.u : x.v) - limit;
    if (dc <= Real(0)) out[m++] = c;
    if ((dc <= Real(0)) != (dx <= Real(0))) {
      const Real w = dc / (dc - dx);
      ClipPoint q;
      q.u = c.u + (x.u - c.u) * w;
      q.v = c.v + (x.v - c.v) * w;
      q.gap = c.gap + (x.gap - c.gap) * w;
      q.id = edge_hash(c.id, x.id, side);
      q.side = side;
      q.crossing = true;
      out[m++] = q;
    }
  }
  return m;
}

// Candidate contacts in the reference frame, before reduction.
struct FaceContacts {
  Vec3 on_ref[9];
  Vec3 on_inc[9];
  Real depth[9];
  std::uint32_t id[9];
  int count;
};

// Clips the incident box's face most opposed to `dir` (unit, reference frame, from the
// reference box towards the incident one) against the reference face whose normal is
// nearest `dir`, projecting along `dir`. Returns false when that face is tilted more than
// acos(kReferenceFaceCosine) from `dir`; else writes the points whose gap is at most
// `contact_distance` (possibly none).
bool clip_box_faces(const RefFrame& f, const Vec3& dir, Real contact_distance, FaceContacts& out) {
  out.count = 0;
  // Plain arrays: glm's operator[] with a run-time index is a switch.
  const Real dv[3] = {dir.x, dir.y, dir.z};
  const Real hh[3] = {f.h.x, f.h.y, f.h.z};
  const Real gg[3] = {f.g.x, f.g.y, f.g.z};
  const Real ad[3] = {std::abs(dv[0]), std::abs(dv[1]), std::abs(dv[2])};
  int i = 0;
  if (ad[1] > ad[0]) i = 1;
  if (ad[2] > ad[i]) i = 2;
  if (!(ad[i] >= kReferenceFaceCosine)) return false;
  const int i1 = (i + 1) % 3;
  const int i2 = (i + 2) % 3;
  const Real s = dv[i] >= Real(0) ? Real(1) : Real(-1);
  const Real inv_cos = Real(1) / ad[i];
  const std::uint32_t ref_index = static_cast<std::uint32_t>(2 * i + (s > Real(0) ? 1 : 0));
  // Incident face: the incident axis most parallel to dir, on the side facing the reference.
  const Real dd[3] = {glm::dot(dir, f.axes[0]), glm::dot(dir, f.axes[1]), glm::dot(dir, f.axes[2])};
  int j = 0;
  if (std::abs(dd[1]) > std::abs(dd[0])) j = 1;
  if (std::abs(dd[2]) > std::abs(dd[j])) j = 2;
  const int j1 = (j + 1) % 3;
  const int j2 = (j + 2) % 3;
  const Real sj = dd[j] <= Real(0) ? Real(1) : Real(-1);  // the face of the incident box facing back
  const Vec3 centre = f.c + (sj * gg[j]) * f.axes[j];
  const Vec3 e1 = gg[j1] * f.axes[j1];
  const Vec3 e2 = gg[j2] * f.axes[j2];
  static constexpr Real kS1[4] = {1, -1, -1, 1};
  static constexpr Real kS2[4] = {1, 1, -1, -1};
  // Corner ids (sign bits on the incident box's axes): bit j from sj, bits j1, j2 from kS1, kS2.
  const std::uint32_t base_bits = sj > Real(0) ? (1u << j) : 0u;
  ClipPoint buf0[8];
  ClipPoint buf1[8];
  for (int v = 0; v < 4; ++v) {
    const Vec3 q = centre + kS1[v] * e1 + kS2[v] * e2;
    const Real qv[3] = {q.x, q.y, q.z};
    const Real gap = (s * qv[i] - hh[i]) * inv_cos;
    ClipPoint& cp = buf0[v];
    cp.u = qv[i1] - gap * dv[i1];
    cp.v = qv[i2] - gap * dv[i2];
    cp.gap = gap;
    cp.id = base_bits | (kS1[v] > Real(0) ? (1u << j1) : 0u) | (kS2[v] > Real(0) ? (1u << j2) : 0u);
    cp.side = 0;
    cp.crossing = false;
  }
  int n = 4;
  n = clip_side(buf0, n, buf1, true, Real(1), hh[i1], 0);
  n = clip_side(buf1, n, buf0, false, Real(1), hh[i2], 1);
  n = clip_side(buf0, n, buf1, true, Real(-1), hh[i1], 2);
  n = clip_side(buf1, n, buf0, false, Real(-1), hh[i2], 3);
  for (int k = 0; k < n; ++k) {
    const ClipPoint& q = buf0[k];
    if (!(q.gap <= contact_distance)) continue;
    Real r3[3];
    r3[i] = s * hh[i];
    r3[i1] = q.u;
    r3[i2] = q.v;
    const Vec3 on_ref(r3[0], r3[1], r3[2]);
    const int c = out.count++;
    out.on_ref[c] = on_ref;
    out.on_inc[c] = on_ref + q.gap * dir;
    out.depth[c] = -q.gap;
    const std::uint32_t rid = q.crossing ? ((ref_index * 32u + q.side) & 0x3FFFu) : ref_index;
    const FeatureKind rk = q.crossing ? FeatureKind::Edge : FeatureKind::Face;
    const FeatureKind ik = q.crossing ? FeatureKind::Edge : FeatureKind::Vertex;
    out.id[c] = f.ref_is_a ? make_feature_id(rk, rid, ik, q.id) : make_feature_id(ik, q.id, rk, rid);
  }
  return true;
}

// Reduces the candidates to at most max_contacts and writes them to `m` in the world frame
// (`pose_ref` maps the reference frame to the world). `normal` is the world normal A to B.
int reduce_to_manifold(const FaceContacts& fc, const Vec3& dir, bool ref_is_a, const Transform& pose_ref,
                       const Vec3& normal, int max_contacts, ContactManifold& m) {
  std::array<int, 4> chosen;
  const int k = std::clamp(max_contacts, 1, kMaxContactPoints);
  const int n = select_contacts(
      fc.count, [&](int q) { return (fc.on_ref[q] + fc.on_inc[q]) * Real(0.5); }, [&](int q) { return fc.depth[q]; },
      [](int) { return true; }, dir, k, chosen);
  for (int q = 0; q < n; ++q) {
    const int c = chosen[static_cast<std::size_t>(q)];
    ContactPoint& out = m.points[static_cast<std::size_t>(q)];
    const Vec3 pr = pose_ref.apply(fc.on_ref[c]);
    const Vec3 pi = pose_ref.apply(fc.on_inc[c]);
    out.point_a = ref_is_a ? pr : pi;
    out.point_b = ref_is_a ? pi : pr;
    out.normal = normal;
    out.depth = fc.depth[c];
    out.feature_id = fc.id[c];
  }
  m.count = n;
  return n;
}

// The closest points of the two supporting edges of edge axis k, as a one-point manifold.
void edge_manifold(const BoxPair& p, const Transform& pose_a, int k, Real sep, const Vec3& n_local,
                   ContactManifold& m) {
  Vec3 a0;
  Vec3 a1;
  Vec3 b0;
  Vec3 b1;
  const int i = (k - 6) / 3;
  const int j = (k - 6) % 3;
  supporting_edges(p, i, j, n_local, a0, a1, b0, b1);
  const geometry::SegmentPair sp = geometry::closest_points_segment_segment(a0, a1, b0, b1);
  m.count = 1;
  ContactPoint& c = m.points[0];
  c.point_a = pose_a.apply(sp.on_a);
  c.point_b = pose_a.apply(sp.on_b);
  c.normal = m.normal;
  c.depth = -sep;
  // Edge ids: the axis and which of the four parallel edges (sign bits of the normal).
  std::uint32_t ea = 0;
  std::uint32_t eb = 0;
  const Real nl[3] = {n_local.x, n_local.y, n_local.z};
  for (int q = 0, bit = 0; q < 3; ++q) {
    if (q == i) continue;
    if (nl[q] >= Real(0)) ea |= 1u << bit;
    ++bit;
  }
  for (int q = 0, bit = 0; q < 3; ++q) {
    if (q == j) continue;
    if (glm::dot(n_local, b_axis(p, q)) <= Real(0)) eb |= 1u << bit;
    ++bit;
  }
  c.feature_id = make_feature_id(FeatureKind::Edge, static_cast<std::uint32_t>(i) * 4u + ea, FeatureKind::Edge,
                                 static_cast<std::uint32_t>(j) * 4u + eb);
}

// Penetration (sep <= 0) along axis k with A-frame normal n_local: candidate contacts of the
// face axis k (< 6) clipped with the given contact distance. Returns the reference frame
// and the projection direction in it.
bool face_axis_contacts(const BoxPair& p, int k, const Vec3& n_local, Real contact_distance, FaceContacts& fc,
                        RefFrame& f, Vec3& dir) {
  if (k < 3) {
    f = frame_of_a(p);
    dir = n_local;
  } else {
    f = frame_of_b(p);
    // n_local = s B_j in A's frame, so -n in B's frame is -s e_j.
    const Vec3 bj = b_axis(p, k - 3);
    const Real sd = glm::dot(n_local, bj) >= Real(0) ? Real(-1) : Real(1);
    dir = Vec3(k == 3 ? sd : Real(0), k == 4 ? sd : Real(0), k == 5 ? sd : Real(0));
  }
  return clip_box_faces(f, dir, contact_distance, fc);
}

// One-point fallback along the A-frame normal: B's support point in -n and its image on A.
void support_point(const BoxPair& p, const Transform& pose_a, const Vec3& n_local, Real sep, ContactManifold& m) {
  Vec3 pb = p.t;
  for (int j = 0; j < 3; ++j) {
    const Vec3 bj = b_axis(p, j);
    pb += (glm::dot(n_local, bj) <= Real(0) ? p.hb[j] : -p.hb[j]) * bj;
  }
  m.count = 1;
  m.points[0] = ContactPoint{pose_a.apply(pb - sep * n_local), pose_a.apply(pb), m.normal, -sep, 0};
}

Transform frame_pose(const RefFrame& f, const Transform& pose_a, const Transform& pose_b) {
  return f.ref_is_a ? pose_a : pose_b;
}

// Manifold of an overlapping pair along axis k (exact separation sep): clipped faces for a
// face axis, the closest points of the supporting edges for an edge axis.
ContactManifold& overlap_on_axis(const BoxPair& p, const Transform& pose_a, const Transform& pose_b, int k, Real sep,
                                 const PairRequest& request, ContactManifold& m) {
  Real check = Real(0);
  Vec3 n_local(Real(0), Real(0), Real(1));
  static_cast<void>(axis_separation(p, k, check, n_local));
  m.status = status_from_distance(sep, p.tol);
  m.normal = pose_a.apply_vector(n_local);
  if (k < 6) {
    FaceContacts fc;
    RefFrame f;
    Vec3 dir(Real(0), Real(0), Real(1));
    if (face_axis_contacts(p, k, n_local, request.contact_distance, fc, f, dir) && fc.count > 0) {
      reduce_to_manifold(fc, dir, f.ref_is_a, frame_pose(f, pose_a, pose_b), m.normal, request.max_contacts, m);
    } else {
      support_point(p, pose_a, n_local, sep, m);
    }
    return m;
  }
  edge_manifold(p, pose_a, k, sep, n_local, m);
  return m;
}

}  // namespace

bool pair_intersect(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return false;
  const BoxPair p = make_pair(a, pose_a, b, pose_b, request);
  const Real limit = std::max(request.contact_distance, Real(0));
  const SatResult s = run_sat(p, limit, cache);
  store_cache(cache, s);
  if (s.early_out || s.max_sep > limit) return false;
  if (s.max_sep <= Real(0)) return true;
  return closest_features(p, s).d2 <= limit * limit;
}

DistanceResult pair_distance(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  const BoxPair p = make_pair(a, pose_a, b, pose_b, request);
  const SatResult s = run_sat(p, kInfinity, nullptr);
  store_cache(cache, s);
  DistanceResult r;
  r.method = PairMethod::Sat;
  if (s.max_sep > Real(0)) {
    const ClosestFeatures f = closest_features(p, s);
    const Real dist = std::sqrt(f.d2);
    Vec3 n = s.max_normal;
    Vec3 unit;
    Real len = Real(0);
    if (dist > p.tol * Real(1e-3) && unit_and_length(f.on_b - f.on_a, unit, len)) n = unit;
    r.signed_distance = std::max(dist, s.max_sep);
    r.point_a = pose_a.apply(f.on_a);
    r.point_b = pose_a.apply(f.on_b);
    r.normal = pose_a.apply_vector(n);
    r.status = status_from_distance(r.signed_distance, p.tol);
    return r;
  }
  // Overlapping: exact depth on the deepest-separating axis. Face axis: the deepest clipped
  // point (the Minkowski face through the origin is the sum of the two supporting features,
  // so the clipped incident face reaches the exact depth); edge axis: the closest points of
  // the two supporting edges.
  r.normal = pose_a.apply_vector(s.max_normal);
  r.signed_distance = s.max_sep;
  r.status = status_from_distance(r.signed_distance, p.tol);
  ContactManifold m;
  m.normal = r.normal;
  bool done = false;
  if (s.max_axis < 6) {
    FaceContacts fc;
    RefFrame f;
    Vec3 dir(Real(0), Real(0), Real(1));
    if (face_axis_contacts(p, s.max_axis, s.max_normal, kInfinity, fc, f, dir) && fc.count > 0) {
      int deepest = 0;
      for (int q = 1; q < fc.count; ++q) {
        if (fc.depth[q] > fc.depth[deepest]) deepest = q;
      }
      const Vec3 on_b = f.ref_is_a ? fc.on_inc[deepest] : fc.on_ref[deepest];
      r.point_b = frame_pose(f, pose_a, pose_b).apply(on_b);
      done = true;
    }
  } else {
    edge_manifold(p, pose_a, s.max_axis, s.max_sep, s.max_normal, m);
    r.point_b = m.points[0].point_b;
    done = true;
  }
  if (!done) {
    support_point(p, pose_a, s.max_normal, s.max_sep, m);
    r.point_b = m.points[0].point_b;
  }
  r.point_a = r.point_b - r.signed_distance * r.normal;
  return r;
}

ContactManifold pair_collide(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return invalid_manifold();
  const BoxPair p = make_pair(a, pose_a, b, pose_b, request);
  const Real limit = std::max(request.contact_distance, Real(0));
  const SatResult s = run_sat(p, limit, cache);
  store_cache(cache, s);
  ContactManifold m;
  m.method = PairMethod::Sat;
  if (s.early_out || s.max_sep > limit || request.max_contacts < 1) {
    m.normal = pose_a.apply_vector(s.max_normal);
    m.status = PairStatus::Separated;
    return m;
  }
  if (s.max_sep > Real(0)) {
    // Separated within the contact distance: faces supporting the exact distance normal,
    // the reference being the box whose face is better aligned with it.
    const ClosestFeatures cf = closest_features(p, s);
    const Real dist = std::sqrt(cf.d2);
    Vec3 n_local = s.max_normal;
    Vec3 unit;
    Real len = Real(0);
    if (dist > p.tol * Real(1e-3) && unit_and_length(cf.on_b - cf.on_a, unit, len)) n_local = unit;
    const Real sd = std::max(dist, s.max_sep);
    m.normal = pose_a.apply_vector(n_local);
    m.status = status_from_distance(sd, p.tol);
    if (!(sd <= request.contact_distance)) return m;
    const RefFrame fa = frame_of_a(p);
    const RefFrame fb = frame_of_b(p);
    const Vec3 n_b = -Vec3(glm::dot(n_local, b_axis(p, 0)), glm::dot(n_local, b_axis(p, 1)),
                           glm::dot(n_local, b_axis(p, 2)));  // -n in B's frame
    const bool use_a = max_abs_component(n_local) >= max_abs_component(n_b);
    const RefFrame& f = use_a ? fa : fb;
    const Vec3 dir = use_a ? n_local : n_b;
    FaceContacts fc;
    if (clip_box_faces(f, dir, request.contact_distance, fc)) {
      // The pair's own closest points, kept when every clipped point is shallower (tilted
      // reference face).
      Real deepest = -kInfinity;
      for (int q = 0; q < fc.count; ++q) deepest = std::max(deepest, fc.depth[q]);
      if (deepest < -sd) {
        const Transform to_ref = use_a ? Transform{} : pose_b.inverse() * pose_a;
        const int c = fc.count++;
        const Vec3 ra = to_ref.apply(cf.on_a);
        const Vec3 rb = to_ref.apply(cf.on_b);
        fc.on_ref[c] = use_a ? ra : rb;
        fc.on_inc[c] = use_a ? rb : ra;
        fc.depth[c] = -sd;
        fc.id[c] = 0;
      }
      if (fc.count > 0) {
        reduce_to_manifold(fc, dir, use_a, use_a ? pose_a : pose_b, m.normal, request.max_contacts, m);
        return m;
      }
    }
    m.count = 1;
    m.points[0] = ContactPoint{pose_a.apply(cf.on_a), pose_a.apply(cf.on_b), m.normal, -sd, 0};
    return m;
  }
  // Overlapping: prefer a face axis (A's, then B's) unless an edge axis is clearly shallower.
  int k = s.face_a_axis;
  Real sep = s.face_a_sep;
  if (s.face_b_sep > kFaceRelative * s.face_a_sep + Real(1e-3) * p.tol) {
    k = s.face_b_axis;
    sep = s.face_b_sep;
  }
  if (s.edge_axis >= 0 && s.edge_sep > kEdgeRelative * sep + Real(1e-3) * p.tol) {
    k = s.edge_axis;
    sep = s.edge_sep;
  }
  Real check = Real(0);
  Vec3 n_local(Real(0), Real(0), Real(1));
  static_cast<void>(axis_separation(p, k, check, n_local));
  m.status = status_from_distance(sep, p.tol);
  m.normal = pose_a.apply_vector(n_local);
  if (k < 6) {
    FaceContacts fc;
    RefFrame f;
    Vec3 dir(Real(0), Real(0), Real(1));
    if (face_axis_contacts(p, k, n_local, request.contact_distance, fc, f, dir) && fc.count > 0) {
      // A preferred (not deepest-separating) face axis is kept only while no point goes
      // deeper than the pair's exact depth; else the exact axis decides.
      Real deepest = -kInfinity;
      for (int q = 0; q < fc.count; ++q) deepest = std::max(deepest, fc.depth[q]);
      if (k == s.max_axis || deepest <= -s.max_sep + p.tol) {
        reduce_to_manifold(fc, dir, f.ref_is_a, frame_pose(f, pose_a, pose_b), m.normal, request.max_contacts, m);
        return m;
      }
    } else if (k == s.max_axis) {
      support_point(p, pose_a, n_local, sep, m);
      return m;
    }
    if (k != s.max_axis) return overlap_on_axis(p, pose_a, pose_b, s.max_axis, s.max_sep, request, m);
    support_point(p, pose_a, n_local, sep, m);
    return m;
  }
  if (k != s.max_axis && -sep > -s.max_sep + p.tol) {
    return overlap_on_axis(p, pose_a, pose_b, s.max_axis, s.max_sep, request, m);
  }
  edge_manifold(p, pose_a, k, sep, n_local, m);
  return m;
}

}  // namespace proxima::narrow
