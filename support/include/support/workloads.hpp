#pragma once
/// @file workloads.hpp
/// Readers for the benchmark workload files (formats W1..W7 of shared/bench/FORMATS.md),
/// the W1 broad-phase motion rule and checksum, and where the files are found.
///
/// Every reader parses the decimal text in double precision, checks the header line
/// (kind, version 1, the keys it needs; unknown keys are ignored), skips blank and `#`
/// lines, checks the record count, normalises every pose quaternion, and returns plain
/// structs of doubles. Benchmarks convert to proxima::Real themselves (to_vec3,
/// to_transform). A malformed file gives an Error whose field is "<path>:<line>" and
/// whose message says what is wrong, so Error::what() reads like a compiler message.

#include <proxima/core/result.hpp>
#include <proxima/core/transform.hpp>

#include <array>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

namespace proxima::bench {

// -------------------------------------------------------------------------------------
// Plain records
// -------------------------------------------------------------------------------------

/// A point or vector in double precision, as read from a file (frame given by its use).
struct Vec3d {
  double x = 0;  ///< x coordinate
  double y = 0;  ///< y coordinate
  double z = 0;  ///< z coordinate

  /// Component by index 0..2.
  double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
  /// Component by index 0..2.
  double& operator[](int i) { return i == 0 ? x : (i == 1 ? y : z); }
  /// Exact equality of every component.
  bool operator==(const Vec3d&) const = default;
};

/// A unit quaternion (w, x, y, z), scalar part first, in double precision.
struct Quatd {
  double w = 1;  ///< scalar part
  double x = 0;  ///< vector part, x
  double y = 0;  ///< vector part, y
  double z = 0;  ///< vector part, z

  /// Exact equality of every component.
  bool operator==(const Quatd&) const = default;
};

/// A pose `px py pz qw qx qy qz`: a local point l is at R(rotation) l + position in the
/// parent frame. The readers divide the written quaternion by its length (FORMATS.md).
struct Pose {
  Vec3d position;  ///< origin of the local frame in the parent frame
  Quatd rotation;  ///< normalised orientation, local to parent
};

/// Converts to proxima::Vec3 (rounding to Real).
Vec3 to_vec3(const Vec3d& v);
/// Converts to proxima::Quat and renormalises in Real so that it is unit at Real's precision.
Quat to_quat(const Quatd& q);
/// Converts to proxima::Transform (position and renormalised rotation in Real).
Transform to_transform(const Pose& pose);
/// Rotates then translates a local point by `pose` in double precision: R l + p.
Vec3d apply(const Pose& pose, const Vec3d& local_point);

/// A header line `<kind> <version> key=value ...` as read.
struct Header {
  std::string kind;                         ///< first token
  int version = 0;                          ///< second token
  std::map<std::string, std::string> keys;  ///< every key=value pair, unknown ones included
};

// ---- W1 ------------------------------------------------------------------------------

/// One moving box of a broad-phase workload: the box is [center - half_extents,
/// center + half_extents], moving by `velocity` per unit time.
struct BroadphaseBox {
  Vec3d center;        ///< centre at frame 0
  Vec3d half_extents;  ///< constant half extents (> 0)
  Vec3d velocity;      ///< displacement per unit time at frame 0
};

/// W1 `broadphase` file: N boxes in the cube [lo, hi]^3, advanced `frames` times.
struct BroadphaseWorkload {
  std::string name;                  ///< the header's name= value
  int frames = 0;                    ///< number of frames to simulate (1..frames are queried)
  double dt = 1;                     ///< time step
  double lo = 0;                     ///< lower wall of the domain cube, every axis
  double hi = 0;                     ///< upper wall of the domain cube, every axis
  std::vector<BroadphaseBox> boxes;  ///< box i = record i, frame 0 state
};

/// Advances every box by one frame with the W1 motion rule (double precision, per axis:
/// x = c + v dt; reflect the centre at lo/hi and flip v). O(N).
void advance_frame(std::vector<BroadphaseBox>& boxes, double dt, double lo, double hi);

/// The splitmix64 finaliser of FORMATS.md (mix64).
std::uint64_t mix64(std::uint64_t x);

/// The W1 checksum of a run: number of overlapping pairs and the wrapping sum of
/// mix64(i N + j) over them (i < j), summed over frames 1..F.
struct PairChecksum {
  std::uint64_t pairs = 0;  ///< total pair count
  std::uint64_t hash = 0;   ///< sum of mix64(i * n + j) modulo 2^64

