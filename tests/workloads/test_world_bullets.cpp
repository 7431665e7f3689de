// world_bullets_expected.txt against the library's continuous queries: for every 10th
// sphere of world_bullets.txt, the centre moves linearly between its frame positions
// (FORMATS.md's continuous query); each frame interval k is checked with
// proxima::time_of_impact (and proxima::shape_cast, the same sweep as a cast) against the
// plates whose boxes meet the segment's swept box, and the first contact (smallest k, then
// smallest s, ties to the lower plate id) must be the file's: same k and plate, s within
// 1e-4 in float and 1e-7 in double.
// Over all 1000 spheres (stride 1, not run by default): double matches every one (largest
// |s - s_file| 5e-10, the file's 9 decimals); float matches 999. Sphere 455 (interval 14,
// plate 1078) grazes the plate's edge (deepest penetration 1.6e-4, distance falling at 0.16
// per unit s): float's answer s = 0.687184 is where the sphere is 1.7e-5 from the plate
// (within the float precision floor of time_of_impact, 64 epsilon times the pair's scale),
// 1.06e-4 before the file's s = 0.687290364, which an independent double computation
// (distance to the box along the segment, bisection) confirms to 1e-10.
#include <gtest/gtest.h>

#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/world/collision_world.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>
#include <random>
#include <string>

#include "workload_test_util.hpp"
#include "world_reference.hpp"

