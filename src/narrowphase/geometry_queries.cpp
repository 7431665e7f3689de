/// @file geometry_queries.cpp
/// Pair queries over any two geometries: dispatch by kind, compounds, and the reduction of
/// collide_all to one manifold.
///
/// Steps:
///  1. Convex-convex: the narrow phase, unchanged. Mesh-convex: mesh_convex.cpp (mesh made
///     side A, answers mirrored when it was B). Mesh-mesh: mesh_mesh.cpp.
///  2. A compound against a non-compound: the other side's box is mapped into the compound's
///     frame; the compound's BVH is walked for the children whose boxes overlap it (inflated
///     by the contact distance), each child answered recursively at its pose (nested
///     compounds included) and tagged with its top-level child index. Distance walks the
///     BVH nearer node first and prunes nodes whose box gap is not below the best answer
///     (branch and bound; the best so far is passed down as a cutoff, so nested parts prune
///     against the global best).
///  3. Compound against compound (boolean, contacts): simultaneous descent of both BVHs over
///     node pairs (B's node box mapped into A's frame, Arvo's box of a rotated box), the
///     larger node split first, fixed stack; leaf pairs recurse on child pairs. Distance
///     descends A's BVH and answers each child against B (which descends B's BVH), sharing
///     the cutoff.
///  4. collide: collide_all, then the deepest contact's normal becomes the manifold normal;
///     contacts whose normal is within about 26 degrees of it (cosine >= 0.9) are
///     candidates, their depths projected on that normal (point_b moved to keep
///     point_b = point_a - depth * normal), and narrow::reduce_contacts keeps at most
///     max_contacts of them: deepest, farthest from it, largest triangle, largest
///     quadrilateral (Gregorius, GDC 2015). Feature ids are mixed with the sub-shape ids
///     so that points from different parts keep distinct ids.

#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/geometry_queries.hpp>
#include <proxima/narrowphase/narrowphase.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "manifold_reduction.hpp"
#include "shapes/geometry_dispatch.hpp"
#include "mesh_convex.hpp"
#include "mesh_mesh.hpp"

