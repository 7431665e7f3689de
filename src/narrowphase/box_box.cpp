// Box-box: separating axes, exact distance and clipped contact manifold, all in the frame of
// one box with fixed-size stack buffers and plain arrays (no general-purpose face structures).
//
// Steps (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996, for the 15 axes; Ericson,
// Real-Time Collision Detection 4.4.1 and 5.1.9; Box2D / Dirk Gregorius, "Robust Contact
// Creation for Physics Simulations", GDC 2015, for the clipping and the face bias):
//  1. Both rotations become matrices once; in A's frame R = A^T B (r[i][j] = A_i . B_j), its
//     absolute value, and t = A^T (cB - cA). The 15 candidate axes are A's 3 face normals,
//     B's 3 and the 9 cross products A_i x B_j; a cross product of nearly parallel edges is
//     skipped (its direction is noise, and a parallel edge pair adds no face to the
//     Minkowski difference). Each axis is normalised so its separation is a length.
//  2. The 6 face axes first, with an early out when one separates by more than the contact
//     distance; then the 9 edge axes. The largest separation decides: > 0 separated,
//     <= 0 overlapping with depth = -(largest separation), exact for polytopes (every face
//     of the Minkowski difference has one of these normals). A PairCache keeps the last
//     axis, tried first: while it still separates, nothing else is computed.
//  3. Separated: the exact distance is the smallest over the 16 corners clamped against the
//     other box and the edge pairs A_i, B_j whose axis separates the boxes by less than the
//     best distance so far (the separation along an axis bounds every distance from below;
//     the supporting edges along the separating side are the only candidates of a pair).
//     The normal is the SAT axis or the closest points' direction, whichever the boxes are
//     farther apart along, and the distance that gap (separated_answer).
//  4. Manifold: a face axis unless an edge axis is clearly shallower (relative bias, so the
//     choice is stable from frame to frame), A's face before B's. Face axis: the incident
//     face's 4 corners are written in the reference face's 2D frame (u, v) with their gap
//     along the normal, clipped against the reference rectangle's 4 sides (one coordinate
//     bound each, sides that clip nothing skipped), reduced to max_contacts by area only
//     when more points survive (deepest, farthest, largest triangle, largest quadrilateral,
//     manifold_reduction.hpp's steps in 2D); only the chosen points are mapped to the world.
//     Edge axis: the closest points of the two supporting edges (closed form, clamped).
//     Separated pairs within the contact distance clip the faces supporting the exact
//     distance normal the same way (the projection direction is then tilted).
#include <proxima/geometry/closest_points.hpp>

#include <array>
#include <cmath>
#include <limits>

#include "face_clipping.hpp"
#include "pairs_polyhedral.hpp"

namespace proxima::narrow {
namespace {

// Edge axes whose |A_i x B_j| (the sine of the angle) is below this are skipped.
const Real kParallelSine = Real(4) * kSqrtEpsilon;
const Real kParallelSine2 = kParallelSine * kParallelSine;
// An edge axis replaces the best face axis in manifolds only when its separation exceeds
// kEdgeRelative * face separation (separations are negative when overlapping).
constexpr Real kEdgeRelative = Real(0.98);
// B's face axis replaces A's only when its separation exceeds kFaceRelative * A's.
constexpr Real kFaceRelative = Real(0.98);
constexpr int kAxes = 15;
constexpr int kNext[3] = {1, 2, 0};
constexpr int kPrev[3] = {2, 0, 1};

// The pair in A's frame, with plain arrays (glm's operator[] with a run-time index is a
// switch) and both world rotations as rows of their axes.
struct BoxPair {
  Real a[3];      // A's half extents
  Real b[3];      // B's half extents
  Real r[3][3];   // r[i][j] = A_i . B_j
  Real ar[3][3];  // |r|
  Real t[3];      // B's centre in A's frame
  Real tb[3];     // the same vector in B's axes: tb[j] = B_j . t
  Real ma[3][3];  // ma[i] = A_i in the world
  Real mb[3][3];  // mb[j] = B_j in the world
  Real tol;       // distance tolerance of the pair
  Real rounding;  // a few rounding errors at the pair's own size (not clamped to 1)
  Real noise;     // the rounding of a face axis's separation, 16 ulps of the pair's size
};

// The axes of a unit quaternion's rotation: m[i] is the image of the unit vector e_i.
void rotation_axes(const Quat& q, Real (&m)[3][3]) {
  const Real x2 = q.x + q.x;
  const Real y2 = q.y + q.y;
  const Real z2 = q.z + q.z;
  const Real xx = q.x * x2;
  const Real yy = q.y * y2;
  const Real zz = q.z * z2;
  const Real xy = q.x * y2;
  const Real xz = q.x * z2;
  const Real yz = q.y * z2;
  const Real wx = q.w * x2;
  const Real wy = q.w * y2;
  const Real wz = q.w * z2;
  m[0][0] = Real(1) - (yy + zz);
  m[0][1] = xy + wz;
  m[0][2] = xz - wy;
  m[1][0] = xy - wz;
  m[1][1] = Real(1) - (xx + zz);
  m[1][2] = yz + wx;
  m[2][0] = xz + wy;
  m[2][1] = yz - wx;
  m[2][2] = Real(1) - (xx + yy);
}

Vec3 row(const Real (&m)[3][3], int i) { return Vec3(m[i][0], m[i][1], m[i][2]); }

// m's rows taken as the axes of a frame: the world vector of local vector v.
Vec3 to_world(const Real (&m)[3][3], const Vec3& v) {
  return Vec3(m[0][0] * v.x + m[1][0] * v.y + m[2][0] * v.z, m[0][1] * v.x + m[1][1] * v.y + m[2][1] * v.z,
              m[0][2] * v.x + m[1][2] * v.y + m[2][2] * v.z);
}

BoxPair make_pair(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                  const PairRequest& request) {
  BoxPair p;
  const Vec3& ha = a.half_extents();
  const Vec3& hb = b.half_extents();
  p.a[0] = ha.x;
  p.a[1] = ha.y;
  p.a[2] = ha.z;
  p.b[0] = hb.x;
  p.b[1] = hb.y;
  p.b[2] = hb.z;
  rotation_axes(pose_a.rotation, p.ma);
  rotation_axes(pose_b.rotation, p.mb);
  const Real dx = pose_b.position.x - pose_a.position.x;
  const Real dy = pose_b.position.y - pose_a.position.y;
  const Real dz = pose_b.position.z - pose_a.position.z;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      p.r[i][j] = p.ma[i][0] * p.mb[j][0] + p.ma[i][1] * p.mb[j][1] + p.ma[i][2] * p.mb[j][2];
      p.ar[i][j] = std::abs(p.r[i][j]);
    }
    p.t[i] = p.ma[i][0] * dx + p.ma[i][1] * dy + p.ma[i][2] * dz;
  }
  for (int j = 0; j < 3; ++j) p.tb[j] = p.mb[j][0] * dx + p.mb[j][1] * dy + p.mb[j][2] * dz;
  Real scale = std::max(std::max(std::max(p.a[0], p.a[1]), std::max(p.a[2], p.b[0])), std::max(p.b[1], p.b[2]));
  scale = std::max(std::max(scale, std::abs(p.t[0])), std::max(std::abs(p.t[1]), std::abs(p.t[2])));
  p.tol = resolve_tolerance(request, scale);
  p.rounding = kRelativeTolerance * scale;
  p.noise = Real(16) * kEpsilon * scale;
  return p;
}

