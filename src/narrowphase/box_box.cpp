// Box-box: separating axes, exact distance and clipped contact manifold.
//
// Steps (Gottschalk, Lin, Manocha, "OBBTree", SIGGRAPH 1996, for the 15 axes; Ericson,
// Real-Time Collision Detection 4.4.1; Box2D / Dirk Gregorius for the clipping):
//  1. Work in A's frame: R = A^T B, t = A^T (cB - cA). The 15 candidate axes are A's 3 face
//     normals, B's 3 and the 9 cross products A_i x B_j; a cross product of nearly parallel
//     edges is skipped (its direction is noise, and a parallel edge pair adds no face to the
//     Minkowski difference). Each axis is normalised so its separation is a length.
//  2. The largest separation over the axes decides: > 0 separated, <= 0 overlapping with
//     depth = -(largest separation), which is exact for polytopes (every face of the
//     Minkowski difference has one of these normals).
//  3. Separated: the exact distance is the smallest over the vertices of each box against
//     the other box (a clamp) and the 18 edge pairs whose common normal direction (+- A_i x
//     B_j) makes them supporting edges of both boxes; every closest pair of two boxes is of
//     one of these kinds.
//  4. Manifold: the chosen axis (a face axis unless an edge axis is clearly shallower, for
//     stable manifolds); face axis: incident face of the other box clipped against the
//     reference face (face_clipping.hpp), reduced to 4 points by area; edge axis: the
//     closest points of the two supporting edges. Separated pairs within the contact
//     distance clip the faces supporting the exact distance normal.
//  5. The last separating axis is kept in PairCache::sat_feature and tried first.
#include <proxima/geometry/closest_points.hpp>

#include <cmath>
#include <limits>

#include "face_clipping.hpp"
#include "pairs_polyhedral.hpp"
#include "supporting_face.hpp"

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

// The pair in A's frame.
struct BoxPair {
  Vec3 a{Real(0)};  // A's half extents
  Vec3 b{Real(0)};  // B's half extents
  Real r[3][3]{};   // r[i][j] = A_i . B_j
  Real ar[3][3]{};  // |r|
  Vec3 t{Real(0)};  // B's centre in A's frame
  Real tol = Real(0);
  Real rounding = Real(0);  // a few rounding errors at the pair's own size (not clamped to 1)
};

BoxPair make_pair(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                  const PairRequest& request) {
  BoxPair p;
  p.a = a.half_extents();
  p.b = b.half_extents();
  const Mat3 ma = pose_a.rotation_matrix();
  const Mat3 mb = pose_b.rotation_matrix();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      p.r[i][j] = glm::dot(ma[i], mb[j]);
      p.ar[i][j] = std::abs(p.r[i][j]);
    }
  }
  const Vec3 d = pose_b.position - pose_a.position;
  p.t = Vec3(glm::dot(d, ma[0]), glm::dot(d, ma[1]), glm::dot(d, ma[2]));
  const Real scale = std::max({max_abs_component(p.a), max_abs_component(p.b), max_abs_component(p.t)});
  p.tol = resolve_tolerance(request, scale);
  p.rounding = kRelativeTolerance * scale;
  return p;
}