namespace proxima::bench {
namespace test_world_bullets {

using namespace test_util;

/// A first contact found by the library: interval, fraction, plate.
struct Found {
  int interval = -1;
  double s = -1;
  std::uint32_t plate = 0;
};

/// Which continuous query of the library answers one interval against one plate.
enum class Query { TimeOfImpact, ShapeCast };

/// The fraction s of the first contact of `sphere` moving from p0 to p1 with `plate`
/// (still at `plate_pose`), or nothing.
std::optional<double> first_contact(Query query, const Shape& sphere, const Transform& p0, const Transform& p1,
                                    const Shape& plate, const Transform& plate_pose) {
  // Double: a length tolerance far below the 1e-7 asked of s (segments are 0.8 to 5 long);
  // float: the library's precision floor.
  const Real tolerance = PROXIMA_DOUBLE ? Real(1e-10) : Real(0);
  if (query == Query::TimeOfImpact) {
    ToiOptions options;
    options.tolerance = tolerance;
    const auto r = time_of_impact(sphere, Motion{p0, p1}, plate, Motion::stationary(plate_pose), options);
    EXPECT_TRUE(r.ok()) << r.error().what();
    if (!r.ok()) return std::nullopt;
    EXPECT_NE(r->status, CcdStatus::MaxIterations);
    EXPECT_NE(r->status, CcdStatus::Failed);
    if (r->status == CcdStatus::Hit || r->status == CcdStatus::InitiallyOverlapping) return double(r->toi);
    return std::nullopt;
  }
  CastOptions options;
  options.tolerance = tolerance;
  const auto r = shape_cast(sphere, p0, p1.position - p0.position, plate, plate_pose, options);
  EXPECT_TRUE(r.ok()) << r.error().what();
  if (!r.ok()) return std::nullopt;
  EXPECT_NE(r->status, CcdStatus::MaxIterations);
  EXPECT_NE(r->status, CcdStatus::Failed);
  if (r->status == CcdStatus::Hit || r->status == CcdStatus::InitiallyOverlapping) return double(r->t);
  return std::nullopt;
}

TEST(WorldBullets, SampledSpheresMatchTheExpectedFirstContacts) {
  const std::string dir = shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  const auto w = read_world_workload(dir, "world_bullets.txt");
  ASSERT_TRUE(w.ok()) << w.error().what();
  const auto expected = read_bullets_expected(workload_path(dir, "world_bullets_expected.txt"));
  ASSERT_TRUE(expected.ok()) << expected.error().what();
  const auto shapes = to_shapes(*w);
  ASSERT_TRUE(shapes.ok()) << shapes.error().what();
  const World& world = w->world;

  std::vector<std::uint32_t> plates;
  std::vector<world_ref::Placed> placed(world.objects.size());
  std::vector<Transform> plate_pose(world.objects.size());
  for (std::uint32_t i = 0; i < world.objects.size(); ++i) {
    if (!world.objects[i].is_static) continue;
    plates.push_back(i);
    placed[i] = world_ref::place(*w, i, world.objects[i].pose);
    plate_pose[i] = world_transform(world.objects[i], world.objects[i].pose);
  }
  const double s_tolerance = PROXIMA_DOUBLE ? 1e-7 : 1e-4;

  for (const Query query : {Query::TimeOfImpact, Query::ShapeCast}) {
    const char* name = query == Query::TimeOfImpact ? "time_of_impact" : "shape_cast";
    SCOPED_TRACE(name);
    int sampled = 0, hits = 0, matched = 0;
    double worst_s = 0;
    for (const BulletContact& e : expected->contacts) {
      if (e.sphere % 10 != 0) continue;
      ASSERT_LT(e.sphere, world.objects.size());
      const WorldObject& sphere = world.objects[e.sphere];
      ASSERT_EQ(sphere.shape.kind, WorldShapeKind::Sphere);
      ++sampled;
      std::optional<Found> found;
      Pose a = pose_at_frame(world, e.sphere, 0);
      for (int k = 0; k < world.frames && !found; ++k) {
        const Pose b = pose_at_frame(world, e.sphere, k + 1);
        Vec3d lo, hi;
        for (int ax = 0; ax < 3; ++ax) {
          lo[ax] = std::min(a.position[ax], b.position[ax]) - sphere.shape.radius - 1e-6;
          hi[ax] = std::max(a.position[ax], b.position[ax]) + sphere.shape.radius + 1e-6;
        }
        const Transform t0 = to_transform(a), t1 = to_transform(b);
        for (const std::uint32_t plate : plates) {
          if (!world_ref::boxes_meet(lo, hi, placed[plate].lo, placed[plate].hi)) continue;
          const auto s = first_contact(query, (*shapes)[e.sphere], t0, t1, (*shapes)[plate], plate_pose[plate]);
          if (s && (!found || *s < found->s)) found = Found{k, *s, plate};
        }
        a = b;
      }
      hits += e.hit ? 1 : 0;
      if (!e.hit) {
        EXPECT_FALSE(found) << "sphere " << e.sphere << ": the file has no contact, the library one in interval "
                            << found->interval << " at s = " << found->s << " with plate " << found->plate;
        if (!found) ++matched;
        continue;
      }
      if (!found) {
        ADD_FAILURE() << "sphere " << e.sphere << ": the file has interval " << e.interval << " s = " << e.s
                      << " plate " << e.plate << ", the library no contact";
        continue;
      }
      EXPECT_EQ(found->interval, e.interval) << "sphere " << e.sphere;
      EXPECT_EQ(found->plate, e.plate) << "sphere " << e.sphere;
      EXPECT_NEAR(found->s, e.s, s_tolerance) << "sphere " << e.sphere;
      if (found->interval == e.interval && found->plate == e.plate) {
        worst_s = std::max(worst_s, std::abs(found->s - e.s));
        if (std::abs(found->s - e.s) <= s_tolerance) ++matched;
      }
    }
    std::printf(
        "[ bullets  ] %s: %d spheres sampled, %d with a contact in the file, %d matched, largest |s - s_file| "
        "%.3g\n",
        name, sampled, hits, matched, worst_s);
    EXPECT_EQ(matched, sampled);
  }
}

// The same file through the library's CollisionWorld: every sphere (continuous mode Auto) and
// plate added, the spheres moved frame by frame, one step per frame; the first impact event
// of each sphere must be the file's first contact: same interval and plate, and s within
// 1e-7 in double; in float either within 1e-4 or at a fraction where the sphere is, in
// double, within float's slack of the plate (a graze, where the distance falls so slowly
// along the path that float's length precision becomes a larger error in s).
TEST(WorldBullets, TheCollisionWorldReportsEveryExpectedImpact) {
  const std::string dir = shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  const auto w = read_world_workload(dir, "world_bullets.txt");
  ASSERT_TRUE(w.ok()) << w.error().what();
  const auto expected = read_bullets_expected(workload_path(dir, "world_bullets_expected.txt"));
  ASSERT_TRUE(expected.ok()) << expected.error().what();
  const auto shapes = to_shapes(*w);
  ASSERT_TRUE(shapes.ok()) << shapes.error().what();
  const World& world = w->world;
  WorldSettings settings;
  if (PROXIMA_DOUBLE) settings.ccd_tolerance = Real(1e-10);
  CollisionWorld cw = std::move(CollisionWorld::create(settings)).value();
  for (std::uint32_t i = 0; i < world.objects.size(); ++i) {
    const WorldObject& o = world.objects[i];
    ObjectDesc d;
    d.geometry = (*shapes)[i];
    d.pose = world_transform(o, pose_at_frame(world, i, 0));
    d.kind = o.is_static ? ObjectKind::Static : ObjectKind::Moving;
    ASSERT_EQ(cw.add(d)->index, i);
  }
  ASSERT_FALSE(cw.step(Real(world.dt)).has_value());
  std::vector<std::optional<Found>> first(world.objects.size());
  std::vector<ObjectMove> moves;
  for (int k = 0; k < world.frames; ++k) {
    moves.clear();
    for (std::uint32_t i = 0; i < world.objects.size(); ++i)
      if (!world.objects[i].is_static)
        moves.push_back({ObjectHandle{i, 0}, world_transform(world.objects[i], pose_at_frame(world, i, k + 1))});
    ASSERT_FALSE(cw.move(moves).has_value());
    ASSERT_FALSE(cw.step(Real(world.dt)).has_value());
    for (const ImpactEvent& e : cw.events().impacts)
      if (!first[e.a.index]) first[e.a.index] = Found{k, double(e.toi), e.b.index};
  }
  int hits = 0, matched = 0, grazes = 0;
  double worst = 0;
  for (const BulletContact& e : expected->contacts) {
    const std::optional<Found>& found = first[e.sphere];
    if (!e.hit) {
      EXPECT_FALSE(found) << "sphere " << e.sphere << ": an impact the file does not have, interval " << found->interval
                          << " s = " << found->s << " plate " << found->plate;
      matched += found ? 0 : 1;
      continue;
    }
    ++hits;
    if (!found) {
      ADD_FAILURE() << "sphere " << e.sphere << ": no impact; the file has interval " << e.interval << " s = " << e.s
                    << " plate " << e.plate;
      continue;
    }
    EXPECT_EQ(found->interval, e.interval) << "sphere " << e.sphere;
    EXPECT_EQ(found->plate, e.plate) << "sphere " << e.sphere;
    const double error = std::abs(found->s - e.s);
    worst = std::max(worst, error);
    bool ok = error <= (PROXIMA_DOUBLE ? 1e-7 : 1e-4);
    if (!ok && !PROXIMA_DOUBLE && found->interval == e.interval && found->plate == e.plate) {
      // The sphere's centre at the reported s, in double, and its gap to the plate.
      const Pose p0 = pose_at_frame(world, e.sphere, e.interval), p1 = pose_at_frame(world, e.sphere, e.interval + 1);
      world_ref::Convex ball{
          {world_ref::add(p0.position, world_ref::mul(found->s, world_ref::sub(p1.position, p0.position)))},
          world.objects[e.sphere].shape.radius};
      const world_ref::Placed plate = world_ref::place(*w, e.plate, world.objects[e.plate].pose);
      const double gap = world_ref::gap(ball, plate.convex);
      ok = gap >= 0 && gap <= 2e-4;
      grazes += ok ? 1 : 0;
      EXPECT_TRUE(ok) << "sphere " << e.sphere << ": s = " << found->s << " against " << e.s << ", gap " << gap;
    } else {
      EXPECT_TRUE(ok) << "sphere " << e.sphere << ": s = " << found->s << " against " << e.s;
    }
    matched += ok && found->interval == e.interval && found->plate == e.plate ? 1 : 0;
  }
  std::printf(
      "[ bullets  ] world: %zu spheres, %d impacts in the file, %d matched (%d float grazes), largest |s - s_file| "
      "%.3g\n",
      expected->contacts.size(), hits, matched, grazes, worst);
  EXPECT_EQ(matched, int(expected->contacts.size()));
}

}  // namespace test_world_bullets
}  // namespace proxima::bench