namespace proxima {
namespace {

constexpr Real kInf = std::numeric_limits<Real>::infinity();

GeometryDistance mirrored(const GeometryDistance& d) { return {proxima::mirrored(d.result), d.b, d.a}; }

void mirror_contacts(std::vector<GeometryContact>& out, std::size_t from) {
  for (std::size_t k = from; k < out.size(); ++k) {
    GeometryContact& c = out[k];
    std::swap(c.contact.point_a, c.contact.point_b);
    c.contact.normal = -c.contact.normal;
    c.contact.feature_id = mirror_feature_id(c.contact.feature_id);
    std::swap(c.a, c.b);
  }
}

/// Calls leaf(i, j) for every pair of children of A and B whose BVH leaves overlap (B's node
/// boxes mapped into A's frame, A's boxes inflated by `margin`). leaf returns false to stop;
/// returns false when stopped.
template <class Leaf>
bool pair_descent(const Compound& a, const Transform& pose_a, const Compound& b, const Transform& pose_b, Real margin,
                  Leaf&& leaf) {
  const auto na = a.bvh().nodes(), nb = b.bvh().nodes();
  const auto pa = a.bvh().primitives(), pb = b.bvh().primitives();
  if (na.empty() || nb.empty()) return true;
  const Transform rel = relative(pose_a, pose_b);
  const auto overlap = [&](std::uint32_t i, std::uint32_t j) {
    return na[i].bounds().inflated(margin).overlaps(nb[j].bounds().transformed(rel));
  };
  struct Pair {
    std::uint32_t i, j;
  };
  Pair stack[2 * Bvh::kMaxDepth + 4];
  std::uint32_t top = 0;
  if (!overlap(0, 0)) return true;
  stack[top++] = {0, 0};
  while (top != 0) {
    const Pair p = stack[--top];
    const BvhNode& x = na[p.i];
    const BvhNode& y = nb[p.j];
    if (x.is_leaf() && y.is_leaf()) {
      for (std::uint32_t s = x.first; s != x.first + x.count; ++s)
        for (std::uint32_t t = y.first; t != y.first + y.count; ++t)
          if (!leaf(pa[s], pb[t])) return false;
      continue;
    }
    const bool split_a = !x.is_leaf() && (y.is_leaf() || x.bounds().surface_area() >= y.bounds().surface_area());
    for (std::uint32_t c = 0; c != 2; ++c) {
      const Pair q = split_a ? Pair{x.first + 1 - c, p.j} : Pair{p.i, y.first + 1 - c};
      if (overlap(q.i, q.j)) stack[top++] = q;
    }
  }
  return true;
}

bool intersect_impl(GeometryRef a, const Transform& pa, GeometryRef b, const Transform& pb, const PairRequest& req);

bool intersect_compound(const Compound& a, const Transform& pa, GeometryRef b, const Transform& pb,
                        const PairRequest& req) {
  const auto kids = a.children();
  if (b.kind() == GeometryKind::Compound) {
    bool hit = false;
    const auto kb = b.compound().children();
    pair_descent(a, pa, b.compound(), pb, req.contact_distance, [&](std::uint32_t i, std::uint32_t j) {
      hit = intersect_impl(GeometryRef(kids[i].geometry), pa * kids[i].pose, GeometryRef(kb[j].geometry),
                           pb * kb[j].pose, req);
      return !hit;
    });
    return hit;
  }
  const Aabb box = world_aabb(b, relative(pa, pb)).inflated(req.contact_distance);
  bool hit = false;
  a.bvh().traverse([&](const BvhNode& n) { return n.bounds().overlaps(box); },
                   [&](std::uint32_t i) {
                     hit = intersect_impl(GeometryRef(kids[i].geometry), pa * kids[i].pose, b, pb, req);
                     return !hit;
                   });
  return hit;
}

bool intersect_impl(GeometryRef a, const Transform& pa, GeometryRef b, const Transform& pb, const PairRequest& req) {
  if (a.kind() == GeometryKind::Compound) return intersect_compound(a.compound(), pa, b, pb, req);
  if (b.kind() == GeometryKind::Compound) return intersect_compound(b.compound(), pb, a, pa, req);
  if (a.kind() == GeometryKind::Convex) {
    if (b.kind() == GeometryKind::Convex) return intersect(a.convex(), pa, b.convex(), pb, req);
    return narrow::mesh_convex_intersect(b.mesh(), pb, a.convex(), pa, req);
  }
  if (b.kind() == GeometryKind::Convex) return narrow::mesh_convex_intersect(a.mesh(), pa, b.convex(), pb, req);
  return narrow::mesh_mesh_intersect(a.mesh(), pa, b.mesh(), pb, req);
}

GeometryDistance distance_impl(GeometryRef a, const Transform& pa, GeometryRef b, const Transform& pb,
                               const PairRequest& req, Real cutoff);

/// Compound A against anything B, only answers below `cutoff` searched for.
GeometryDistance distance_compound(const Compound& a, const Transform& pa, GeometryRef b, const Transform& pb,
                                   const PairRequest& req, Real cutoff) {
  GeometryDistance best;
  best.result.signed_distance = kInf;
  Real bound = cutoff;
  const auto nodes = a.bvh().nodes();
  const auto prims = a.bvh().primitives();
  const auto kids = a.children();
  if (nodes.empty()) return best;
  const Aabb box = world_aabb(b, relative(pa, pb));
  struct Entry {
    std::uint32_t node;
    Real gap;
  };
  Entry stack[Bvh::kMaxDepth + 2];
  std::uint32_t top = 0;
  stack[top++] = {0, detail::aabb_gap(nodes[0].bounds(), box)};
  while (top != 0) {
    const Entry e = stack[--top];
    if (e.gap > bound && e.gap > Real(0)) continue;  // a box gap bounds gaps, not depths
    const BvhNode& node = nodes[e.node];
    if (node.is_leaf()) {
      for (std::uint32_t s = node.first; s != node.first + node.count; ++s) {
        const std::uint32_t i = prims[s];
        GeometryDistance d = distance_impl(GeometryRef(kids[i].geometry), pa * kids[i].pose, b, pb, req, bound);
        if (d.result.signed_distance < bound || (d.result.signed_distance == bound && i < best.a.child)) {
          best = d;
          best.a.child = i;
          bound = d.result.signed_distance;
        }
      }
      continue;
    }
    const std::uint32_t l = node.first, r = node.first + 1;
    const Real gl = detail::aabb_gap(nodes[l].bounds(), box), gr = detail::aabb_gap(nodes[r].bounds(), box);
    if (gl <= gr) {
      if (gr <= bound || gr <= Real(0)) stack[top++] = {r, gr};
      if (gl <= bound || gl <= Real(0)) stack[top++] = {l, gl};
    } else {
      if (gl <= bound || gl <= Real(0)) stack[top++] = {l, gl};
      if (gr <= bound || gr <= Real(0)) stack[top++] = {r, gr};
    }
  }
  return best;
}

GeometryDistance distance_impl(GeometryRef a, const Transform& pa, GeometryRef b, const Transform& pb,
                               const PairRequest& req, Real cutoff) {
  if (a.kind() == GeometryKind::Compound) return distance_compound(a.compound(), pa, b, pb, req, cutoff);
  if (b.kind() == GeometryKind::Compound) return mirrored(distance_compound(b.compound(), pb, a, pa, req, cutoff));
  if (a.kind() == GeometryKind::Convex) {
    if (b.kind() == GeometryKind::Convex) return {distance(a.convex(), pa, b.convex(), pb, req), {}, {}};
    return mirrored(narrow::mesh_convex_distance(b.mesh(), pb, a.convex(), pa, req, cutoff));
  }
  if (b.kind() == GeometryKind::Convex)
    return narrow::mesh_convex_distance(a.mesh(), pa, b.convex(), pb, req, cutoff);
  return narrow::mesh_mesh_distance(a.mesh(), pa, b.mesh(), pb, req);
}

void collide_impl(GeometryRef a, const Transform& pa, GeometryRef b, const Transform& pb, const PairRequest& req,
                  std::vector<GeometryContact>& out);

void collide_compound(const Compound& a, const Transform& pa, GeometryRef b, const Transform& pb,
                      const PairRequest& req, std::vector<GeometryContact>& out) {
  const auto kids = a.children();
  if (b.kind() == GeometryKind::Compound) {
    const auto kb = b.compound().children();
    pair_descent(a, pa, b.compound(), pb, req.contact_distance, [&](std::uint32_t i, std::uint32_t j) {
      const std::size_t from = out.size();
      collide_impl(GeometryRef(kids[i].geometry), pa * kids[i].pose, GeometryRef(kb[j].geometry), pb * kb[j].pose, req,
                   out);
      for (std::size_t k = from; k < out.size(); ++k) {
        out[k].a.child = i;
        out[k].b.child = j;
      }
      return true;
    });
    return;
  }
  const Aabb box = world_aabb(b, relative(pa, pb)).inflated(req.contact_distance);
  a.bvh().traverse([&](const BvhNode& n) { return n.bounds().overlaps(box); },
                   [&](std::uint32_t i) {
                     const std::size_t from = out.size();
                     collide_impl(GeometryRef(kids[i].geometry), pa * kids[i].pose, b, pb, req, out);
                     for (std::size_t k = from; k < out.size(); ++k) out[k].a.child = i;
                     return true;
                   });
}

void collide_impl(GeometryRef a, const Transform& pa, GeometryRef b, const Transform& pb, const PairRequest& req,
                  std::vector<GeometryContact>& out) {
  const std::size_t from = out.size();
  if (a.kind() == GeometryKind::Compound) return collide_compound(a.compound(), pa, b, pb, req, out);
  if (b.kind() == GeometryKind::Compound) {
    collide_compound(b.compound(), pb, a, pa, req, out);
    mirror_contacts(out, from);
    return;
  }
  if (a.kind() == GeometryKind::Convex) {
    if (b.kind() == GeometryKind::Convex) {
      const ContactManifold m = collide(a.convex(), pa, b.convex(), pb, req);
      for (int i = 0; i < m.count; ++i) out.push_back({m.points[static_cast<std::size_t>(i)], {}, {}});
      return;
    }
    narrow::mesh_convex_collide_all(b.mesh(), pb, a.convex(), pa, req, out);
    mirror_contacts(out, from);
    return;
  }
  if (b.kind() == GeometryKind::Convex)
    return narrow::mesh_convex_collide_all(a.mesh(), pa, b.convex(), pb, req, out);
  narrow::mesh_mesh_collide_all(a.mesh(), pa, b.mesh(), pb, req, out);
}

std::uint32_t mix_sub_ids(const GeometryContact& c) {
  std::uint32_t h = 0x811c9dc5u;
  for (std::uint32_t x : {c.a.child, c.a.triangle, c.b.child, c.b.triangle}) h = (h ^ x) * 0x01000193u;
  return h;
}

}  // namespace

bool intersect(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
               const PairRequest& request) {
  return intersect_impl(a, pose_a, b, pose_b, request);
}

GeometryDistance distance(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
                          const PairRequest& request) {
  GeometryDistance d = distance_impl(a, pose_a, b, pose_b, request, kInf);
  if (!(d.result.signed_distance < kInf)) {  // no part answered (e.g. only degenerate triangles)
    d.result = DistanceResult{};
    d.result.signed_distance = kInf;
    d.result.status = PairStatus::Separated;
  }
  return d;
}

void collide_all(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
                 const PairRequest& request, std::vector<GeometryContact>& contacts) {
  collide_impl(a, pose_a, b, pose_b, request, contacts);
}

ContactManifold collide(GeometryRef a, const Transform& pose_a, GeometryRef b, const Transform& pose_b,
                        const PairRequest& request) {
  if (a.kind() == GeometryKind::Convex && b.kind() == GeometryKind::Convex)
    return collide(a.convex(), pose_a, b.convex(), pose_b, request);
  thread_local std::vector<GeometryContact> all;
  thread_local std::vector<ContactPoint> candidates;
  all.clear();
  candidates.clear();
  collide_impl(a, pose_a, b, pose_b, request, all);
  ContactManifold m;
  if (all.empty()) return m;
  std::size_t deepest = 0;
  for (std::size_t k = 1; k < all.size(); ++k)
    if (all[k].contact.depth > all[deepest].contact.depth) deepest = k;
  const Vec3 n = all[deepest].contact.normal;
  for (const GeometryContact& c : all) {
    const Real cosine = glm::dot(c.contact.normal, n);
    if (cosine < Real(0.9)) continue;
    ContactPoint p = c.contact;
    p.depth = c.contact.depth * cosine;
    p.normal = n;
    p.point_b = p.point_a - p.depth * n;
    p.feature_id ^= mix_sub_ids(c);
    candidates.push_back(p);
  }
  m.count = narrow::reduce_contacts(candidates, n, std::clamp(request.max_contacts, 1, kMaxContactPoints), m.points);
  m.normal = n;
  const ContactPoint& top = m.points[0];
  const Real scale = std::max({std::abs(top.point_a.x), std::abs(top.point_a.y), std::abs(top.point_a.z)});
  const Real tol = request.tolerance > Real(0) ? request.tolerance : linear_tolerance(scale);
  m.status = status_from_distance(-top.depth, tol);
  m.method = PairMethod::Analytic;
  return m;
}

}  // namespace proxima