// B's axis j in A's frame.
Vec3 b_axis(const BoxPair& p, int j) { return Vec3(p.r[0][j], p.r[1][j], p.r[2][j]); }

// Separation of the boxes along axis k (0-2 A's faces, 3-5 B's, 6-14 A_i x B_j with
// i = (k-6)/3, j = (k-6)%3), and the unit axis in A's frame pointing from A to B. Returns
// false for a skipped (parallel) edge axis.
bool axis_separation(const BoxPair& p, int k, Real& sep, Vec3& axis) {
  Real l[3] = {Real(0), Real(0), Real(0)};
  if (k < 3) {
    const int i = k;
    sep = std::abs(p.t[i]) - (p.a[i] + p.b[0] * p.ar[i][0] + p.b[1] * p.ar[i][1] + p.b[2] * p.ar[i][2]);
    l[i] = p.t[i] >= Real(0) ? Real(1) : Real(-1);
    axis = Vec3(l[0], l[1], l[2]);
    return true;
  }
  if (k < 6) {
    const int j = k - 3;
    sep = std::abs(p.tb[j]) - (p.a[0] * p.ar[0][j] + p.a[1] * p.ar[1][j] + p.a[2] * p.ar[2][j] + p.b[j]);
    const Real s = p.tb[j] >= Real(0) ? Real(1) : Real(-1);
    axis = s * b_axis(p, j);
    return true;
  }
  const int i = (k - 6) / 3;
  const int j = (k - 6) % 3;
  const int i1 = kNext[i];
  const int i2 = kPrev[i];
  const int j1 = kNext[j];
  const int j2 = kPrev[j];
  const Real len2 = p.r[i1][j] * p.r[i1][j] + p.r[i2][j] * p.r[i2][j];
  if (!(len2 > kParallelSine2)) return false;
  const Real len = std::sqrt(len2);
  const Real ra = p.a[i1] * p.ar[i2][j] + p.a[i2] * p.ar[i1][j];
  const Real rb = p.b[j1] * p.ar[i][j2] + p.b[j2] * p.ar[i][j1];
  const Real tl = p.t[i2] * p.r[i1][j] - p.t[i1] * p.r[i2][j];
  sep = (std::abs(tl) - (ra + rb)) / len;
  const Real sign = tl < Real(0) ? Real(-1) : Real(1);
  l[i1] = -sign * p.r[i2][j] / len;
  l[i2] = sign * p.r[i1][j] / len;
  axis = Vec3(l[0], l[1], l[2]);
  return true;
}

// The unit axis k in A's frame, A to B (k not a skipped edge axis; the same direction as
// axis_separation's, without the separation).
Vec3 axis_normal(const BoxPair& p, int k) {
  if (k < 3) {
    const Real s = p.t[k] >= Real(0) ? Real(1) : Real(-1);
    return Vec3(k == 0 ? s : Real(0), k == 1 ? s : Real(0), k == 2 ? s : Real(0));
  }
  if (k < 6) return (p.tb[k - 3] >= Real(0) ? Real(1) : Real(-1)) * b_axis(p, k - 3);
  const int i = (k - 6) / 3;
  const int j = (k - 6) % 3;
  const int i1 = kNext[i];
  const int i2 = kPrev[i];
  const Real len2 = p.r[i1][j] * p.r[i1][j] + p.r[i2][j] * p.r[i2][j];
  if (!(len2 > kParallelSine2)) return Vec3(Real(0), Real(0), Real(1));
  const Real tl = p.t[i2] * p.r[i1][j] - p.t[i1] * p.r[i2][j];
  const Real f = (tl < Real(0) ? Real(-1) : Real(1)) / std::sqrt(len2);
  Real l[3] = {Real(0), Real(0), Real(0)};
  l[i1] = -f * p.r[i2][j];
  l[i2] = f * p.r[i1][j];
  return Vec3(l[0], l[1], l[2]);
}

// The world normal of axis k, A to B.
Vec3 world_normal(const BoxPair& p, int k) {
  if (k < 3) return p.t[k] >= Real(0) ? row(p.ma, k) : -row(p.ma, k);
  if (k < 6) return p.tb[k - 3] >= Real(0) ? row(p.mb, k - 3) : -row(p.mb, k - 3);
  return to_world(p.ma, axis_normal(p, k));
}

struct BoxSat {
  Real sep[kAxes];  // per axis; edges (6-14) only when edges_done, -infinity when skipped
  Real max_sep;     // over the computed axes (an edge axis must beat a face axis by the rounding)
  int max_axis;
  int face_a_axis;  // A's best face axis (0-2), the first on ties
  int face_b_axis;  // B's best face axis (3-5)
  int edge_axis;    // best edge axis (6-14), -1 when none
  bool edges_done;
};

// Separations along the 6 face axes, the best of A's and of B's, and the largest.
void face_separations(const BoxPair& p, BoxSat& s) {
  for (int i = 0; i < 3; ++i) {
    s.sep[i] = std::abs(p.t[i]) - (p.a[i] + p.b[0] * p.ar[i][0] + p.b[1] * p.ar[i][1] + p.b[2] * p.ar[i][2]);
  }
  for (int j = 0; j < 3; ++j) {
    s.sep[3 + j] = std::abs(p.tb[j]) - (p.a[0] * p.ar[0][j] + p.a[1] * p.ar[1][j] + p.a[2] * p.ar[2][j] + p.b[j]);
  }
  s.face_a_axis = s.sep[1] > s.sep[0] ? 1 : 0;
  if (s.sep[2] > s.sep[s.face_a_axis]) s.face_a_axis = 2;
  s.face_b_axis = s.sep[4] > s.sep[3] ? 4 : 3;
  if (s.sep[5] > s.sep[s.face_b_axis]) s.face_b_axis = 5;
  // Largest face axis, A's first on ties.
  s.max_axis = s.sep[s.face_b_axis] > s.sep[s.face_a_axis] ? s.face_b_axis : s.face_a_axis;
  s.max_sep = s.sep[s.max_axis];
  s.edge_axis = -1;
  s.edges_done = false;
}

// How much edge axis k (6-14) must beat the face axes by: its separation's rounding, the
// face axes' noise over |A_i x B_j|, at most the pair's rounding.
Real edge_margin(const BoxPair& p, int k) {
  const int i = (k - 6) / 3;
  const int j = (k - 6) % 3;
  const Real len2 = p.r[kNext[i]][j] * p.r[kNext[i]][j] + p.r[kPrev[i]][j] * p.r[kPrev[i]][j];
  return p.noise * p.noise < p.rounding * p.rounding * len2 ? p.noise / std::sqrt(len2) : p.rounding;
}

