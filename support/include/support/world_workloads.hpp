#pragma once
/// @file world_workloads.hpp
/// The W8 collision worlds of shared/bench/FORMATS.md: the `world` reader (with the hull
/// file and the OBJ meshes it names), the W8 motion rule (the pose of an object at a
/// frame, in double precision exactly as FORMATS.md writes it), the conversion of the
/// objects to proxima shapes, and the reader of `world_bullets_expected.txt`.
///
/// As for W1..W7 (workloads.hpp): plain structs of doubles, the header checked (kind,
/// version 1, the keys needed; unknown keys ignored), blank and `#` lines skipped, pose
/// quaternions normalised, and a malformed file gives an Error whose field is
/// "<path>:<line>".

#include <proxima/shapes/shape.hpp>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "support/workloads.hpp"

namespace proxima::bench {

// ---- W8 records ------------------------------------------------------------------------

/// Kind of a W8 shape.
enum class WorldShapeKind {
  Sphere,     ///< `sphere r`: the ball of radius r around the local origin
  Box,        ///< `box hx hy hz`: {l : |l_a| <= h_a}
  Capsule,    ///< `capsule r hl`: points within r of the segment (0,0,-hl)-(0,0,hl)
  Hull,       ///< `hull k`: convex hull of shape k of the hulls= file
  Mesh,       ///< `mesh <file>`: the triangles (surface) of an OBJ file (static only)
  HalfSpace,  ///< `halfspace nx ny nz d`: {x : n.x <= d} in world coordinates (static only)
};

/// One W8 shape, in its object's local frame (a half-space: in the world frame).
struct WorldShape {
  WorldShapeKind kind = WorldShapeKind::Sphere;  ///< which of the fields below are used
  double radius = 0;                             ///< sphere and capsule radius
  double half_length = 0;                        ///< capsule: half the length of its z segment
  Vec3d half_extents;                            ///< box half extents
  std::uint32_t hull = 0;                        ///< hull: shape id in the hulls= file
  std::string mesh;                              ///< mesh: OBJ file name (same folder)
  Vec3d normal;                                  ///< half-space: outward normal, world, as written
  double offset = 0;                             ///< half-space: d of n.x <= d
};

/// One W8 object: its shape, its pose at t = 0 and its constant velocities.
struct WorldObject {
  std::uint32_t id = 0;    ///< object id (= its index in World::objects)
  bool is_static = false;  ///< static objects never move (velocities zero)
  WorldShape shape;        ///< the shape, local frame
  Pose pose;               ///< pose at t = 0 (quaternion normalised); half-spaces: ignored
  Vec3d velocity;          ///< linear velocity of the local origin, world, per unit time
  Vec3d angular_velocity;  ///< angular velocity omega, world, radians per unit time
};

/// W8 `world` file.
struct World {
  std::string name;                  ///< header name= (default: the file stem)
  int frames = 0;                    ///< header frames=: the frames are 0..frames
  double dt = 0;                     ///< header dt=: frame k is at t = k * dt
  Vec3d lo;                          ///< header lo=: lower corner of the fold box
  Vec3d hi;                          ///< header hi=: upper corner of the fold box
  std::string hulls_file;            ///< header hulls= (a convex_shapes file, same folder)
  std::vector<WorldObject> objects;  ///< object i = record i

  /// Number of objects (the N of the pair hash mix64(i N + j)).
  std::uint64_t size() const { return objects.size(); }
};

/// A W8 world with the files it names: the hulls= file and every mesh's OBJ, with every
/// hull id checked against the hull file.
struct WorldWorkload {
  World world;                            ///< the world file
  ConvexShapes hulls;                     ///< the hulls= file (W2 format)
  std::map<std::string, ObjMesh> meshes;  ///< every OBJ file a mesh object names, by name
};

/// One answer of `world_bullets_expected.txt`: the first contact of a sphere with a plate
/// along its piecewise linear path, or none.
struct BulletContact {
  std::uint32_t sphere = 0;  ///< sphere id
  bool hit = false;          ///< false: the line reads "<id> -1 -1 -1" (no contact)
  int interval = -1;         ///< frame interval k (0..F-1) of the first contact, or -1
  double s = -1;             ///< fraction s in [0, 1] of that interval (9 decimals), or -1
  std::uint32_t plate = 0;   ///< plate id (hit only)
};

/// `world_bullets_expected` file.
struct BulletsExpected {
  std::string world_file;               ///< header world= (file name, same folder)
  std::vector<BulletContact> contacts;  ///< the records, in order
};

// ---- Readers -----------------------------------------------------------------------------

/// W8 `world` (needs objects, frames, dt, lo, hi, hulls; name defaults to the file stem).
/// Checks: ids 0..N-1 in order, positive sizes, mesh and half-space objects static, static
/// objects with zero velocities, a non-zero half-space normal. Hull ids are not checked
/// against the hull file here; read_world_workload does.
Result<World> read_world(const std::string& path);
/// Reads `dir`/`file` (a W8 world), its hulls= file and every OBJ file its meshes name.
Result<WorldWorkload> read_world_workload(const std::string& dir, const std::string& file);
/// `world_bullets_expected` (needs count, world).
Result<BulletsExpected> read_bullets_expected(const std::string& path);

// ---- Motion rule ---------------------------------------------------------------------------

/// The time of frame k: t = k * dt (one double multiplication).
inline double frame_time(int frame, double dt) { return static_cast<double>(frame) * dt; }
/// Folds x into [lo, hi] by the W8 triangle wave (reflected at both walls):
/// u = fmod(x - lo, 2W) (+ 2W when negative), lo + (u <= W ? u : 2W - u), W = hi - lo.
double fold_coordinate(double x, double lo, double hi);
/// The W8 motion rule at time t in double precision, every operation rounded as
/// FORMATS.md writes it (no fused multiply-add): position p0 + v t folded into [lo, hi] per
/// axis, orientation exp(omega t / 2) (x) q0 renormalised. Static objects: their pose as
/// written (no folding).
Pose pose_at_time(const WorldObject& object, double t, const Vec3d& lo, const Vec3d& hi);
/// The pose of object `index` at frame k (t = frame_time(k, dt)).
Pose pose_at_frame(const World& world, std::size_t index, int frame);

// ---- Proxima shapes ----------------------------------------------------------------------

/// The OBJ mesh as the library's IndexedMesh (vertices rounded to Real).
IndexedMesh to_indexed_mesh(const ObjMesh& mesh);
/// The convex hull of a W2 point set (points rounded to Real); errors of ConvexHull::create.
Result<ConvexHull> to_convex_hull(const ConvexShape& shape);
/// The library shape of one W8 shape: Sphere, Box, Capsule (local z axis, as W8's), the
/// ConvexHull of its hull's points, the TriangleMesh of its OBJ, or the HalfSpace
/// {n.x <= d} (local = world frame: place it with world_transform). Hulls and meshes are
/// built here (qhull, a BVH): use to_shapes for a whole world. Errors: those of the
/// shape's create, or InvalidArgument for an unknown hull id or mesh file.
Result<Shape> to_shape(const WorldShape& shape, const WorldWorkload& workload);
/// The library shapes of every object, index = object id; each hull id and mesh file is
/// built once and shared by the objects that use it (a Shape copy shares its data).
Result<std::vector<Shape>> to_shapes(const WorldWorkload& workload);
/// The placement of an object's library shape for a pose from the motion rule: the pose
/// rounded to Real (to_transform), or the identity for a half-space (its pose is ignored).
Transform world_transform(const WorldObject& object, const Pose& pose);

}  // namespace proxima::bench
