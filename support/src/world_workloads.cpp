// The W8 collision worlds (shared/bench/FORMATS.md, "W8 collision worlds"): the `world`
// and `world_bullets_expected` readers (same machinery as the W1..W7 readers,
// text_parse.hpp), the W8 motion rule and the conversion to proxima shapes.
// The motion rule is computed in double with every operation rounded as written: this
// file is compiled with -ffp-contract=off (support/CMakeLists.txt), so that no product
// and sum are fused into one rounding, and the expressions keep FORMATS.md's order.
#include "support/world_workloads.hpp"

#include <cmath>
#include <memory>

#include "text_parse.hpp"

namespace proxima::bench {
using namespace detail;

namespace {

WorldShape parse_world_shape(const Source& src, std::string_view text) {
  const auto t = split(text);
  if (t.empty()) src.fail_here("empty shape field");
  WorldShape s;
  if (t[0] == "sphere") {
    expect_tokens(src, t, 2, "sphere r");
    s.kind = WorldShapeKind::Sphere;
    s.radius = parse_positive(src, t[1], "sphere radius");
  } else if (t[0] == "box") {
    expect_tokens(src, t, 4, "box hx hy hz");
    s.kind = WorldShapeKind::Box;
    s.half_extents = parse_positive_vec3(src, t, 1, "box half extents");
  } else if (t[0] == "capsule") {
    expect_tokens(src, t, 3, "capsule r hl");
    s.kind = WorldShapeKind::Capsule;
    s.radius = parse_positive(src, t[1], "capsule radius");
    s.half_length = parse_double(src, t[2]);
    if (!(s.half_length >= 0)) src.fail_here("capsule half length must be >= 0");
  } else if (t[0] == "hull") {
    expect_tokens(src, t, 2, "hull k");
    s.kind = WorldShapeKind::Hull;
    const std::uint64_t id = parse_unsigned(src, t[1], "hull id");
    if (id > 0xffffffffu) src.fail_here("hull id too large");
    s.hull = static_cast<std::uint32_t>(id);
  } else if (t[0] == "mesh") {
    expect_tokens(src, t, 2, "mesh <file>");
    s.kind = WorldShapeKind::Mesh;
    s.mesh = std::string(t[1]);
  } else if (t[0] == "halfspace") {
    expect_tokens(src, t, 5, "halfspace nx ny nz d");
    s.kind = WorldShapeKind::HalfSpace;
    s.normal = parse_vec3(src, t, 1);
    if (s.normal.x == 0 && s.normal.y == 0 && s.normal.z == 0) src.fail_here("zero half-space normal");
    s.offset = parse_double(src, t[4]);
  } else {
    src.fail_here("unknown shape " + quoted(t[0]) + " (expected sphere, box, capsule, hull, mesh or halfspace)");
  }
  return s;
}

/// Reads a world file; hull ids must be below `hull_limit`.
World parse_world(const std::string& path, std::uint64_t hull_limit, const std::string& hulls_file) {
  Source src(path);
  const Header h = expect_header(src, "world");
  World w;
  const std::uint64_t n = require_count(src, h, "objects");
  if (n > 0xffffffffu) fail(path, 1, "objects= is too large");
  const std::uint64_t frames = require_count(src, h, "frames");
  if (frames > 100000000u) fail(path, 1, "frames= is too large");
  w.frames = static_cast<int>(frames);
  w.dt = require_number(src, h, "dt");
  if (!(w.dt > 0)) fail(path, 1, "dt= must be > 0");
  const auto lo = require_numbers<3>(src, h, "lo");
  const auto hi = require_numbers<3>(src, h, "hi");
  w.lo = {lo[0], lo[1], lo[2]};
  w.hi = {hi[0], hi[1], hi[2]};
  if (!(w.lo.x < w.hi.x && w.lo.y < w.hi.y && w.lo.z < w.hi.z)) {
    fail(path, 1, "lo= must be smaller than hi= on every axis");
  }
  w.hulls_file = require_key(src, h, "hulls");
  const auto name = h.keys.find("name");
  w.name = name != h.keys.end() ? name->second : file_stem(path);
  w.objects.reserve(reservable(src, n));
  std::string_view line;
  for (std::uint64_t k = 0; k < n; ++k) {
    if (!src.next_record(line)) {
      fail(path, src.line(), "file ends after " + std::to_string(k) + " of the " + std::to_string(n) + " objects");
    }
    const ObjectRecord record = parse_object_record(src, line, k);
    WorldObject o;
    o.id = static_cast<std::uint32_t>(k);
    o.is_static = record.is_static;
    o.shape = parse_world_shape(src, record.shape);
    if (o.shape.kind == WorldShapeKind::Hull && o.shape.hull >= hull_limit) {
      src.fail_here("hull id " + std::to_string(o.shape.hull) + " beyond the " + std::to_string(hull_limit) +
                    " shapes of " + hulls_file);
    }
    if (!o.is_static && (o.shape.kind == WorldShapeKind::Mesh || o.shape.kind == WorldShapeKind::HalfSpace)) {
      src.fail_here("a mesh or half-space object must be static");
    }
    const auto pose = split(record.pose);
    expect_tokens(src, pose, 7, "px py pz qw qx qy qz");
    o.pose = parse_pose(src, pose, 0);
    const auto velocities = split(record.velocities);
    expect_tokens(src, velocities, 6, "vx vy vz wx wy wz");
    o.velocity = parse_vec3(src, velocities, 0);
    o.angular_velocity = parse_vec3(src, velocities, 3);
    if (o.is_static && (o.velocity != Vec3d{} || o.angular_velocity != Vec3d{})) {
      src.fail_here("a static object has non-zero velocities");
    }
    w.objects.push_back(std::move(o));
  }
  if (src.next_record(line)) src.fail_here("more objects than the header's objects=" + std::to_string(n));
  return w;
}

}  // namespace

Result<World> read_world(const std::string& path) {
  return guarded<World>([&]() { return parse_world(path, std::uint64_t{1} << 32, "the hulls file"); });
}

Result<WorldWorkload> read_world_workload(const std::string& dir, const std::string& file) {
  const std::string path = workload_path(dir, file);
  const std::string hulls_file = header_value(path, "hulls");
  if (hulls_file.empty()) {
    auto world = read_world(path);  // reports why
    if (!world) return world.error();
    return make_error(ErrorCode::InvalidArgument, path + ":1", "empty hulls= key");
  }
  auto hulls = read_convex_shapes(workload_path(dir, hulls_file));
  if (!hulls) return hulls.error();
  const std::uint64_t limit = hulls->shapes.size();
  auto world = guarded<World>([&]() { return parse_world(path, limit, hulls_file); });
  if (!world) return world.error();
  WorldWorkload out{std::move(world).value(), std::move(hulls).value(), {}};
  for (const WorldObject& o : out.world.objects) {
    if (o.shape.kind != WorldShapeKind::Mesh || out.meshes.count(o.shape.mesh) != 0) continue;
    auto mesh = read_obj(workload_path(dir, o.shape.mesh));
    if (!mesh) return mesh.error();
    out.meshes.emplace(o.shape.mesh, std::move(mesh).value());
  }
  return out;
}

Result<BulletsExpected> read_bullets_expected(const std::string& path) {
  return guarded<BulletsExpected>([&]() -> BulletsExpected {
    Source src(path);
    const Header h = expect_header(src, "world_bullets_expected");
    const std::uint64_t count = require_count(src, h, "count");
    BulletsExpected out;
    out.world_file = require_key(src, h, "world");
    out.contacts.reserve(reservable(src, count));
    read_records(src, count, [&](const std::vector<std::string_view>& t) {
      expect_tokens(src, t, 4, "sphere k s plate");
      BulletContact c;
      const std::uint64_t sphere = parse_unsigned(src, t[0], "sphere id");
      if (sphere > 0xffffffffu) src.fail_here("sphere id too large");
      c.sphere = static_cast<std::uint32_t>(sphere);
      if (t[1] == "-1" && t[2] == "-1" && t[3] == "-1") {
        out.contacts.push_back(c);
        return;
      }
      const std::uint64_t k = parse_unsigned(src, t[1], "interval k");
      if (k > 100000000u) src.fail_here("interval k too large");
      c.hit = true;
      c.interval = static_cast<int>(k);
      c.s = parse_double(src, t[2]);
      if (!(c.s >= 0 && c.s <= 1)) src.fail_here("s must be in [0, 1], found " + quoted(t[2]));
      const std::uint64_t plate = parse_unsigned(src, t[3], "plate id");
      if (plate > 0xffffffffu) src.fail_here("plate id too large");
      c.plate = static_cast<std::uint32_t>(plate);
      out.contacts.push_back(c);
    });
    return out;
  });
}

// ---------------------------------------------------------------------------------
// Motion rule (double, no fused multiply-add, FORMATS.md's order of operations)
// ---------------------------------------------------------------------------------

double fold_coordinate(double x, double lo, double hi) {
  const double width = hi - lo;
  const double period = 2 * width;
  double u = std::fmod(x - lo, period);
  if (u < 0) u = u + period;
  return lo + (u <= width ? u : period - u);
}

Pose pose_at_time(const WorldObject& object, double t, const Vec3d& lo, const Vec3d& hi) {
  if (object.is_static) return object.pose;
  Pose p;
  for (int a = 0; a < 3; ++a) {
    const double x = object.pose.position[a] + object.velocity[a] * t;
    p.position[a] = fold_coordinate(x, lo[a], hi[a]);
  }
  const double wx = object.angular_velocity.x, wy = object.angular_velocity.y, wz = object.angular_velocity.z;
  const double n = std::sqrt(wx * wx + wy * wy + wz * wz);
  if (n == 0) {
    p.rotation = object.pose.rotation;
    return p;
  }
  const double h = 0.5 * (n * t);
  const double s = std::sin(h);
  const double w1 = std::cos(h), x1 = s * (wx / n), y1 = s * (wy / n), z1 = s * (wz / n);
  const Quatd& q0 = object.pose.rotation;
  const double w2 = q0.w, x2 = q0.x, y2 = q0.y, z2 = q0.z;
  const double qw = w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2;
  const double qx = w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2;
  const double qy = w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2;
  const double qz = w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2;
  const double length = std::sqrt(qw * qw + qx * qx + qy * qy + qz * qz);
  p.rotation = {qw / length, qx / length, qy / length, qz / length};
  return p;
}

Pose pose_at_frame(const World& world, std::size_t index, int frame) {
  return pose_at_time(world.objects[index], frame_time(frame, world.dt), world.lo, world.hi);
}

// ---------------------------------------------------------------------------------
// Proxima shapes
// ---------------------------------------------------------------------------------

IndexedMesh to_indexed_mesh(const ObjMesh& mesh) {
  IndexedMesh out;
  out.vertices.reserve(mesh.vertices.size());
  for (const Vec3d& v : mesh.vertices) out.vertices.push_back(to_vec3(v));
  out.triangles.assign(mesh.triangles.begin(), mesh.triangles.end());
  return out;
}

Result<ConvexHull> to_convex_hull(const ConvexShape& shape) {
  std::vector<Vec3> points;
  points.reserve(shape.points.size());
  for (const Vec3d& p : shape.points) points.push_back(to_vec3(p));
  return ConvexHull::create(points);
}

Result<Shape> to_shape(const WorldShape& shape, const WorldWorkload& workload) {
  switch (shape.kind) {
    case WorldShapeKind::Sphere: {
      auto s = Sphere::create(static_cast<Real>(shape.radius));
      if (!s) return s.error();
      return Shape(*s);
    }
    case WorldShapeKind::Box: {
      auto b = Box::create(to_vec3(shape.half_extents));
      if (!b) return b.error();
      return Shape(*b);
    }
    case WorldShapeKind::Capsule: {
      // Both proxima's Capsule and W8's capsule are the segment (0,0,-hl)-(0,0,hl) + r.
      auto c = Capsule::create(static_cast<Real>(shape.radius), static_cast<Real>(shape.half_length));
      if (!c) return c.error();
      return Shape(*c);
    }
    case WorldShapeKind::Hull: {
      if (shape.hull >= workload.hulls.shapes.size()) {
        return make_error(ErrorCode::InvalidArgument, "hull",
                          "hull id " + std::to_string(shape.hull) + " beyond the hull file");
      }
      auto h = to_convex_hull(workload.hulls.shapes[shape.hull]);
      if (!h) return h.error();
      return Shape(std::move(h).value());
    }
    case WorldShapeKind::Mesh: {
      const auto it = workload.meshes.find(shape.mesh);
      if (it == workload.meshes.end()) {
        return make_error(ErrorCode::InvalidArgument, "mesh", "mesh file " + shape.mesh + " not loaded");
      }
      auto m = TriangleMesh::create(to_indexed_mesh(it->second));
      if (!m) return m.error();
      return Shape(std::move(m).value());
    }
    case WorldShapeKind::HalfSpace: {
      auto h = HalfSpace::create(to_vec3(shape.normal), static_cast<Real>(shape.offset));
      if (!h) return h.error();
      return Shape(*h);
    }
  }
  return make_error(ErrorCode::InvalidArgument, "kind", "unknown shape kind");
}

namespace {

/// The error of object `id`'s shape, its field prefixed with "objects[id].".
Error object_error(std::uint32_t id, const Error& e) {
  return make_error(e.code, "objects[" + std::to_string(id) + "]" + (e.field.empty() ? "" : "." + e.field), e.message);
}

}  // namespace

Result<std::vector<Shape>> to_shapes(const WorldWorkload& workload) {
  std::vector<Shape> out;
  out.reserve(workload.world.objects.size());
  std::map<std::uint32_t, Shape> hulls;
  std::map<std::string, Shape> meshes;
  for (const WorldObject& o : workload.world.objects) {
    if (o.shape.kind == WorldShapeKind::Hull || o.shape.kind == WorldShapeKind::Mesh) {
      const bool hull = o.shape.kind == WorldShapeKind::Hull;
      const Shape* built = nullptr;
      if (hull && hulls.count(o.shape.hull) != 0) built = &hulls.at(o.shape.hull);
      if (!hull && meshes.count(o.shape.mesh) != 0) built = &meshes.at(o.shape.mesh);
      if (built == nullptr) {
        auto s = to_shape(o.shape, workload);
        if (!s) return object_error(o.id, s.error());
        built = hull ? &hulls.emplace(o.shape.hull, std::move(s).value()).first->second
                     : &meshes.emplace(o.shape.mesh, std::move(s).value()).first->second;
      }
      out.push_back(*built);
      continue;
    }
    auto s = to_shape(o.shape, workload);
    if (!s) return object_error(o.id, s.error());
    out.push_back(std::move(s).value());
  }
  return out;
}

Transform world_transform(const WorldObject& object, const Pose& pose) {
  if (object.shape.kind == WorldShapeKind::HalfSpace) return Transform::identity();
  return to_transform(pose);
}

}  // namespace proxima::bench
