// Clipping of an incident feature against a reference feature.
//
// Steps (Box2D's b2ClipPolygons, Jolt's ManifoldBetweenTwoFaces, after Gregorius, "Robust
// Contact Creation for Physics Simulations", GDC 2015):
//  1. the reference is the feature best aligned with the normal (a polygon before a
//     segment); it must be within acos(kReferenceFaceCosine) of it;
//  2. its side planes are the planes through its edges that contain the normal (for a
//     segment, the two planes through its ends orthogonal to it and containing the normal),
//     so clipped points project along the normal into the reference feature;
//  3. the incident polygon (or segment) is clipped by each side plane (Sutherland–Hodgman;
//     a segment is clipped parametrically);
//  4. each remaining point is projected along the normal onto the reference plane; its gap
//     is the projection length minus the two core radii, and points with a gap above the
//     contact distance are dropped.
#include "face_clipping.hpp"

#include <algorithm>
#include <cmath>
#include <span>

#include "manifold_reduction.hpp"

namespace proxima::narrow {
namespace {

// Clip buffers live on the stack uninitialised: no default member initialisers here.
struct ClipVertex {
  Vec3 p;
  std::uint32_t id;  // incident vertex id, or a hash of (incident edge, side) for crossings
  std::uint32_t side;
  bool crossing;  // made by a side plane
};

// A clipped contact before reduction (raw, see ClipVertex).
struct Candidate {
  Vec3 point_a;
  Vec3 point_b;
  Real depth;
  std::uint32_t feature_id;
};

// Candidates of one clipping, with room for one extra (the distance witness).
struct CandidateSet {
  Candidate points[kMaxClipPoints + 1];
  int count;
};

constexpr std::uint32_t edge_hash(std::uint32_t a, std::uint32_t b, std::uint32_t side) {
  const std::uint32_t lo = std::min(a, b);
  const std::uint32_t hi = std::max(a, b);
  return (lo * 131u + hi * 7u + side * 977u) & 0x3FFFu;
}

// Alignment of a feature with `dir`: a polygon's normal cosine, a segment's sine with the
// direction (1 when orthogonal), -1 for a point.
Real alignment(const SupportingFace& f, const Vec3& dir) {
  if (f.count >= 3) return glm::dot(f.normal, dir);
  if (f.count == 2) {
    Vec3 u;
    Real l = Real(0);
    if (!unit_and_length(f.points[1] - f.points[0], u, l)) return Real(-1);
    const Real c = glm::dot(u, dir);
    return std::sqrt(std::max(Real(0), Real(1) - c * c));
  }
  return Real(-1);
}

// clip_features into raw candidates.
bool clip_candidates(const SupportingFace& fa, const SupportingFace& fb, const Vec3& normal, Real contact_distance,
                     CandidateSet& out) {
  out.count = 0;
  const Real sa = alignment(fa, normal);
  const Real sb = alignment(fb, -normal);
  const bool a_ok = sa >= kReferenceFaceCosine;
  const bool b_ok = sb >= kReferenceFaceCosine;
  if (!a_ok && !b_ok) return false;
  bool ref_is_a = a_ok;
  if (a_ok && b_ok) {
    if ((fa.count >= 3) != (fb.count >= 3)) {
      ref_is_a = fa.count >= 3;
    } else {
      ref_is_a = sa >= sb;
    }
  }
  const SupportingFace& ref = ref_is_a ? fa : fb;
  const SupportingFace& inc = ref_is_a ? fb : fa;
  if (inc.count < 2) return false;
  const Vec3 dir = ref_is_a ? normal : -normal;  // from the reference towards the incident

  // Reference plane and side planes.
  const Vec3 ref_p = ref.points[0];
  Vec3 ref_n = ref.normal;
  Vec3 side_p[kMaxFacePoints];
  Vec3 side_n[kMaxFacePoints];
  int sides = 0;
  if (ref.count >= 3) {
    for (int i = 0; i < ref.count; ++i) {
      const Vec3& p0 = ref.points[i];
      const Vec3& p1 = ref.points[(i + 1) % ref.count];
      side_p[sides] = p0;
      // Planes containing the projection direction, so that a point clipped inside them
      // projects (along the normal) inside the reference face.
      side_n[sides] = glm::cross(p1 - p0, dir);
      ++sides;
    }
  } else {
    Vec3 u;
    Real l = Real(0);
    if (!unit_and_length(ref.points[1] - ref.points[0], u, l)) return false;
    Real nl = Real(0);
    if (!unit_and_length(dir - glm::dot(dir, u) * u, ref_n, nl)) return false;
    const Vec3 across = u - glm::dot(u, dir) * dir;
    side_p[0] = ref.points[0];
    side_n[0] = -across;
    side_p[1] = ref.points[1];
    side_n[1] = across;
    sides = 2;
  }

  // Clip the incident feature.
  ClipVertex buf_a[kMaxClipPoints];
  ClipVertex buf_b[kMaxClipPoints];
  int n_in = inc.count;
  for (int i = 0; i < n_in; ++i) buf_a[i] = ClipVertex{inc.points[i], inc.ids[i], 0, false};
  if (inc.count == 2) {
    for (int s = 0; s < sides && n_in == 2; ++s) {
      const Real d0 = glm::dot(buf_a[0].p - side_p[s], side_n[s]);
      const Real d1 = glm::dot(buf_a[1].p - side_p[s], side_n[s]);
      if (d0 > Real(0) && d1 > Real(0)) {
        n_in = 0;
        break;
      }
      const std::uint32_t h = edge_hash(inc.ids[0], inc.ids[1], static_cast<std::uint32_t>(s));
      if (d0 > Real(0)) {
        const Vec3 p = buf_a[0].p + (buf_a[1].p - buf_a[0].p) * (d0 / (d0 - d1));
        buf_a[0] = ClipVertex{p, h, static_cast<std::uint32_t>(s), true};
      } else if (d1 > Real(0)) {
        const Vec3 p = buf_a[1].p + (buf_a[0].p - buf_a[1].p) * (d1 / (d1 - d0));
        buf_a[1] = ClipVertex{p, h, static_cast<std::uint32_t>(s), true};
      }
    }
  } else {
    ClipVertex* in = buf_a;
    ClipVertex* outp = buf_b;
    for (int s = 0; s < sides && n_in > 0; ++s) {
      int n_out = 0;
      for (int i = 0; i < n_in; ++i) {
        const ClipVertex& c = in[i];
        const ClipVertex& x = in[(i + 1) % n_in];
        const Real dc = glm::dot(c.p - side_p[s], side_n[s]);
        const Real dx = glm::dot(x.p - side_p[s], side_n[s]);
        if (dc <= Real(0) && n_out < kMaxClipPoints) outp[n_out++] = c;
        if ((dc <= Real(0)) != (dx <= Real(0)) && n_out < kMaxClipPoints) {
          const Vec3 p = c.p + (x.p - c.p) * (dc / (dc - dx));
          outp[n_out++] =
              ClipVertex{p, edge_hash(c.id, x.id, static_cast<std::uint32_t>(s)), static_cast<std::uint32_t>(s), true};
        }
      }
      std::swap(in, outp);
      n_in = n_out;
    }
    if (in != buf_a) std::copy(in, in + n_in, buf_a);
  }

  // Project onto the reference plane and keep the points within the contact distance.
  const Real denom = glm::dot(dir, ref_n);
  if (!(denom > Real(0))) return false;
  const Real ra = fa.radius;
  const Real rb = fb.radius;
  const FeatureKind ref_kind = ref.count >= 3 ? FeatureKind::Face : FeatureKind::Edge;
  for (int i = 0; i < n_in && out.count < kMaxClipPoints; ++i) {
    const ClipVertex& q = buf_a[i];
    const Real t = glm::dot(q.p - ref_p, ref_n) / denom;
    const Real gap = t - ra - rb;
    if (!(gap <= contact_distance)) continue;
    const Vec3 on_ref = q.p - t * dir;
    Candidate& c = out.points[out.count++];
    c.depth = -gap;
    const std::uint32_t ref_index = q.crossing ? ((ref.index * 32u + q.side) & 0x3FFFu) : ref.index;
    const FeatureKind rk = q.crossing ? FeatureKind::Edge : ref_kind;
    const FeatureKind ik = q.crossing ? FeatureKind::Edge : FeatureKind::Vertex;
    if (ref_is_a) {
      c.point_a = on_ref + ra * normal;
      c.point_b = q.p - rb * normal;
      c.feature_id = make_feature_id(rk, ref_index, ik, q.id);
    } else {
      c.point_b = on_ref - rb * normal;
      c.point_a = q.p + ra * normal;
      c.feature_id = make_feature_id(ik, q.id, rk, ref_index);
    }
  }
  return true;
}

}  // namespace

bool clip_features(const SupportingFace& fa, const SupportingFace& fb, const Vec3& normal, Real contact_distance,
                   ClippedContacts& out) {
  CandidateSet set;
  out.count = 0;
  if (!clip_candidates(fa, fb, normal, contact_distance, set)) return false;
  for (int i = 0; i < set.count; ++i) {
    const Candidate& c = set.points[i];
    out.points[static_cast<std::size_t>(i)] = ContactPoint{c.point_a, c.point_b, normal, c.depth, c.feature_id};
  }
  out.count = set.count;
  return true;
}

namespace {

Real deepest_candidate(const CandidateSet& set) {
  Real deepest = set.points[0].depth;
  for (int i = 1; i < set.count; ++i) deepest = std::max(deepest, set.points[i].depth);
  return deepest;
}

// The candidates reduced to request.max_contacts (the deepest first, then the largest area)
// and written to m.
bool reduce_into(const CandidateSet& set, const Vec3& normal, const PairRequest& request, ContactManifold& m) {
  const int k = std::clamp(request.max_contacts, 1, kMaxContactPoints);
  std::array<int, 4> chosen;
  const int n = select_contacts(
      set.count, [&](int i) { return (set.points[i].point_a + set.points[i].point_b) * Real(0.5); },
      [&](int i) { return set.points[i].depth; }, [](int) { return true; }, normal, k, chosen);
  for (int i = 0; i < n; ++i) {
    const Candidate& c = set.points[chosen[static_cast<std::size_t>(i)]];
    m.points[static_cast<std::size_t>(i)] = ContactPoint{c.point_a, c.point_b, normal, c.depth, c.feature_id};
  }
  m.count = n;
  return n > 0;
}

}  // namespace

bool clipped_manifold(const SupportingFace& fa, const SupportingFace& fb, const Vec3& normal,
                      const PairRequest& request, ContactManifold& m, const ContactPoint* witness) {
  CandidateSet set;
  if (!clip_candidates(fa, fb, normal, request.contact_distance, set) || set.count == 0) return false;
  // Keep the pair's own closest (deepest) point when clipping measured every point as
  // shallower (tilted reference face): it then becomes the first point of the reduction.
  if (witness != nullptr && deepest_candidate(set) < witness->depth) {
    set.points[set.count++] = Candidate{witness->point_a, witness->point_b, witness->depth, witness->feature_id};
  }
  return reduce_into(set, normal, request, m);
}

bool deep_clipped_manifold(const SupportingFace& fa, const SupportingFace& fb, const Vec3& normal,
                           const PairRequest& request, Real witness_depth, ContactManifold& m) {
  CandidateSet set;
  if (!clip_candidates(fa, fb, normal, request.contact_distance, set) || set.count == 0) return false;
  if (deepest_candidate(set) < witness_depth) return false;
  return reduce_into(set, normal, request, m);
}

}  // namespace proxima::narrow
