// Batched queries on numpy arrays: intersect_batch, distance_batch (pairs of poses),
// raycast_batch, closest_point_batch and contains_batch (one placed shape, many rays or
// points). Steps of each call: read and validate every row first (an error names the first
// bad row and writes nothing), then release the GIL and run the library's query per row,
// spread over a thread pool, writing each answer into its row of the output array.
#include <proxima/core/validate.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <unistd.h>

#include "batch_arrays.hpp"
#include "module_parts.hpp"
#include "shape_object.hpp"

namespace proxima::python {

RowReader::RowReader(py::handle value, py::ssize_t cols, const char* field, bool allow_single) {
  if (value.is_none() && allow_single) {  // identity pose
    array_ = py::array_t<double>(7);
    double* d = static_cast<py::array_t<double>&>(array_).mutable_data();
    for (int i = 0; i < 7; ++i) d[i] = i == 6 ? 1.0 : 0.0;
  } else if (allow_single && py::isinstance<Transform>(value)) {
    const Transform t = value.cast<Transform>();
    py::array_t<double> row(7);
    double* d = row.mutable_data();
    for (int i = 0; i < 3; ++i) d[i] = double(t.position[i]);
    d[3] = double(t.rotation.x), d[4] = double(t.rotation.y), d[5] = double(t.rotation.z), d[6] = double(t.rotation.w);
    array_ = row;
  } else if (py::isinstance<py::array>(value) &&
             (py::reinterpret_borrow<py::array>(value).dtype().equal(py::dtype::of<double>()) ||
              py::reinterpret_borrow<py::array>(value).dtype().equal(py::dtype::of<float>()))) {
    array_ = py::reinterpret_borrow<py::array>(value);
  } else {
    try {
      array_ = py::array_t<double, py::array::forcecast>::ensure(value);
    } catch (const py::error_already_set&) {
    }
    if (!array_) raise_argument_error(field, "expected an array of numbers");
  }
  f64_ = array_.dtype().equal(py::dtype::of<double>());
  data_ = static_cast<const char*>(array_.data());
  if (array_.ndim() == 1 && allow_single && array_.shape(0) == cols) {
    single_ = true;
    rows_ = 1;
    col_stride_ = array_.strides(0);
    return;
  }
  if (array_.ndim() != 2 || array_.shape(1) != cols) {
    raise_argument_error(field, "expected an (N, " + std::to_string(cols) + ") array" +
                                    (allow_single ? " or one row of " + std::to_string(cols) + " numbers" : ""));
  }
  rows_ = array_.shape(0);
  row_stride_ = array_.strides(0);
  col_stride_ = array_.strides(1);
}

py::ssize_t common_rows(const RowReader& a, const char* field_a, const RowReader& b, const char* field_b) {
  if (a.single() && b.single()) return 1;
  if (a.single()) return b.rows();
  if (b.single() || a.rows() == b.rows()) return a.rows();
  raise_argument_error(field_b,
                       "has " + std::to_string(b.rows()) + " rows but " + field_a + " has " + std::to_string(a.rows()));
}

std::vector<Transform> read_poses(const RowReader& rows, py::ssize_t n, const char* field) {
  std::vector<Transform> poses(rows.single() ? 1 : static_cast<std::size_t>(n));
  const py::ssize_t bad =
      rows.find_rejected(0, static_cast<py::ssize_t>(poses.size()), [&](py::ssize_t i, const auto& number) {
        const std::optional<Transform> t =
            Transform::from_values({number(0), number(1), number(2)}, Quat{number(6), number(3), number(4), number(5)});
        if (t) poses[static_cast<std::size_t>(i)] = *t;
        return t.has_value();
      });
  if (bad < 0) return poses;
  const Vec3 p{Real(rows.at(bad, 0)), Real(rows.at(bad, 1)), Real(rows.at(bad, 2))};
  const Quat q{Real(rows.at(bad, 6)), Real(rows.at(bad, 3)), Real(rows.at(bad, 4)), Real(rows.at(bad, 5))};
  Error e = Transform::create(p, q).error();
  e.field = std::string(field) + (rows.single() ? "" : "[" + std::to_string(bad) + "]") + "." + e.field;
  raise_error(e);
}

Executor& thread_pool(std::size_t threads) {
  static std::mutex mutex;
  static std::map<std::size_t, std::unique_ptr<ThreadPool>>* pools = nullptr;
  static pid_t owner = 0;
  const std::lock_guard<std::mutex> lock(mutex);
  if (pools == nullptr || owner != getpid()) {
    pools = new std::map<std::size_t, std::unique_ptr<ThreadPool>>();  // a forked parent's pools are abandoned
    owner = getpid();
  }
  std::unique_ptr<ThreadPool>& p = (*pools)[threads];
  if (!p) p = std::make_unique<ThreadPool>(threads);
  return *p;
}

void parallel_for(std::size_t n, long threads, RangeTask task) {
  const std::size_t count = resolve_threads(threads);
  py::gil_scoped_release release;
  if (count <= 1 || n < 256) {
    if (n > 0) task(0, n);
    return;
  }
  thread_pool(count).run(n, task);
}

std::vector<double> read_limits(py::handle max_t, py::ssize_t n) {
  if (max_t.is_none()) return {std::numeric_limits<double>::infinity()};
  py::array_t<double, py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::forcecast>::ensure(max_t);
  } catch (const py::error_already_set&) {
  }
  if (a && a.ndim() == 0) return {*a.data()};
  if (!a || a.ndim() != 1 || a.shape(0) != n) raise_argument_error("max_t", "expected a number or one per ray");
  return {a.data(), a.data() + n};
}