// Separations along the 9 edge axes, then the best edge axis and the largest axis overall.
// An axis whose separation cannot exceed `floor` is skipped (-infinity) without its square
// root and division: with len = |A_i x B_j|, sep = e / len > floor is decided on e and
// floor^2 len^2. `floor` = -infinity computes every axis (then edges_done).
void edge_separations(const BoxPair& p, BoxSat& s, Real floor = -kRealInfinity) {
  const bool all = floor == -kRealInfinity;
  const Real floor2 = all ? Real(0) : floor * floor;  // (never infinity times a zero length)
  const bool below = floor < Real(0);
  for (int i = 0; i < 3; ++i) {
    const int i1 = kNext[i];
    const int i2 = kPrev[i];
    for (int j = 0; j < 3; ++j) {
      const int j1 = kNext[j];
      const int j2 = kPrev[j];
      const Real len2 = p.r[i1][j] * p.r[i1][j] + p.r[i2][j] * p.r[i2][j];
      const Real ra = p.a[i1] * p.ar[i2][j] + p.a[i2] * p.ar[i1][j];
      const Real rb = p.b[j1] * p.ar[i][j2] + p.b[j2] * p.ar[i][j1];
      const Real tl = p.t[i2] * p.r[i1][j] - p.t[i1] * p.r[i2][j];
      const Real e = std::abs(tl) - (ra + rb);
      // Non-short-circuit tests: the outcome is data-dependent, branches would mispredict.
      const Real ee = e * e;
      const Real ff = floor2 * len2;
      const bool may_exceed = all | (below ? ((e >= Real(0)) | (ee < ff)) : ((e > Real(0)) & (ee > ff)));
      s.sep[6 + 3 * i + j] = ((len2 > kParallelSine2) & may_exceed) ? e / std::sqrt(len2) : -kRealInfinity;
    }
  }
  Real edge_sep = -kRealInfinity;
  for (int k = 6; k < kAxes; ++k) {
    const Real e = s.sep[k];
    if (e > edge_sep) {
      edge_sep = e;
      s.edge_axis = k;
    }
  }
  // An edge axis must beat the face axes by more than its separation's rounding: nearly
  // parallel edges give an axis next to a face normal with the same separation up to
  // rounding, and their supporting edges would not witness it. The separation is divided by
  // |A_i x B_j|, so is its rounding; the margin is capped at the pair's rounding (a face
  // axis chosen over an edge axis that is better by less than that, a fixed 100 ulps, left
  // box-box depths up to 95 ulps deeper than the pair's).
  if (s.edge_axis >= 0 && edge_sep > s.max_sep && edge_sep > s.max_sep + edge_margin(p, s.edge_axis)) {
    s.max_sep = edge_sep;
    s.max_axis = s.edge_axis;
  }
  s.edges_done = all;
}

// The full SAT (no early out).
BoxSat full_sat(const BoxPair& p) {
  BoxSat s;
  face_separations(p, s);
  edge_separations(p, s);
  return s;
}

// PairCache::sat_feature: the last largest-separation axis, with kOverlapFlag when it did
// not separate the pair (by more than the query's limit).
constexpr std::uint32_t kOverlapFlag = 0x100u;

void store_cache(PairCache* cache, const BoxPair& p, int axis, bool separated) {
  if (cache == nullptr) return;
  cache->sat_feature = static_cast<std::uint32_t>(axis) | (separated ? 0u : kOverlapFlag);
  cache->axis = axis_normal(p, axis);
  cache->valid = true;
}

// The cached axis when it separated the pair last time and still separates it by more than
// `limit` (its A-frame direction refreshed in the cache), else -1. A pair that overlapped
// last time starts cold: its axis would rarely separate it now.
int cached_separating_axis(const BoxPair& p, Real limit, PairCache* cache) {
  if (cache == nullptr || !cache->valid || cache->sat_feature >= static_cast<std::uint32_t>(kAxes)) return -1;
  const int k = static_cast<int>(cache->sat_feature);
  Real sep = Real(0);
  Vec3 axis;
  if (!axis_separation(p, k, sep, axis) || !(sep > limit)) return -1;
  cache->axis = axis;
  return k;
}

// Supporting edge of A (index i) and B (index j) along the A-frame normal n: centres and
// B's edge direction, in A's frame (A's edge runs along A_i).
void supporting_edges(const BoxPair& p, int i, int j, const Vec3& n, Vec3& ca, Vec3& cb, Vec3& eb) {
  const Real nn[3] = {n.x, n.y, n.z};
  Real c[3];
  for (int m = 0; m < 3; ++m) c[m] = m == i ? Real(0) : (nn[m] >= Real(0) ? p.a[m] : -p.a[m]);
  ca = Vec3(c[0], c[1], c[2]);
  cb = Vec3(p.t[0], p.t[1], p.t[2]);
  for (int m = 0; m < 3; ++m) {
    if (m == j) continue;
    const Real nb = nn[0] * p.r[0][m] + nn[1] * p.r[1][m] + nn[2] * p.r[2][m];
    cb += (nb <= Real(0) ? p.b[m] : -p.b[m]) * b_axis(p, m);
  }
  eb = b_axis(p, j);
}

// Closest points in A's frame of A's edge (centre ca, direction A_i, half length a_i) and
// B's edge (centre cb, unit direction eb, half length b_j): the lines' closest points,
// clamped to the segments (Ericson 5.1.9 with centred parameters).
void closest_edge_points(const BoxPair& p, int i, int j, const Vec3& ca, const Vec3& cb, const Vec3& eb, Vec3& on_a,
                         Vec3& on_b) {
  const Vec3 w = cb - ca;
  const Real wv[3] = {w.x, w.y, w.z};
  const Real c = p.r[i][j];         // A_i . B_j
  const Real da = wv[i];            // A_i . w
  const Real db = glm::dot(eb, w);  // B_j . w
  const Real denom = Real(1) - c * c;
  // s along A_i, u along B_j: minimise |w + u eb - s A_i|.
  Real s = denom > Real(0) ? (da - c * db) / denom : Real(0);
  s = std::clamp(s, -p.a[i], p.a[i]);
  Real u = c * s - db;
  if (u < -p.b[j] || u > p.b[j]) {
    u = std::clamp(u, -p.b[j], p.b[j]);
    s = std::clamp(da + c * u, -p.a[i], p.a[i]);
  }
  on_a = ca;
  Real oa[3] = {on_a.x, on_a.y, on_a.z};
  oa[i] += s;
  on_a = Vec3(oa[0], oa[1], oa[2]);
  on_b = cb + u * eb;
}

// Closest points of two boxes in A's frame and their squared distance.
struct ClosestFeatures {
  Real d2 = kRealInfinity;
  Vec3 on_a{Real(0)};
  Vec3 on_b{Real(0)};
};

