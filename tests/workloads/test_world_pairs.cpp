// The W8 per-frame query at frames 0 and F of every collision world, three ways:
//   - the independent double reference of world_reference.hpp must give MANIFEST.txt's pair
//     count, hash and split by partner kind exactly (this checks the reader, the motion
//     rule and the reference);
//   - the library (proxima::intersect over SortedSweep's pairs of world_aabb boxes, static
//     pairs never formed) in double must give the same pair set, so MANIFEST's values;
//   - the library's CollisionWorld (every object added at its frame-0 pose, moved to its
//     frame-F pose, continuous detection off, one step each) must give the same pairs;
//   - in float a pair may go either way when it is within float rounding of touching: every
//     pair on which the library and the reference disagree must be within kFloatSlack of
//     touching, measured in double (the reference's gap when it says apart; a plane along
//     which the overlap is that small when it says touching).
#include <gtest/gtest.h>

#include <proxima/broadphase/sweep_and_prune.hpp>
#include <proxima/core/tolerance.hpp>
#include <proxima/narrowphase/narrowphase.hpp>
#include <proxima/world/collision_world.hpp>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <regex>
#include <set>

#include "workload_test_util.hpp"
#include "world_reference.hpp"

namespace proxima::bench {
namespace test_world_pairs {

using namespace test_util;
using world_ref::IdPair;
using world_ref::Placed;

/// What MANIFEST.txt says about one frame of a world.
struct Published {
  bool found = false;
  PairChecksum checksum;
  std::map<std::string, std::uint64_t> split;  ///< "moving", "static", "halfspace", "mesh"
};

/// The values of `frame<k> pairs=<n> hash=<h> (<kind> <n>, ...)` in a MANIFEST note.
Published published(const std::string& notes, int frame) {
  Published p;
  std::smatch m;
  const std::regex re("frame" + std::to_string(frame) + R"( pairs=(\d+) hash=([0-9a-f]{16}) \(([^)]*)\))");
  if (!std::regex_search(notes, m, re)) return p;
  p.found = true;
  p.checksum.pairs = std::stoull(m[1].str());
  p.checksum.hash = std::stoull(m[2].str(), nullptr, 16);
  const std::string parts = m[3].str();
  const std::regex item(R"(([a-z]+) (\d+))");
  for (auto it = std::sregex_iterator(parts.begin(), parts.end(), item); it != std::sregex_iterator(); ++it) {
    p.split[(*it)[1].str()] = std::stoull((*it)[2].str());
  }
  return p;
}

/// The W1 pair hash of a sorted pair list.
PairChecksum checksum_of(const std::vector<IdPair>& pairs, std::uint64_t n) {
  PairChecksum c;
  for (const auto& [i, j] : pairs) c.add(i, j, n);
  return c;
}

/// MANIFEST's partner kind of a pair (at least one of them is moving).
std::string partner_kind(const World& w, const IdPair& p) {
  const WorldObject& a = w.objects[p.first];
  const WorldObject& b = w.objects[p.second];
  if (!a.is_static && !b.is_static) return "moving";
  const WorldObject& partner = a.is_static ? a : b;
  if (partner.shape.kind == WorldShapeKind::HalfSpace) return "halfspace";
  if (partner.shape.kind == WorldShapeKind::Mesh) return "mesh";
  return "static";
}

/// The library's pairs of frame k: every object at its frame-k pose, SortedSweep over the
/// world_aabb boxes (static objects as Static proxies), proxima::intersect on each pair.
std::vector<IdPair> library_pairs(const WorldWorkload& w, const std::vector<Shape>& shapes, int frame,
                                  std::vector<Transform>& poses) {
  const std::size_t n = w.world.objects.size();
  poses.resize(n);
  std::vector<Aabb> boxes(n);
  Aabb scene = Aabb::empty();
  for (std::size_t i = 0; i < n; ++i) {
    const WorldObject& o = w.world.objects[i];
    poses[i] = world_transform(o, pose_at_frame(w.world, i, frame));
    boxes[i] = world_aabb(shapes[i], poses[i]);
    if (o.shape.kind != WorldShapeKind::HalfSpace) scene = merge(scene, boxes[i]);
  }
  // A half-space's box is unbounded (kRealMax) on most sides, beyond what a broad phase
  // takes (kMaxCoordinate): clip it to the box of everything else, grown by 1.
  const Aabb clip{scene.min - Vec3(Real(1)), scene.max + Vec3(Real(1))};
  SortedSweep sweep;
  for (std::size_t i = 0; i < n; ++i) {
    const WorldObject& o = w.world.objects[i];
    Aabb box = boxes[i];
    if (o.shape.kind == WorldShapeKind::HalfSpace) box = {glm::max(box.min, clip.min), glm::min(box.max, clip.max)};
    const BroadPhaseStatus status =
        sweep.insert(static_cast<ProxyId>(i), box, o.is_static ? ProxyKind::Static : ProxyKind::Moving);
    EXPECT_EQ(status, BroadPhaseStatus::Ok) << "object " << i;
  }
  std::vector<ProxyPair> candidates;
  sweep.find_pairs(candidates);
  std::vector<IdPair> out;
  for (const ProxyPair& c : candidates) {
    if (intersect(shapes[c.lo], poses[c.lo], shapes[c.hi], poses[c.hi])) out.emplace_back(c.lo, c.hi);
  }
  return out;
}

/// A CollisionWorld holding every object of `w` at its frame-0 pose (object i is handle
/// index i), continuous detection off (a jump from frame 0 to F is not a motion).
CollisionWorld make_collision_world(const WorldWorkload& w, const std::vector<Shape>& shapes) {
  WorldSettings settings;
  settings.continuous = false;
  CollisionWorld world = std::move(CollisionWorld::create(settings)).value();
  for (std::size_t i = 0; i < shapes.size(); ++i) {
    const WorldObject& o = w.world.objects[i];
    ObjectDesc d;
    d.geometry = shapes[i];
    d.pose = world_transform(o, pose_at_frame(w.world, i, 0));
    d.kind = o.is_static ? ObjectKind::Static : ObjectKind::Moving;
    const auto h = world.add(d);
    EXPECT_TRUE(h.ok() && h->index == i) << "object " << i;
  }
  return world;
}

/// The touching pairs of `world` after one step with every moving object at its frame-k pose.
std::vector<IdPair> collision_world_pairs(CollisionWorld& world, const WorldWorkload& w, int frame) {
  std::vector<ObjectMove> moves;
  for (std::size_t i = 0; i < w.world.objects.size(); ++i) {
    const WorldObject& o = w.world.objects[i];
    if (!o.is_static)
      moves.push_back({ObjectHandle{std::uint32_t(i), 0}, world_transform(o, pose_at_frame(w.world, i, frame))});
  }
  EXPECT_FALSE(world.move(moves).has_value());
  EXPECT_FALSE(world.step(Real(w.world.dt)).has_value());
  std::vector<IdPair> out;
  for (const WorldManifold& m : world.contacts()) out.emplace_back(m.pair.a.index, m.pair.b.index);
  return out;
}

Vec3d to_vec3d(const Vec3& v) { return {double(v.x), double(v.y), double(v.z)}; }

/// How far the pair {a, b} is from the decision that the reference did not make: the
/// reference's gap when it says apart; when it says touching, the smallest overlap of the
/// two shapes' projections (an upper bound of the penetration depth) along the library's
/// distance normal, its opposite and, for a mesh triangle, the triangle's normals.
double distance_to_flip(const Placed& a, const Placed& b, bool touching, const Vec3d& library_normal) {
  using namespace world_ref;
  if (b.kind == WorldShapeKind::HalfSpace || b.kind == WorldShapeKind::Mesh) {
    return distance_to_flip(b, a, touching, mul(-1, library_normal));
  }
  if (a.kind == WorldShapeKind::HalfSpace) {
    return std::abs(dot(b.convex.support(mul(-1, a.normal)), a.normal) - b.convex.radius - a.offset);
  }
  std::vector<Vec3d> directions;
  const double len = std::sqrt(dot(library_normal, library_normal));
  if (len > 0) directions = {mul(1 / len, library_normal), mul(-1 / len, library_normal)};
  auto least_overlap = [&](const Convex& x, const Convex& y, std::vector<Vec3d> dirs) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vec3d& n : dirs) best = std::min({best, overlap_along(x, y, n), overlap_along(y, x, n)});
    return best;
  };
  if (a.kind == WorldShapeKind::Mesh) {
    // Apart: the nearest triangle's gap. Touching: every touching triangle must be left by a
    // small shift, so the worst of their least overlaps.
    double result = touching ? 0.0 : std::numeric_limits<double>::infinity();
    for (const std::uint32_t t : mesh_candidates(a, b.lo, b.hi)) {
      const Convex tri = triangle_convex(a.triangles[t]);
      const double g = gap(tri, b.convex);
      if (!touching) {
        result = std::min(result, g);
        continue;
      }
      if (g > 0) continue;
      Vec3d n = cross(sub(tri.points[1], tri.points[0]), sub(tri.points[2], tri.points[0]));
      n = mul(1 / std::sqrt(dot(n, n)), n);
      std::vector<Vec3d> dirs = directions;
      dirs.push_back(n);
      dirs.push_back(mul(-1, n));
      result = std::max(result, least_overlap(tri, b.convex, dirs));
    }
    return result;
  }
  if (!touching) return gap(a.convex, b.convex);
  return least_overlap(a.convex, b.convex, directions);
}