namespace proxima::bench {
namespace test_world_bullets_rotating {

// world_bullets with the plates turning: each plate gets a seeded angular velocity (a random
// axis, 0.5 to 3 rad/s) about its centre and becomes a moving object; the spheres use
// continuous mode Bullet (swept against moving objects). The reference never calls the
// library's narrow phase: per frame interval and plate, conservative advancement in double on
// the exact sphere-box gap in the plate's turning frame (the gap is Lipschitz in s with the
// constant |dC| + |w| dt max|C - c|), from s = 0 until the gap is below 1e-10. The world's
// first impact of each sphere must be the reference's: same interval and plate, s within
// 1e-4 (float) or 1e-6 (double), or, where the two differ by more, the reference gap at the
// world's s within float's slack (a graze); no impact where the reference has none.

/// Rotation matrix of the unit quaternion q (columns are the rotated axes).
std::array<Vec3d, 3> matrix(const Quatd& q) {
  const double w = q.w, x = q.x, y = q.y, z = q.z;
  return {Vec3d{1 - 2 * (y * y + z * z), 2 * (x * y + w * z), 2 * (x * z - w * y)},
          Vec3d{2 * (x * y - w * z), 1 - 2 * (x * x + z * z), 2 * (y * z + w * x)},
          Vec3d{2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}};
}

/// Gap between a sphere (centre p, radius r) and a box (centre c, rotation q, half extents h).
double sphere_box_gap(const Vec3d& p, double r, const Vec3d& c, const Quatd& q, const Vec3d& h) {
  const std::array<Vec3d, 3> m = matrix(q);
  const Vec3d d = world_ref::sub(p, c);
  double outside2 = 0, inside = -1e300;
  for (int a = 0; a < 3; ++a) {
    const double local = std::abs(world_ref::dot(m[a], d)), half = a == 0 ? h.x : a == 1 ? h.y : h.z;
    const double e = local - half;
    if (e > 0) outside2 += e * e;
    inside = std::max(inside, e);
  }
  return (outside2 > 0 ? std::sqrt(outside2) : inside) - r;
}

struct Contact {
  int interval = -1;
  double s = 0;
  std::uint32_t plate = 0;
};

TEST(WorldBullets, TurningPlatesAgainstAnIndependentReference) {
  const std::string dir = test_util::shared_dir();
  if (dir.empty()) GTEST_SKIP() << "shared workloads not found in " << workload_dir();
  auto read = read_world_workload(dir, "world_bullets.txt");
  ASSERT_TRUE(read.ok()) << read.error().what();
  WorldWorkload workload = *read;
  World& world = workload.world;
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), rate(0.5, 3.0);
  std::vector<std::uint32_t> plates;
  for (WorldObject& o : world.objects) {
    if (!o.is_static) continue;
    plates.push_back(o.id);
    Vec3d axis;
    do axis = {unit(rng), unit(rng), unit(rng)};
    while (world_ref::dot(axis, axis) > 1 || world_ref::dot(axis, axis) < 1e-3);
    o.angular_velocity = world_ref::mul(rate(rng) / std::sqrt(world_ref::dot(axis, axis)), axis);
    o.is_static = false;
  }
  const auto shapes = to_shapes(workload);
  ASSERT_TRUE(shapes.ok()) << shapes.error().what();
  const double dt = world.dt;

