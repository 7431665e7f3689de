// Readers of the benchmark workload files (shared/bench/FORMATS.md, formats W1..W7).
//   1. read the whole file; the first line is the header `<kind> <version> key=value ...`:
//      check the kind and version 1, collect the keys (unknown ones are ignored);
//   2. for each following line that is not blank and not a `#` comment, split it into
//      space-separated tokens and parse the numbers in double with std::from_chars
//      (the nearest double to the decimal text, as the format requires);
//   3. normalise every pose quaternion (divide by its length) and check the record
//      count against the header;
//   4. any problem becomes an Error whose field is "<path>:<line>".
// The W1 pair finder is a sort-and-sweep on x (Baraff's sweep-and-prune with a forward
// scan, Ericson, Real-Time Collision Detection, 7.5.1): sort boxes by min x, and for
// each box scan the following ones while their min x <= its max x, testing y and z.
#include "support/workloads.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <sstream>

#include "support/sha256.hpp"
#include "text_parse.hpp"

namespace proxima::bench {
using namespace detail;

namespace {

CcdShape parse_ccd_shape(const Source& src, std::string_view text) {
  const auto t = split(text);
  if (t.empty()) src.fail_here("empty shape field");
  CcdShape s;
  if (t[0] == "sphere") {
    expect_tokens(src, t, 2, "sphere r");
    s.kind = CcdShapeKind::Sphere;
    s.radius = parse_positive(src, t[1], "sphere radius");
  } else if (t[0] == "box") {
    expect_tokens(src, t, 4, "box hx hy hz");
    s.kind = CcdShapeKind::Box;
    s.half_extents = parse_positive_vec3(src, t, 1, "box half extents");
  } else if (t[0] == "hull") {
    expect_tokens(src, t, 2, "hull id");
    s.kind = CcdShapeKind::Hull;
    const std::uint64_t id = parse_unsigned(src, t[1], "hull id");
    if (id > 0xffffffffu) src.fail_here("hull id too large");
    s.hull = static_cast<std::uint32_t>(id);
  } else {
    src.fail_here("unknown shape " + quoted(t[0]) + " (expected sphere, box or hull)");
  }
  return s;
}

}  // namespace

// ---------------------------------------------------------------------------------
// Conversions
// ---------------------------------------------------------------------------------

Vec3 to_vec3(const Vec3d& v) { return Vec3(static_cast<Real>(v.x), static_cast<Real>(v.y), static_cast<Real>(v.z)); }

Quat to_quat(const Quatd& q) {
  return glm::normalize(
      Quat(static_cast<Real>(q.w), static_cast<Real>(q.x), static_cast<Real>(q.y), static_cast<Real>(q.z)));
}

Transform to_transform(const Pose& pose) { return Transform{to_vec3(pose.position), to_quat(pose.rotation)}; }

Vec3d apply(const Pose& pose, const Vec3d& l) {
  const double w = pose.rotation.w, x = pose.rotation.x, y = pose.rotation.y, z = pose.rotation.z;
  return {(1 - 2 * (y * y + z * z)) * l.x + 2 * (x * y - w * z) * l.y + 2 * (x * z + w * y) * l.z + pose.position.x,
          2 * (x * y + w * z) * l.x + (1 - 2 * (x * x + z * z)) * l.y + 2 * (y * z - w * x) * l.z + pose.position.y,
          2 * (x * z - w * y) * l.x + 2 * (y * z + w * x) * l.y + (1 - 2 * (x * x + y * y)) * l.z + pose.position.z};
}

// ---------------------------------------------------------------------------------
// W1 motion and checksum
// ---------------------------------------------------------------------------------

void advance_frame(std::vector<BroadphaseBox>& boxes, double dt, double lo, double hi) {
  for (BroadphaseBox& b : boxes) {
    for (int a = 0; a < 3; ++a) {
      double x = b.center[a] + b.velocity[a] * dt;
      if (x < lo) {
        x = 2 * lo - x;
        b.velocity[a] = -b.velocity[a];
      } else if (x > hi) {
        x = 2 * hi - x;
        b.velocity[a] = -b.velocity[a];
      }
      b.center[a] = x;
    }
  }
}

std::uint64_t mix64(std::uint64_t x) {
  std::uint64_t z = x + 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

std::string PairChecksum::hash_hex() const {
  static constexpr char kHex[] = "0123456789abcdef";
  std::string out(16, '0');
  for (int i = 0; i < 16; ++i) out[15 - i] = kHex[(hash >> (4 * i)) & 15];
  return out;
}

std::string PairChecksum::to_string() const { return "pairs=" + std::to_string(pairs) + " hash=" + hash_hex(); }

std::vector<std::pair<std::uint32_t, std::uint32_t>> overlapping_pairs(const std::vector<BroadphaseBox>& boxes) {
  struct Entry {
    double min_x, max_x, min_y, max_y, min_z, max_z;
    std::uint32_t index;
  };
  std::vector<Entry> entries(boxes.size());
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const BroadphaseBox& b = boxes[i];
    entries[i] = {b.center.x - b.half_extents.x, b.center.x + b.half_extents.x, b.center.y - b.half_extents.y,
                  b.center.y + b.half_extents.y, b.center.z - b.half_extents.z, b.center.z + b.half_extents.z,
                  static_cast<std::uint32_t>(i)};
  }
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.min_x < b.min_x || (a.min_x == b.min_x && a.index < b.index);
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> pairs;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const Entry& a = entries[k];
    // Every later entry has min_x >= a.min_x, so x overlap <=> its min_x <= a.max_x.
    for (std::size_t m = k + 1; m < entries.size() && entries[m].min_x <= a.max_x; ++m) {
      const Entry& b = entries[m];
      if (a.min_y <= b.max_y && b.min_y <= a.max_y && a.min_z <= b.max_z && b.min_z <= a.max_z) {
        pairs.emplace_back(std::min(a.index, b.index), std::max(a.index, b.index));
      }
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

PairChecksum reference_checksum(const BroadphaseWorkload& workload) {
  std::vector<BroadphaseBox> boxes = workload.boxes;
  const std::uint64_t n = boxes.size();
  PairChecksum sum;
  for (int frame = 1; frame <= workload.frames; ++frame) {
    advance_frame(boxes, workload.dt, workload.lo, workload.hi);
    for (const auto& [i, j] : overlapping_pairs(boxes)) sum.add(i, j, n);
  }
  return sum;
}

KnownChecksum published_checksum(std::string_view name) {
  if (name == "broadphase_uniform_10k") return {true, {720303u, 0xc1e09e3295fd3406ull}};
  if (name == "broadphase_uniform_100k") return {true, {7369738u, 0xfca122572cefbcddull}};
  if (name == "broadphase_clustered_100k") return {true, {16152504u, 0x68b8cf6bf40bc812ull}};
  return {};
}

// ---------------------------------------------------------------------------------
// Readers
// ---------------------------------------------------------------------------------

Result<Header> read_header(const std::string& path) {
  return guarded<Header>([&]() -> Header {
    Source src(path);
    Header h = parse_header(src);
    if (h.version != 1) {
      src.fail_here("unsupported version " + std::to_string(h.version) + " of " + quoted(h.kind) +
                    " (this reader knows version 1)");
    }
    return h;
  });
}

Result<BroadphaseWorkload> read_broadphase(const std::string& path) {
  return guarded<BroadphaseWorkload>([&]() -> BroadphaseWorkload {
    Source src(path);
    const Header h = expect_header(src, "broadphase");
    BroadphaseWorkload w;
    const std::uint64_t n = require_count(src, h, "n");
    if (n > 0xffffffffu) fail(path, 1, "n= is too large");
    const std::uint64_t frames = require_count(src, h, "frames");
    if (frames > 100000000u) fail(path, 1, "frames= is too large");
    w.frames = static_cast<int>(frames);
    w.dt = require_number(src, h, "dt");
    w.lo = require_number(src, h, "lo");
    w.hi = require_number(src, h, "hi");
    if (!(w.lo < w.hi)) fail(path, 1, "lo= must be smaller than hi=");
    const auto name = h.keys.find("name");
    w.name = name != h.keys.end() ? name->second : file_stem(path);
    w.boxes.reserve(reservable(src, n));
    read_records(src, n, [&](const std::vector<std::string_view>& t) {
      expect_tokens(src, t, 9, "cx cy cz hx hy hz vx vy vz");
      BroadphaseBox b;
      b.center = parse_vec3(src, t, 0);
      b.half_extents = parse_vec3(src, t, 3);
      if (!(b.half_extents.x >= 0 && b.half_extents.y >= 0 && b.half_extents.z >= 0)) {
        src.fail_here("half extents must be >= 0");
      }
      b.velocity = parse_vec3(src, t, 6);
      w.boxes.push_back(b);
    });
    return w;
  });
}

Result<ConvexShapes> read_convex_shapes(const std::string& path) {
  return guarded<ConvexShapes>([&]() -> ConvexShapes {
    Source src(path);
    const Header h = expect_header(src, "convex_shapes");
    const std::uint64_t count = require_count(src, h, "count");
    const std::uint64_t points = require_count(src, h, "points");
    if (points == 0 || points > 100000000u) fail(path, 1, "points= must be in [1, 1e8]");
    ConvexShapes out;
    out.points_per_shape = static_cast<int>(points);
    out.shapes.reserve(reservable(src, count));
    std::string_view line;
    for (std::uint64_t k = 0; k < count; ++k) {
      if (!src.next_record(line)) {
        fail(path, src.line(), "file ends after " + std::to_string(k) + " of the " + std::to_string(count) + " shapes");
      }
      const auto t = split(line);
      if (t.empty() || t[0] != "shape") src.fail_here("expected 'shape <id> <P> <ax> <ay> <az>'");
      expect_tokens(src, t, 6, "shape id P ax ay az");
      if (parse_unsigned(src, t[1], "shape id") != k) {
        src.fail_here("shape id " + std::string(t[1]) + " out of order, expected " + std::to_string(k));
      }
      if (parse_unsigned(src, t[2], "point count") != points) {
        src.fail_here("shape has " + std::string(t[2]) + " points, the header says points=" + std::to_string(points));
      }
      ConvexShape shape;
      shape.semi_axes = parse_vec3(src, t, 3);
      shape.points.reserve(reservable(src, points));
      for (std::uint64_t p = 0; p < points; ++p) {
        if (!src.next_record(line)) {
          fail(path, src.line(),
               "file ends inside shape " + std::to_string(k) + " after " + std::to_string(p) + " of its " +
                   std::to_string(points) + " points");
        }
        const auto pt = split(line);
        expect_tokens(src, pt, 3, "x y z");
        shape.points.push_back(parse_vec3(src, pt, 0));
      }
      out.shapes.push_back(std::move(shape));
    }
    if (src.next_record(line)) src.fail_here("more shapes than the header's count=" + std::to_string(count));
    return out;
  });
}

namespace {

/// Reads a convex_pairs file; shape ids must be below `shape_limit`.
ConvexPairs parse_convex_pairs(const std::string& path, std::uint64_t shape_limit, const std::string& shapes_file) {
  Source src(path);
  const Header h = expect_header(src, "convex_pairs");
  const std::uint64_t count = require_count(src, h, "count");
  ConvexPairs out;
  out.shapes_file = require_key(src, h, "shapes");
  out.pairs.reserve(reservable(src, count));
  read_records(src, count, [&](const std::vector<std::string_view>& t) {
    expect_tokens(src, t, 16, "a b pA(7) pB(7)");
    ConvexPair p;
    const std::uint64_t a = parse_unsigned(src, t[0], "shape id");
    const std::uint64_t b = parse_unsigned(src, t[1], "shape id");
    if (a >= shape_limit || b >= shape_limit) {
      src.fail_here("shape id " + std::to_string(std::max(a, b)) + " beyond the " + std::to_string(shape_limit) +
                    " shapes of " + shapes_file);
    }
    p.a = static_cast<std::uint32_t>(a);
    p.b = static_cast<std::uint32_t>(b);
    p.pose_a = parse_pose(src, t, 2);
    p.pose_b = parse_pose(src, t, 9);
    out.pairs.push_back(p);
  });
  return out;
}

}  // namespace

Result<ConvexPairs> read_convex_pairs(const std::string& path) {
  return guarded<ConvexPairs>([&]() { return parse_convex_pairs(path, std::uint64_t{1} << 32, "the shapes file"); });
}

Result<std::vector<BoxPair>> read_box_pairs(const std::string& path) {
  return guarded<std::vector<BoxPair>>([&]() -> std::vector<BoxPair> {
    Source src(path);
    const Header h = expect_header(src, "box_pairs");
    const std::uint64_t count = require_count(src, h, "count");
    std::vector<BoxPair> out;
    out.reserve(reservable(src, count));
    read_records(src, count, [&](const std::vector<std::string_view>& t) {
      expect_tokens(src, t, 20, "hA(3) pA(7) hB(3) pB(7)");
      BoxPair p;
      p.half_extents_a = parse_positive_vec3(src, t, 0, "half extents of box a");
      p.pose_a = parse_pose(src, t, 3);
      p.half_extents_b = parse_positive_vec3(src, t, 10, "half extents of box b");
      p.pose_b = parse_pose(src, t, 13);
      out.push_back(p);
    });
    return out;
  });
}

Result<ObjMesh> read_obj(const std::string& path) {
  return guarded<ObjMesh>([&]() -> ObjMesh {
    Source src(path);
    ObjMesh mesh;
    std::string_view line;
    std::vector<std::uint32_t> polygon;
    while (src.next_record(line)) {
      const auto t = split(line);
      if (t[0] == "v") {
        if (t.size() != 4 && t.size() != 5) src.fail_here("expected 'v x y z'");
        mesh.vertices.push_back(parse_vec3(src, t, 1));
      } else if (t[0] == "f") {
        if (t.size() < 4) src.fail_here("a face needs at least 3 vertices");
        polygon.clear();
        for (std::size_t i = 1; i < t.size(); ++i) {
          std::string_view index_text = t[i].substr(0, t[i].find('/'));
          long long index = 0;
          const auto [ptr, ec] = std::from_chars(index_text.data(), index_text.data() + index_text.size(), index);
          if (ec != std::errc() || ptr != index_text.data() + index_text.size() || index == 0) {
            src.fail_here("bad vertex index " + quoted(t[i]) + " (indices are 1-based)");
          }
          const long long n = static_cast<long long>(mesh.vertices.size());
          const long long zero_based = index > 0 ? index - 1 : n + index;
          if (zero_based < 0 || zero_based >= n) {
            src.fail_here("vertex index " + std::string(index_text) + " out of range (" + std::to_string(n) +
                          " vertices so far)");
          }
          polygon.push_back(static_cast<std::uint32_t>(zero_based));
        }
        for (std::size_t i = 1; i + 1 < polygon.size(); ++i) {
          mesh.triangles.push_back({polygon[0], polygon[i], polygon[i + 1]});
        }
      } else if (t[0] == "vn" || t[0] == "vt" || t[0] == "vp" || t[0] == "o" || t[0] == "g" || t[0] == "s" ||
                 t[0] == "usemtl" || t[0] == "mtllib") {
        continue;
      } else {
        src.fail_here("unsupported OBJ statement " + quoted(t[0]) + " (the reader knows v and f)");
      }
    }
    if (mesh.vertices.empty() || mesh.triangles.empty()) fail(path, src.line(), "no vertices or no faces");
    return mesh;
  });
}

Result<MeshPoses> read_mesh_poses(const std::string& path) {
  return guarded<MeshPoses>([&]() -> MeshPoses {
    Source src(path);
    const Header h = expect_header(src, "mesh_poses");
    const std::uint64_t count = require_count(src, h, "count");
    MeshPoses out;
    out.mesh_a = require_key(src, h, "a");
    out.mesh_b = require_key(src, h, "b");
    out.poses.reserve(reservable(src, count));
    read_records(src, count, [&](const std::vector<std::string_view>& t) {
      expect_tokens(src, t, 7, "px py pz qw qx qy qz");
      out.poses.push_back(parse_pose(src, t, 0));
    });
    return out;
  });
}

Result<RayQueries> read_rays(const std::string& path) {
  return guarded<RayQueries>([&]() -> RayQueries {
    Source src(path);
    const Header h = expect_header(src, "rays");
    const std::uint64_t count = require_count(src, h, "count");
    RayQueries out;
    out.mesh = require_key(src, h, "mesh");
    out.rays.reserve(reservable(src, count));
    read_records(src, count, [&](const std::vector<std::string_view>& t) {
      expect_tokens(src, t, 7, "ox oy oz dx dy dz tmax");
      RayQuery r;
      r.origin = parse_vec3(src, t, 0);
      r.direction = parse_vec3(src, t, 3);
      if (r.direction.x == 0 && r.direction.y == 0 && r.direction.z == 0) src.fail_here("zero ray direction");
      r.max_t = parse_double(src, t[6]);
      if (!(r.max_t >= 0)) src.fail_here("tmax must be >= 0");
      out.rays.push_back(r);
    });
    return out;
  });
}

namespace {

/// Reads a ccd_pairs file; hull ids must be below `hull_limit`.
CcdPairs parse_ccd_pairs(const std::string& path, std::uint64_t hull_limit, const std::string& hulls_file) {
  Source src(path);
  const Header h = expect_header(src, "ccd_pairs");
  const std::uint64_t count = require_count(src, h, "count");
  CcdPairs out;
  out.hulls_file = require_key(src, h, "hulls");
  out.cases.reserve(reservable(src, count));
  std::string_view line;
  for (std::uint64_t k = 0; k < count; ++k) {
    if (!src.next_record(line)) {
      fail(path, src.line(), "file ends after " + std::to_string(k) + " of the " + std::to_string(count) + " cases");
    }
    std::vector<std::string_view> parts;
    std::size_t start = 0;
    while (true) {
      const std::size_t bar = line.find('|', start);
      parts.push_back(line.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start));
      if (bar == std::string_view::npos) break;
      start = bar + 1;
    }
    if (parts.size() != 4) {
      src.fail_here("expected 4 fields separated by '|' (shapeA | shapeB | pA0 pA1 | pB0 pB1), found " +
                    std::to_string(parts.size()));
    }
    CcdCase c;
    c.a = parse_ccd_shape(src, parts[0]);
    c.b = parse_ccd_shape(src, parts[1]);
    for (const CcdShape* shape : {&c.a, &c.b}) {
      if (shape->kind == CcdShapeKind::Hull && shape->hull >= hull_limit) {
        src.fail_here("hull id " + std::to_string(shape->hull) + " beyond the " + std::to_string(hull_limit) +
                      " shapes of " + hulls_file);
      }
    }
    const auto pa = split(parts[2]);
    expect_tokens(src, pa, 14, "pA0(7) pA1(7)");
    const auto pb = split(parts[3]);
    expect_tokens(src, pb, 14, "pB0(7) pB1(7)");
    c.a0 = parse_pose(src, pa, 0);
    c.a1 = parse_pose(src, pa, 7);
    c.b0 = parse_pose(src, pb, 0);
    c.b1 = parse_pose(src, pb, 7);
    out.cases.push_back(c);
  }
  if (src.next_record(line)) src.fail_here("more cases than the header's count=" + std::to_string(count));
  return out;
}

}  // namespace

Result<CcdPairs> read_ccd_pairs(const std::string& path) {
  return guarded<CcdPairs>([&]() { return parse_ccd_pairs(path, std::uint64_t{1} << 32, "the hulls file"); });
}

namespace {

template <class Record, class Parse>
PrimitivePairs<Record> read_primitive_pairs(const std::string& path, const char* kind, std::size_t fields,
                                            const char* layout, Materialize materialize, Parse parse) {
  Source src(path);
  const Header h = expect_header(src, kind);
  const std::uint64_t count = require_count(src, h, "count");
  const std::uint64_t repeat = require_count(src, h, "repeat");
  if (repeat == 0) fail(path, 1, "repeat= must be >= 1");
  if (count > 0 && repeat > kMaxWorkloadQueries / count) {
    fail(path, 1, "count= * repeat= is more than kMaxWorkloadQueries (2^24)");
  }
  PrimitivePairs<Record> out;
  out.repeat = repeat;
  out.distinct.reserve(reservable(src, count));
  read_records(src, count, [&](const std::vector<std::string_view>& t) {
    expect_tokens(src, t, fields, layout);
    out.distinct.push_back(parse(src, t));
  });
  if (materialize == Materialize::Yes) {
    out.queries.reserve(out.query_count());
    for (std::size_t r = 0; r < out.repeat; ++r) {
      out.queries.insert(out.queries.end(), out.distinct.begin(), out.distinct.end());
    }
  }
  return out;
}

}  // namespace

Result<PrimitivePairs<SpherePair>> read_sphere_pairs(const std::string& path, Materialize materialize) {
  return guarded<PrimitivePairs<SpherePair>>([&]() {
    return read_primitive_pairs<SpherePair>(path, "sphere_pairs", 8, "x1 y1 z1 r1 x2 y2 z2 r2", materialize,
                                            [](const Source& src, const std::vector<std::string_view>& t) {
                                              SpherePair p;
                                              p.center1 = parse_vec3(src, t, 0);
                                              p.radius1 = parse_positive(src, t[3], "r1");
                                              p.center2 = parse_vec3(src, t, 4);
                                              p.radius2 = parse_positive(src, t[7], "r2");
                                              return p;
                                            });
  });
}

Result<PrimitivePairs<CapsulePair>> read_capsule_pairs(const std::string& path, Materialize materialize) {
  return guarded<PrimitivePairs<CapsulePair>>([&]() {
    return read_primitive_pairs<CapsulePair>(path, "capsule_pairs", 14, "a0(3) a1(3) ra b0(3) b1(3) rb", materialize,
                                             [](const Source& src, const std::vector<std::string_view>& t) {
                                               CapsulePair p;
                                               p.a0 = parse_vec3(src, t, 0);
                                               p.a1 = parse_vec3(src, t, 3);
                                               p.radius_a = parse_positive(src, t[6], "ra");
                                               p.b0 = parse_vec3(src, t, 7);
                                               p.b1 = parse_vec3(src, t, 10);
                                               p.radius_b = parse_positive(src, t[13], "rb");
                                               return p;
                                             });
  });
}

Result<ConvexWorkload> read_convex_workload(const std::string& dir, int points) {
  const std::string pairs_path = workload_path(dir, "convex_pairs_" + std::to_string(points) + ".txt");
  const std::string shapes_file = header_value(pairs_path, "shapes");
  if (shapes_file.empty()) {
    auto pairs = read_convex_pairs(pairs_path);  // reports why
    if (!pairs) return pairs.error();
    return make_error(ErrorCode::InvalidArgument, pairs_path + ":1", "empty shapes= key");
  }
  auto shapes = read_convex_shapes(workload_path(dir, shapes_file));
  if (!shapes) return shapes.error();
  const std::uint64_t limit = shapes->shapes.size();
  auto pairs = guarded<ConvexPairs>([&]() { return parse_convex_pairs(pairs_path, limit, shapes_file); });
  if (!pairs) return pairs.error();
  return ConvexWorkload{std::move(shapes).value(), std::move(pairs).value()};
}

Result<CcdWorkload> read_ccd_workload(const std::string& dir) {
  const std::string pairs_path = workload_path(dir, "ccd_pairs.txt");
  const std::string hulls_file = header_value(pairs_path, "hulls");
  if (hulls_file.empty()) {
    auto pairs = read_ccd_pairs(pairs_path);  // reports why
    if (!pairs) return pairs.error();
    return make_error(ErrorCode::InvalidArgument, pairs_path + ":1", "empty hulls= key");
  }
  auto hulls = read_convex_shapes(workload_path(dir, hulls_file));
  if (!hulls) return hulls.error();
  const std::uint64_t limit = hulls->shapes.size();
  auto pairs = guarded<CcdPairs>([&]() { return parse_ccd_pairs(pairs_path, limit, hulls_file); });
  if (!pairs) return pairs.error();
  return CcdWorkload{std::move(hulls).value(), std::move(pairs).value()};
}

// ---------------------------------------------------------------------------------
// Locations and checksums
// ---------------------------------------------------------------------------------

std::string workload_dir() {
  if (const char* env = std::getenv("PROXIMA_WORKLOADS"); env != nullptr && env[0] != '\0') return env;
  return PROXIMA_DEFAULT_WORKLOAD_DIR;
}

std::string workload_dir(int& argc, char** argv) {
  std::string found;
  int out = 1;
  for (int i = 1; i < argc; ++i) {
    const std::string_view arg = argv[i];
    if (arg.starts_with("--workloads=")) {
      found = std::string(arg.substr(12));
      continue;
    }
    if (arg == "--workloads" && i + 1 < argc) {
      found = argv[++i];
      continue;
    }
    argv[out++] = argv[i];
  }
  if (out < argc) argv[out] = nullptr;
  argc = out;
  return found.empty() ? workload_dir() : found;
}

std::string workload_path(const std::string& dir, const std::string& name) {
  if (dir.empty()) return name;
  return dir.back() == '/' ? dir + name : dir + "/" + name;
}

Result<std::string> sha256_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return make_error(ErrorCode::InvalidArgument, path, "cannot open the file");
  Sha256 hasher;
  std::vector<char> buffer(1 << 16);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    hasher.update(buffer.data(), static_cast<std::size_t>(in.gcount()));
  }
  return Sha256::to_hex(hasher.finish());
}

Result<ChecksumReport> verify_checksums(const std::string& dir) {
  const std::string list = workload_path(dir, "SHA256SUMS");
  return guarded<ChecksumReport>([&]() -> ChecksumReport {
    Source src(list);
    ChecksumReport report;
    std::string_view line;
    while (src.next_record(line)) {
      const auto t = split(line);
      if (t.size() != 2 || t[0].size() != 64 ||
          t[0].find_first_not_of("0123456789abcdefABCDEF") != std::string_view::npos) {
        src.fail_here("expected '<64 hex digits>  <file name>'");
      }
      std::string name(t[1]);
      if (!name.empty() && name[0] == '*') name.erase(0, 1);  // sha256sum's binary-mode marker
      std::string expected(t[0]);
      std::transform(expected.begin(), expected.end(), expected.begin(),
                     [](char c) { return static_cast<char>(c >= 'A' && c <= 'F' ? c - 'A' + 'a' : c); });
      const auto digest = sha256_file(workload_path(dir, name));
      if (!digest) {
        report.missing.push_back(name);
      } else if (*digest == expected) {
        report.matched.push_back(name);
      } else {
        report.mismatched.push_back(name);
      }
    }
    return report;
  });
}

}  // namespace proxima::bench