std::vector<Vec3> read_points(py::handle points) {
  const RowReader r(points, 3, "points", false);
  std::vector<Vec3> list(static_cast<std::size_t>(r.rows()));
  const py::ssize_t bad = r.find_rejected(0, r.rows(), [&](py::ssize_t i, const auto& number) {
    Vec3& p = list[static_cast<std::size_t>(i)];
    p = {number(0), number(1), number(2)};
    return validate::is_acceptable(p);
  });
  if (bad >= 0) raise_error(make_error(ErrorCode::NotFinite, "points[" + std::to_string(bad) + "]", "must be finite"));
  return list;
}

namespace {

void put(double (&out)[3], const Vec3& v) { out[0] = double(v.x), out[1] = double(v.y), out[2] = double(v.z); }

/// The shapes and validated poses of intersect_batch and distance_batch.
struct PosePairs {
  const PyShape& a;
  const PyShape& b;
  std::vector<Transform> poses_a, poses_b;  // one pose: broadcast to every row
  py::ssize_t n = 0;
};

PosePairs read_pairs(py::handle a, py::handle poses_a, py::handle b, py::handle poses_b) {
  const PyShape& sa = to_shape(a, "a");
  const PyShape& sb = to_shape(b, "b");
  const RowReader ra(poses_a, 7, "poses_a", true), rb(poses_b, 7, "poses_b", true);
  const py::ssize_t n = common_rows(ra, "poses_a", rb, "poses_b");
  return {sa, sb, read_poses(ra, n, "poses_a"), read_poses(rb, n, "poses_b"), n};
}

/// Calls query(i, pose_a, pose_b) for every row of the pairs on the thread pool.
template <class Query>
void for_each_pose_pair(const PosePairs& p, long threads, Query&& query) {
  const std::size_t step_a = p.poses_a.size() == 1 ? 0 : 1, step_b = p.poses_b.size() == 1 ? 0 : 1;
  parallel_for(static_cast<std::size_t>(p.n), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) query(i, p.poses_a[i * step_a], p.poses_b[i * step_b]);
  });
}

py::array intersect_batch(py::handle a, py::handle poses_a, py::handle b, py::handle poses_b, py::handle out,
                          long threads) {
  const PosePairs p = read_pairs(a, poses_a, b, poses_b);
  py::array_t<bool> result = output_array<bool>(out, p.n);
  bool* rows = result.mutable_data();
  for_each_pose_pair(p, threads, [&](std::size_t i, const Transform& ta, const Transform& tb) {
    rows[i] = intersect(p.a.ref(), ta, p.b.ref(), tb);
  });
  return result;
}

