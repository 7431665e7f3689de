// Solid-leaf BSP tree of a closed polyhedron (face planes and axis-aligned planes).
//
// Steps (Naylor, "Constructing good partitioning trees", Graphics Interface 1993; Ericson,
// Real-Time Collision Detection, 2005, sections 8.3-8.4):
//  1. Validate the mesh with analyse_mesh (check_build_input): closed, consistently and
//     outward oriented, no degenerate triangle. Compute every face plane once (add_faces:
//     double precision, relative to the centre of the mesh's box); fragments keep the plane
//     of the face they came from.
//  2. Build iteratively (build: an explicit task stack, so deep trees do not exhaust the call
//     stack). For a node's polygon list (split_node): score up to max_candidates face planes
//     (choose_face_plane) and (nodes of at least 8 polygons) six axis-aligned planes, the
//     median and the middle of the polygon centroids on each axis (choose_axis_plane), by
//     k * splits + (1 - k) * |front - back| - consumed (score: counted over at most 64 of the
//     node's polygons; consumed: polygons coplanar with a face plane), and take the cheapest.
//     Face planes alone (pure autopartition) give a chain of depth n on a convex solid, since
//     every face plane leaves all other faces behind it; the axis-aligned planes are what
//     balances such trees (Naylor 1993 on splitting planes not taken from faces). An axis
//     plane is kept only when both sides receive polygons, each fewer than the node has
//     (try_axis_split). Polygons within the plane thickness of a face plane and facing its
//     way are consumed, coplanar ones facing the other way go to the front, the others to
//     their side, straddling ones are split (partition; PolygonPool::split: Sutherland-Hodgman
//     with thick planes, Ericson 8.3.4).
//  3. After a face plane, an empty front list is an outside leaf (in front of an outward face
//     with no other face in the cell), an empty back list an inside leaf (make_leaf).
//  4. Point queries descend by the sign of the plane distance; within the tolerance both
//     sides are visited and differing answers mean OnBoundary (Ericson 8.4.1). Segment
//     queries visit the leaves in increasing t, splitting the parameter interval at each
//     plane crossing (Ericson 8.4.2), and merge adjacent inside pieces.

#include <proxima/core/tolerance.hpp>
#include <proxima/shapes/bsp_polyhedron.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace proxima {

namespace {

// A stack with 64 entries in place and a heap overflow (queries on deep trees).
template <class T>
class WorkStack {
 public:
  void push(const T& v) {
    if (size_ < local_.size()) {
      local_[size_] = v;
    } else {
      overflow_.push_back(v);
    }
    ++size_;
  }
  T pop() {
    --size_;
    if (size_ >= local_.size()) {
      T v = overflow_.back();
      overflow_.pop_back();
      return v;
    }
    return local_[size_];
  }
  bool empty() const { return size_ == 0; }

 private:
  std::array<T, 64> local_{};
  std::vector<T> overflow_;
  std::size_t size_ = 0;
};

// A plane n . x = d in double precision (relative to the tree's reference point).
struct PlaneD {
  std::array<double, 3> n{0, 0, 1};
  double d = 0;
  double distance(const std::array<double, 3>& p) const { return n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - d; }
};

// A point in double precision (relative to the tree's reference point).
using P3 = std::array<double, 3>;

// A convex polygon: a range of the point pool and the face plane it lies in.
struct Polygon {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  std::uint32_t plane = 0;
};

// Where a point or polygon lies against a thick plane.
enum class Side : std::uint8_t { Front, Back, On, Straddle };

// Every polygon of the build (the faces, then the fragments of splits) over one point
// pool, with the face planes and the plane tests at the build's thickness.
struct PolygonPool {
  std::vector<P3> points;
  std::vector<Polygon> polygons;
  std::vector<PlaneD> planes;
  double thickness = 0;

