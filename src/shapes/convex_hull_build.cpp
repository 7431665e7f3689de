// ConvexHull::create: the convex hull of a point cloud, built with qhull.
//
// Steps:
//  1. Validate: at least 4 points, every coordinate finite and within kMaxCoordinate.
//  2. Normalise in double: translate to the centre of the points' box and divide by its
//     largest extent, so that qhull's tolerances see the same unit-size problem at 1e-4
//     and at 1e4 scales and far from the origin.
//  3. Flatness check: farthest pair, farthest point from their line, farthest point from
//     the plane of the three (an O(n) approximation of the cloud's width); a cloud that is
//     coincident, collinear or coplanar within tolerance is Degenerate.
//  4. Run qhull (Barber, Dobkin, Huhdanpaa, "The Quickhull Algorithm for Convex Hulls",
//     ACM TOMS 1996) in double: 'Qs' searches every point for the initial simplex, 'C-0'
//     pre-merges within qhull's roundoff, and the post-merge centrum radius 'Cr' (r = 2
//     epsilon of Real at the points' distance from the origin: the rounding of the input
//     coordinates) merges facets until every centrum is r below its neighbours' planes.
//     Faces coplanar within the resolution of the input become one polygon (a rotated
//     box keeps six faces), and no sliver or shallow dent made of rounding noise is left,
//     where face outlines would be arbitrary and hill-climbing could stop short. For a
//     thin cloud r is capped at kRelativeTolerance times its thickness: merging by plane
//     distance moves a thin rim sideways by r / thickness. Qhull's messages go to a
//     memory stream, read back for the error message. Its memory is freed on every path.
//  5. Each facet's vertex loop comes from qhull's own topology: the ridges of a merged
//     facet are walked end to end (as qhull's qh_facet3vertex does), a simplicial facet's
//     order follows its orientation flag, so every edge is traversed once in each
//     direction by its two faces. The loops are turned to be counter-clockwise seen from
//     outside (one global orientation, checked face by face against qhull's normals). A
//     merged facet is planar only within r: where its outline bends inwards by more than
//     that, it is cut into triangles by ear clipping, which keep the facet's plane.
//  6. Vertices shared by only two faces lie on a straight edge and are removed from both
//     loops (they would stall hill-climbing). Compact the vertex indices, recompute each
//     face plane from its loop (Newell's method, offset = the largest vertex offset),
//     pair each directed edge with its reverse and check the closed 2-manifold (each
//     directed edge once, its reverse in another face, V - E + F = 2). Build the vertex
//     adjacency (CSR). If qhull or a check fails, qhull runs again with a 10x larger
//     post-merge radius (three times at most) before Internal is reported.
//  7. Box, scale, tolerance; the hull's width over its face normals must exceed the
//     flatness tolerance; mass properties (convex_hull_mass.cpp).

#include <proxima/core/tolerance.hpp>
#include <proxima/core/validate.hpp>
#include <proxima/shapes/convex_hull.hpp>

#include <libqhull_r/qhull_ra.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "shapes/convex_hull_data.hpp"
#include "shapes/double_vector.hpp"

namespace proxima {

namespace {

using detail::D3;

// Relative width below which a cloud counts as flat: the resolution of Real, so that the
// float and double builds reject what they cannot represent as a solid.
constexpr double kFlatRelative = double(kRelativeTolerance);

// Owns an in-memory FILE (POSIX open_memstream) for qhull's messages and closes it on every
// path. (A temporary file on disk cost more than the whole hull build for small clouds.)
class MessageFile {
 public:
  MessageFile() : file_(open_memstream(&buffer_, &size_)) {
    if (file_ == nullptr) {
      file_ = std::fopen("/dev/null", "w");
      readable_ = false;
    }
  }
  ~MessageFile() {
    if (file_ != nullptr) std::fclose(file_);
    std::free(buffer_);
  }
  MessageFile(const MessageFile&) = delete;
  MessageFile& operator=(const MessageFile&) = delete;

  FILE* get() const { return file_; }

  // The line of qhull's error (code QH6xxx and message) among what it wrote (warnings are
  // QH7xxx), else its first line, or "".
  std::string error_line() {
    if (file_ == nullptr || !readable_) return {};
    std::fflush(file_);
    const std::string text = buffer_ != nullptr ? std::string(buffer_, size_) : std::string();
    std::string first;
    std::size_t begin = 0;
    while (begin <= text.size()) {
      std::size_t stop = text.find('\n', begin);
      if (stop == std::string::npos) stop = text.size();
      std::string line = text.substr(begin, std::min<std::size_t>(stop - begin, 300));
      if (line.rfind("QH6", 0) == 0) return line;
      if (first.empty()) first = line;
      begin = stop + 1;
    }
    return first;
  }