/// Largest distance from touching at which the float library may decide a pair either
/// way: intersect's own tolerance, linear_tolerance(pair scale) = 100 epsilon (1.2e-5 in
/// float) times the largest coordinate or size of the pair, doubled for the float rounding
/// of the poses and shapes it is given.
double float_slack(const Placed& a, const Placed& b) {
  double scale = 1;
  for (const Placed* p : {&a, &b}) {
    for (const Vec3d& x : p->convex.points) scale = std::max({scale, std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  }
  return 2 * 100 * double(std::numeric_limits<float>::epsilon()) * scale;
}

/// The shape word of an object ("sphere", "box", ...).
const char* shape_name(const WorldObject& o) {
  static constexpr const char* kNames[] = {"sphere", "box", "capsule", "hull", "mesh", "halfspace"};
  return kNames[static_cast<int>(o.shape.kind)];
}

struct WorldCase {
  const char* file;
  const char* manifest_name;
};

/// gtest's text of a case (its file name, not the struct's bytes).
void PrintTo(const WorldCase& c, std::ostream* os) { *os << c.file; }

class WorldPairs : public ::testing::TestWithParam<WorldCase> {};

TEST_P(WorldPairs, FramesZeroAndLastMatchTheManifest) {
  const std::string dir = shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  const WorldCase c = GetParam();
  const auto manifest = read_manifest(dir);
  const auto entry = manifest.find(c.file);
  ASSERT_NE(entry, manifest.end()) << c.file;
  const auto start = std::chrono::steady_clock::now();
  const auto w = read_world_workload(dir, c.file);
  ASSERT_TRUE(w.ok()) << w.error().what();
  const auto shapes = to_shapes(*w);
  ASSERT_TRUE(shapes.ok()) << shapes.error().what();
  const std::uint64_t n = w->world.size();
  CollisionWorld world = make_collision_world(*w, *shapes);
  for (const int frame : {0, w->world.frames}) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    const Published expected = published(entry->second.notes, frame);
    ASSERT_TRUE(expected.found) << entry->second.notes;

    // The double reference against MANIFEST.txt.
    const std::vector<Placed> placed = world_ref::place_all(*w, frame);
    const std::vector<IdPair> reference = world_ref::touching_pairs(placed);
    EXPECT_EQ(checksum_of(reference, n), expected.checksum) << "reference " << checksum_of(reference, n).to_string();
    std::map<std::string, std::uint64_t> split;
    for (const IdPair& p : reference) ++split[partner_kind(w->world, p)];
    EXPECT_EQ(split, expected.split);

    // The library: the narrow phase over a broad phase, and the collision world.
    std::vector<Transform> poses;
    const std::vector<IdPair> library = library_pairs(*w, *shapes, frame, poses);
    const std::vector<IdPair> in_world = collision_world_pairs(world, *w, frame);
    for (const auto& [what, found] : {std::pair{"library", &library}, std::pair{"world", &in_world}}) {
      std::vector<IdPair> only_library, only_reference;
      std::set_difference(found->begin(), found->end(), reference.begin(), reference.end(),
                          std::back_inserter(only_library));
      std::set_difference(reference.begin(), reference.end(), found->begin(), found->end(),
                          std::back_inserter(only_reference));
      std::printf("[ world    ] %s frame %d: reference %s, %s %s, only %s %zu, only reference %zu\n", c.manifest_name,
                  frame, checksum_of(reference, n).to_string().c_str(), what,
                  checksum_of(*found, n).to_string().c_str(), what, only_library.size(), only_reference.size());
      if (PROXIMA_DOUBLE) {
        EXPECT_EQ(checksum_of(*found, n), expected.checksum) << what;
        EXPECT_TRUE(only_library.empty() && only_reference.empty()) << what;
      }
      for (const auto* list : {&only_library, &only_reference}) {
        const bool touching = list == &only_reference;
        for (const IdPair& p : *list) {
          const DistanceResult d = distance((*shapes)[p.first], poses[p.first], (*shapes)[p.second], poses[p.second]);
          const double flip = distance_to_flip(placed[p.first], placed[p.second], touching, to_vec3d(d.normal));
          const double slack = float_slack(placed[p.first], placed[p.second]);
          std::printf(
              "[ world    ]   %s pair %u %u (%s-%s): reference %s, library distance %.3g, %.3g from the other "
              "answer (slack %.3g)\n",
              what, p.first, p.second, shape_name(w->world.objects[p.first]), shape_name(w->world.objects[p.second]),
              touching ? "touching" : "apart", double(d.signed_distance), flip, slack);
          EXPECT_LE(flip, slack) << what << " pair " << p.first << " " << p.second;
        }
      }
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("[ world    ] %s: %.2f s\n", c.manifest_name, seconds);
}

INSTANTIATE_TEST_SUITE_P(SharedWorlds, WorldPairs,
                         ::testing::Values(WorldCase{"world_mixed_10k.txt", "world_mixed_10k"},
                                           WorldCase{"world_terrain.txt", "world_terrain"},
                                           WorldCase{"world_bullets.txt", "world_bullets"},
                                           WorldCase{"world_level_40k.txt", "world_level_40k"}),
                         [](const ::testing::TestParamInfo<WorldCase>& param) {
                           return std::string(param.param.manifest_name);
                         });

}  // namespace test_world_pairs
}  // namespace proxima::bench