  Side side_of_point(const PlaneD& pl, const P3& p) const {
    const double s = pl.distance(p);
    if (s > thickness) return Side::Front;
    if (s < -thickness) return Side::Back;
    return Side::On;
  }
  Side side_of_polygon(const PlaneD& pl, const Polygon& poly) const {
    bool front = false;
    bool back = false;
    for (std::uint32_t i = 0; i < poly.count; ++i) {
      const Side s = side_of_point(pl, points[poly.first + i]);
      front = front || s == Side::Front;
      back = back || s == Side::Back;
    }
    if (front && back) return Side::Straddle;
    if (front) return Side::Front;
    if (back) return Side::Back;
    return Side::On;
  }

  // True when the polygon's face normal points the way of the plane's normal.
  bool same_facing(const PlaneD& pl, const Polygon& poly) const {
    const PlaneD& own = planes[poly.plane];
    return own.n[0] * pl.n[0] + own.n[1] * pl.n[1] + own.n[2] * pl.n[2] > 0;
  }
  P3 centroid(const Polygon& poly) const {
    P3 c{0, 0, 0};
    for (std::uint32_t i = 0; i < poly.count; ++i) {
      for (std::size_t a = 0; a < 3; ++a) c[a] += points[poly.first + i][a];
    }
    for (double& x : c) x /= double(poly.count);
    return c;
  }

  // Splits `poly` by `pl` (thick plane), appending the pieces with >= 3 vertices.
  void split(const PlaneD& pl, std::uint32_t poly_index, std::vector<std::uint32_t>& front_list,
             std::vector<std::uint32_t>& back_list) {
    const Polygon poly = polygons[poly_index];
    std::vector<P3> f;
    std::vector<P3> b;
    P3 a = points[poly.first + poly.count - 1];
    Side sa = side_of_point(pl, a);
    for (std::uint32_t i = 0; i < poly.count; ++i) {
      const P3 c = points[poly.first + i];
      const Side sc = side_of_point(pl, c);
      auto intersect = [&]() {
        const double da = pl.distance(a);
        const double dc = pl.distance(c);
        const double t = da / (da - dc);
        return P3{a[0] + t * (c[0] - a[0]), a[1] + t * (c[1] - a[1]), a[2] + t * (c[2] - a[2])};
      };
      if (sc == Side::Front) {
        if (sa == Side::Back) {
          const P3 x = intersect();
          f.push_back(x);
          b.push_back(x);
        }
        f.push_back(c);
      } else if (sc == Side::Back) {
        if (sa == Side::Front) {
          const P3 x = intersect();
          f.push_back(x);
          b.push_back(x);
        } else if (sa == Side::On) {
          b.push_back(a);
        }
        b.push_back(c);
      } else {
        f.push_back(c);
        if (sa == Side::Back) b.push_back(c);
      }
      a = c;
      sa = sc;
    }
    auto emit = [&](const std::vector<P3>& loop, std::vector<std::uint32_t>& list) {
      if (loop.size() < 3) return;
      Polygon piece{static_cast<std::uint32_t>(points.size()), static_cast<std::uint32_t>(loop.size()), poly.plane};
      points.insert(points.end(), loop.begin(), loop.end());
      list.push_back(static_cast<std::uint32_t>(polygons.size()));
      polygons.push_back(piece);
    };
    emit(f, front_list);
    emit(b, back_list);
  }
};

// Candidate planes are scored against at most this many polygons of the node (evenly spread),
// so that choosing a plane costs O(max_candidates) per node rather than O(n max_candidates).
constexpr std::size_t kScoredPolygons = 64;
// Axis-aligned candidate planes are scored only for nodes with at least this many polygons
// (below it a chain of face planes is as short as anything an axis split leaves).
constexpr std::size_t kAxisMinPolygons = 8;

// A node still to build: its polygons and where its index goes in the parent.
struct Task {
  std::vector<std::uint32_t> polys;
  std::uint32_t parent = 0;  // kBspOutside for the root
  bool front_side = false;   // the parent's front (or back) child
  std::uint32_t depth = 0;   // inner nodes above it
};

// Step 1: the first problem of the mesh or the options, nothing when the build can go on.
std::optional<Error> check_build_input(const IndexedMesh& mesh, const BspBuildOptions& options) {
  Result<MeshReport> analysed = analyse_mesh(mesh);
  if (!analysed) return analysed.error();
  const MeshReport& report = *analysed;
  if (!report.closed) {
    return make_error(ErrorCode::InvalidArgument, "mesh",
                      "not closed: " + std::to_string(report.boundary_edges) + " boundary and " +
                          std::to_string(report.non_manifold_edges) +
                          " non-manifold edges (repair_mesh welds duplicated vertices)");
  }
  if (!report.oriented) {
    return make_error(ErrorCode::InvalidArgument, "mesh",
                      "not consistently oriented: " + std::to_string(report.inconsistent_edges) +
                          " edges traversed the same way by both triangles");
  }
  if (report.degenerate_triangles != 0) {
    return make_error(ErrorCode::InvalidArgument, "mesh",
                      std::to_string(report.degenerate_triangles) + " degenerate (zero-area) triangles");
  }
  if (!(report.volume > Real(0))) {
    return make_error(ErrorCode::InvalidArgument, "mesh",
                      "encloses a non-positive volume: the triangles face inward (reverse their winding)");
  }
  if (!(options.split_weight >= Real(0) && options.split_weight <= Real(1))) {
    return make_error(ErrorCode::OutOfRange, "options.split_weight", "must lie in [0, 1]");
  }
  if (options.max_candidates == 0) {
    return make_error(ErrorCode::OutOfRange, "options.max_candidates", "must be at least 1");
  }
  if (!std::isfinite(options.plane_thickness)) {
    return make_error(ErrorCode::NotFinite, "options.plane_thickness", "must be finite");
  }
  return std::nullopt;
}

// The tree under construction: the polygon pool, the nodes made so far and the
// stack of nodes still to build.
class TreeBuilder {
 public:
  TreeBuilder(const BspBuildOptions& options, double thickness) : options_(options) { pool_.thickness = thickness; }

