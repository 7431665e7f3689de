// proxima_bench_python_loop: the C++ side of bench/python/batch_overhead.py. It reads one
// batch of queries from a binary file written by that script (so both sides see the same
// rows), runs the plain C++ loop over them (one library call per row, the answer stored in a
// preallocated vector, one thread) several times, prints the times as one JSON line and
// writes the answers to a file so that the script can check they equal the Python ones.
// Two loops are timed: "prepared" calls the library on inputs already converted to its types
// (Transform, Ray, Vec3); "rows" reads the same float64 rows inside the loop and converts
// each one (Transform::create, as a caller holding arrays of numbers must), then calls.
//
//   proxima_bench_python_loop INPUT ANSWERS
//
// INPUT (little-endian, no padding):
//   "PXLOOP01"  u32 query (1 distance, 2 raycast, 3 closest point)  u32 repeats
//   shape:      u32 kind, then 1 sphere: f64 radius | 2 box: f64[3] half extents |
//               3 hull: u64 n, f64[n][3] points | 4 mesh: u64 nv, u64 nt, f64[nv][3], u32[nt][3]
//               (built with repair on, as proxima.TriangleMesh does by default) |
//               5 capsule: f64 radius, f64 half length
//   distance:   shape a, shape b, u64 n, f64[n][7] poses a, f64[n][7] poses b
//   raycast:    shape, f64[7] pose, u64 n, f64[n][6] rays (origin, direction), f64[n] max_t
//   closest:    shape, f64[7] pose, u64 n, f64[n][3] points
// Poses are px py pz qx qy qz qw (proxima's Python order); every number is rounded to Real
// and every pose goes through Transform::create, as the Python bindings do.
// ANSWERS: f64 per row: distance: signed_distance | raycast: hit (0 or 1), t (max_t on a
// miss) | closest: point x y z, signed_distance.
// Printed: {"real": "float"|"double", "prepared": {"wall_s": [...], "cpu_s": [...]}, "rows": {...}}
// with the wall and thread CPU seconds of each repeat of each loop.
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/shapes/placed.hpp>
#include <proxima/shapes/shape.hpp>
#include <proxima/shapes/shape_queries.hpp>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <functional>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using proxima::Real;
using proxima::Shape;
using proxima::Transform;
using proxima::Vec3;