// Exact closest points of two separated boxes, in A's frame (step 3). `s` must come from a
// full SAT run (edges_done).
ClosestFeatures closest_features(const BoxPair& p, const BoxSat& s) {
  ClosestFeatures best;
  const Vec3 av(p.a[0], p.a[1], p.a[2]);
  const Vec3 bv(p.b[0], p.b[1], p.b[2]);
  const Vec3 t(p.t[0], p.t[1], p.t[2]);
  const Vec3 bx = b_axis(p, 0);
  const Vec3 by = b_axis(p, 1);
  const Vec3 bz = b_axis(p, 2);
  // B's corners against A.
  for (int c = 0; c < 8; ++c) {
    const Vec3 v = t + ((c & 1) ? bv.x : -bv.x) * bx + ((c & 2) ? bv.y : -bv.y) * by + ((c & 4) ? bv.z : -bv.z) * bz;
    const Vec3 q = glm::clamp(v, -av, av);
    const Real d2 = length_squared(v - q);
    if (d2 < best.d2) best = {d2, q, v};
  }
  // A's corners against B (in B's frame, centred on B).
  for (int c = 0; c < 8; ++c) {
    const Vec3 v((c & 1) ? av.x : -av.x, (c & 2) ? av.y : -av.y, (c & 4) ? av.z : -av.z);
    const Vec3 w = v - t;
    const Vec3 local(glm::dot(w, bx), glm::dot(w, by), glm::dot(w, bz));
    const Vec3 q = glm::clamp(local, -bv, bv);
    const Real d2 = length_squared(local - q);
    if (d2 < best.d2) best = {d2, v, t + q.x * bx + q.y * by + q.z * bz};
  }
  // Edge pairs: the closest points of edges A_i, B_j (inner points of both) differ along
  // +-(A_i x B_j), on the side where that axis separates the boxes, by at least its
  // separation; a pair whose axis does not separate, or separates by more than the best
  // distance so far, cannot improve it.
  for (int k = 0; k < 9; ++k) {
    const Real sep = s.sep[6 + k];
    if (!(sep > Real(0)) || sep * sep >= best.d2) continue;
    Real check = Real(0);
    Vec3 n(Real(0), Real(0), Real(1));
    if (!axis_separation(p, 6 + k, check, n)) continue;
    const int i = k / 3;
    const int j = k % 3;
    Vec3 ca;
    Vec3 cb;
    Vec3 eb;
    supporting_edges(p, i, j, n, ca, cb, eb);
    Vec3 a1 = ca;
    Vec3 a0 = ca;
    a1[i] += p.a[i];
    a0[i] -= p.a[i];
    const geometry::SegmentPair sp =
        geometry::closest_points_segment_segment(a0, a1, cb - p.b[j] * eb, cb + p.b[j] * eb);
    if (sp.distance_squared < best.d2) best = {sp.distance_squared, sp.on_a, sp.on_b};
  }
  return best;
}

// Gap of the boxes along the unit A-frame direction n (A to B): t . n less both supports, a
// lower bound of their distance, equal to it along the distance's own normal.
Real gap_along(const BoxPair& p, const Vec3& n) {
  Real gap = p.t[0] * n.x + p.t[1] * n.y + p.t[2] * n.z;
  gap -= p.a[0] * std::abs(n.x) + p.a[1] * std::abs(n.y) + p.a[2] * std::abs(n.z);
  for (int j = 0; j < 3; ++j) gap -= p.b[j] * std::abs(glm::dot(b_axis(p, j), n));
  return gap;
}

// A separated pair's answer in A's frame: the closest points, and as the normal whichever of
// the SAT's axis, the points' direction and that direction taken across each box axis (the
// edges' directions) the boxes are farther apart along, the distance being that gap (any
// direction's gap is a lower bound of the distance). The axis is exact where a face or two
// crossing edges are closest, the direction across an edge where a corner meets the edge's
// inside, the points' direction where two corners are (its rounding, the points' over
// their distance, then moves the gap only to second order); a short gap's direction is
// mostly rounding, which tilted the normal and left the gap along it off the distance.
struct SeparatedAnswer {
  ClosestFeatures f;
  Vec3 normal;  // unit, A's frame
  Real distance = Real(0);
};

SeparatedAnswer separated_answer(const BoxPair& p, const BoxSat& s) {
  SeparatedAnswer r{closest_features(p, s), axis_normal(p, s.max_axis), s.max_sep};
  // The edge directions, A's and B's axes in turn.
  const Vec3 x(Real(1), Real(0), Real(0));
  const Vec3 y(Real(0), Real(1), Real(0));
  const Vec3 z(Real(0), Real(0), Real(1));
  const std::array<Vec3, 6> edges{x, b_axis(p, 0), y, b_axis(p, 1), z, b_axis(p, 2)};
  widest_gap_direction(
      r.f.on_b - r.f.on_a, edges, [&](const Vec3& n) { return gap_along(p, n); }, r.normal, r.distance);
  return r;
}

// ---- Face clipping in the reference box's 2D face frame -------------------------------

// A candidate contact on the reference face: 2D coordinates (u, v) along the reference
// box's axes i1, i2, gap along the projection direction, and its feature: an incident
// corner (sign bits) with side kCorner, or a crossing of an incident edge (hash) with the
// side plane that made it. No default member initialisers (the buffers stay raw).
struct ClipPoint {
  Real u;
  Real v;
  Real gap;
  std::uint16_t id;
  std::uint16_t side;
};

constexpr std::uint16_t kCorner = 0xFFu;

// Candidates: at most 8 after clipping a quadrilateral by 4 sides, plus one slot for a
// distance witness.
struct FacePoints {
  ClipPoint p[9];
  int count;
};

// The reference face and the projection: the reference box's face i on side s (normal
// s e_i in its frame), its half extents, whether it is A, and the projection direction
// (from the reference box towards the incident one) in the world.
struct Reference {
  int i;
  int i1;
  int i2;
  Real s;
  Real h[3];
  bool is_a;
  Vec3 dir_world;
};

constexpr std::uint16_t edge_hash(std::uint32_t a, std::uint32_t b, std::uint32_t side) {
  const std::uint32_t lo = std::min(a, b);
  const std::uint32_t hi = std::max(a, b);
  return static_cast<std::uint16_t>((lo * 131u + hi * 7u + side * 977u) & 0x3FFFu);
}