  // Step 1 (end): every triangle as a polygon with its face plane, in double precision
  // relative to `reference`; an error for a zero-area triangle.
  std::optional<Error> add_faces(const IndexedMesh& mesh, const Vec3& reference);

  // Steps 2-3: builds the nodes, from a root task holding every face.
  void build();

  // The nodes built, root first.
  std::vector<BspNode>& nodes() { return nodes_; }
  // Statistics of the build.
  const BspStats& stats() const { return stats_; }

 private:
  // Where a candidate plane sends the scored sample of a node's polygons.
  struct Score {
    double cost = 0;
    std::size_t front = 0;
    std::size_t back = 0;
  };

  void make_leaf(const Task& task);
  void split_node(Task& task);
  Score score(const PlaneD& pl, bool face, const Task& task) const;
  std::pair<std::uint32_t, double> choose_face_plane(const Task& task) const;
  std::optional<PlaneD> choose_axis_plane(const Task& task, double best_face_cost);
  std::uint32_t partition(const PlaneD& pl, bool face, const Task& task, Task& front, Task& back);
  bool try_axis_split(const PlaneD& pl, const Task& task, Task& front, Task& back);
  void link(const Task& task, std::uint32_t child);

  BspBuildOptions options_;
  PolygonPool pool_;
  std::vector<BspNode> nodes_;
  BspStats stats_;
  std::vector<Task> tasks_;
  std::vector<P3> centroids_;       // scratch of choose_axis_plane
  std::vector<double> coordinate_;  // ...
};

std::optional<Error> TreeBuilder::add_faces(const IndexedMesh& mesh, const Vec3& reference) {
  const std::size_t nt = mesh.triangles.size();
  pool_.points.reserve(nt * 3 + nt);
  pool_.polygons.reserve(nt * 2);
  pool_.planes.reserve(nt);
  auto rel = [&](const Vec3& v) {
    return P3{double(v.x) - double(reference.x), double(v.y) - double(reference.y), double(v.z) - double(reference.z)};
  };
  for (std::size_t t = 0; t < nt; ++t) {
    const TriangleIndices& tri = mesh.triangles[t];
    const P3 a = rel(mesh.vertices[tri[0]]);
    const P3 b = rel(mesh.vertices[tri[1]]);
    const P3 c = rel(mesh.vertices[tri[2]]);
    const P3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const P3 e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    P3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) {
      return make_error(ErrorCode::Degenerate, "mesh.triangles[" + std::to_string(t) + "]", "zero-area triangle");
    }
    for (double& x : n) x /= len;
    PlaneD pl;
    pl.n = n;
    pl.d = (n[0] * (a[0] + b[0] + c[0]) + n[1] * (a[1] + b[1] + c[1]) + n[2] * (a[2] + b[2] + c[2])) / 3.0;
    pool_.planes.push_back(pl);
    pool_.polygons.push_back(Polygon{static_cast<std::uint32_t>(pool_.points.size()), 3u,
                                     static_cast<std::uint32_t>(pool_.planes.size() - 1)});
    pool_.points.push_back(a);
    pool_.points.push_back(b);
    pool_.points.push_back(c);
  }
  stats_.input_faces = static_cast<std::uint32_t>(nt);
  return std::nullopt;
}