  /// Adds one unordered pair {i, j} (either order) of an n-box workload.
  void add(std::uint64_t i, std::uint64_t j, std::uint64_t n) {
    const std::uint64_t a = i < j ? i : j;
    const std::uint64_t b = i < j ? j : i;
    ++pairs;
    hash += mix64(a * n + b);
  }
  /// Adds another checksum (frames or threads computed separately).
  void merge(const PairChecksum& other) {
    pairs += other.pairs;
    hash += other.hash;
  }
  /// The hash as 16 lower-case hex digits.
  std::string hash_hex() const;
  /// "pairs=<pairs> hash=<16 hex digits>", the form FORMATS.md prints.
  std::string to_string() const;
  /// Exact equality.
  bool operator==(const PairChecksum&) const = default;
};

/// Every overlapping pair (i < j, closed boxes, computed in double as c - h, c + h) of
/// the boxes in their current state, found by sort-and-sweep on x: O(N log N + K).
/// Pairs are sorted by (i, j).
std::vector<std::pair<std::uint32_t, std::uint32_t>> overlapping_pairs(const std::vector<BroadphaseBox>& boxes);

/// The reference checksum of a whole W1 run: frames 1..F, each advanced with
/// advance_frame and queried with overlapping_pairs. O(F (N log N + K)).
PairChecksum reference_checksum(const BroadphaseWorkload& workload);

/// The checksum FORMATS.md publishes for a shared file name ("broadphase_uniform_10k"),
/// or pairs = hash = 0 with `found` false for an unknown name.
struct KnownChecksum {
  bool found = false;     ///< true for the three shared files
  PairChecksum checksum;  ///< the published values
};
/// Looks up the published checksum of a shared W1 workload by its name= value.
KnownChecksum published_checksum(std::string_view name);

// ---- W2 ------------------------------------------------------------------------------

/// One convex shape: the convex hull of `points` (local frame; every point is a vertex).
struct ConvexShape {
  Vec3d semi_axes;            ///< the ellipsoid the points were drawn on (informational)
  std::vector<Vec3d> points;  ///< the points, local frame
};

/// W2 `convex_shapes` file.
struct ConvexShapes {
  int points_per_shape = 0;         ///< header points=
  std::vector<ConvexShape> shapes;  ///< shape id = index
};

/// One W2 query: shapes `a` and `b` at their poses (world frame).
struct ConvexPair {
  std::uint32_t a = 0;  ///< index into ConvexShapes::shapes
  std::uint32_t b = 0;  ///< index into ConvexShapes::shapes
  Pose pose_a;          ///< placement of shape a
  Pose pose_b;          ///< placement of shape b
};

/// W2 `convex_pairs` file.
struct ConvexPairs {
  std::string shapes_file;        ///< header shapes= (a file name in the same folder)
  std::vector<ConvexPair> pairs;  ///< the queries, in order
};

// ---- W3 ------------------------------------------------------------------------------

/// One W3 query: two oriented boxes {R l + p : |l_i| <= h_i}.
struct BoxPair {
  Vec3d half_extents_a;  ///< half extents of box a
  Pose pose_a;           ///< placement of box a
  Vec3d half_extents_b;  ///< half extents of box b
  Pose pose_b;           ///< placement of box b
};

// ---- W4 ------------------------------------------------------------------------------

/// A triangle mesh read from the OBJ subset (0-based indices, counter-clockwise seen from
/// outside).
struct ObjMesh {
  std::vector<Vec3d> vertices;                          ///< vertex positions, local frame
  std::vector<std::array<std::uint32_t, 3>> triangles;  ///< vertex indices, 0-based
};

/// W4 `mesh_poses` file: poses of mesh b in the frame of mesh a.
struct MeshPoses {
  std::string mesh_a;       ///< header a= (OBJ file name, at the identity)
  std::string mesh_b;       ///< header b= (OBJ file name, placed by each pose)
  std::vector<Pose> poses;  ///< the queries, in order
};

// ---- W5 ------------------------------------------------------------------------------

/// One W5 ray: points origin + t direction for 0 <= t <= max_t; direction as written
/// (unit only to about 1e-5, not renormalised), so t is in units of |direction|.
struct RayQuery {
  Vec3d origin;      ///< start point, mesh frame
  Vec3d direction;   ///< direction as written
  double max_t = 0;  ///< largest parameter
};

/// W5 `rays` file.
struct RayQueries {
  std::string mesh;            ///< header mesh= (OBJ file name)
  std::vector<RayQuery> rays;  ///< the queries, in order
};

// ---- W6 ------------------------------------------------------------------------------

/// Kind of a W6 shape.
enum class CcdShapeKind { Sphere, Box, Hull };

/// One W6 shape in its local frame (sphere and box centred at the origin).
struct CcdShape {
  CcdShapeKind kind = CcdShapeKind::Sphere;  ///< which of the fields below is used
  double radius = 0;                         ///< sphere radius
  Vec3d half_extents;                        ///< box half extents
  std::uint32_t hull = 0;                    ///< hull id into the hulls= shapes file
};

/// One W6 case: both shapes move from pose 0 (t = 0) to pose 1 (t = 1), position linearly,
/// orientation by slerp (the file has q0 . q1 >= 0).
struct CcdCase {
  CcdShape a;  ///< first shape
  CcdShape b;  ///< second shape
  Pose a0;     ///< pose of a at t = 0
  Pose a1;     ///< pose of a at t = 1
  Pose b0;     ///< pose of b at t = 0
  Pose b1;     ///< pose of b at t = 1
};

/// W6 `ccd_pairs` file.
struct CcdPairs {
  std::string hulls_file;      ///< header hulls= (a convex_shapes file in the same folder)
  std::vector<CcdCase> cases;  ///< the queries, in order
};

// ---- W7 ------------------------------------------------------------------------------

/// One W7 sphere pair.
struct SpherePair {
  Vec3d center1;   ///< centre of sphere 1
  double radius1;  ///< radius of sphere 1
  Vec3d center2;   ///< centre of sphere 2
  double radius2;  ///< radius of sphere 2
};

/// One W7 capsule pair: capsule = points within radius of the segment [p0, p1].
struct CapsulePair {
  Vec3d a0;         ///< first end of capsule a's segment
  Vec3d a1;         ///< second end of capsule a's segment
  double radius_a;  ///< radius of capsule a
  Vec3d b0;         ///< first end of capsule b's segment
  Vec3d b1;         ///< second end of capsule b's segment
  double radius_b;  ///< radius of capsule b
};

/// Largest count * repeat of a file of distinct queries repeated (W7 pairs, W9 sprites):
/// 2^24, sixteen times the shared workloads' 10^6, so that materialising them stays within
/// about a gigabyte; a larger product is an error naming the header.
inline constexpr std::uint64_t kMaxWorkloadQueries = std::uint64_t{1} << 24;

/// A W7 file: `distinct` pairs (header count=) repeated `repeat` times. The workload is
/// the count * repeat queries in order, query k using distinct[k mod count]; `queries`
/// holds them materialised (when the reader was asked to), so that a benchmark streams
/// them from memory.
template <class Record>
struct PrimitivePairs {
  std::size_t repeat = 1;        ///< header repeat=
  std::vector<Record> distinct;  ///< the pairs as written
  std::vector<Record> queries;   ///< count * repeat records, or empty if not materialised