// Separation of the boxes along axis k (0-2 A's faces, 3-5 B's, 6-14 A_i x B_j with
// i = (k-6)/3, j = (k-6)%3), and the unit axis in A's frame pointing from A to B. Returns
// false for a skipped (parallel) edge axis.
bool axis_separation(const BoxPair& p, int k, Real& sep, Vec3& axis) {
  if (k < 3) {
    const int i = k;
    const Real rb = p.b[0] * p.ar[i][0] + p.b[1] * p.ar[i][1] + p.b[2] * p.ar[i][2];
    sep = std::abs(p.t[i]) - (p.a[i] + rb);
    axis = Vec3(Real(0));
    axis[i] = p.t[i] >= Real(0) ? Real(1) : Real(-1);
    return true;
  }
  if (k < 6) {
    const int j = k - 3;
    const Real ra = p.a[0] * p.ar[0][j] + p.a[1] * p.ar[1][j] + p.a[2] * p.ar[2][j];
    const Real tj = p.t[0] * p.r[0][j] + p.t[1] * p.r[1][j] + p.t[2] * p.r[2][j];
    sep = std::abs(tj) - (ra + p.b[j]);
    const Real s = tj >= Real(0) ? Real(1) : Real(-1);
    axis = s * Vec3(p.r[0][j], p.r[1][j], p.r[2][j]);
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
  const Real ra = p.a[i1] * p.ar[i2][j] + p.a[i2] * p.ar[i1][j];
  const Real rb = p.b[j1] * p.ar[i][j2] + p.b[j2] * p.ar[i][j1];
  const Real tl = p.t[i2] * p.r[i1][j] - p.t[i1] * p.r[i2][j];
  sep = (std::abs(tl) - (ra + rb)) / len;
  Vec3 l(Real(0));
  l[i1] = -p.r[i2][j] / len;
  l[i2] = p.r[i1][j] / len;
  axis = tl >= Real(0) ? l : -l;
  return true;
}

struct SatResult {
  Real max_sep = -std::numeric_limits<Real>::infinity();  // over all axes (exact)
  int max_axis = 0;
  Vec3 max_normal{Real(0), Real(0), Real(1)};
  Real face_a_sep = -std::numeric_limits<Real>::infinity();
  int face_a_axis = 0;
  Real face_b_sep = -std::numeric_limits<Real>::infinity();
  int face_b_axis = 3;
  Real edge_sep = -std::numeric_limits<Real>::infinity();
  int edge_axis = -1;
  bool early_out = false;  // stopped at an axis separating by more than the limit
};

// Runs the 15 axes, stopping early at one separating by more than `limit`.
SatResult run_sat(const BoxPair& p, Real limit, const PairCache* cache) {
  SatResult s;
  if (cache != nullptr && cache->valid && cache->sat_feature < static_cast<std::uint32_t>(kAxes)) {
    Real sep = Real(0);
    Vec3 axis;
    const int k = static_cast<int>(cache->sat_feature);
    if (axis_separation(p, k, sep, axis) && sep > limit) {
      s.max_sep = sep;
      s.max_axis = k;
      s.max_normal = axis;
      s.early_out = true;
      return s;
    }
  }
  for (int k = 0; k < kAxes; ++k) {
    Real sep = Real(0);
    Vec3 axis;
    if (!axis_separation(p, k, sep, axis)) continue;
    // An edge axis must beat the face axes by more than the tolerance: nearly parallel
    // edges give an axis next to a face normal with the same separation up to rounding,
    // and its supporting edges would not witness it.
    if (sep > s.max_sep + (k >= 6 && s.max_axis < 6 ? p.rounding : Real(0))) {
      s.max_sep = sep;
      s.max_axis = k;
      s.max_normal = axis;
    }
    if (k < 3) {
      if (sep > s.face_a_sep) {
        s.face_a_sep = sep;
        s.face_a_axis = k;
      }
    } else if (k < 6) {
      if (sep > s.face_b_sep) {
        s.face_b_sep = sep;
        s.face_b_axis = k;
      }
    } else if (sep > s.edge_sep) {
      s.edge_sep = sep;
      s.edge_axis = k;
    }
    if (sep > limit) {
      s.early_out = true;
      return s;
    }
  }
  return s;
}

void store_cache(PairCache* cache, const SatResult& s) {
  if (cache == nullptr) return;
  cache->sat_feature = static_cast<std::uint32_t>(s.max_axis);
  cache->axis = s.max_normal;
  cache->valid = true;
}

// Closest points of two boxes in A's frame and their squared distance.
struct ClosestFeatures {
  Real d2 = std::numeric_limits<Real>::infinity();
  Vec3 on_a{Real(0)};
  Vec3 on_b{Real(0)};
};

// Exact closest points of two separated boxes, in A's frame (step 3).
ClosestFeatures closest_features(const BoxPair& p) {
  ClosestFeatures best;
  const Vec3 bx(p.r[0][0], p.r[1][0], p.r[2][0]);
  const Vec3 by(p.r[0][1], p.r[1][1], p.r[2][1]);
  const Vec3 bz(p.r[0][2], p.r[1][2], p.r[2][2]);
  const Vec3 baxes[3] = {bx, by, bz};
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
  // Supporting edge pairs along +-(A_i x B_j).
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const int i1 = (i + 1) % 3;
      const int i2 = (i + 2) % 3;
      const Real len = std::sqrt(p.r[i1][j] * p.r[i1][j] + p.r[i2][j] * p.r[i2][j]);
      if (!(len > kParallelSine)) continue;
      Vec3 l(Real(0));
      l[i1] = -p.r[i2][j];
      l[i2] = p.r[i1][j];
      for (int sign = 0; sign < 2; ++sign) {
        const Vec3 n = sign == 0 ? l : -l;
        Vec3 ca(Real(0));
        ca[i1] = n[i1] >= Real(0) ? p.a[i1] : -p.a[i1];
        ca[i2] = n[i2] >= Real(0) ? p.a[i2] : -p.a[i2];
        Vec3 ea(Real(0));
        ea[i] = p.a[i];
        Vec3 cb = p.t;
        for (int m = 0; m < 3; ++m) {
          if (m == j) continue;
          cb += (glm::dot(n, baxes[m]) <= Real(0) ? p.b[m] : -p.b[m]) * baxes[m];
        }
        const Vec3 eb = p.b[j] * baxes[j];
        const geometry::SegmentPair sp = geometry::closest_points_segment_segment(ca - ea, ca + ea, cb - eb, cb + eb);
        if (sp.distance_squared < best.d2) best = {sp.distance_squared, sp.on_a, sp.on_b};
      }
    }
  }
  return best;
}

