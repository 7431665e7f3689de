// Tessellation of every shape kind for drawing (debug/tessellate.hpp).
//
// Steps:
//   1. Shapes of revolution about local z (sphere, capsule, cylinder, cone; the ellipsoid
//      as a unit sphere scaled per axis; the segment's thin prism) are a profile of rings
//      (radius, z) from top to bottom, turned about z: a ring of radius 0 is a pole (one
//      vertex, a fan), two consecutive rings are joined by quads split in two triangles.
//   2. Polyhedra (box, convex hull) fan each face from its first vertex; the triangle mesh
//      is copied; a compound appends its children placed at their poses.
//   3. Surfaces without inside (triangle, half-space square) are written with both windings.
#include <proxima/debug/tessellate.hpp>
#include <proxima/shapes/shape.hpp>

#include <algorithm>
#include <cmath>
#include <utility>

namespace proxima::debug {

namespace {

struct Ring {
  Real radius;
  Real z;
};

void add_triangle(DrawMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  mesh.indices.insert(mesh.indices.end(), {a, b, c});
}

/// Appends the ring's vertices (one for a pole) and returns the index of the first.
std::uint32_t add_ring(DrawMesh& mesh, const Ring& ring, int slices) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  if (ring.radius == Real(0)) {
    mesh.positions.emplace_back(Real(0), Real(0), ring.z);
    return first;
  }
  for (int j = 0; j < slices; ++j) {
    const Real phi = Real(2) * kPi * Real(j) / Real(slices);
    mesh.positions.emplace_back(ring.radius * std::cos(phi), ring.radius * std::sin(phi), ring.z);
  }
  return first;
}

/// Joins ring `upper` (first vertex u) to ring `lower` (first vertex l), outward faces.
void join_rings(DrawMesh& mesh, const Ring& upper, std::uint32_t u, const Ring& lower, std::uint32_t l, int slices) {
  const auto n = static_cast<std::uint32_t>(slices);
  for (std::uint32_t j = 0; j < n; ++j) {
    const std::uint32_t k = (j + 1) % n;
    if (upper.radius == Real(0)) {
      add_triangle(mesh, u, l + j, l + k);
    } else if (lower.radius == Real(0)) {
      add_triangle(mesh, u + j, l, u + k);
    } else {
      add_triangle(mesh, u + j, l + j, l + k);
      add_triangle(mesh, u + j, l + k, u + k);
    }
  }
}

/// The surface of revolution of `profile` (top to bottom) about local z.
DrawMesh lathe(const std::vector<Ring>& profile, int slices) {
  DrawMesh mesh;
  std::uint32_t previous = add_ring(mesh, profile[0], slices);
  for (std::size_t i = 1; i < profile.size(); ++i) {
    const std::uint32_t current = add_ring(mesh, profile[i], slices);
    join_rings(mesh, profile[i - 1], previous, profile[i], current, slices);
    previous = current;
  }
  return mesh;
}

/// Rings of a sphere of `radius` from the pole at +z (latitudes 0..pi over `stacks`), the
/// upper half raised by `shift` and the lower half lowered by it (a capsule's caps).
std::vector<Ring> sphere_profile(Real radius, Real shift, int stacks) {
  std::vector<Ring> rings;
  for (int i = 0; i <= stacks; ++i) {
    const Real theta = kPi * Real(i) / Real(stacks);
    const Real z = radius * std::cos(theta);
    const Real r = (i == 0 || i == stacks) ? Real(0) : radius * std::sin(theta);
    if (2 * i == stacks && shift > Real(0)) {  // the equator splits into the two caps' rims
      rings.push_back({r, shift});
      rings.push_back({r, -shift});
      continue;
    }
    rings.push_back({r, 2 * i < stacks ? z + shift : z - shift});
  }
  return rings;
}

void add_face_fans(DrawMesh& mesh, std::span<const std::uint32_t> loop) {
  for (std::size_t k = 1; k + 1 < loop.size(); ++k) add_triangle(mesh, loop[0], loop[k], loop[k + 1]);
}

DrawMesh box_mesh(const Vec3& h) {
  DrawMesh mesh;
  for (int i = 0; i < 8; ++i) {
    mesh.positions.emplace_back((i & 1) ? h.x : -h.x, (i & 2) ? h.y : -h.y, (i & 4) ? h.z : -h.z);
  }
  // Corner index bits: x = 1, y = 2, z = 4; each loop counter-clockwise seen from outside.
  const std::uint32_t faces[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                                     {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& face : faces) add_face_fans(mesh, face);
  return mesh;
}

DrawMesh hull_mesh(const ConvexHull& hull) {
  DrawMesh mesh;
  mesh.positions.assign(hull.vertices().begin(), hull.vertices().end());
  for (std::uint32_t f = 0; f < hull.faces().size(); ++f) add_face_fans(mesh, hull.face_vertices(f));
  return mesh;
}

/// Both windings of every triangle of `mesh` (a surface seen from both sides).
void add_back_faces(DrawMesh& mesh) {
  const std::size_t count = mesh.indices.size();
  for (std::size_t i = 0; i < count; i += 3)
    add_triangle(mesh, mesh.indices[i], mesh.indices[i + 2], mesh.indices[i + 1]);
}

DrawMesh triangle_mesh_of(const Triangle& triangle) {
  DrawMesh mesh;
  mesh.positions = {triangle.vertex(0), triangle.vertex(1), triangle.vertex(2)};
  add_triangle(mesh, 0, 1, 2);
  add_back_faces(mesh);
  return mesh;
}

DrawMesh halfspace_mesh(const HalfSpace& halfspace, Real extent) {
  const Vec3 n = halfspace.normal();
  const Vec3 helper = std::abs(n.x) < Real(0.9) ? Vec3(1, 0, 0) : Vec3(0, 1, 0);
  const Vec3 u = glm::normalize(glm::cross(helper, n)) * extent;
  const Vec3 v = glm::cross(n, u);  // u x v points along n: counter-clockwise seen from +n
  const Vec3 c = n * halfspace.offset();
  DrawMesh mesh;
  mesh.positions = {c - u - v, c + u - v, c + u + v, c - u + v};
  mesh.indices = {0, 1, 2, 0, 2, 3};
  add_back_faces(mesh);
  return mesh;
}

DrawMesh octahedron(Real r) {
  DrawMesh mesh;
  mesh.positions = {Vec3(r, 0, 0), Vec3(-r, 0, 0), Vec3(0, r, 0), Vec3(0, -r, 0), Vec3(0, 0, r), Vec3(0, 0, -r)};
  mesh.indices = {4, 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 5, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3};
  return mesh;
}

DrawMesh segment_mesh(const Segment& segment, Real r) {
  const Vec3 axis = segment.b() - segment.a();
  const Real length = glm::length(axis);
  if (!(length > Real(0))) return octahedron(r);
  const Real h = length / 2;
  DrawMesh prism = lathe({{0, h}, {r, h}, {r, -h}, {0, -h}}, 6);
  const Quat turn(Vec3(0, 0, 1), axis / length);  // shortest arc from local z to the axis
  DrawMesh mesh;
  append_placed(prism, Transform{(segment.a() + segment.b()) / Real(2), turn}, mesh);
  return mesh;
}

DrawMesh mesh_copy(const TriangleMesh& source) {
  DrawMesh mesh;
  mesh.positions.assign(source.vertices().begin(), source.vertices().end());
  for (const TriangleIndices& t : source.triangles()) add_triangle(mesh, t[0], t[1], t[2]);
  return mesh;
}

}  // namespace

void append_placed(const DrawMesh& mesh, const Transform& pose, DrawMesh& out) {
  const auto offset = static_cast<std::uint32_t>(out.positions.size());
  for (const Vec3& p : mesh.positions) out.positions.push_back(pose.apply(p));
  for (std::uint32_t i : mesh.indices) out.indices.push_back(i + offset);
}

DrawMesh tessellate(ShapeRef shape, const TessellationOptions& options) {
  const int slices = std::clamp(options.segments, 3, 256);
  const int stacks = std::max(2, slices / 2 + (slices / 2) % 2);  // even: the equator is a ring
  switch (shape.type()) {
    case ShapeType::Point: return octahedron(options.marker_radius);
    case ShapeType::Segment: return segment_mesh(shape.as<Segment>(), options.marker_radius);
    case ShapeType::Triangle: return triangle_mesh_of(shape.as<Triangle>());
    case ShapeType::Sphere: return lathe(sphere_profile(shape.as<Sphere>().radius(), 0, stacks), slices);
    case ShapeType::Capsule: {
      const Capsule& c = shape.as<Capsule>();
      return lathe(sphere_profile(c.radius(), c.half_length(), stacks), slices);
    }
    case ShapeType::Box: return box_mesh(shape.as<Box>().half_extents());
    case ShapeType::Cylinder: {
      const Cylinder& c = shape.as<Cylinder>();
      const Real r = c.radius(), h = c.half_length();
      return lathe({{0, h}, {r, h}, {r, -h}, {0, -h}}, slices);
    }
    case ShapeType::Cone: {
      const Cone& c = shape.as<Cone>();
      return lathe({{0, c.half_length()}, {c.radius(), -c.half_length()}, {0, -c.half_length()}}, slices);
    }
    case ShapeType::Ellipsoid: {
      DrawMesh mesh = lathe(sphere_profile(Real(1), 0, stacks), slices);
      for (Vec3& p : mesh.positions) p *= shape.as<Ellipsoid>().radii();
      return mesh;
    }
    case ShapeType::ConvexHull: return hull_mesh(shape.as<ConvexHull>());
    case ShapeType::HalfSpace: return halfspace_mesh(shape.as<HalfSpace>(), options.halfspace_extent);
    case ShapeType::TriangleMesh: return mesh_copy(shape.as<TriangleMesh>());
    default: break;
  }
  DrawMesh mesh;
  for (const CompoundChild& child : shape.as<Compound>().children()) {
    append_placed(tessellate(child.shape, options), child.pose, mesh);
  }
  return mesh;
}

}  // namespace proxima::debug