void TreeBuilder::build() {
  Task root;
  root.polys.resize(pool_.polygons.size());
  for (std::size_t i = 0; i < root.polys.size(); ++i) root.polys[i] = static_cast<std::uint32_t>(i);
  root.parent = kBspOutside;  // no parent
  tasks_.push_back(std::move(root));
  while (!tasks_.empty()) {
    Task task = std::move(tasks_.back());
    tasks_.pop_back();
    if (task.polys.empty()) {
      make_leaf(task);
    } else {
      split_node(task);
    }
  }
  stats_.node_count = static_cast<std::uint32_t>(nodes_.size());
}

// Writes `child` into the parent's front or back link (nothing for the root).
void TreeBuilder::link(const Task& task, std::uint32_t child) {
  if (task.parent == kBspOutside) return;
  BspNode& parent = nodes_[task.parent];
  (task.front_side ? parent.front : parent.back) = child;
}

// Step 3: a node without polygons is a leaf: outside in front of its parent's plane (an
// outward face with no other face in the cell), inside behind it.
void TreeBuilder::make_leaf(const Task& task) {
  const std::uint32_t leaf = task.front_side ? kBspOutside : kBspInside;
  ++(leaf == kBspInside ? stats_.inside_leaves : stats_.outside_leaves);
  link(task, leaf);
}

// Cost of splitting the node by `pl` over its scored sample: k * splits + (1 - k) *
// |front - back|, less the polygons a face plane consumes (coplanar and facing its way:
// never tested again below it), so that a box's face planes beat any axis plane.
TreeBuilder::Score TreeBuilder::score(const PlaneD& pl, bool face, const Task& task) const {
  const std::size_t np = task.polys.size();
  const std::size_t scored = std::min<std::size_t>(np, kScoredPolygons);
  Score s;
  std::size_t splits = 0;
  std::size_t on = 0;
  for (std::size_t si = 0; si < scored; ++si) {
    const Polygon& poly = pool_.polygons[task.polys[si * np / scored]];
    switch (pool_.side_of_polygon(pl, poly)) {
      case Side::Front: ++s.front; break;
      case Side::Back: ++s.back; break;
      case Side::Straddle:
        ++splits;
        ++s.front;
        ++s.back;
        break;
      case Side::On: on += pool_.same_facing(pl, poly) ? 1 : 0; break;
    }
  }
  const double k = double(options_.split_weight);
  s.cost = k * double(splits) + (1.0 - k) * std::abs(double(s.front) - double(s.back)) - (face ? double(on) : 0.0);
  return s;
}