py::array distance_batch(py::handle a, py::handle poses_a, py::handle b, py::handle poses_b, py::handle out,
                         long threads) {
  const PosePairs p = read_pairs(a, poses_a, b, poses_b);
  py::array_t<DistanceRow> result = output_array<DistanceRow>(out, p.n);
  DistanceRow* rows = result.mutable_data();
  for_each_pose_pair(p, threads, [&](std::size_t i, const Transform& ta, const Transform& tb) {
    const DistanceResult r = distance(p.a.ref(), ta, p.b.ref(), tb);
    DistanceRow& row = rows[i];
    row.signed_distance = double(r.signed_distance);
    put(row.point_a, r.point_a);
    put(row.point_b, r.point_b);
    put(row.normal, r.normal);
    row.status = static_cast<std::uint8_t>(r.status);
  });
  return result;
}

std::int64_t part_number(const SubShapeId& sub) {
  if (sub.triangle != kNoIndex) return sub.triangle;
  if (sub.child != kNoIndex) return sub.child;
  return -1;
}

/// The error of ray `i`, which raycast_batch's checks rejected.
[[noreturn]] void raise_ray_error(const Ray& ray, py::ssize_t i, bool one_limit) {
  const std::string row = "[" + std::to_string(i) + "]";
  if (!validate::is_acceptable(ray.origin) || !validate::is_acceptable(ray.direction))
    raise_error(make_error(ErrorCode::NotFinite, "rays" + row, "must be finite"));
  if (ray.direction == Vec3(Real(0))) raise_argument_error("rays" + row + ".direction", "must not be zero");
  raise_argument_error(one_limit ? "max_t" : "max_t" + row, "must be >= 0");
}

py::array raycast_batch(py::handle shape, py::handle pose, py::handle rays, py::handle max_t, py::handle out,
                        long threads) {
  const PyShape& s = to_shape(shape, "shape");
  const Transform t = to_transform(pose, "pose");
  const RowReader r(rays, 6, "rays", false);
  const py::ssize_t n = r.rows();
  const std::vector<double> limits = read_limits(max_t, n);
  std::vector<Ray> list(static_cast<std::size_t>(n));
  std::vector<Real> extent(static_cast<std::size_t>(n));
  const auto limit = [&](py::ssize_t i) {
    return limits.size() == 1 ? limits[0] : limits[static_cast<std::size_t>(i)];
  };
  const py::ssize_t bad = r.find_rejected(0, n, [&](py::ssize_t i, const auto& number) {
    Ray& ray = list[static_cast<std::size_t>(i)];
    ray.origin = {number(0), number(1), number(2)};
    ray.direction = {number(3), number(4), number(5)};
    const double m = limit(i);
    extent[static_cast<std::size_t>(i)] = m > double(kRealMax) ? kRealMax : Real(m);
    return validate::is_acceptable(ray.origin) && validate::is_acceptable(ray.direction) &&
           ray.direction != Vec3(Real(0)) && m >= 0;
  });
  if (bad >= 0) raise_ray_error(list[static_cast<std::size_t>(bad)], bad, limits.size() == 1);
  py::array_t<RayHitRow> result = output_array<RayHitRow>(out, n);
  RayHitRow* rows = result.mutable_data();
  parallel_for(static_cast<std::size_t>(n), threads, [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) {
      const std::optional<RayHit> hit = raycast(s.ref(), t, list[i], extent[i]);
      RayHitRow& row = rows[i];
      row.hit = hit.has_value();
      row.t = hit ? double(hit->t) : double(extent[i]);
      put(row.point, hit ? hit->point : Vec3(Real(0)));
      put(row.normal, hit ? hit->normal : Vec3(Real(0)));
      row.part = hit ? part_number(hit->sub) : -1;
    }
  });
  return result;
}

template <class F>
void with_point_shape(const PyShape& s, const char* what, F&& f) {
  visit_shape(s.ref(), [&](const auto& shape) {
    using S = std::decay_t<decltype(shape)>;
    if constexpr (PointQueryable<S>) {
      f(shape);
    } else {
      raise_argument_error("shape", std::string("a ") + to_string(kShapeTypeOf<S>) + " has no " + what);
    }
  });
}

