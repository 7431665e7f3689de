// Solid-leaf BSP tree of a closed polyhedron (face planes and axis-aligned planes).
//
// Steps (Naylor, "Constructing good partitioning trees", Graphics Interface 1993; Ericson,
// Real-Time Collision Detection, 2005, sections 8.3-8.4):
//  1. Validate the mesh with analyse_mesh: closed, consistently and outward oriented, no
//     degenerate triangle. Compute every face plane once (double precision, relative to the
//     centre of the mesh's box); fragments keep the plane of the face they came from.
//  2. Build iteratively (an explicit task stack, so deep trees do not exhaust the call stack):
//     for a node's polygon list, score up to max_candidates face planes and (nodes of at
//     least 8 polygons) six axis-aligned planes, the median and the middle of the polygon
//     centroids on each axis, by k * splits + (1 - k) * |front - back| - consumed (counted
//     over at most 64 of the node's polygons; consumed: polygons coplanar with a face plane),
//     and take the cheapest. Face planes alone (pure autopartition) give a chain of depth n on
//     a convex solid, since every face plane leaves all other faces behind it; the
//     axis-aligned planes are what balances such trees (Naylor 1993 on splitting planes not
//     taken from faces). An axis plane is kept only when both sides receive polygons, each
//     fewer than the node has. Polygons within the plane thickness of a face plane and facing
//     its way are consumed, coplanar ones facing the other way go to the front, the others to
//     their side, straddling ones are split (Sutherland-Hodgman with thick planes, Ericson
//     8.3.4).
//  3. After a face plane, an empty front list is an outside leaf (in front of an outward face with no other face
//     in the cell), an empty back list an inside leaf.
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

struct PlaneD {
  std::array<double, 3> n{0, 0, 1};
  double d = 0;
  double distance(const std::array<double, 3>& p) const { return n[0] * p[0] + n[1] * p[1] + n[2] * p[2] - d; }
};

using P3 = std::array<double, 3>;

// A convex polygon: a range of the point pool and the face plane it lies in.
struct Polygon {
  std::uint32_t first = 0;
  std::uint32_t count = 0;
  std::uint32_t plane = 0;
};

enum class Side : std::uint8_t { Front, Back, On, Straddle };

struct Builder {
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

struct Task {
  std::vector<std::uint32_t> polys;
  std::uint32_t parent = 0;
  bool front_side = false;
  std::uint32_t depth = 0;
};

}  // namespace