// Step 2a: the cheapest of up to max_candidates face planes spread over the node's polygons
// (plane index and cost).
std::pair<std::uint32_t, double> TreeBuilder::choose_face_plane(const Task& task) const {
  const std::size_t np = task.polys.size();
  const std::size_t candidates = std::min<std::size_t>(np, options_.max_candidates);
  std::uint32_t best_face = pool_.polygons[task.polys[0]].plane;
  double best_face_cost = std::numeric_limits<double>::infinity();
  for (std::size_t ci = 0; ci < candidates; ++ci) {
    const std::uint32_t plane = pool_.polygons[task.polys[ci * np / candidates]].plane;
    const double cost = score(pool_.planes[plane], true, task).cost;
    if (cost < best_face_cost) {
      best_face_cost = cost;
      best_face = plane;
    }
  }
  return {best_face, best_face_cost};
}

// Step 2b: for nodes of at least kAxisMinPolygons (with options.axis_planes), the six
// axis-aligned planes through the median and the middle of the sampled polygon centroids
// on each axis; the cheapest that leaves sampled polygons on both sides and beats
// `best_face_cost`, if any.
std::optional<PlaneD> TreeBuilder::choose_axis_plane(const Task& task, double best_face_cost) {
  const std::size_t np = task.polys.size();
  if (!options_.axis_planes || np < kAxisMinPolygons) return std::nullopt;
  const std::size_t scored = std::min<std::size_t>(np, kScoredPolygons);
  centroids_.clear();
  for (std::size_t si = 0; si < scored; ++si)
    centroids_.push_back(pool_.centroid(pool_.polygons[task.polys[si * np / scored]]));
  std::optional<PlaneD> best_axis;
  double best_axis_cost = best_face_cost;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    coordinate_.clear();
    for (const P3& c : centroids_) coordinate_.push_back(c[axis]);
    const auto mid = coordinate_.begin() + std::ptrdiff_t(coordinate_.size() / 2);
    std::nth_element(coordinate_.begin(), mid, coordinate_.end());
    const auto [lo, hi] = std::minmax_element(coordinate_.begin(), coordinate_.end());
    for (const double offset : {*mid, 0.5 * (*lo + *hi)}) {
      PlaneD pl;
      pl.n = {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
      pl.d = offset;
      const Score s = score(pl, false, task);
      if (s.front != 0 && s.back != 0 && s.cost < best_axis_cost) {
        best_axis_cost = s.cost;
        best_axis = pl;
      }
    }
  }
  return best_axis;
}

// Step 2c: sends every polygon of the node to `front` or `back` (straddling ones split);
// returns the number split. Coplanar: a polygon facing the plane's way is the plane
// (consumed) when the plane is a face plane and bounds the back side otherwise; one facing
// the other way bounds the solid in front, so it goes there.
std::uint32_t TreeBuilder::partition(const PlaneD& pl, bool face, const Task& task, Task& front, Task& back) {
  front.polys.clear();
  back.polys.clear();
  std::uint32_t splits = 0;
  for (const std::uint32_t pi : task.polys) {
    switch (pool_.side_of_polygon(pl, pool_.polygons[pi])) {
      case Side::Front: front.polys.push_back(pi); break;
      case Side::Back: back.polys.push_back(pi); break;
      case Side::Straddle:
        ++splits;
        pool_.split(pl, pi, front.polys, back.polys);
        break;
      case Side::On:
        if (pool_.same_facing(pl, pool_.polygons[pi])) {
          if (!face) back.polys.push_back(pi);
        } else {
          front.polys.push_back(pi);
        }
        break;
    }
  }
  return splits;
}

