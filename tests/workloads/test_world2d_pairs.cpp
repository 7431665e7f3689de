// The W9 2D world's per-frame query at frames 0 and F (`world2d_mixed_20k.txt`), two ways:
//   - the independent long-double reference of tests/d2/d2_reference.hpp (Minkowski-difference
//     hulls of the cores, radii subtracted; candidate pairs from a sweep over bounding discs)
//     must give MANIFEST.txt's pair count and hash exactly (this checks the reader, the motion
//     rule and the reference);
//   - the library's d2::CollisionWorld (every object added at its frame-0 pose, moved to its
//     frame-F pose, continuous detection off, one step each) must give the same pairs in
//     double; in float a pair may go either way only within kFloatSlack of touching, measured
//     by the reference.
#include <gtest/gtest.h>

#include <proxima/d2/collision_world.hpp>

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>
#include <support/world2d_workloads.hpp>

#include "d2/d2_reference.hpp"
#include "workload_test_util.hpp"

namespace proxima::bench {
namespace test_world2d_pairs {

using namespace test_util;
using d2::test::LD;
using d2::test::RefPose;
using d2::test::RefShape;
using IdPair = std::pair<std::uint32_t, std::uint32_t>;

/// How far from touching (length units, by the reference) a float answer may differ.
constexpr LD kFloatSlack = 2e-4L;

/// The core points and radius of a W9 shape (box2d: its four corners).
RefShape reference_shape(const World2dShape& s) {
  RefShape r;
  r.radius = s.radius;
  if (s.kind == World2dShapeKind::Box2d) {
    const LD hx = s.half_extents.x, hy = s.half_extents.y;
    r.core = {{-hx, -hy}, {hx, -hy}, {hx, hy}, {-hx, hy}};
    return r;
  }
  if (s.kind == World2dShapeKind::Circle) {
    r.core = {{0, 0}};
    return r;
  }
  for (const Vec2d& p : s.points) r.core.push_back({p.x, p.y});
  return r;
}

RefPose reference_pose(const Pose2d& p) { return {p.position.x, p.position.y, p.angle}; }

/// The reference's touching pairs of frame k (not both static) and every pair's signed distance.
std::vector<IdPair> reference_pairs(const World2d& w, const std::vector<RefShape>& shapes, int frame,
                                    std::map<IdPair, LD>& distances) {
  const std::size_t n = w.objects.size();
  struct Disc {
    LD x, y, r;
    std::uint32_t id;
  };
  std::vector<Disc> discs(n);
  std::vector<RefPose> poses(n);
  for (std::size_t i = 0; i < n; ++i) {
    poses[i] = reference_pose(pose2d_at_frame(w, i, frame));
    LD reach = 0;
    for (const d2::test::P& p : shapes[i].core) reach = std::max(reach, d2::test::norm(p));
    discs[i] = {poses[i].x, poses[i].y, reach + shapes[i].radius, static_cast<std::uint32_t>(i)};
  }
  std::sort(discs.begin(), discs.end(), [](const Disc& a, const Disc& b) { return a.x - a.r < b.x - b.r; });
  std::vector<IdPair> out;
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n && discs[j].x - discs[j].r <= discs[i].x + discs[i].r; ++j) {
      const Disc& a = discs[i];
      const Disc& b = discs[j];
      if (std::hypot(a.x - b.x, a.y - b.y) > a.r + b.r + 1e-9L) continue;
      if (w.objects[a.id].is_static && w.objects[b.id].is_static) continue;
      const IdPair pair = a.id < b.id ? IdPair{a.id, b.id} : IdPair{b.id, a.id};
      const LD d =
          d2::test::signed_distance(shapes[pair.first], poses[pair.first], shapes[pair.second], poses[pair.second]);
      distances[pair] = d;
      if (d <= 0) out.push_back(pair);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(World2dPairs, FramesZeroAndLastMatchTheManifest) {
  const std::string dir = shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  const auto manifest = read_manifest(dir);
  const auto entry = manifest.find("world2d_mixed_20k.txt");
  ASSERT_NE(entry, manifest.end());
  const auto w = read_world2d(workload_path(dir, "world2d_mixed_20k.txt"));
  ASSERT_TRUE(w.ok()) << w.error().what();
  const std::size_t n = w->objects.size();
  std::vector<RefShape> ref_shapes;
  WorldSettings settings;
  settings.continuous = false;
  d2::CollisionWorld world = d2::CollisionWorld::create(settings).value();
  for (std::size_t i = 0; i < n; ++i) {
    const World2dObject& o = w->objects[i];
    ref_shapes.push_back(reference_shape(o.shape));
    d2::ObjectDesc desc{to_d2_shape(o.shape).value(), to_d2_pose(pose2d_at_frame(*w, i, 0))};
    desc.kind = o.is_static ? d2::ObjectKind::Static : d2::ObjectKind::Moving;
    ASSERT_EQ(world.add(desc).value().index, i);
  }
  for (const int frame : {0, w->frames}) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    std::smatch m;
    const std::regex re("frame" + std::to_string(frame) + R"( pairs=(\d+) hash=([0-9a-f]{16}))");
    ASSERT_TRUE(std::regex_search(entry->second.notes, m, re)) << entry->second.notes;
    std::map<IdPair, LD> distances;
    const std::vector<IdPair> expected = reference_pairs(*w, ref_shapes, frame, distances);
    PairChecksum reference;
    for (const auto& [i, j] : expected) reference.add(i, j, n);
    EXPECT_EQ(reference.pairs, std::stoull(m[1].str()));
    EXPECT_EQ(reference.hash, std::stoull(m[2].str(), nullptr, 16));

    if (frame != 0) {
      for (std::size_t i = 0; i < n; ++i) {
        if (!w->objects[i].is_static) {
          ASSERT_FALSE(world.move({static_cast<std::uint32_t>(i), 0}, to_d2_pose(pose2d_at_frame(*w, i, frame))));
        }
      }
    }
    ASSERT_FALSE(world.step());
    std::set<IdPair> library;
    for (const auto* list : {&world.events().begin, &world.events().persist}) {
      for (const ContactEvent& e : *list) library.insert({e.pair.a.index, e.pair.b.index});
    }
    const std::set<IdPair> truth(expected.begin(), expected.end());
    int disagreements = 0;
    for (const IdPair& p : truth) {
      if (library.count(p)) continue;
      ++disagreements;
      EXPECT_TRUE(sizeof(Real) == 4 && -distances[p] <= kFloatSlack)
          << "missed pair " << p.first << "," << p.second << " depth " << static_cast<double>(-distances[p]);
    }
    for (const IdPair& p : library) {
      if (truth.count(p)) continue;
      ++disagreements;
      const auto d = distances.find(p);
      EXPECT_TRUE(sizeof(Real) == 4 && d != distances.end() && d->second <= kFloatSlack)
          << "extra pair " << p.first << "," << p.second;
    }
    std::cout << "[ world2d  ] frame " << frame << ": " << truth.size() << " pairs, library disagrees on "
              << disagreements << "\n";
  }
}

}  // namespace test_world2d_pairs
}  // namespace proxima::bench