 private:
  char* buffer_ = nullptr;
  std::size_t size_ = 0;
  FILE* file_ = nullptr;
  bool readable_ = true;
};

// Frees qhull's long and short memory on every path.
class QhullSession {
 public:
  explicit QhullSession(FILE* errfile) : qh_(std::make_unique<qhT>()) { qh_zero(qh_.get(), errfile); }
  ~QhullSession() {
    qh_freeqhull(qh_.get(), !qh_ALL);
    int curlong = 0;
    int totlong = 0;
    qh_memfreeshort(qh_.get(), &curlong, &totlong);
  }
  QhullSession(const QhullSession&) = delete;
  QhullSession& operator=(const QhullSession&) = delete;

  qhT* get() const { return qh_.get(); }

 private:
  std::unique_ptr<qhT> qh_;
};

// What qhull produced: one vertex loop (input point ids) per facet with the facet's
// outward unit normal, or an error.
struct QhullOutcome {
  std::vector<std::vector<int>> loops;
  std::vector<D3> normals;
  std::vector<std::size_t> plane_of;  // loop whose points define each loop's plane (itself, or the
                                      // merged facet it was cut from)
  std::size_t face_count = 0;         // loops [0, face_count) are faces, the rest plane sources
  double max_outside = 0;             // farthest input point above its facet's hyperplane (normalised)
  int exit_code = 0;
  std::string message;
};

// The next ridge around `facet` after `at`, and the vertex it leads to (the walk of
// qhull's qh_nextridge3d, written without its error exits). nullptr when the ridges do
// not close.
ridgeT* next_ridge(ridgeT* at, facetT* facet, vertexT** vertex_out) {
  vertexT* at_vertex = (at->top == facet) ? SETsecondt_(at->vertices, vertexT) : SETfirstt_(at->vertices, vertexT);
  ridgeT* ridge = nullptr;
  ridgeT** ridgep = nullptr;
  FOREACHridge_(facet->ridges) {
    if (ridge == at) continue;
    vertexT* first = nullptr;
    vertexT* other = nullptr;
    if (ridge->top == facet) {
      other = SETsecondt_(ridge->vertices, vertexT);
      first = SETfirstt_(ridge->vertices, vertexT);
    } else {
      first = SETsecondt_(ridge->vertices, vertexT);
      other = SETfirstt_(ridge->vertices, vertexT);
    }
    if (first == at_vertex) {
      *vertex_out = other;
      return ridge;
    }
  }
  return nullptr;
}

// Number of elements of a qhull set (its element array ends with a null pointer);
// unlike qh_setsize it has no error exit, which would end the process outside qhull.
int set_count(setT* set) {
  if (set == nullptr) return 0;
  int n = 0;
  for (setelemT* e = &set->e[0]; e->p != nullptr; ++e) ++n;
  return n;
}

QhullOutcome run_qhull(const std::vector<D3>& pts, double post_merge_radius) {
  QhullOutcome out;
  std::vector<coordT> coords(pts.size() * 3);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    coords[3 * i + 0] = pts[i][0];
    coords[3 * i + 1] = pts[i][1];
    coords[3 * i + 2] = pts[i][2];
  }
  MessageFile messages;
  QhullSession session(messages.get());
  qhT* qh = session.get();
  char command[64];
  std::snprintf(command, sizeof command, "qhull Qs C-0 C%.3g", post_merge_radius);
  out.exit_code =
      qh_new_qhull(qh, 3, static_cast<int>(pts.size()), coords.data(), False, command, nullptr, messages.get());
  if (out.exit_code != 0) {
    out.message = messages.error_line();
    return out;
  }
  out.max_outside = std::max({0.0, qh->max_outside, qh->max_vertex});
  auto fail = [&](const char* why) {
    out.exit_code = qh_ERRqhull;
    out.message = why;
    out.loops.clear();
    return out;
  };
  auto point_id = [&](vertexT* v) {
    const int id = qh_pointid(qh, v->point);
    return (id >= 0 && static_cast<std::size_t>(id) < pts.size()) ? id : -1;
  };
  facetT* facet = nullptr;
  FORALLfacets {
    std::vector<int> loop;
    const int count = set_count(facet->vertices);
    if (facet->simplicial) {
      // Vertex set sorted by decreasing id; the orientation flag says which way round.
      if (count != 3) return fail("a simplicial facet without 3 vertices");
      vertexT* v0 = SETfirstt_(facet->vertices, vertexT);
      vertexT* v1 = SETsecondt_(facet->vertices, vertexT);
      vertexT* v2 = SETelemt_(facet->vertices, 2, vertexT);
      if (facet->toporient) {
        loop = {point_id(v0), point_id(v1), point_id(v2)};
      } else {
        loop = {point_id(v1), point_id(v0), point_id(v2)};
      }
    } else {
      if (set_count(facet->ridges) < 3) return fail("a facet without ridges");
      ridgeT* first = SETfirstt_(facet->ridges, ridgeT);
      ridgeT* ridge = first;
      vertexT* vertex = nullptr;
      while ((ridge = next_ridge(ridge, facet, &vertex)) != nullptr) {
        loop.push_back(point_id(vertex));
        if (static_cast<int>(loop.size()) > count || ridge == first) break;
      }
      if (ridge == nullptr || static_cast<int>(loop.size()) != count) return fail("the ridges of a facet do not close");
    }
    for (int id : loop) {
      if (id < 0) return fail("a facet vertex is not an input point");
    }
    const D3 n{facet->normal[0], facet->normal[1], facet->normal[2]};
    const double nl = detail::norm(n);
    if (!(nl > 0.5)) return fail("a facet without a valid plane");
    out.loops.push_back(std::move(loop));
    out.normals.push_back({n[0] / nl, n[1] / nl, n[2] / nl});
  }
  return out;
}

// Coordinates of the loop's points in the plane of unit normal n, (u, w, n) right-handed.
std::vector<std::array<double, 2>> project_loop(const std::vector<int>& loop, const D3& n, const std::vector<D3>& pts) {
  const D3 helper = std::abs(n[0]) < 0.6 ? D3{1, 0, 0} : (std::abs(n[1]) < 0.6 ? D3{0, 1, 0} : D3{0, 0, 1});
  D3 u = detail::cross(helper, n);
  const double ul = detail::norm(u);
  u = {u[0] / ul, u[1] / ul, u[2] / ul};
  const D3 w = detail::cross(n, u);
  std::vector<std::array<double, 2>> q;
  q.reserve(loop.size());
  for (int id : loop) q.push_back({detail::dot(pts[id], u), detail::dot(pts[id], w)});
  return q;
}

double turn2(const std::array<double, 2>& a, const std::array<double, 2>& b, const std::array<double, 2>& c) {
  return (b[0] - a[0]) * (c[1] - b[1]) - (b[1] - a[1]) * (c[0] - b[0]);
}

double length2(const std::array<double, 2>& a, const std::array<double, 2>& b) {
  return std::hypot(b[0] - a[0], b[1] - a[1]);
}

// True when the CCW loop turns left at every vertex, or right by less than `slack`
// (the vertex lies within slack inside the line of its neighbours' edges).
bool is_convex_loop(const std::vector<int>& loop, const D3& n, const std::vector<D3>& pts, double slack) {
  const auto q = project_loop(loop, n, pts);
  const std::size_t k = q.size();
  for (std::size_t i = 0; i < k; ++i) {
    const auto& a = q[i];
    const auto& b = q[(i + 1) % k];
    const auto& c = q[(i + 2) % k];
    if (turn2(a, b, c) < -slack * (length2(a, b) + length2(b, c))) return false;
  }
  return true;
}

// Ear clipping (Meisters 1975; Eberly, "Triangulation by Ear Clipping") of a simple CCW
// loop in the plane of n. Returns false when no ear is left (the outline crosses itself).
bool ear_clip(const std::vector<int>& loop, const D3& n, const std::vector<D3>& pts,
              std::vector<std::array<int, 3>>& triangles) {
  const auto all = project_loop(loop, n, pts);
  std::vector<std::size_t> rest(loop.size());
  for (std::size_t i = 0; i < rest.size(); ++i) rest[i] = i;
  auto inside = [&](std::size_t p, std::size_t a, std::size_t b, std::size_t c) {
    return turn2(all[a], all[b], all[p]) >= 0 && turn2(all[b], all[c], all[p]) >= 0 &&
           turn2(all[c], all[a], all[p]) >= 0;
  };
  while (rest.size() > 3) {
    bool clipped = false;
    for (std::size_t i = 0; i < rest.size() && !clipped; ++i) {
      const std::size_t a = rest[(i + rest.size() - 1) % rest.size()];
      const std::size_t b = rest[i];
      const std::size_t c = rest[(i + 1) % rest.size()];
      if (!(turn2(all[a], all[b], all[c]) > 0)) continue;
      bool empty = true;
      for (std::size_t p : rest) {
        if (p != a && p != b && p != c && inside(p, a, b, c)) {
          empty = false;
          break;
        }
      }
      if (!empty) continue;
      triangles.push_back({loop[a], loop[b], loop[c]});
      rest.erase(rest.begin() + static_cast<std::ptrdiff_t>(i));
      clipped = true;
    }
    if (!clipped) return false;
  }
  triangles.push_back({loop[rest[0]], loop[rest[1]], loop[rest[2]]});
  return true;
}

// Turns qhull's loops counter-clockwise seen from outside and removes the vertices that
// only two faces share; cuts loops that bend inwards by more than `slack` (normalised
// length) into triangles. Returns an empty string, or why the loops are unusable.
std::string orient_and_simplify(QhullOutcome& hull, const std::vector<D3>& pts, double slack) {
  // One orientation for all loops (the ridge walk is consistent between neighbours):
  // the sign of the total area vector against qhull's outward normals.
  std::vector<double> along(hull.loops.size());
  std::vector<double> area(hull.loops.size());
  double total = 0;
  for (std::size_t f = 0; f < hull.loops.size(); ++f) {
    const std::vector<int>& loop = hull.loops[f];
    D3 a{0, 0, 0};
    const D3& o = pts[loop[0]];
    for (std::size_t k = 1; k + 1 < loop.size(); ++k) {
      const D3 t = detail::cross(detail::sub(pts[loop[k]], o), detail::sub(pts[loop[k + 1]], o));
      a = {a[0] + t[0], a[1] + t[1], a[2] + t[2]};
    }
    along[f] = detail::dot(a, hull.normals[f]);
    area[f] = detail::norm(a);
    total += along[f];
  }
  const bool flip = total < 0;
  for (std::size_t f = 0; f < hull.loops.size(); ++f) {
    // A face of visible size must agree with the global orientation.
    if (area[f] > 1e-9 && (flip ? -along[f] : along[f]) < 0.5 * area[f]) return "inconsistent facet orientation";
    if (flip) std::reverse(hull.loops[f].begin(), hull.loops[f].end());
  }

  // Vertices of exactly two faces lie on the straight edge between them.
  std::vector<int> face_count(pts.size(), 0);
  for (const auto& loop : hull.loops) {
    for (int id : loop) ++face_count[id];
  }
  for (auto& loop : hull.loops) {
    loop.erase(std::remove_if(loop.begin(), loop.end(), [&](int id) { return face_count[id] == 2; }), loop.end());
    if (loop.size() < 3) return "a facet collapsed to an edge";
  }

  // A merged facet is planar only within the merge radius; where its outline bends
  // inwards by more than that, it is cut into triangles (convex pieces for every query).
  // The pieces keep the plane of the whole facet (appended after the kept loops).
  std::vector<std::vector<int>> loops;
  std::vector<std::size_t> plane_of;
  std::vector<std::vector<int>> cut;
  std::vector<std::size_t> cut_from;
  for (std::size_t f = 0; f < hull.loops.size(); ++f) {
    if (is_convex_loop(hull.loops[f], hull.normals[f], pts, slack)) {
      plane_of.push_back(loops.size());
      loops.push_back(std::move(hull.loops[f]));
      continue;
    }
    std::vector<std::array<int, 3>> triangles;
    if (!ear_clip(hull.loops[f], hull.normals[f], pts, triangles)) return "a merged facet outline is not simple";
    for (const auto& t : triangles) {
      cut.push_back({t[0], t[1], t[2]});
      cut_from.push_back(f);
    }
  }
  // Cut facets' own loops are kept at the end, only as plane sources (not faces).
  const std::size_t faces = loops.size() + cut.size();
  std::vector<std::size_t> source_slot(hull.loops.size(), 0);
  std::vector<std::vector<int>> sources;
  for (std::size_t k = 0; k < cut.size(); ++k) {
    if (k == 0 || cut_from[k] != cut_from[k - 1]) {
      source_slot[cut_from[k]] = faces + sources.size();
      sources.push_back(hull.loops[cut_from[k]]);
    }
    plane_of.push_back(source_slot[cut_from[k]]);
    loops.push_back(std::move(cut[k]));
  }
  hull.face_count = faces;
  for (auto& src : sources) loops.push_back(std::move(src));
  hull.loops = std::move(loops);
  hull.plane_of = std::move(plane_of);
  return {};
}

// Builds vertices, faces (planes by Newell's method), edges and adjacency from the
// oriented loops, checking the closed 2-manifold. Returns an empty string, or why not.
std::string assemble(std::span<const Vec3> points, const QhullOutcome& hull, detail::HullData& data,
                     std::vector<D3>& vd, double& planarity) {
  planarity = 0;
  std::vector<std::uint32_t> remap(points.size(), std::numeric_limits<std::uint32_t>::max());
  vd.clear();
  for (const std::vector<int>& ids : hull.loops) {
    for (int id : ids) {
      if (remap[id] == std::numeric_limits<std::uint32_t>::max()) {
        remap[id] = static_cast<std::uint32_t>(data.vertices.size());
        data.vertices.push_back(points[id]);
        vd.push_back({double(points[id].x), double(points[id].y), double(points[id].z)});
      }
    }
  }
  const std::size_t nv = data.vertices.size();

  // Planes by Newell's method over the loop of the facet each face comes from (a face cut
  // out of a bent merged facet keeps the whole facet's plane), relative to its centroid;
  // offset = the largest vertex offset, so every vertex lies on or below the plane.
  data.faces.reserve(hull.face_count);
  for (std::size_t fi = 0; fi < hull.face_count; ++fi) {
    const std::vector<int>& ids = hull.loops[fi];
    const std::vector<int>& plane_ids = hull.loops[hull.plane_of[fi]];
    HullFace face;
    face.first_index = static_cast<std::uint32_t>(data.face_indices.size());
    face.index_count = static_cast<std::uint32_t>(ids.size());
    D3 c{0, 0, 0};
    for (int id : plane_ids) {
      const D3& v = vd[remap[id]];
      for (int a = 0; a < 3; ++a) c[a] += v[a];
    }
    for (int a = 0; a < 3; ++a) c[a] /= double(plane_ids.size());
    D3 n{0, 0, 0};
    for (std::size_t k = 0; k < plane_ids.size(); ++k) {
      const D3 p = detail::sub(vd[remap[plane_ids[k]]], c);
      const D3 q = detail::sub(vd[remap[plane_ids[(k + 1) % plane_ids.size()]]], c);
      const D3 pq = detail::cross(p, q);
      for (int a = 0; a < 3; ++a) n[a] += pq[a];
    }
    const double nl = detail::norm(n);
    if (!(nl > 0)) return std::string("a merged facet has zero area");
    n = {n[0] / nl, n[1] / nl, n[2] / nl};
    double offset = -std::numeric_limits<double>::max();
    double lowest = std::numeric_limits<double>::max();
    for (int id : plane_ids) {
      offset = std::max(offset, detail::dot(n, vd[remap[id]]));
      lowest = std::min(lowest, detail::dot(n, vd[remap[id]]));
    }
    for (int id : ids) data.face_indices.push_back(remap[id]);
    planarity = std::max(planarity, offset - lowest);
    // The loop must turn counter-clockwise about its plane's normal (a piece cut from a
    // facet whose outline folded over would not).
    D3 area{0, 0, 0};
    for (std::size_t k = 1; k + 1 < ids.size(); ++k) {
      const D3 t = detail::cross(detail::sub(vd[remap[ids[k]]], vd[remap[ids[0]]]),
                                 detail::sub(vd[remap[ids[k + 1]]], vd[remap[ids[0]]]));
      area = {area[0] + t[0], area[1] + t[1], area[2] + t[2]};
    }
    if (detail::dot(area, n) < -1e-6 * detail::norm(area)) return std::string("a face is inverted");
    face.normal = Vec3(Real(n[0]), Real(n[1]), Real(n[2]));
    face.offset = Real(offset);
    data.faces.push_back(face);
  }

  // Directed edges (a -> b, face), sorted by (a, b): each must meet its reverse once.
  struct Directed {
    std::uint64_t key;
    std::uint32_t face;
  };
  std::vector<Directed> directed;
  directed.reserve(data.face_indices.size());
  for (std::uint32_t fi = 0; fi < data.faces.size(); ++fi) {
    const HullFace& f = data.faces[fi];
    for (std::uint32_t k = 0; k < f.index_count; ++k) {
      const std::uint64_t a = data.face_indices[f.first_index + k];
      const std::uint64_t b = data.face_indices[f.first_index + (k + 1) % f.index_count];
      directed.push_back({(a << 32) | b, fi});
    }
  }
  std::sort(directed.begin(), directed.end(), [](const Directed& x, const Directed& y) { return x.key < y.key; });
  for (std::size_t k = 1; k < directed.size(); ++k) {
    if (directed[k].key == directed[k - 1].key) return std::string("an edge is shared by more than two faces");
  }
  auto find_face = [&](std::uint64_t key) -> std::int64_t {
    auto it = std::lower_bound(directed.begin(), directed.end(), key,
                               [](const Directed& x, std::uint64_t k) { return x.key < k; });
    if (it == directed.end() || it->key != key) return -1;
    return it->face;
  };
  for (const Directed& d : directed) {
    const std::uint32_t a = static_cast<std::uint32_t>(d.key >> 32);
    const std::uint32_t b = static_cast<std::uint32_t>(d.key & 0xffffffffu);
    const std::int64_t other = find_face((std::uint64_t(b) << 32) | a);
    if (other < 0 || static_cast<std::uint32_t>(other) == d.face) {
      return std::string("the merged facets do not form a closed surface");
    }
    if (a < b) data.edges.push_back({a, b, d.face, static_cast<std::uint32_t>(other)});
  }
  const std::int64_t euler = std::int64_t(nv) - std::int64_t(data.edges.size()) + std::int64_t(data.faces.size());
  if (euler != 2) return std::string("the merged facets do not form a sphere (V - E + F != 2)");

  data.neighbor_offsets.assign(nv + 1, 0);
  for (const HullEdge& e : data.edges) {
    ++data.neighbor_offsets[e.v0 + 1];
    ++data.neighbor_offsets[e.v1 + 1];
  }
  for (std::size_t v = 0; v < nv; ++v) data.neighbor_offsets[v + 1] += data.neighbor_offsets[v];
  data.neighbors.resize(data.neighbor_offsets[nv]);
  {
    std::vector<std::uint32_t> fill(data.neighbor_offsets.begin(), data.neighbor_offsets.end() - 1);
    for (const HullEdge& e : data.edges) {
      data.neighbors[fill[e.v0]++] = e.v1;
      data.neighbors[fill[e.v1]++] = e.v0;
    }
  }

  // Hill-climbing moves: every other vertex of every merged facet around a vertex (a
  // superset of the edge neighbours, with the diagonals of facets that merging left
  // slightly bent, including those cut into pieces). Facets of more than kMaxMates
  // vertices (large flat polygons such as a cylinder's caps) add only their loop edges,
  // keeping the lists linear in the hull's size.
  constexpr std::size_t kMaxMates = 32;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> mates;
  for (std::size_t li = 0; li < hull.loops.size(); ++li) {
    const std::vector<int>& loop = hull.loops[li];
    if (li < hull.face_count && hull.plane_of[li] != li) continue;  // a piece: its facet is listed
    if (loop.size() > kMaxMates) {
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const std::uint32_t a = remap[loop[k]];
        const std::uint32_t b = remap[loop[(k + 1) % loop.size()]];
        mates.push_back({a, b});
        mates.push_back({b, a});
      }
      continue;
    }
    for (int a : loop) {
      for (int b : loop) {
        if (a != b) mates.push_back({remap[a], remap[b]});
      }
    }
  }
  // Pieces of a large cut facet still need their own edges (diagonals of the cut).
  for (std::size_t li = 0; li < hull.face_count; ++li) {
    if (hull.plane_of[li] == li || hull.loops[hull.plane_of[li]].size() <= kMaxMates) continue;
    const std::vector<int>& loop = hull.loops[li];
    for (std::size_t k = 0; k < loop.size(); ++k) {
      const std::uint32_t a = remap[loop[k]];
      const std::uint32_t b = remap[loop[(k + 1) % loop.size()]];
      mates.push_back({a, b});
      mates.push_back({b, a});
    }
  }
  std::sort(mates.begin(), mates.end());
  mates.erase(std::unique(mates.begin(), mates.end()), mates.end());
  data.climb_offsets.assign(nv + 1, 0);
  data.climb_neighbors.reserve(mates.size());
  for (const auto& [from, to] : mates) {
    ++data.climb_offsets[from + 1];
    data.climb_neighbors.push_back(to);
  }
  for (std::size_t v = 0; v < nv; ++v) data.climb_offsets[v + 1] += data.climb_offsets[v];