// Step 2d: an axis plane has no face to tell inside from outside, so it is kept only when
// both sides get polygons, each fewer than the node has (the recursion then terminates).
// Else the fragments of the rejected split are dropped and false returned.
bool TreeBuilder::try_axis_split(const PlaneD& pl, const Task& task, Task& front, Task& back) {
  const std::size_t np = task.polys.size();
  const std::size_t mark = pool_.polygons.size();
  const std::size_t point_mark = pool_.points.size();
  const std::uint32_t splits = partition(pl, false, task, front, back);
  if (!front.polys.empty() && !back.polys.empty() && front.polys.size() < np && back.polys.size() < np) {
    stats_.split_faces += splits;
    return true;
  }
  pool_.polygons.resize(mark);
  pool_.points.resize(point_mark);
  return false;
}

// Step 2: an inner node: the chosen plane (an accepted axis plane, else the best face
// plane), its two children pushed on the stack (front on top).
void TreeBuilder::split_node(Task& task) {
  const auto [best_face, best_face_cost] = choose_face_plane(task);
  const std::optional<PlaneD> best_axis = choose_axis_plane(task, best_face_cost);
  Task front_task;
  Task back_task;
  PlaneD pl = pool_.planes[best_face];
  bool face = true;
  if (best_axis && try_axis_split(*best_axis, task, front_task, back_task)) {
    pl = *best_axis;
    face = false;
  }
  if (face) stats_.split_faces += partition(pl, true, task, front_task, back_task);
  const std::uint32_t index = static_cast<std::uint32_t>(nodes_.size());
  BspNode node;
  node.normal = Vec3(Real(pl.n[0]), Real(pl.n[1]), Real(pl.n[2]));
  node.offset = Real(pl.d);
  nodes_.push_back(node);
  link(task, index);
  stats_.depth = std::max(stats_.depth, task.depth + 1);
  task.polys.clear();
  task.polys.shrink_to_fit();
  front_task.parent = index;
  front_task.front_side = true;
  front_task.depth = task.depth + 1;
  back_task.parent = index;
  back_task.front_side = false;
  back_task.depth = task.depth + 1;
  tasks_.push_back(std::move(back_task));
  tasks_.push_back(std::move(front_task));
}

}  // namespace

Result<BspPolyhedron> BspPolyhedron::create(const IndexedMesh& mesh, const BspBuildOptions& options) {
  if (std::optional<Error> bad = check_build_input(mesh, options)) return std::move(*bad);
  BspPolyhedron tree;
  for (const Vec3& v : mesh.vertices) tree.bounds_.grow(v);
  tree.reference_ = tree.bounds_.center();
  const Real extent = max_abs_component(tree.bounds_.extents());
  const Real thickness = options.plane_thickness >= Real(0) ? options.plane_thickness
                                                            : Real(4) * kRelativeTolerance * std::max(extent, Real(0));
  tree.tolerance_ = std::max(Real(2) * thickness, linear_tolerance(extent) * Real(0.5));
  TreeBuilder builder(options, double(thickness));
  if (std::optional<Error> bad = builder.add_faces(mesh, tree.reference_)) return std::move(*bad);
  builder.build();
  tree.nodes_ = std::move(builder.nodes());
  tree.stats_ = builder.stats();
  return tree;
}

PointClass BspPolyhedron::classify(const Vec3& point, Real tolerance) const {
  if (!is_finite(point) || nodes_.empty()) return PointClass::Outside;
  const Real tol = tolerance >= Real(0) ? tolerance : tolerance_;
  const Vec3 p = point - reference_;
  bool inside = false;
  bool outside = false;
  WorkStack<std::uint32_t> stack;
  stack.push(0);
  while (!stack.empty()) {
    std::uint32_t id = stack.pop();
    while (id < kBspInside) {
      const BspNode& node = nodes_[id];
      const Real s = glm::dot(node.normal, p) - node.offset;
      if (s > tol) {
        id = node.front;
      } else if (s < -tol) {
        id = node.back;
      } else {
        stack.push(node.back);
        id = node.front;
      }
    }
    (id == kBspInside ? inside : outside) = true;
    if (inside && outside) return PointClass::OnBoundary;
  }
  return inside ? PointClass::Inside : PointClass::Outside;
}