// Keeps the part of polygon in[0..n) where sign * (u or v) <= limit; writes it to `out` and
// returns its size (<= n + 1). A crossing is made only where the two ends lie strictly on
// opposite sides (an end on the side plane is kept as it is, so no point is doubled).
int clip_side(const ClipPoint* in, int n, ClipPoint* out, bool along_u, Real sign, Real limit, std::uint16_t side) {
  Real d[8];
  for (int k = 0; k < n; ++k) d[k] = sign * (along_u ? in[k].u : in[k].v) - limit;
  int m = 0;
  for (int k = 0; k < n; ++k) {
    const int q = k + 1 == n ? 0 : k + 1;
    const Real dc = d[k];
    const Real dx = d[q];
    if (dc <= Real(0)) out[m++] = in[k];
    if ((dc < Real(0) && dx > Real(0)) || (dc > Real(0) && dx < Real(0))) {
      const Real w = dc / (dc - dx);
      ClipPoint& c = out[m++];
      c.u = in[k].u + (in[q].u - in[k].u) * w;
      c.v = in[k].v + (in[q].v - in[k].v) * w;
      c.gap = in[k].gap + (in[q].gap - in[k].gap) * w;
      c.id = edge_hash(in[k].id, in[q].id, side);
      c.side = side;
    }
  }
  return m;
}

// The incident box seen from the reference box: half extents g, axes m[j] (incident axis j
// in the reference frame, m[j][c] its component c) and centre c.
struct Incident {
  Real g[3];
  Real m[3][3];
  Real c[3];
};

Incident incident_of_b(const BoxPair& p) {
  Incident f;
  for (int j = 0; j < 3; ++j) {
    f.g[j] = p.b[j];
    f.c[j] = p.t[j];
    for (int c = 0; c < 3; ++c) f.m[j][c] = p.r[c][j];
  }
  return f;
}

Incident incident_of_a(const BoxPair& p) {
  Incident f;
  for (int i = 0; i < 3; ++i) {
    f.g[i] = p.a[i];
    f.c[i] = -p.tb[i];
    for (int c = 0; c < 3; ++c) f.m[i][c] = p.r[i][c];
  }
  return f;
}

// Clips the incident box's face most opposed to `dir` (unit, reference frame, from the
// reference box towards the incident one) against the reference face whose normal is
// nearest `dir`, projecting along `dir`. Returns false when that face is tilted more than
// acos(kReferenceFaceCosine) from `dir`; else fills `ref` (but is_a and dir_world) and
// writes to `out` the points whose gap is at most `contact_distance` (possibly none). For
// a face axis `dir` is a unit coordinate vector and the projection is exact.
bool clip_box_faces(const Real (&h)[3], const Incident& f, const Vec3& dir, Real contact_distance, Reference& ref,
                    FacePoints& out) {
  out.count = 0;
  const Real dv[3] = {dir.x, dir.y, dir.z};
  const Real ad[3] = {std::abs(dv[0]), std::abs(dv[1]), std::abs(dv[2])};
  int i = 0;
  if (ad[1] > ad[0]) i = 1;
  if (ad[2] > ad[i]) i = 2;
  if (!(ad[i] >= kReferenceFaceCosine)) return false;
  const int i1 = kNext[i];
  const int i2 = kPrev[i];
  const Real s = dv[i] >= Real(0) ? Real(1) : Real(-1);
  const Real inv_cos = Real(1) / ad[i];
  ref.i = i;
  ref.i1 = i1;
  ref.i2 = i2;
  ref.s = s;
  ref.h[0] = h[0];
  ref.h[1] = h[1];
  ref.h[2] = h[2];
  // Incident face: the incident axis most parallel to dir, on the side facing the reference.
  const Real dd[3] = {f.m[0][0] * dv[0] + f.m[0][1] * dv[1] + f.m[0][2] * dv[2],
                      f.m[1][0] * dv[0] + f.m[1][1] * dv[1] + f.m[1][2] * dv[2],
                      f.m[2][0] * dv[0] + f.m[2][1] * dv[1] + f.m[2][2] * dv[2]};
  int j = 0;
  if (std::abs(dd[1]) > std::abs(dd[0])) j = 1;
  if (std::abs(dd[2]) > std::abs(dd[j])) j = 2;
  const int j1 = kNext[j];
  const int j2 = kPrev[j];
  const Real sj = dd[j] <= Real(0) ? Real(1) : Real(-1);  // the face of the incident box facing back
  // Corners centre +- e1 +- e2 in the reference frame's coordinates i, i1, i2.
  const Real cj = sj * f.g[j];
  const Real c0 = f.c[i] + cj * f.m[j][i];
  const Real c1 = f.c[i1] + cj * f.m[j][i1];
  const Real c2 = f.c[i2] + cj * f.m[j][i2];
  const Real e10 = f.g[j1] * f.m[j1][i];
  const Real e11 = f.g[j1] * f.m[j1][i1];
  const Real e12 = f.g[j1] * f.m[j1][i2];
  const Real e20 = f.g[j2] * f.m[j2][i];
  const Real e21 = f.g[j2] * f.m[j2][i1];
  const Real e22 = f.g[j2] * f.m[j2][i2];
  // Corner ids (sign bits on the incident box's axes): bit j from sj, bits j1, j2 from the
  // signs of e1, e2: + +, - +, - -, + -.
  const unsigned base_bits = sj > Real(0) ? (1u << j) : 0u;
  const unsigned b1 = 1u << j1;
  const unsigned b2 = 1u << j2;
  ClipPoint buf0[8];
  ClipPoint buf1[8];
  const Real pi[4] = {c0 + e10 + e20, c0 - e10 + e20, c0 - e10 - e20, c0 + e10 - e20};
  const Real p1[4] = {c1 + e11 + e21, c1 - e11 + e21, c1 - e11 - e21, c1 + e11 - e21};
  const Real p2[4] = {c2 + e12 + e22, c2 - e12 + e22, c2 - e12 - e22, c2 + e12 - e22};
  const unsigned ids[4] = {base_bits | b1 | b2, base_bits | b2, base_bits, base_bits | b1};
  const Real hi = h[i];
  const Real h1 = h[i1];
  const Real h2 = h[i2];
  const Real du = dv[i1];
  const Real dw = dv[i2];
  unsigned outside = 0;  // sides some corner lies beyond (bit side)
  for (int v = 0; v < 4; ++v) {
    const Real gap = (s * pi[v] - hi) * inv_cos;
    ClipPoint& c = buf0[v];
    c.u = p1[v] - gap * du;
    c.v = p2[v] - gap * dw;
    c.gap = gap;
    c.id = static_cast<std::uint16_t>(ids[v]);
    c.side = kCorner;
    outside |= (c.u > h1 ? 1u : 0u) | (c.v > h2 ? 2u : 0u) | (-c.u > h1 ? 4u : 0u) | (-c.v > h2 ? 8u : 0u);
  }
  // Sutherland-Hodgman over the sides some corner lies beyond (a side no corner crosses
  // cuts nothing: the polygon stays in the hull of the corners).
  ClipPoint* cur = buf0;
  ClipPoint* other = buf1;
  int n = 4;
  if (outside & 1u) {
    n = clip_side(cur, n, other, true, Real(1), h1, 0);
    std::swap(cur, other);
  }
  if ((outside & 2u) && n > 0) {
    n = clip_side(cur, n, other, false, Real(1), h2, 1);
    std::swap(cur, other);
  }
  if ((outside & 4u) && n > 0) {
    n = clip_side(cur, n, other, true, Real(-1), h1, 2);
    std::swap(cur, other);
  }
  if ((outside & 8u) && n > 0) {
    n = clip_side(cur, n, other, false, Real(-1), h2, 3);
    std::swap(cur, other);
  }
  int kept = 0;
  for (int k = 0; k < n; ++k) {
    if (cur[k].gap <= contact_distance) out.p[kept++] = cur[k];
  }
  out.count = kept;
  return true;
}