// Supporting edge of A (index i) and B (index j) along the A-frame normal n, as segments.
void supporting_edges(const BoxPair& p, int i, int j, const Vec3& n, Vec3& a0, Vec3& a1, Vec3& b0, Vec3& b1) {
  Vec3 ca(Real(0));
  for (int m = 0; m < 3; ++m) {
    if (m != i) ca[m] = n[m] >= Real(0) ? p.a[m] : -p.a[m];
  }
  Vec3 ea(Real(0));
  ea[i] = p.a[i];
  a0 = ca - ea;
  a1 = ca + ea;
  Vec3 cb = p.t;
  Vec3 eb(Real(0));
  for (int m = 0; m < 3; ++m) {
    const Vec3 bm(p.r[0][m], p.r[1][m], p.r[2][m]);
    if (m == j) {
      eb = p.b[m] * bm;
    } else {
      cb += (glm::dot(n, bm) <= Real(0) ? p.b[m] : -p.b[m]) * bm;
    }
  }
  b0 = cb - eb;
  b1 = cb + eb;
}

// Penetration (sep <= 0) along axis k with A-frame normal n: manifold points in `m`
// (world frame). For face axes the clipped faces; for edge axes the edges' closest points.
bool overlap_manifold(const BoxPair& p, const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                      int k, Real sep, const Vec3& n_local, const PairRequest& request, ContactManifold& m) {
  const Vec3 n = pose_a.apply_vector(n_local);
  m.normal = n;
  if (k < 6) {
    const SupportingFace fa = supporting_face(a, pose_a, n);
    const SupportingFace fb = supporting_face(b, pose_b, -n);
    if (clipped_manifold(fa, fb, n, request, m)) return true;
  } else {
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
    c.normal = n;
    c.depth = -sep;
    // Edge ids: the axis and which of the four parallel edges (sign bits of the normal).
    std::uint32_t ea = 0;
    std::uint32_t eb = 0;
    for (int q = 0, bit = 0; q < 3; ++q) {
      if (q == i) continue;
      if (n_local[q] >= Real(0)) ea |= 1u << bit;
      ++bit;
    }
    for (int q = 0, bit = 0; q < 3; ++q) {
      if (q == j) continue;
      const Vec3 bq(p.r[0][q], p.r[1][q], p.r[2][q]);
      if (glm::dot(n_local, bq) <= Real(0)) eb |= 1u << bit;
      ++bit;
    }
    c.feature_id = make_feature_id(FeatureKind::Edge, static_cast<std::uint32_t>(i) * 4u + ea, FeatureKind::Edge,
                                   static_cast<std::uint32_t>(j) * 4u + eb);
    return true;
  }
  return false;
}

