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
//     ACM TOMS 1996) in double with pre-merging 'C-r', r = 4 epsilon of Real (relative to
//     the hull's size), so that facets coplanar within the resolution of Real merge into
//     convex polygons (a rotated box keeps six faces in float); 'Qs' searches every point
//     for the initial simplex. Qhull's messages go to a temporary file, read back for the
//     error message. Its memory is freed on every path.
//  5. Each facet's vertex loop comes from qhull's own topology: the ridges of a merged
//     facet are walked end to end (as qhull's qh_facet3vertex does), a simplicial facet's
//     order follows its orientation flag, so every edge is traversed once in each
//     direction by its two faces. The loops are turned to be counter-clockwise seen from
//     outside (one global orientation, checked face by face against qhull's normals).
//  6. Vertices shared by only two faces lie on a straight edge and are removed from both
//     loops (they would stall hill-climbing). Compact the vertex indices, recompute each
//     face plane from its loop (Newell's method, offset = the largest vertex offset),
//     pair each directed edge with its reverse, check the closed 2-manifold (each directed
//     edge once with its reverse in another face, V - E + F = 2), build the vertex
//     adjacency (CSR). If qhull or any check fails, qhull runs again with only its own
//     double-precision merging ('C-0') before Internal is reported.
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
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace proxima {

namespace detail {
// Defined in convex_hull_mass.cpp: volume, centroid and unit-density inertia of the
// closed polyhedron held in `data` (vertices and CCW face loops).
bool compute_hull_mass(ConvexHull::Data& data);
}  // namespace detail

namespace {

using D3 = std::array<double, 3>;

D3 sub(const D3& a, const D3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
double dot(const D3& a, const D3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
D3 cross(const D3& a, const D3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const D3& a) { return std::sqrt(dot(a, a)); }

// Relative width below which a cloud counts as flat: the resolution of Real, so that the
// float and double builds reject what they cannot represent as a solid.
constexpr double kFlatRelative = double(kRelativeTolerance);

// Owns a temporary FILE for qhull's messages and closes it on every path.
class MessageFile {
 public:
  MessageFile() : file_(std::tmpfile()) {
    if (file_ == nullptr) {
#if defined(_WIN32)
      file_ = std::fopen("NUL", "w");
#else
      file_ = std::fopen("/dev/null", "w");
#endif
      readable_ = false;
    }
  }
  ~MessageFile() {
    if (file_ != nullptr) std::fclose(file_);
  }
  MessageFile(const MessageFile&) = delete;
  MessageFile& operator=(const MessageFile&) = delete;

  FILE* get() const { return file_; }

  // The first line of what qhull wrote (its error code and message), or "".
  std::string first_line() const {
    if (file_ == nullptr || !readable_) return {};
    std::fflush(file_);
    std::rewind(file_);
    std::string line;
    int c = 0;
    while ((c = std::fgetc(file_)) != EOF && c != '\n' && line.size() < 300) line.push_back(static_cast<char>(c));
    return line;
  }

 private:
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

QhullOutcome run_qhull(const std::vector<D3>& pts, double merge_radius) {
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
  std::snprintf(command, sizeof command, "qhull Qs C-%.3g", merge_radius);
  out.exit_code =
      qh_new_qhull(qh, 3, static_cast<int>(pts.size()), coords.data(), False, command, nullptr, messages.get());
  if (out.exit_code != 0) {
    out.message = messages.first_line();
    return out;
  }
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
    const int count = qh_setsize(qh, facet->vertices);
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
      if (facet->ridges == nullptr || qh_setsize(qh, facet->ridges) < 3) return fail("a facet without ridges");
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
    const double nl = norm(n);
    if (!(nl > 0.5)) return fail("a facet without a valid plane");
    out.loops.push_back(std::move(loop));
    out.normals.push_back({n[0] / nl, n[1] / nl, n[2] / nl});
  }
  return out;
}

// Turns qhull's loops counter-clockwise seen from outside and removes the vertices that
// only two faces share. With `require_convex`, a loop that turns the wrong way at some
// vertex by more than the resolution of Real (which merging within a radius can leave
// where neighbours are nearly coplanar) makes the loops unusable. Returns an empty
// string, or why the loops are unusable.
std::string orient_and_simplify(QhullOutcome& hull, const std::vector<D3>& pts, bool require_convex) {
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
      const D3 t = cross(sub(pts[loop[k]], o), sub(pts[loop[k + 1]], o));
      a = {a[0] + t[0], a[1] + t[1], a[2] + t[2]};
    }
    along[f] = dot(a, hull.normals[f]);
    area[f] = norm(a);
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
  if (require_convex) {
    const double min_sine = -16.0 * double(kEpsilon);
    for (std::size_t f = 0; f < hull.loops.size(); ++f) {
      const std::vector<int>& loop = hull.loops[f];
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const D3 ab = sub(pts[loop[(k + 1) % loop.size()]], pts[loop[k]]);
        const D3 bc = sub(pts[loop[(k + 2) % loop.size()]], pts[loop[(k + 1) % loop.size()]]);
        if (dot(cross(ab, bc), hull.normals[f]) < min_sine * norm(ab) * norm(bc)) return "a merged facet is not convex";
      }
    }
  }
  return {};
}

// Builds vertices, faces (planes by Newell's method), edges and adjacency from the
// oriented loops, checking the closed 2-manifold. Returns an empty string, or why not.
std::string assemble(std::span<const Vec3> points, const QhullOutcome& hull, ConvexHull::Data& data,
                     std::vector<D3>& vd) {
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

  data.faces.reserve(hull.loops.size());
  for (const std::vector<int>& ids : hull.loops) {
    HullFace face;
    face.first_index = static_cast<std::uint32_t>(data.face_indices.size());
    face.index_count = static_cast<std::uint32_t>(ids.size());
    D3 c{0, 0, 0};
    for (int id : ids) {
      const D3& v = vd[remap[id]];
      for (int a = 0; a < 3; ++a) c[a] += v[a];
    }
    for (int a = 0; a < 3; ++a) c[a] /= double(ids.size());
    D3 n{0, 0, 0};  // Newell's method, relative to the loop centroid
    for (std::size_t k = 0; k < ids.size(); ++k) {
      const D3 p = sub(vd[remap[ids[k]]], c);
      const D3 q = sub(vd[remap[ids[(k + 1) % ids.size()]]], c);
      const D3 pq = cross(p, q);
      for (int a = 0; a < 3; ++a) n[a] += pq[a];
    }
    const double nl = norm(n);
    if (!(nl > 0)) return std::string("a merged facet has zero area");
    n = {n[0] / nl, n[1] / nl, n[2] / nl};
    double offset = -std::numeric_limits<double>::max();
    for (int id : ids) {
      offset = std::max(offset, dot(n, vd[remap[id]]));
      data.face_indices.push_back(remap[id]);
    }
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
  const D3 line = sub(pts[i1], pts[i0]);
  const double line_len = norm(line);  // >= 1 - rounding: the longest axis spans the box
  std::size_t i2 = i0;
  double best = 0;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double d = norm(cross(sub(pts[i], pts[i0]), line)) / line_len;
    if (d > best) {
      best = d;
      i2 = i;
    }
  }
  if (!(best > kFlatRelative)) return degenerate("all points are collinear (within tolerance)");
  D3 plane_n = cross(line, sub(pts[i2], pts[i0]));
  const double pn = norm(plane_n);
  plane_n = {plane_n[0] / pn, plane_n[1] / pn, plane_n[2] / pn};
  double thickness_lo = 0;
  double thickness_hi = 0;
  for (const D3& p : pts) {
    const double d = dot(sub(p, pts[i0]), plane_n);
    thickness_lo = std::min(thickness_lo, d);
    thickness_hi = std::max(thickness_hi, d);
  }
  if (!(thickness_hi - thickness_lo > kFlatRelative)) {
    return degenerate("all points are coplanar (within tolerance)");
  }

  // 4-6. qhull, oriented loops, the polyhedron. The first run merges facets that are
  // coplanar within the rounding of Real at the hull's size (a rotated box keeps six
  // faces in float); if that run or the checks of its output fail, qhull runs again with
  // only its own double-precision merging ('C-0').
  auto data = std::make_shared<Data>();
  std::vector<D3> vd;  // hull vertices in double, original frame
  std::string failure;
  for (const double radius : {4.0 * double(kEpsilon), 0.0}) {
    QhullOutcome hull = run_qhull(pts, radius);
    if (hull.exit_code == qh_ERRsingular) return degenerate("qhull found the points flat (" + hull.message + ")");
    if (hull.exit_code != 0) {
      failure = "exit code " + std::to_string(hull.exit_code) + (hull.message.empty() ? "" : ": " + hull.message);
      continue;
    }
    failure = orient_and_simplify(hull, pts, radius > 0);
    if (!failure.empty()) continue;
    *data = Data{};
    failure = assemble(points, hull, *data, vd);
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
  const Vec3 far = glm::max(glm::abs(data->local_box.min), glm::abs(data->local_box.max));
  // Geometric tolerance at the hull's size plus the rounding of a plane test n . p - d at
  // the hull's distance from the origin (a few ulps of the largest coordinate).
  data->tolerance = kRelativeTolerance * data->scale + Real(16) * kEpsilon * std::max({far.x, far.y, far.z});
  double width = std::numeric_limits<double>::max();
  std::uint32_t start = 0;
  for (const HullFace& f : data->faces) {
    const D3 n{double(f.normal.x), double(f.normal.y), double(f.normal.z)};
    // Deepest vertex below the face: steepest descent of n . v over the adjacency.
    std::uint32_t cur = start;
    double cur_d = dot(n, vd[cur]);
    for (bool moved = true; moved;) {
      moved = false;
      for (std::uint32_t k = data->neighbor_offsets[cur]; k < data->neighbor_offsets[cur + 1]; ++k) {
        const std::uint32_t nb = data->neighbors[k];
        const double d = dot(n, vd[nb]);
        if (d < cur_d) {
          cur_d = d;
          cur = nb;
          moved = true;
        }
      }
    }
    start = cur;
    width = std::min(width, double(f.offset) - cur_d);
  }
  if (!(width > kFlatRelative * extent)) return degenerate("all points are coplanar (within tolerance)");
  if (!detail::compute_hull_mass(*data)) return degenerate("the hull has no volume");

  return ConvexHull(std::move(data));
}

}  // namespace proxima