Real BspPolyhedron::clamp_max_t(const Ray& ray, Real max_t) const {
  // Beyond the parameter where the ray is farther from the box centre than the box's half
  // diagonal, every point is outside: infinite max_t is clamped there.
  if (std::isfinite(max_t)) return max_t;
  const Real dir2 = length_squared(ray.direction);
  if (!(dir2 > Real(0))) return Real(0);
  const Real reach = glm::length(ray.origin - bounds_.center()) + glm::length(bounds_.half_extents());
  return reach / std::sqrt(dir2) * Real(1.001) + Real(1);
}

template <class Visit>
void BspPolyhedron::walk_segment(const Vec3& origin, const Vec3& direction, Real t0, Real t1, Visit&& visit) const {
  struct Item {
    std::uint32_t id;
    Real ta;
    Real tb;
  };
  const Vec3 o = origin - reference_;
  WorkStack<Item> stack;
  stack.push({0, t0, t1});
  while (!stack.empty()) {
    const Item item = stack.pop();
    if (item.id >= kBspInside) {
      if (!visit(item.id == kBspInside, item.ta, item.tb)) return;
      continue;
    }
    const BspNode& node = nodes_[item.id];
    const Real a = glm::dot(node.normal, o) - node.offset;
    const Real bdot = glm::dot(node.normal, direction);
    const Real sa = a + bdot * item.ta;
    const Real sb = a + bdot * item.tb;
    if (sa >= Real(0) && sb >= Real(0)) {
      stack.push({node.front, item.ta, item.tb});
    } else if (sa <= Real(0) && sb <= Real(0)) {
      stack.push({node.back, item.ta, item.tb});
    } else {
      const Real tm = std::clamp(-a / bdot, item.ta, item.tb);
      const std::uint32_t near = sa > Real(0) ? node.front : node.back;
      const std::uint32_t far = sa > Real(0) ? node.back : node.front;
      stack.push({far, tm, item.tb});
      stack.push({near, item.ta, tm});
    }
  }
}

void BspPolyhedron::classify_segment(const Ray& ray, Real max_t, std::vector<BspInterval>& intervals) const {
  if (nodes_.empty() || !is_finite(ray.origin) || !is_finite(ray.direction) || std::isnan(max_t) || max_t < Real(0)) {
    return;
  }
  const Real t1 = clamp_max_t(ray, max_t);
  const std::size_t first = intervals.size();
  walk_segment(ray.origin, ray.direction, Real(0), t1, [&](bool inside, Real ta, Real tb) {
    if (!inside || !(tb > ta)) return true;
    if (intervals.size() > first && intervals.back().t_exit >= ta) {
      intervals.back().t_exit = std::max(intervals.back().t_exit, tb);
    } else {
      intervals.push_back({ta, tb});
    }
    return true;
  });
}

std::optional<BspInterval> BspPolyhedron::first_interval(const Ray& ray, Real max_t) const {
  if (nodes_.empty() || !is_finite(ray.origin) || !is_finite(ray.direction) || std::isnan(max_t) || max_t < Real(0)) {
    return std::nullopt;
  }
  const Real t1 = clamp_max_t(ray, max_t);
  std::optional<BspInterval> result;
  walk_segment(ray.origin, ray.direction, Real(0), t1, [&](bool inside, Real ta, Real tb) {
    if (!(tb > ta)) return true;
    if (inside) {
      if (result && result->t_exit >= ta) {
        result->t_exit = std::max(result->t_exit, tb);
      } else if (!result) {
        result = BspInterval{ta, tb};
      }
      return true;
    }
    return !result;  // an outside piece after the first inside one ends it
  });
  return result;
}

}  // namespace proxima