// One-point fallback along axis k: B's support point in -n and its image on A.
void support_point(const Box& b, const Transform& pose_b, const Vec3& n, Real sep, ContactManifold& m) {
  const Vec3 pb = pose_b.apply(b.support(pose_b.inverse_apply_vector(-n)));
  m.count = 1;
  m.points[0] = ContactPoint{pb - sep * n, pb, n, -sep, 0};
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
  return closest_features(p).d2 <= limit * limit;
}

DistanceResult pair_distance(const Box& a, const Transform& pose_a, const Box& b, const Transform& pose_b,
                             const PairRequest& request, PairCache* cache) {
  if (!finite_poses(pose_a, pose_b)) return invalid_distance();
  const BoxPair p = make_pair(a, pose_a, b, pose_b, request);
  const SatResult s = run_sat(p, std::numeric_limits<Real>::infinity(), nullptr);
  store_cache(cache, s);
  DistanceResult r;
  r.method = PairMethod::Sat;
  if (s.max_sep > Real(0)) {
    const ClosestFeatures f = closest_features(p);
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
  // Overlapping: exact depth on the deepest-separating axis; witnesses from its manifold.
  ContactManifold m;
  PairRequest all = request;
  all.max_contacts = kMaxContactPoints;
  all.contact_distance = std::numeric_limits<Real>::max();
  if (!overlap_manifold(p, a, pose_a, b, pose_b, s.max_axis, s.max_sep, s.max_normal, all, m)) {
    support_point(b, pose_b, pose_a.apply_vector(s.max_normal), s.max_sep, m);
  }
  r.normal = pose_a.apply_vector(s.max_normal);
  r.signed_distance = s.max_sep;
  // The deepest clipped point is the witness; move it onto the exact depth.
  int deepest = 0;
  for (int i = 1; i < m.count; ++i) {
    if (m.points[i].depth > m.points[deepest].depth) deepest = i;
  }
  r.point_b = m.points[deepest].point_b;
  r.point_a = r.point_b - r.signed_distance * r.normal;
  r.status = status_from_distance(r.signed_distance, p.tol);
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
    // Separated within the contact distance: faces supporting the exact distance normal.
    const DistanceResult d = pair_distance(a, pose_a, b, pose_b, request, nullptr);
    m.normal = d.normal;
    m.status = d.status;
    if (!(d.signed_distance <= request.contact_distance)) return m;
    const SupportingFace fa = supporting_face(a, pose_a, d.normal);
    const SupportingFace fb = supporting_face(b, pose_b, -d.normal);
    const ContactPoint witness{d.point_a, d.point_b, d.normal, -d.signed_distance, 0};
    if (!clipped_manifold(fa, fb, d.normal, request, m, &witness)) {
      m = manifold_from_distance(d, request);
    }
    m.method = PairMethod::Sat;
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
  Vec3 n_local;
  static_cast<void>(axis_separation(p, k, check, n_local));
  m.status = status_from_distance(sep, p.tol);
  if (!overlap_manifold(p, a, pose_a, b, pose_b, k, sep, n_local, request, m)) {
    support_point(b, pose_b, pose_a.apply_vector(n_local), sep, m);
  }
  m.normal = pose_a.apply_vector(n_local);
  return m;
}

}  // namespace proxima::narrow