  return {};
}

Error internal(const std::string& what) {
  return make_error(ErrorCode::Internal, "points", "qhull failed to build the convex hull: " + what);
}

Error degenerate(const std::string& what) {
  return make_error(ErrorCode::Degenerate, "points", what + "; a convex hull needs a solid of non-zero volume");
}

std::string point_field(std::size_t i, char axis) { return "points[" + std::to_string(i) + "]." + axis; }

}  // namespace

Result<ConvexHull> ConvexHull::create(std::span<const Vec3> points) {
  // 1. Validation.
  if (points.size() < 4) {
    return make_error(ErrorCode::TooFew, "points",
                      "a convex hull needs at least 4 points, got " + std::to_string(points.size()));
  }
  if (points.size() > static_cast<std::size_t>(std::numeric_limits<int>::max() / 4)) {
    return make_error(ErrorCode::OutOfRange, "points", "too many points for qhull");
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) {
      if (auto e = validate::finite(points[i][a], point_field(i, "xyz"[a]))) return *e;
    }
  }

  // 2. Normalisation to a unit-size box centred on the origin (double).
  D3 lo{points[0].x, points[0].y, points[0].z};
  D3 hi = lo;
  for (const Vec3& p : points) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], double(p[a]));
      hi[a] = std::max(hi[a], double(p[a]));
    }
  }
  const D3 center{0.5 * (lo[0] + hi[0]), 0.5 * (lo[1] + hi[1]), 0.5 * (lo[2] + hi[2])};
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  if (!(extent > 0)) return degenerate("all points coincide");
  std::vector<D3> pts(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (int a = 0; a < 3; ++a) pts[i][a] = (double(points[i][a]) - center[a]) / extent;
  }

  // The input's own resolution: Real's rounding at the points' distance from the origin,
  // relative to the extent (normalised units).
  const double far_ratio =
      std::max({std::abs(lo[0]), std::abs(lo[1]), std::abs(lo[2]), std::abs(hi[0]), std::abs(hi[1]), std::abs(hi[2])}) /
      extent;
  // Flat below the resolution of Real at the hull's size, below a few roundings of the
  // input (a thinner solid would be made of rounding noise), or below 1e4 roundings of
  // qhull's double arithmetic (thinner slabs come back with inverted slivers).
  const double flat = std::max(
      {kFlatRelative, 8.0 * double(kEpsilon) * far_ratio, 1e4 * double(std::numeric_limits<double>::epsilon())});

  // 3. Flatness: farthest pair (from the extremes of the longest box axis), farthest point
  // from their line, farthest point from the plane of the three.
  int axis = 0;
  for (int a = 1; a < 3; ++a) {
    if (hi[a] - lo[a] > hi[axis] - lo[axis]) axis = a;
  }
  std::size_t i0 = 0;
  std::size_t i1 = 0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    if (pts[i][axis] < pts[i0][axis]) i0 = i;
    if (pts[i][axis] > pts[i1][axis]) i1 = i;
  }
  const D3 line = detail::sub(pts[i1], pts[i0]);
  const double line_len = detail::norm(line);  // >= 1 - rounding: the longest axis spans the box
  std::size_t i2 = i0;
  double best = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double d = detail::norm(detail::cross(detail::sub(pts[i], pts[i0]), line)) / line_len;
    if (d > best) {
      best = d;
      i2 = i;
    }
  }
  if (!(best > flat)) return degenerate("all points are collinear (within tolerance)");
  D3 plane_n = detail::cross(line, detail::sub(pts[i2], pts[i0]));
  const double pn = detail::norm(plane_n);
  plane_n = {plane_n[0] / pn, plane_n[1] / pn, plane_n[2] / pn};
  double thickness_lo = 0;
  double thickness_hi = 0;
  for (const D3& p : pts) {
    const double d = detail::dot(detail::sub(p, pts[i0]), plane_n);
    thickness_lo = std::min(thickness_lo, d);
    thickness_hi = std::max(thickness_hi, d);
  }
  if (!(thickness_hi - thickness_lo > flat)) {
    return degenerate("all points are coplanar (within tolerance)");
  }

  // 4-6. qhull, oriented loops, the polyhedron; retried with more merging when qhull or
  // the checks of its output fail.
  auto data = std::make_shared<detail::HullData>();
  std::vector<D3> vd;  // hull vertices in double, original frame
  std::string failure;
  double planarity = 0;
  double merge_deviation = 0;
  // Merging by plane distance r moves the rim of a thin solid sideways by r / (its
  // thickness), so a thin cloud merges less (down to qhull's roundoff).
  const double thickness = std::min(best, thickness_hi - thickness_lo);
  const double base_radius =
      std::min(2.0 * double(kEpsilon) * std::max(1.0, far_ratio), double(kRelativeTolerance) * thickness);
  for (int attempt = 0; attempt < 4; ++attempt) {
    const double radius = base_radius * std::pow(10.0, attempt);
    QhullOutcome hull = run_qhull(pts, radius);
    if (hull.exit_code == qh_ERRsingular) return degenerate("qhull found the points flat (" + hull.message + ")");
    if (hull.exit_code != 0) {
      failure = "exit code " + std::to_string(hull.exit_code) + (hull.message.empty() ? "" : ": " + hull.message);
      continue;
    }
    failure = orient_and_simplify(hull, pts, 2.0 * radius);
    if (!failure.empty()) continue;
    *data = detail::HullData{};
    failure = assemble(points, hull, *data, vd, planarity);
    // Input points may lie above the merged faces by qhull's outer distance plus the
    // faces' own deviation from planarity.
    merge_deviation = hull.max_outside * extent + planarity;
    if (failure.empty()) break;
  }
  if (!failure.empty()) return internal(failure);

  // 7. Box, scale, tolerance; the hull's width over its face normals (each face against
  // its farthest vertex, found by hill-climbing in double) must exceed the flatness
  // tolerance, as the cloud's did; then the mass properties.
  data->local_box = Aabb::empty();
  for (const Vec3& v : data->vertices) data->local_box.grow(v);
  const Vec3 ext = data->local_box.extents();
  data->scale = std::max({ext.x, ext.y, ext.z});
  // Geometric tolerance at the hull's size plus how far the merged faces deviate from the
  // input points. Queries work relative to the box centre (exact differences for hulls
  // far from the origin), so no term grows with the distance from the origin.
  data->tolerance = kRelativeTolerance * data->scale + Real(merge_deviation);
  data->reference = data->local_box.center();
  data->shifted_vertices.reserve(data->vertices.size());
  for (const Vec3& v : data->vertices) data->shifted_vertices.push_back(v - data->reference);
  {
    // Blocks of four vertices as x x x x y y y y z z z z; padding repeats vertex 0, which
    // can never be the first vertex of largest dot product ahead of vertex 0 itself.
    const std::size_t nv = data->shifted_vertices.size();
    const std::size_t blocks = (nv + 3) / 4;
    data->scan_blocks.assign(blocks * 12, Real(0));
    for (std::size_t i = 0; i < blocks * 4; ++i) {
      const Vec3& p = data->shifted_vertices[i < nv ? i : 0];
      Real* block = data->scan_blocks.data() + (i / 4) * 12 + (i % 4);
      block[0] = p.x;
      block[4] = p.y;
      block[8] = p.z;
    }
  }
  const D3 ref{double(data->reference.x), double(data->reference.y), double(data->reference.z)};
  data->shifted_offsets.reserve(data->faces.size());
  for (const HullFace& f : data->faces) {
    // max over the loop of n . (v - reference), in double.
    const D3 n{double(f.normal.x), double(f.normal.y), double(f.normal.z)};
    double off = -std::numeric_limits<double>::max();
    for (std::uint32_t k = 0; k < f.index_count; ++k)
      off = std::max(off, detail::dot(n, detail::sub(vd[data->face_indices[f.first_index + k]], ref)));
    data->shifted_offsets.push_back(Real(off));
  }
  // Faces are visited breadth-first over shared edges, each descent warm-started from
  // its neighbour's answer (nearby normals have nearby deepest vertices): O(F) overall.
  double width = std::numeric_limits<double>::max();
  std::vector<D3> shifted(vd.size());
  for (std::size_t i = 0; i < vd.size(); ++i) shifted[i] = detail::sub(vd[i], ref);
  const std::size_t nf = data->faces.size();
  std::vector<std::uint32_t> face_offsets(nf + 1, 0);
  for (const HullEdge& e : data->edges) {
    ++face_offsets[e.face0 + 1];
    ++face_offsets[e.face1 + 1];
  }
  for (std::size_t f = 0; f < nf; ++f) face_offsets[f + 1] += face_offsets[f];
  std::vector<std::uint32_t> face_adjacent(face_offsets[nf]);
  {
    std::vector<std::uint32_t> fill(face_offsets.begin(), face_offsets.end() - 1);
    for (const HullEdge& e : data->edges) {
      face_adjacent[fill[e.face0]++] = e.face1;
      face_adjacent[fill[e.face1]++] = e.face0;
    }
  }
  constexpr std::uint32_t kUnvisited = std::numeric_limits<std::uint32_t>::max();
  std::vector<std::uint32_t> deepest(nf, kUnvisited);
  std::vector<std::uint32_t> queue{0};
  std::vector<std::uint32_t> start_of(nf, 0);
  deepest[0] = 0;  // marks face 0 as queued; replaced below
  for (std::size_t head = 0; head < queue.size(); ++head) {
    const std::uint32_t fi = queue[head];
    const HullFace& f = data->faces[fi];
    const D3 n{double(f.normal.x), double(f.normal.y), double(f.normal.z)};
    // Deepest vertex below the face: steepest descent of n . v over the face mates,
    // relative to the box centre.
    std::uint32_t cur = start_of[fi];
    double cur_d = detail::dot(n, shifted[cur]);
    for (bool moved = true; moved;) {
      moved = false;
      const std::uint32_t begin = data->climb_offsets[cur];
      const std::uint32_t end = data->climb_offsets[cur + 1];
      std::uint32_t next = cur;
      for (std::uint32_t k = begin; k < end; ++k) {
        const std::uint32_t nb = data->climb_neighbors[k];
        const double d = detail::dot(n, shifted[nb]);
        if (d < cur_d) {
          cur_d = d;
          next = nb;
          moved = true;
        }
      }
      cur = next;
    }
    deepest[fi] = cur;
    width = std::min(width, double(data->shifted_offsets[fi]) - cur_d);
    for (std::uint32_t k = face_offsets[fi]; k < face_offsets[fi + 1]; ++k) {
      const std::uint32_t g = face_adjacent[k];
      if (deepest[g] != kUnvisited) continue;
      deepest[g] = cur;  // queued
      start_of[g] = cur;
      queue.push_back(g);
    }
  }
  if (!(width > flat * extent)) return degenerate("all points are coplanar (within tolerance)");
  if (!detail::compute_hull_mass(*data)) return degenerate("the hull has no volume");

  return ConvexHull(std::move(data));
}

}  // namespace proxima