  /// Number of queries of the workload: count * repeat.
  std::size_t query_count() const { return distinct.size() * repeat; }
  /// Query k (0 <= k < query_count()).
  const Record& query(std::size_t k) const { return distinct[k % distinct.size()]; }
};

/// Converts the count * repeat queries of `pairs` with `convert` into the caller's own
/// record type (e.g. float SoA rows), in query order.
template <class Out, class Record, class Convert>
std::vector<Out> materialize(const PrimitivePairs<Record>& pairs, Convert convert) {
  std::vector<Out> out;
  out.reserve(pairs.query_count());
  for (std::size_t k = 0; k < pairs.query_count(); ++k) out.push_back(convert(pairs.query(k)));
  return out;
}

/// Whether a W7 reader also fills PrimitivePairs::queries.
enum class Materialize { No, Yes };

// -------------------------------------------------------------------------------------
// Readers. Each returns the file's records or an Error naming "<path>:<line>".
// -------------------------------------------------------------------------------------

/// Reads and checks the header line of `path` (any kind, version 1).
Result<Header> read_header(const std::string& path);

/// W1 `broadphase` (needs n, frames, dt, lo, hi; name defaults to the file stem).
Result<BroadphaseWorkload> read_broadphase(const std::string& path);
/// W2 `convex_shapes` (needs count, points).
Result<ConvexShapes> read_convex_shapes(const std::string& path);
/// W2 `convex_pairs` (needs count, shapes). Shape ids are not checked against the shapes
/// file here; read_convex_workload does.
Result<ConvexPairs> read_convex_pairs(const std::string& path);
/// W3 `box_pairs` (needs count).
Result<std::vector<BoxPair>> read_box_pairs(const std::string& path);
/// W4 OBJ subset: `v x y z`, `f i j k` (1-based; also `i/t/n` forms, negative relative
/// indices, polygons fanned into triangles); `vn`, `vt`, `o`, `g`, `s`, `usemtl`, `mtllib`
/// lines are ignored, any other statement is an error.
Result<ObjMesh> read_obj(const std::string& path);
/// W4 `mesh_poses` (needs count, a, b).
Result<MeshPoses> read_mesh_poses(const std::string& path);
/// W5 `rays` (needs count, mesh).
Result<RayQueries> read_rays(const std::string& path);
/// W6 `ccd_pairs` (needs count, hulls).
Result<CcdPairs> read_ccd_pairs(const std::string& path);
/// W7 `sphere_pairs` (needs count, repeat).
Result<PrimitivePairs<SpherePair>> read_sphere_pairs(const std::string& path,
                                                     Materialize materialize = Materialize::Yes);
/// W7 `capsule_pairs` (needs count, repeat).
Result<PrimitivePairs<CapsulePair>> read_capsule_pairs(const std::string& path,
                                                       Materialize materialize = Materialize::Yes);

/// A W2 workload: the pairs file and the shapes file it names (same folder), with every
/// shape id checked.
struct ConvexWorkload {
  ConvexShapes shapes;  ///< the shapes file
  ConvexPairs pairs;    ///< the pairs file
};
/// Reads `convex_pairs_<points>.txt` of `dir` and its shapes file.
Result<ConvexWorkload> read_convex_workload(const std::string& dir, int points);

/// A W6 workload: the cases and the hull file they name (same folder), ids checked.
struct CcdWorkload {
  ConvexShapes hulls;  ///< the hulls= file
  CcdPairs pairs;      ///< the cases
};
/// Reads `ccd_pairs.txt` of `dir` and its hulls file.
Result<CcdWorkload> read_ccd_workload(const std::string& dir);

// -------------------------------------------------------------------------------------
// Where the files are, and their checksums
// -------------------------------------------------------------------------------------

/// The folder of the shared workloads: `--workloads=DIR` on the command line (the
/// argument is removed from argv, so call this before benchmark::Initialize), else the
/// PROXIMA_WORKLOADS environment variable, else PROXIMA_DEFAULT_WORKLOAD_DIR.
std::string workload_dir(int& argc, char** argv);
/// The folder without command-line arguments (environment, then the default).
std::string workload_dir();
/// `dir`/`name`.
std::string workload_path(const std::string& dir, const std::string& name);

/// SHA-256 of a file as 64 lower-case hex digits.
Result<std::string> sha256_file(const std::string& path);

/// Outcome of verify_checksums.
struct ChecksumReport {
  std::vector<std::string> matched;     ///< files whose digest matches
  std::vector<std::string> mismatched;  ///< files whose digest differs
  std::vector<std::string> missing;     ///< files listed but absent
  /// True when every listed file is present and matches.
  bool ok() const { return mismatched.empty() && missing.empty() && !matched.empty(); }
};
/// Checks every file listed in `dir`/SHA256SUMS (`<hex>  <name>` lines). An unreadable or
/// malformed SHA256SUMS is an Error.
Result<ChecksumReport> verify_checksums(const std::string& dir);

}  // namespace proxima::bench