/// Sequential reader of the input file's bytes.
class Input {
 public:
  explicit Input(const std::string& path) {
    std::ifstream file(path, std::ios::binary);
    if (!file) throw std::runtime_error("cannot open " + path);
    bytes_.assign(std::istreambuf_iterator<char>(file), {});
  }
  template <class T>
  T get() {
    T value;
    need(sizeof(T));
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::vector<double> doubles(std::size_t count) { return array<double>(count); }
  template <class T>
  std::vector<T> array(std::size_t count) {
    need(count * sizeof(T));
    std::vector<T> values(count);
    std::memcpy(values.data(), bytes_.data() + at_, count * sizeof(T));
    at_ += count * sizeof(T);
    return values;
  }
  void expect_magic() {
    need(8);
    if (std::memcmp(bytes_.data(), "PXLOOP01", 8) != 0) throw std::runtime_error("not a PXLOOP01 file");
    at_ = 8;
  }

 private:
  void need(std::size_t n) const {
    if (at_ + n > bytes_.size()) throw std::runtime_error("input file truncated");
  }
  std::vector<char> bytes_;
  std::size_t at_ = 0;
};

template <class S>
S take(proxima::Result<S>&& result) {
  if (!result.ok()) throw std::runtime_error(result.error().what());
  return std::move(*result);
}

Vec3 vec3_at(const std::vector<double>& d, std::size_t i) { return {Real(d[i]), Real(d[i + 1]), Real(d[i + 2])}; }

Shape read_shape(Input& in) {
  switch (in.get<std::uint32_t>()) {
    case 1: return take(proxima::Sphere::create(Real(in.get<double>())));
    case 2: {
      const std::vector<double> h = in.doubles(3);
      return take(proxima::Box::create(vec3_at(h, 0)));
    }
    case 3: {
      const std::vector<double> d = in.doubles(3 * in.get<std::uint64_t>());
      std::vector<Vec3> points;
      for (std::size_t i = 0; i < d.size(); i += 3) points.push_back(vec3_at(d, i));
      return take(proxima::ConvexHull::create(points));
    }
    case 4: {
      const auto vertex_count = in.get<std::uint64_t>();
      const auto triangle_count = in.get<std::uint64_t>();
      const std::vector<double> v = in.doubles(3 * vertex_count);
      const std::vector<std::uint32_t> t = in.array<std::uint32_t>(3 * triangle_count);
      proxima::IndexedMesh mesh;
      for (std::size_t i = 0; i < v.size(); i += 3) mesh.vertices.push_back(vec3_at(v, i));
      for (std::size_t i = 0; i < t.size(); i += 3) mesh.triangles.push_back({t[i], t[i + 1], t[i + 2]});
      return take(proxima::TriangleMesh::create(std::move(mesh)));
    }
    case 5: {
      const double radius = in.get<double>();
      return take(proxima::Capsule::create(Real(radius), Real(in.get<double>())));
    }
    default: throw std::runtime_error("unknown shape kind");
  }
}

/// A pose row px py pz qx qy qz qw as the bindings convert it: rounded to Real, validated.
Transform pose_of_row(const double* d) {
  const proxima::Quat q{Real(d[6]), Real(d[3]), Real(d[4]), Real(d[5])};
  return take(Transform::create({Real(d[0]), Real(d[1]), Real(d[2])}, q));
}

std::vector<Transform> to_poses(const std::vector<double>& rows) {
  std::vector<Transform> poses;
  for (std::size_t i = 0; i < rows.size(); i += 7) poses.push_back(pose_of_row(&rows[i]));
  return poses;
}

/// The ray of a row ox oy oz dx dy dz and its length limit, rounded to Real.
proxima::Ray ray_of_row(const double* d) {
  return {{Real(d[0]), Real(d[1]), Real(d[2])}, {Real(d[3]), Real(d[4]), Real(d[5])}};
}
Real limit_of(double max_t) { return max_t > double(proxima::kRealMax) ? proxima::kRealMax : Real(max_t); }

/// Thread CPU time in seconds.
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Timing {
  std::vector<double> wall, cpu;  ///< seconds per repeat
};

/// The timings of both loops.
struct Timings {
  Timing prepared;  ///< library types made before the loop
  Timing rows;      ///< float64 rows converted inside the loop
};

Timing time_loop(std::uint32_t repeats, const std::function<void()>& loop) {
  Timing timing;
  for (std::uint32_t r = 0; r < repeats; ++r) {
    const double cpu0 = thread_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    loop();
    timing.wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count());
    timing.cpu.push_back(thread_seconds() - cpu0);
  }
  return timing;
}

/// Runs both loops of the query over the input's rows, alternating; fills `answers`.
Timings time_both(std::uint32_t repeats, const std::function<void()>& prepared, const std::function<void()>& rows) {
  Timings t;
  for (std::uint32_t r = 0; r < repeats; ++r) {
    const Timing a = time_loop(1, prepared), b = time_loop(1, rows);
    t.prepared.wall.push_back(a.wall[0]), t.prepared.cpu.push_back(a.cpu[0]);
    t.rows.wall.push_back(b.wall[0]), t.rows.cpu.push_back(b.cpu[0]);
  }
  return t;
}

Timings run_distance(Input& in, std::uint32_t repeats, std::vector<double>& answers) {
  const Shape a = read_shape(in), b = read_shape(in);
  const auto n = in.get<std::uint64_t>();
  const std::vector<double> rows_a = in.doubles(7 * n), rows_b = in.doubles(7 * n);
  const std::vector<Transform> poses_a = to_poses(rows_a), poses_b = to_poses(rows_b);
  std::vector<proxima::DistanceResult> results(n);
  const Timings timings = time_both(
      repeats,
      [&] {
        for (std::size_t i = 0; i < n; ++i) results[i] = proxima::distance(a, poses_a[i], b, poses_b[i]);
      },
      [&] {
        for (std::size_t i = 0; i < n; ++i)
          results[i] = proxima::distance(a, pose_of_row(&rows_a[7 * i]), b, pose_of_row(&rows_b[7 * i]));
      });
  for (const proxima::DistanceResult& r : results) answers.push_back(double(r.signed_distance));
  return timings;
}