// Chooses at most k (1..4) of the n candidates (manifold_reduction.hpp's steps, with areas
// in the reference plane) and writes their indices to `chosen`, the deepest first; when
// n <= k and not `always`, every point in polygon order starting from the deepest. Returns
// how many.
int choose_points(const FacePoints& fp, int k, bool always, std::array<int, 4>& chosen) {
  const int n = fp.count;
  const ClipPoint* P = fp.p;
  int i0 = 0;
  for (int q = 1; q < n; ++q) {
    if (P[q].gap < P[i0].gap) i0 = q;
  }
  if (n <= k && !always) {
    for (int q = 0; q < n; ++q) chosen[static_cast<std::size_t>(q)] = (i0 + q) % n;
    return n;
  }
  chosen[0] = i0;
  if (k == 1) return 1;
  const Real u0 = P[i0].u;
  const Real v0 = P[i0].v;
  const Real g0 = P[i0].gap;
  // Farthest from the deepest (positions: midpoints of the two surface points, so half the
  // gap lies along the normal).
  int i1 = -1;
  Real best = Real(0);
  for (int q = 0; q < n; ++q) {
    const Real du = P[q].u - u0;
    const Real dw = P[q].v - v0;
    const Real dg = Real(0.5) * (P[q].gap - g0);
    const Real d2 = du * du + dw * dw + dg * dg;
    if (q != i0 && d2 > best) {
      i1 = q;
      best = d2;
    }
  }
  if (i1 < 0) return 1;
  chosen[1] = i1;
  if (k == 2) return 2;
  const Real eu = P[i1].u - u0;
  const Real ev = P[i1].v - v0;
  // Largest triangle.
  int i2 = -1;
  best = Real(0);
  Real orientation = Real(0);
  for (int q = 0; q < n; ++q) {
    if (q == i0 || q == i1) continue;
    const Real area = eu * (P[q].v - v0) - ev * (P[q].u - u0);
    if (std::abs(area) > best) {
      i2 = q;
      best = std::abs(area);
      orientation = area;
    }
  }
  if (i2 < 0) return 2;
  chosen[2] = i2;
  if (k == 3) return 3;
  // Largest area added outside the triangle (i0, i1, i2), oriented like `orientation`.
  const Real sg = orientation > Real(0) ? Real(1) : Real(-1);
  const Real pu[3] = {u0, P[i1].u, P[i2].u};
  const Real pv[3] = {v0, P[i1].v, P[i2].v};
  int i3 = -1;
  best = Real(0);
  for (int q = 0; q < n; ++q) {
    if (q == i0 || q == i1 || q == i2) continue;
    Real added = -kRealInfinity;
    for (int e = 0; e < 3; ++e) {
      const int f = e == 2 ? 0 : e + 1;
      const Real area = (pu[f] - pu[e]) * (P[q].v - pv[e]) - (pv[f] - pv[e]) * (P[q].u - pu[e]);
      added = std::max(added, -sg * area);
    }
    if (added > best) {
      i3 = q;
      best = added;
    }
  }
  if (i3 < 0) return 3;
  chosen[3] = i3;
  return 4;
}

// Writes the chosen candidates to `m` in the world frame. `pos_ref` and `axes_ref` (rows:
// the reference box's axes in the world) place the reference box; `normal` is the world
// normal A to B (m.normal). A candidate with index `witness` takes the world points
// `witness_a`, `witness_b` instead and feature id 0.
void write_points(const FacePoints& fp, const Reference& ref, const Vec3& pos_ref, const Real (&axes_ref)[3][3],
                  const Vec3& normal, int max_contacts, ContactManifold& m, int witness = -1,
                  const Vec3& witness_a = Vec3(0), const Vec3& witness_b = Vec3(0)) {
  std::array<int, 4> chosen;
  // A witness may coincide with a clipped point: the reduction drops such a double.
  const int n = choose_points(fp, std::clamp(max_contacts, 1, kMaxContactPoints), witness >= 0, chosen);
  const std::uint32_t ref_index = static_cast<std::uint32_t>(2 * ref.i + (ref.s > Real(0) ? 1 : 0));
  const Vec3 base = pos_ref + (ref.s * ref.h[ref.i]) * row(axes_ref, ref.i);
  const Vec3 eu = row(axes_ref, ref.i1);
  const Vec3 ev = row(axes_ref, ref.i2);
  for (int q = 0; q < n; ++q) {
    const ClipPoint& c = fp.p[chosen[static_cast<std::size_t>(q)]];
    ContactPoint& out = m.points[static_cast<std::size_t>(q)];
    out.normal = normal;
    out.depth = -c.gap;
    if (chosen[static_cast<std::size_t>(q)] == witness) {
      out.point_a = witness_a;
      out.point_b = witness_b;
      out.feature_id = 0;
      continue;
    }
    const Vec3 on_ref = base + c.u * eu + c.v * ev;
    const Vec3 on_inc = on_ref + c.gap * ref.dir_world;
    out.point_a = ref.is_a ? on_ref : on_inc;
    out.point_b = ref.is_a ? on_inc : on_ref;
    const bool crossing = c.side != kCorner;
    const std::uint32_t rid = crossing ? ((ref_index * 32u + c.side) & 0x3FFFu) : ref_index;
    const FeatureKind rk = crossing ? FeatureKind::Edge : FeatureKind::Face;
    const FeatureKind ik = crossing ? FeatureKind::Edge : FeatureKind::Vertex;
    out.feature_id = ref.is_a ? make_feature_id(rk, rid, ik, c.id) : make_feature_id(ik, c.id, rk, rid);
  }
  m.count = n;
}

// Candidates of face axis k (< 6) whose gap is at most contact_distance; `ref` tells where
// they lie. The reference is A for k < 3, else B; the projection is along the axis.
void face_axis_points(const BoxPair& p, int k, Real contact_distance, Reference& ref, FacePoints& fp) {
  if (k < 3) {
    const Real sd = p.t[k] >= Real(0) ? Real(1) : Real(-1);
    const Vec3 dir(k == 0 ? sd : Real(0), k == 1 ? sd : Real(0), k == 2 ? sd : Real(0));
    static_cast<void>(clip_box_faces(p.a, incident_of_b(p), dir, contact_distance, ref, fp));
    ref.is_a = true;
    ref.dir_world = sd * row(p.ma, k);
  } else {
    // The normal is s B_j (s the sign of tb[j]); from B towards A it is -s e_j in B's frame.
    const int j = k - 3;
    const Real sd = p.tb[j] >= Real(0) ? Real(-1) : Real(1);
    const Vec3 dir(j == 0 ? sd : Real(0), j == 1 ? sd : Real(0), j == 2 ? sd : Real(0));
    static_cast<void>(clip_box_faces(p.b, incident_of_a(p), dir, contact_distance, ref, fp));
    ref.is_a = false;
    ref.dir_world = sd * row(p.mb, j);
  }
}