Result<BspPolyhedron> BspPolyhedron::create(const IndexedMesh& mesh, const BspBuildOptions& options) {
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

  BspPolyhedron tree;
  for (const Vec3& v : mesh.vertices) tree.bounds_.grow(v);
  tree.reference_ = tree.bounds_.center();
  const Real extent = max_abs_component(tree.bounds_.extents());
  const Real thickness = options.plane_thickness >= Real(0) ? options.plane_thickness
                                                            : Real(4) * kRelativeTolerance * std::max(extent, Real(0));
  tree.tolerance_ = std::max(Real(2) * thickness, linear_tolerance(extent) * Real(0.5));

  Builder b;
  b.thickness = double(thickness);
  const std::size_t nt = mesh.triangles.size();
  b.points.reserve(nt * 3 + nt);
  b.polygons.reserve(nt * 2);
  b.planes.reserve(nt);
  auto rel = [&](const Vec3& v) {
    return P3{double(v.x) - double(tree.reference_.x), double(v.y) - double(tree.reference_.y),
              double(v.z) - double(tree.reference_.z)};
  };
  for (std::size_t t = 0; t < nt; ++t) {
    const TriangleIndices& tri = mesh.triangles[t];
    const P3 a = rel(mesh.vertices[tri[0]]);
    const P3 bb = rel(mesh.vertices[tri[1]]);
    const P3 c = rel(mesh.vertices[tri[2]]);
    const P3 e1{bb[0] - a[0], bb[1] - a[1], bb[2] - a[2]};
    const P3 e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    P3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) {
      return make_error(ErrorCode::Degenerate, "mesh.triangles[" + std::to_string(t) + "]", "zero-area triangle");
    }
    for (double& x : n) x /= len;
    PlaneD pl;
    pl.n = n;
    pl.d = (n[0] * (a[0] + bb[0] + c[0]) + n[1] * (a[1] + bb[1] + c[1]) + n[2] * (a[2] + bb[2] + c[2])) / 3.0;
    b.planes.push_back(pl);
    b.polygons.push_back(
        Polygon{static_cast<std::uint32_t>(b.points.size()), 3u, static_cast<std::uint32_t>(b.planes.size() - 1)});
    b.points.push_back(a);
    b.points.push_back(bb);
    b.points.push_back(c);
  }

  const double k = double(options.split_weight);
  std::vector<P3> centroids;
  std::vector<double> coordinate;
  std::vector<Task> tasks;
  {
    Task root;
    root.polys.resize(nt);
    for (std::size_t i = 0; i < nt; ++i) root.polys[i] = static_cast<std::uint32_t>(i);
    root.parent = kBspOutside;  // no parent
    tasks.push_back(std::move(root));
  }
  tree.stats_.input_faces = static_cast<std::uint32_t>(nt);
  auto link = [&](const Task& task, std::uint32_t child) {
    if (task.parent == kBspOutside) return;
    BspNode& parent = tree.nodes_[task.parent];
    (task.front_side ? parent.front : parent.back) = child;
  };
  while (!tasks.empty()) {
    Task task = std::move(tasks.back());
    tasks.pop_back();
    if (task.polys.empty()) {
      const std::uint32_t leaf = task.front_side ? kBspOutside : kBspInside;
      ++(leaf == kBspInside ? tree.stats_.inside_leaves : tree.stats_.outside_leaves);
      link(task, leaf);
      continue;
    }
    // Choose the splitting plane: up to max_candidates face planes spread over the list and,
    // for lists of at least kAxisMinPolygons, six axis-aligned planes (the median and the
    // middle of the polygon centroids on each axis), all scored against the same sample.
    const std::size_t np = task.polys.size();
    const std::size_t candidates = std::min<std::size_t>(np, options.max_candidates);
    const std::size_t scored = std::min<std::size_t>(np, kScoredPolygons);
    auto score = [&](const PlaneD& pl, bool face, std::size_t& front, std::size_t& back) {
      front = 0;
      back = 0;
      std::size_t splits = 0;
      std::size_t on = 0;
      for (std::size_t si = 0; si < scored; ++si) {
        switch (b.side_of_polygon(pl, b.polygons[task.polys[si * np / scored]])) {
          case Side::Front: ++front; break;
          case Side::Back: ++back; break;
          case Side::Straddle:
            ++splits;
            ++front;
            ++back;
            break;
          case Side::On: on += b.same_facing(pl, b.polygons[task.polys[si * np / scored]]) ? 1 : 0; break;
        }
      }
      // Coplanar polygons facing its way are consumed by a face plane (never tested again below it): they
      // lower its cost, so that a box's face planes beat any axis plane.
      return k * double(splits) + (1.0 - k) * std::abs(double(front) - double(back)) - (face ? double(on) : 0.0);
    };
    std::uint32_t best_face = b.polygons[task.polys[0]].plane;
    double best_face_cost = std::numeric_limits<double>::infinity();
    for (std::size_t ci = 0; ci < candidates; ++ci) {
      const std::uint32_t plane = b.polygons[task.polys[ci * np / candidates]].plane;
      std::size_t front = 0;
      std::size_t back = 0;
      const double cost = score(b.planes[plane], true, front, back);
      if (cost < best_face_cost) {
        best_face_cost = cost;
        best_face = plane;
      }
    }
    std::optional<PlaneD> best_axis;
    if (options.axis_planes && np >= kAxisMinPolygons) {
      centroids.clear();
      for (std::size_t si = 0; si < scored; ++si)
        centroids.push_back(b.centroid(b.polygons[task.polys[si * np / scored]]));
      double best_axis_cost = best_face_cost;
      for (std::size_t axis = 0; axis < 3; ++axis) {
        coordinate.clear();
        for (const P3& c : centroids) coordinate.push_back(c[axis]);
        const auto mid = coordinate.begin() + std::ptrdiff_t(coordinate.size() / 2);
        std::nth_element(coordinate.begin(), mid, coordinate.end());
        const auto [lo, hi] = std::minmax_element(coordinate.begin(), coordinate.end());
        for (const double offset : {*mid, 0.5 * (*lo + *hi)}) {
          PlaneD pl;
          pl.n = {axis == 0 ? 1.0 : 0.0, axis == 1 ? 1.0 : 0.0, axis == 2 ? 1.0 : 0.0};
          pl.d = offset;
          std::size_t front = 0;
          std::size_t back = 0;
          const double cost = score(pl, false, front, back);
          if (front != 0 && back != 0 && cost < best_axis_cost) {
            best_axis_cost = cost;
            best_axis = pl;
          }
        }
      }
    }
    Task front_task;
    Task back_task;
    auto partition = [&](const PlaneD& pl, bool face) {
      front_task.polys.clear();
      back_task.polys.clear();
      std::uint32_t splits = 0;
      for (const std::uint32_t pi : task.polys) {
        switch (b.side_of_polygon(pl, b.polygons[pi])) {
          case Side::Front: front_task.polys.push_back(pi); break;
          case Side::Back: back_task.polys.push_back(pi); break;
          case Side::Straddle:
            ++splits;
            b.split(pl, pi, front_task.polys, back_task.polys);
            break;
          case Side::On:
            // Coplanar: a polygon facing the plane's way is the plane (consumed) when the
            // plane is a face plane and bounds the back side otherwise; one facing the
            // other way bounds the solid in front, so it goes there.
            if (b.same_facing(pl, b.polygons[pi])) {
              if (!face) back_task.polys.push_back(pi);
            } else {
              front_task.polys.push_back(pi);
            }
            break;
        }
      }
      return splits;
    };
    PlaneD pl = b.planes[best_face];
    bool face = true;
    if (best_axis) {
      // An axis plane has no face to tell inside from outside, so it is kept only when both
      // sides get polygons, each fewer than the node has (the recursion then terminates).
      const std::size_t mark = b.polygons.size();
      const std::size_t point_mark = b.points.size();
      const std::uint32_t splits = partition(*best_axis, false);
      if (!front_task.polys.empty() && !back_task.polys.empty() && front_task.polys.size() < np &&
          back_task.polys.size() < np) {
        pl = *best_axis;
        face = false;
        tree.stats_.split_faces += splits;
      } else {
        b.polygons.resize(mark);  // drop the fragments of the rejected split
        b.points.resize(point_mark);
      }
    }
    if (face) tree.stats_.split_faces += partition(pl, true);
    const std::uint32_t index = static_cast<std::uint32_t>(tree.nodes_.size());
    BspNode node;
    node.normal = Vec3(Real(pl.n[0]), Real(pl.n[1]), Real(pl.n[2]));
    node.offset = Real(pl.d);
    tree.nodes_.push_back(node);
    link(task, index);
    tree.stats_.depth = std::max(tree.stats_.depth, task.depth + 1);
    task.polys.clear();
    task.polys.shrink_to_fit();
    front_task.parent = index;
    front_task.front_side = true;
    front_task.depth = task.depth + 1;
    back_task.parent = index;
    back_task.front_side = false;
    back_task.depth = task.depth + 1;
    tasks.push_back(std::move(back_task));
    tasks.push_back(std::move(front_task));
  }
  tree.stats_.node_count = static_cast<std::uint32_t>(tree.nodes_.size());
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