Timings run_raycast(Input& in, std::uint32_t repeats, std::vector<double>& answers) {
  const Shape shape = read_shape(in);
  const Transform pose = pose_of_row(in.doubles(7).data());
  const auto n = in.get<std::uint64_t>();
  const std::vector<double> d = in.doubles(6 * n), limits = in.doubles(n);
  std::vector<proxima::Ray> rays(n);
  std::vector<Real> max_t(n);
  for (std::size_t i = 0; i < n; ++i) rays[i] = ray_of_row(&d[6 * i]), max_t[i] = limit_of(limits[i]);
  std::vector<std::optional<proxima::RayHit>> hits(n);
  const Timings timings = time_both(
      repeats,
      [&] {
        for (std::size_t i = 0; i < n; ++i) hits[i] = proxima::raycast(shape, pose, rays[i], max_t[i]);
      },
      [&] {
        for (std::size_t i = 0; i < n; ++i)
          hits[i] = proxima::raycast(shape, pose, ray_of_row(&d[6 * i]), limit_of(limits[i]));
      });
  for (std::size_t i = 0; i < n; ++i) {
    answers.push_back(hits[i] ? 1.0 : 0.0);
    answers.push_back(hits[i] ? double(hits[i]->t) : double(max_t[i]));
  }
  return timings;
}

Timings run_closest_point(Input& in, std::uint32_t repeats, std::vector<double>& answers) {
  const Shape shape = read_shape(in);
  const Transform pose = pose_of_row(in.doubles(7).data());
  const auto n = in.get<std::uint64_t>();
  const std::vector<double> d = in.doubles(3 * n);
  std::vector<Vec3> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = vec3_at(d, 3 * i);
  const auto* mesh = std::get_if<proxima::TriangleMesh>(&shape);
  if (mesh == nullptr) throw std::runtime_error("closest point: the shape must be a mesh");
  std::vector<proxima::SurfacePoint> results(n);
  const Timings timings = time_both(
      repeats,
      [&] {
        for (std::size_t i = 0; i < n; ++i) results[i] = proxima::closest_point(*mesh, pose, points[i]);
      },
      [&] {
        for (std::size_t i = 0; i < n; ++i) results[i] = proxima::closest_point(*mesh, pose, vec3_at(d, 3 * i));
      });
  for (const proxima::SurfacePoint& r : results) {
    for (int k = 0; k < 3; ++k) answers.push_back(double(r.point[k]));
    answers.push_back(double(r.signed_distance));
  }
  return timings;
}

/// `, "<name>": {"wall_s": [...], "cpu_s": [...]}` (seconds per repeat).
void print_timing(const char* name, const Timing& t) {
  std::printf(", \"%s\": {\"wall_s\": [", name);
  for (std::size_t i = 0; i < t.wall.size(); ++i) std::printf("%s%.9g", i ? ", " : "", t.wall[i]);
  std::printf("], \"cpu_s\": [");
  for (std::size_t i = 0; i < t.cpu.size(); ++i) std::printf("%s%.9g", i ? ", " : "", t.cpu[i]);
  std::printf("]}");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s INPUT ANSWERS\n", argv[0]);
    return 2;
  }
  try {
    Input in(argv[1]);
    in.expect_magic();
    const auto query = in.get<std::uint32_t>();
    const auto repeats = std::max<std::uint32_t>(1, in.get<std::uint32_t>());
    std::vector<double> answers;
    Timings timings;
    if (query == 1)
      timings = run_distance(in, repeats, answers);
    else if (query == 2)
      timings = run_raycast(in, repeats, answers);
    else if (query == 3)
      timings = run_closest_point(in, repeats, answers);
    else
      throw std::runtime_error("unknown query");
    std::ofstream out(argv[2], std::ios::binary);
    out.write(reinterpret_cast<const char*>(answers.data()), std::streamsize(answers.size() * sizeof(double)));
    if (!out) throw std::runtime_error(std::string("cannot write ") + argv[2]);
    std::printf("{\"real\": \"%s\"", sizeof(Real) == 4 ? "float" : "double");
    print_timing("prepared", timings.prepared);
    print_timing("rows", timings.rows);
    std::printf("}\n");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "proxima_bench_python_loop: %s\n", e.what());
    return 1;
  }
  return 0;
}