// The closest points of the two supporting edges of edge axis k (A-frame normal n_local),
// as a one-point manifold with depth -sep.
void edge_manifold(const BoxPair& p, const Transform& pose_a, int k, Real sep, const Vec3& n_local,
                   ContactManifold& m) {
  const int i = (k - 6) / 3;
  const int j = (k - 6) % 3;
  Vec3 ca;
  Vec3 cb;
  Vec3 eb;
  supporting_edges(p, i, j, n_local, ca, cb, eb);
  Vec3 on_a;
  Vec3 on_b;
  closest_edge_points(p, i, j, ca, cb, eb, on_a, on_b);
  m.count = 1;
  ContactPoint& c = m.points[0];
  c.point_a = pose_a.position + to_world(p.ma, on_a);
  c.point_b = pose_a.position + to_world(p.ma, on_b);
  c.normal = m.normal;
  c.depth = -sep;
  // Edge ids: the axis and which of the four parallel edges (sign bits of the normal).
  std::uint32_t ea = 0;
  std::uint32_t ebits = 0;
  const Real nl[3] = {n_local.x, n_local.y, n_local.z};
  for (int q = 0, bit = 0; q < 3; ++q) {
    if (q == i) continue;
    if (nl[q] >= Real(0)) ea |= 1u << bit;
    ++bit;
  }
  for (int q = 0, bit = 0; q < 3; ++q) {
    if (q == j) continue;
    if (nl[0] * p.r[0][q] + nl[1] * p.r[1][q] + nl[2] * p.r[2][q] <= Real(0)) ebits |= 1u << bit;
    ++bit;
  }
  c.feature_id = make_feature_id(FeatureKind::Edge, static_cast<std::uint32_t>(i) * 4u + ea, FeatureKind::Edge,
                                 static_cast<std::uint32_t>(j) * 4u + ebits);
}

// One-point fallback along the A-frame normal: B's support point in -n and its image on A.
void support_point(const BoxPair& p, const Transform& pose_a, const Vec3& n_local, Real sep, ContactManifold& m) {
  Vec3 pb(p.t[0], p.t[1], p.t[2]);
  for (int j = 0; j < 3; ++j) {
    const Vec3 bj = b_axis(p, j);
    pb += (glm::dot(n_local, bj) <= Real(0) ? p.b[j] : -p.b[j]) * bj;
  }
  m.count = 1;
  m.points[0] = ContactPoint{pose_a.position + to_world(p.ma, pb - sep * n_local), pose_a.position + to_world(p.ma, pb),
                             m.normal, -sep, 0};
}

// Manifold of an overlapping pair along axis k (exact separation sep): clipped faces for a
// face axis, the closest points of the supporting edges for an edge axis.
ContactManifold& overlap_on_axis(const BoxPair& p, const Transform& pose_a, const Transform& pose_b, int k, Real sep,
                                 const PairRequest& request, ContactManifold& m) {
  const Vec3 n_local = axis_normal(p, k);
  m.status = status_from_distance(sep, p.tol);
  m.normal = world_normal(p, k);
  if (k < 6) {
    Reference ref;
    FacePoints fp;
    face_axis_points(p, k, request.contact_distance, ref, fp);
    if (fp.count > 0) {
      write_points(fp, ref, ref.is_a ? pose_a.position : pose_b.position, ref.is_a ? p.ma : p.mb, m.normal,
                   request.max_contacts, m);
    } else {
      support_point(p, pose_a, n_local, sep, m);
    }
    return m;
  }
  edge_manifold(p, pose_a, k, sep, n_local, m);
  return m;
}

// Separated pairs within the contact distance: faces supporting the exact distance normal,
// the reference being the box whose face is better aligned with it.
ContactManifold& near_manifold(const BoxPair& p, const Transform& pose_a, const Transform& pose_b, const BoxSat& s,
                               const PairRequest& request, ContactManifold& m) {
  const SeparatedAnswer sa = separated_answer(p, s);
  const ClosestFeatures& cf = sa.f;
  const Vec3 n_local = sa.normal;
  const Real sd = sa.distance;
  m.normal = to_world(p.ma, n_local);
  m.status = status_from_distance(sd, p.tol);
  const Vec3 world_a = pose_a.position + to_world(p.ma, cf.on_a);
  const Vec3 world_b = pose_a.position + to_world(p.ma, cf.on_b);
  if (!(sd <= request.contact_distance)) return m;
  const Vec3 n_b = -Vec3(glm::dot(n_local, b_axis(p, 0)), glm::dot(n_local, b_axis(p, 1)),
                         glm::dot(n_local, b_axis(p, 2)));  // -n in B's frame
  const bool use_a = max_abs_component(n_local) >= max_abs_component(n_b);
  Reference ref;
  FacePoints fp;
  const bool clipped = use_a ? clip_box_faces(p.a, incident_of_b(p), n_local, request.contact_distance, ref, fp)
                             : clip_box_faces(p.b, incident_of_a(p), n_b, request.contact_distance, ref, fp);
  if (clipped) {
    ref.is_a = use_a;
    ref.dir_world = use_a ? m.normal : -m.normal;
    // The pair's own closest points, kept when every clipped point is shallower (tilted
    // reference face).
    Real smallest_gap = kRealInfinity;
    for (int q = 0; q < fp.count; ++q) smallest_gap = std::min(smallest_gap, fp.p[q].gap);
    int witness = -1;
    if (smallest_gap > sd) {
      // Its position for the reduction: the reference-side witness in the reference frame.
      const Vec3 on_ref = use_a ? cf.on_a : cf.on_b;
      const Vec3 local = use_a ? on_ref
                               : Vec3(glm::dot(on_ref - Vec3(p.t[0], p.t[1], p.t[2]), b_axis(p, 0)),
                                      glm::dot(on_ref - Vec3(p.t[0], p.t[1], p.t[2]), b_axis(p, 1)),
                                      glm::dot(on_ref - Vec3(p.t[0], p.t[1], p.t[2]), b_axis(p, 2)));
      witness = fp.count++;
      ClipPoint& w = fp.p[witness];
      w.u = local[ref.i1];
      w.v = local[ref.i2];
      w.gap = sd;
      w.id = 0;
      w.side = kCorner;
    }
    if (fp.count > 0) {
      write_points(fp, ref, use_a ? pose_a.position : pose_b.position, use_a ? p.ma : p.mb, m.normal,
                   request.max_contacts, m, witness, world_a, world_b);
      return m;
    }
  }
  m.count = 1;
  m.points[0] = ContactPoint{world_a, world_b, m.normal, -sd, 0};
  return m;
}

}  // namespace