py::array closest_point_batch(py::handle shape, py::handle pose, py::handle points, py::handle out, long threads) {
  const PyShape& s = to_shape(shape, "shape");
  const Transform t = to_transform(pose, "pose");
  const std::vector<Vec3> list = read_points(points);
  const auto n = static_cast<py::ssize_t>(list.size());
  py::array_t<SurfacePointRow> result = output_array<SurfacePointRow>(out, n);
  SurfacePointRow* rows = result.mutable_data();
  with_point_shape(s, "closest point", [&](const auto& geometry) {
    parallel_for(list.size(), threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const SurfacePoint sp = closest_point(geometry, t, list[i]);
        put(rows[i].point, sp.point);
        put(rows[i].normal, sp.normal);
        rows[i].signed_distance = double(sp.signed_distance);
      }
    });
  });
  return result;
}

py::array contains_batch(py::handle shape, py::handle pose, py::handle points, py::handle out, long threads) {
  const PyShape& s = to_shape(shape, "shape");
  const Transform t = to_transform(pose, "pose");
  const std::vector<Vec3> list = read_points(points);
  py::array_t<bool> result = output_array<bool>(out, static_cast<py::ssize_t>(list.size()));
  bool* rows = result.mutable_data();
  with_point_shape(s, "point containment", [&](const auto& geometry) {
    parallel_for(list.size(), threads, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) rows[i] = contains(geometry, t, list[i]);
    });
  });
  return result;
}

}  // namespace

void bind_batch(py::module_& m) {
  PYBIND11_NUMPY_DTYPE(DistanceRow, signed_distance, point_a, point_b, normal, status);
  PYBIND11_NUMPY_DTYPE(RayHitRow, hit, t, point, normal, part);
  PYBIND11_NUMPY_DTYPE(SurfacePointRow, point, normal, signed_distance);
  m.attr("DISTANCE_DTYPE") = py::dtype::of<DistanceRow>();
  m.attr("RAY_HIT_DTYPE") = py::dtype::of<RayHitRow>();
  m.attr("SURFACE_POINT_DTYPE") = py::dtype::of<SurfacePointRow>();
  const char* threads_doc = " threads: 0 uses every hardware thread, 1 the calling thread; the GIL is released.";
  m.def("intersect_batch", &intersect_batch, py::arg("a"), py::arg("poses_a"), py::arg("b"), py::arg("poses_b"),
        py::kw_only(), py::arg("out") = py::none(), py::arg("threads") = 0,
        (std::string("intersect for each row of poses_a and poses_b ((N, 7) arrays: px, py, pz, qx, qy, qz, qw; "
                     "either may be one pose). Returns (or fills `out`, written in place) a bool array (N,).") +
         threads_doc)
            .c_str());
  m.def("distance_batch", &distance_batch, py::arg("a"), py::arg("poses_a"), py::arg("b"), py::arg("poses_b"),
        py::kw_only(), py::arg("out") = py::none(), py::arg("threads") = 0,
        (std::string("distance for each row of poses_a and poses_b. Returns (or fills `out`) an array of "
                     "DISTANCE_DTYPE: signed_distance, point_a, point_b, normal, status (a PairStatus value).") +
         threads_doc)
            .c_str());
  m.def("raycast_batch", &raycast_batch, py::arg("shape"), py::arg("pose"), py::arg("rays"),
        py::arg("max_t") = py::none(), py::kw_only(), py::arg("out") = py::none(), py::arg("threads") = 0,
        (std::string("Cast each ray (an (N, 6) array: origin, direction; world frame) at the placed shape; max_t "
                     "is one number or one per ray (default: unbounded). Returns (or fills `out`) an array of "
                     "RAY_HIT_DTYPE: hit, t, point, normal, part (-1: none).") +
         threads_doc)
            .c_str());
  m.def("closest_point_batch", &closest_point_batch, py::arg("shape"), py::arg("pose"), py::arg("points"),
        py::kw_only(), py::arg("out") = py::none(), py::arg("threads") = 0,
        (std::string("Nearest surface point of the placed shape to each point of an (N, 3) array. Returns (or "
                     "fills `out`) an array of SURFACE_POINT_DTYPE: point, normal, signed_distance (negative "
                     "inside).") +
         threads_doc)
            .c_str());
  m.def(
      "contains_batch", &contains_batch, py::arg("shape"), py::arg("pose"), py::arg("points"), py::kw_only(),
      py::arg("out") = py::none(), py::arg("threads") = 0,
      (std::string("Whether the placed shape contains each point of an (N, 3) array: a bool array (N,).") + threads_doc)
          .c_str());
}

}  // namespace proxima::python