  // The reference: first contact of each sphere.
  const int spheres = static_cast<int>(world.objects.size() - plates.size());
  std::vector<std::optional<Contact>> reference(static_cast<std::size_t>(spheres));
  int undecided = 0;
  for (int i = 0; i < spheres; ++i) {
    const WorldObject& ball = world.objects[static_cast<std::size_t>(i)];
    const double r = ball.shape.radius;
    for (int k = 0; k < world.frames && !reference[std::size_t(i)]; ++k) {
      const Vec3d c0 = pose_at_frame(world, std::size_t(i), k).position;
      const Vec3d c1 = pose_at_frame(world, std::size_t(i), k + 1).position;
      const Vec3d dc = world_ref::sub(c1, c0);
      for (std::uint32_t p : plates) {
        const WorldObject& plate = world.objects[p];
        const Vec3d c = plate.pose.position, h = plate.shape.half_extents;
        const double reach = std::sqrt(world_ref::dot(h, h)) + r;
        const double seg = test_util::segment_distance(c0, c1, c, c);
        if (seg > reach) continue;
        const Vec3d& om = plate.angular_velocity;
        const double far = std::max(std::sqrt(world_ref::dot(world_ref::sub(c0, c), world_ref::sub(c0, c))),
                                    std::sqrt(world_ref::dot(world_ref::sub(c1, c), world_ref::sub(c1, c))));
        const double lipschitz = std::sqrt(world_ref::dot(dc, dc)) + std::sqrt(world_ref::dot(om, om)) * dt * far;
        double s = 0;
        int steps = 0;
        for (; s <= 1 && steps < 200000; ++steps) {
          const Quatd turned = pose_at_time(plate, frame_time(k, dt) + s * dt, world.lo, world.hi).rotation;
          const double gap = sphere_box_gap(world_ref::add(c0, world_ref::mul(s, dc)), r, c, turned, h);
          if (gap <= 1e-10) break;
          s += gap / lipschitz;
        }
        if (steps == 200000) {
          ++undecided;
          continue;
        }
        if (s <= 1 && (!reference[std::size_t(i)] || s < reference[std::size_t(i)]->s))
          reference[std::size_t(i)] = Contact{k, s, p};
      }
    }
  }