bool pair_intersect(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                    const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return false;
  const BoxPair p = make_pair(a, pose_a, b, pose_b, request);
  const Real limit = contact_reach(request.contact_distance, p.tol);  // the touching rule
  const int cached = cached_separating_axis(p, limit, cache);
  if (cached >= 0) return false;
  BoxSat s;
  face_separations(p, s);
  if (s.max_sep <= limit) edge_separations(p, s);
  store_cache(cache, p, s.max_axis, s.max_sep > limit);
  if (s.max_sep > limit) return false;
  if (s.max_sep <= Real(0)) return true;
  // As pair_distance: the gap along the separated answer's normal within the reach.
  return separated_answer(p, s).distance <= limit;
}

DistanceResult pair_distance(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_distance();
  const BoxPair p = make_pair(a, pose_a, b, pose_b, request);
  const BoxSat s = full_sat(p);
  store_cache(cache, p, s.max_axis, s.max_sep > Real(0));
  const Vec3 max_normal = axis_normal(p, s.max_axis);
  DistanceResult r;
  r.method = PairMethod::Sat;
  if (s.max_sep > Real(0)) {
    const SeparatedAnswer sa = separated_answer(p, s);
    r.signed_distance = sa.distance;
    r.point_a = pose_a.position + to_world(p.ma, sa.f.on_a);
    r.point_b = pose_a.position + to_world(p.ma, sa.f.on_b);
    r.normal = to_world(p.ma, sa.normal);
    r.status = status_from_distance(r.signed_distance, p.tol);
    r.tolerance = p.tol;
    return r;
  }
  // Overlapping: exact depth on the deepest-separating axis. Face axis: the deepest clipped
  // point (the Minkowski face through the origin is the sum of the two supporting features,
  // so the clipped incident face reaches the exact depth); edge axis: the closest points of
  // the two supporting edges.
  r.normal = world_normal(p, s.max_axis);
  r.signed_distance = s.max_sep;
  r.status = status_from_distance(r.signed_distance, p.tol);
  r.tolerance = p.tol;
  ContactManifold m;
  m.normal = r.normal;
  if (s.max_axis < 6) {
    Reference ref;
    FacePoints fp;
    face_axis_points(p, s.max_axis, kRealInfinity, ref, fp);
    if (fp.count > 0) {
      write_points(fp, ref, ref.is_a ? pose_a.position : pose_b.position, ref.is_a ? p.ma : p.mb, r.normal, 1, m);
    } else {
      support_point(p, pose_a, max_normal, s.max_sep, m);
    }
  } else {
    edge_manifold(p, pose_a, s.max_axis, s.max_sep, max_normal, m);
  }
  r.point_b = m.points[0].point_b;
  r.point_a = r.point_b - r.signed_distance * r.normal;
  return r;
}

ContactManifold pair_collide(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request_in, PairCache* cache) {
  if (!poses_in_range(pose_a, pose_b)) return invalid_manifold();
  const BoxPair p = make_pair(a, pose_a, b, pose_b, request_in);
  // Gaps are compared with the contact reach (the touching rule of contact.hpp).
  const PairRequest request = request_within_reach(request_in, p.tol);
  const Real limit = request.contact_distance;
  ContactManifold m;
  m.method = PairMethod::Sat;
  m.status = PairStatus::Separated;
  // Warm start: the last axis, while it still separates.
  const int cached = cached_separating_axis(p, limit, cache);
  if (cached >= 0) {
    m.normal = world_normal(p, cached);
    return m;
  }
  BoxSat s;
  face_separations(p, s);
  if (s.max_sep <= limit) {
    // Only edge axes that may separate, be the largest or be preferred (below) count:
    // those that cannot exceed every threshold, less the rounding, are skipped.
    const Real bias = Real(1e-3) * p.tol;
    Real chosen = s.sep[s.face_a_axis];
    if (s.sep[s.face_b_axis] > kFaceRelative * chosen + bias) chosen = s.sep[s.face_b_axis];
    const Real floor = std::min(std::min(kEdgeRelative * chosen + bias, s.max_sep + p.rounding), limit) - p.rounding;
    edge_separations(p, s, floor);
  }
  if (s.max_sep > Real(0) && s.max_sep <= limit) s = full_sat(p);  // the near path needs every axis
  store_cache(cache, p, s.max_axis, s.max_sep > limit);
  if (s.max_sep > limit || request.max_contacts < 1) {
    m.normal = world_normal(p, s.max_axis);
    return m;
  }
  if (s.max_sep > Real(0)) return near_manifold(p, pose_a, pose_b, s, request, m);
  // Overlapping: prefer a face axis (A's, then B's) unless an edge axis is clearly shallower.
  int k = s.face_a_axis;
  Real sep = s.sep[k];
  if (s.sep[s.face_b_axis] > kFaceRelative * sep + Real(1e-3) * p.tol) {
    k = s.face_b_axis;
    sep = s.sep[k];
  }
  if (s.edge_axis >= 0 && s.sep[s.edge_axis] > kEdgeRelative * sep + Real(1e-3) * p.tol) {
    k = s.edge_axis;
    sep = s.sep[k];
  }
  if (k < 6) {
    Reference ref;
    FacePoints fp;
    face_axis_points(p, k, request.contact_distance, ref, fp);
    if (fp.count > 0) {
      // A preferred (not deepest-separating) face axis is kept only while no point goes
      // deeper than the pair's exact depth; else the exact axis decides.
      Real smallest_gap = fp.p[0].gap;
      for (int q = 1; q < fp.count; ++q) smallest_gap = std::min(smallest_gap, fp.p[q].gap);
      if (k == s.max_axis || -smallest_gap <= -s.max_sep + p.tol) {
        m.status = status_from_distance(s.max_sep, p.tol);  // the pair's depth, as distance answers it
        m.normal = ref.is_a ? ref.dir_world : -ref.dir_world;
        write_points(fp, ref, ref.is_a ? pose_a.position : pose_b.position, ref.is_a ? p.ma : p.mb, m.normal,
                     request.max_contacts, m);
        return m;
      }
    }
    // No point (rounding) or a preferred axis that went too deep: the exact axis decides
    // (for k == max_axis this ends in the one-point fallback).
    return overlap_on_axis(p, pose_a, pose_b, s.max_axis, s.max_sep, request, m);
  }
  if (k != s.max_axis && -sep > -s.max_sep + p.tol) {
    return overlap_on_axis(p, pose_a, pose_b, s.max_axis, s.max_sep, request, m);
  }
  const Vec3 n_local = axis_normal(p, k);
  m.status = status_from_distance(s.max_sep, p.tol);  // the pair's depth, as distance answers it
  m.normal = to_world(p.ma, n_local);
  edge_manifold(p, pose_a, k, sep, n_local, m);
  return m;
}

}  // namespace proxima::narrow