  // The world.
  WorldSettings settings;
  if (PROXIMA_DOUBLE) settings.ccd_tolerance = Real(1e-10);
  CollisionWorld cw = std::move(CollisionWorld::create(settings)).value();
  for (std::uint32_t i = 0; i < world.objects.size(); ++i) {
    ObjectDesc d;
    d.geometry = (*shapes)[i];
    d.pose = world_transform(world.objects[i], pose_at_frame(world, i, 0));
    d.ccd = i < std::uint32_t(spheres) ? CcdMode::Bullet : CcdMode::Off;
    // Spheres meet plates only (the reference knows no sphere-sphere contact).
    d.filter = i < std::uint32_t(spheres) ? CollisionFilter{1, 2, 0} : CollisionFilter{2, 1, 0};
    ASSERT_EQ(cw.add(d)->index, i);
  }
  ASSERT_FALSE(cw.step(Real(dt)).has_value());
  std::vector<std::optional<Contact>> found(static_cast<std::size_t>(spheres));
  std::vector<ObjectMove> moves;
  for (int k = 0; k < world.frames; ++k) {
    moves.clear();
    for (std::uint32_t i = 0; i < world.objects.size(); ++i)
      moves.push_back({ObjectHandle{i, 0}, world_transform(world.objects[i], pose_at_frame(world, i, k + 1))});
    ASSERT_FALSE(cw.move(moves).has_value());
    ASSERT_FALSE(cw.step(Real(dt)).has_value());
    for (const ImpactEvent& e : cw.events().impacts)
      if (e.a.index < std::uint32_t(spheres) && !found[e.a.index])
        found[e.a.index] = Contact{k, double(e.toi), e.b.index};
  }

  const double s_tolerance = PROXIMA_DOUBLE ? 1e-6 : 1e-4, slack = PROXIMA_DOUBLE ? 1e-8 : 2e-4;
  int hits = 0, matched = 0, grazes = 0;
  for (int i = 0; i < spheres; ++i) {
    const auto& want = reference[std::size_t(i)];
    const auto& got = found[std::size_t(i)];
    hits += want ? 1 : 0;
    if (!want && !got) {
      ++matched;
      continue;
    }
    // Where the two differ, the world's answer must be a graze: the reference gap at the
    // world's time within slack.
    auto gap_at = [&](const Contact& c) {
      const WorldObject& plate = world.objects[c.plate];
      const Vec3d c0 = pose_at_frame(world, std::size_t(i), c.interval).position;
      const Vec3d c1 = pose_at_frame(world, std::size_t(i), c.interval + 1).position;
      return sphere_box_gap(world_ref::add(c0, world_ref::mul(c.s, world_ref::sub(c1, c0))),
                            world.objects[std::size_t(i)].shape.radius, plate.pose.position,
                            pose_at_time(plate, frame_time(c.interval, dt) + c.s * dt, world.lo, world.hi).rotation,
                            plate.shape.half_extents);
    };
    if (want && got && got->interval == want->interval && got->plate == want->plate &&
        std::abs(got->s - want->s) <= s_tolerance) {
      ++matched;
      continue;
    }
    if (got && std::abs(gap_at(*got)) <= slack &&
        (!want || got->interval < want->interval ||
         (got->interval == want->interval && got->s <= want->s + s_tolerance))) {
      ++grazes;  // the world stops at a graze the reference passed (or reached a hair later)
      ++matched;
      continue;
    }
    ADD_FAILURE() << "sphere " << i << ": reference "
                  << (want ? std::to_string(want->interval) + " s=" + std::to_string(want->s) + " plate " +
                                 std::to_string(want->plate)
                           : std::string("none"))
                  << ", world "
                  << (got ? std::to_string(got->interval) + " s=" + std::to_string(got->s) + " plate " +
                                std::to_string(got->plate)
                          : std::string("none"));
  }
  std::printf(
      "[ bullets  ] turning plates: %d spheres, %d reference impacts, %d matched (%d grazes), %d undecided "
      "reference intervals\n",
      spheres, hits, matched, grazes, undecided);
  EXPECT_EQ(matched, spheres);
  EXPECT_EQ(undecided, 0);
}

}  // namespace test_world_bullets_rotating
}  // namespace proxima::bench
