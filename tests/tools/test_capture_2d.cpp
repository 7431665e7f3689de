// A 2D world's capture (debug::CaptureRecorder2D) read back by the tool's reader and drawn by
// `proxima render`'s renderer: the header says dimension 2; the scene lists every object with
// its 2D geometry, its pose in the plane z = 0 and its fill as a flat mesh whose area is the
// shape's (the polygons' exactly, the circle's inscribed polygon's), and a snapshot that
// loads into a world with the recorded state hash; each step carries the objects that moved,
// were added or removed, the world's manifolds (the world's own numbers, at z = 0) and a
// draw stream of outlines and contacts in the plane z = 0; through a known camera (40 pixels
// per metre, the origin at the picture's centre) the crate's colour lies where the crate is,
// the ground's below it, the background around; a failing stream is an error naming "out".
#include <gtest/gtest.h>

#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder_2d.hpp>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "base64_decode.hpp"
#include "capture_reader.hpp"
#include "capture_render.hpp"

namespace proxima::test_capture_2d {

struct Recorded2D {
  std::string text;
  std::vector<d2::WorldManifold> manifolds;  ///< after the last step
  std::size_t impacts = 0;                   ///< of the last step
  std::vector<d2::ObjectDesc> descs;         ///< ground, crate, sensor, as added
  std::vector<d2::ObjectHandle> handles;     ///< ground, crate, sensor, ball (removed before step 2)
  std::uint64_t hash_at_scene = 0;           ///< the world's state hash when the scene was written
};

/// A static ground box, a crate 0.2 above it, a sensor and a ball; two steps, the crate moved
/// 0.1 into the ground and the ball removed before the second.
Recorded2D record_2d(const debug::CaptureOptions& options) {
  Recorded2D r;
  d2::CollisionWorld world = d2::CollisionWorld::create().value();
  const auto add = [&](const d2::ObjectDesc& desc) {
    r.descs.push_back(desc);
    r.handles.push_back(world.add(desc).value());
    return r.handles.back();
  };
  add({d2::Polygon::box(Real(2), Real(0.5)).value(), d2::Pose::identity(), d2::ObjectKind::Static});
  const d2::ObjectHandle crate =
      add({d2::Polygon::box(Real(0.5), Real(0.5)).value(), d2::Pose::from({0, Real(1.2)}, Real(0.25))});
  d2::ObjectDesc sensor{d2::Circle::create(Real(0.3)).value(), d2::Pose::from({Real(1.5), Real(1.5)}, 0)};
  sensor.sensor = true;
  add(sensor);
  const d2::ObjectHandle ball = add({d2::Circle::create(Real(0.2)).value(), d2::Pose::from({Real(-1.5), Real(2)}, 0)});
  std::ostringstream out;
  debug::CaptureRecorder2D recorder(out, options);
  EXPECT_FALSE(world.step());
  r.hash_at_scene = world.state_hash();
  EXPECT_FALSE(recorder.record_step(world, Real(0.02)));
  EXPECT_FALSE(world.move(crate, d2::Pose::from({0, Real(0.9)}, 0)));
  EXPECT_FALSE(world.remove(ball));
  EXPECT_FALSE(world.step());
  EXPECT_FALSE(recorder.record_step(world, Real(0.02)));
  EXPECT_EQ(recorder.steps_recorded(), 2u);
  r.manifolds.assign(world.manifolds().begin(), world.manifolds().end());
  r.impacts = world.events().impacts.size();
  r.text = out.str();
  return r;
}

debug::CaptureOptions camera_above() {
  debug::CaptureOptions options;
  options.camera = debug::CaptureCamera{Vec3(0, 0, 10), Vec3(0), Vec3(0, 1, 0), Real(0), Real(5)};
  return options;
}

/// Sum of the signed areas of a mesh's triangles seen from +z (positive: counter-clockwise).
double signed_area(const tool::CaptureObject& o) {
  double area = 0;
  for (std::size_t i = 0; i + 2 < o.indices.size(); i += 3) {
    const Vec3 a = o.positions[o.indices[i]], b = o.positions[o.indices[i + 1]], c = o.positions[o.indices[i + 2]];
    area += 0.5 * (double(b.x - a.x) * double(c.y - a.y) - double(b.y - a.y) * double(c.x - a.x));
  }
  return area;
}

TEST(Capture2D, TheSceneListsEveryObjectWithItsFillAndSnapshot) {
  const Recorded2D r = record_2d({});
  std::istringstream in(r.text);
  const Result<tool::Capture> read = tool::read_capture(in);
  ASSERT_TRUE(read.ok()) << read.error().what();
  const tool::Capture& c = read.value();
  EXPECT_EQ(c.dimension, 2);
  ASSERT_EQ(c.objects.size(), 4u);
  const char* types[] = {"polygon", "polygon", "circle", "circle"};
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(c.objects[i].id, r.handles[i].to_integer());
    EXPECT_EQ(c.objects[i].geometry_type, types[i]);
    EXPECT_EQ(c.objects[i].sensor, i == 2);
    EXPECT_TRUE(std::all_of(c.objects[i].positions.begin(), c.objects[i].positions.end(),
                            [](const Vec3& p) { return p.z == 0; }));
  }
  EXPECT_EQ(c.objects[0].color, debug::object_color(r.descs[0]));
  EXPECT_NEAR(signed_area(c.objects[0]), 4 * 2 * 0.5, 1e-5);  // the ground box, 4 x 1
  EXPECT_NEAR(signed_area(c.objects[1]), 1, 1e-6);            // the crate
  const int n = debug::TessellationOptions{}.segments;        // the inscribed n-gon of the sensor
  EXPECT_EQ(c.objects[2].indices.size(), 3u * std::size_t(n));
  EXPECT_NEAR(signed_area(c.objects[2]), 0.5 * n * 0.09 * std::sin(2 * M_PI / n), 1e-6);
  // The crate's pose: position at z = 0 and the turn of 0.25 rad about +z.
  const Transform crate = c.objects[1].pose;
  EXPECT_EQ(crate.position, Vec3(0, Real(1.2), 0));
  EXPECT_NEAR(crate.rotation.w, std::cos(0.125), 1e-6);
  EXPECT_NEAR(crate.rotation.z, std::sin(0.125), 1e-6);
  EXPECT_EQ(crate.rotation.x, 0);
  EXPECT_EQ(crate.rotation.y, 0);
  ASSERT_FALSE(c.snapshot.empty());
  std::istringstream snapshot(test::decode_base64(c.snapshot));
  const Result<d2::CollisionWorld> world = d2::CollisionWorld::load(snapshot);
  ASSERT_TRUE(world.ok()) << world.error().what();
  EXPECT_EQ(world.value().state_hash(), r.hash_at_scene);
}

TEST(Capture2D, StepsCarryMovesRemovalsManifoldsAndOutlines) {
  const Recorded2D r = record_2d({});
  std::istringstream in(r.text);
  const tool::Capture c = tool::read_capture(in).value();
  ASSERT_EQ(c.steps.size(), 2u);
  EXPECT_TRUE(c.steps[0].contacts.empty());  // the crate starts 0.2 above the ground
  const Result<std::vector<tool::CaptureObject>> after = tool::objects_at(c, 1);
  ASSERT_TRUE(after.ok()) << after.error().what();
  ASSERT_EQ(after.value().size(), 3u);  // the ball is removed
  EXPECT_EQ(after.value()[1].pose.position, Vec3(0, Real(0.9), 0));
  EXPECT_EQ(after.value()[1].pose.rotation, Quat(1, 0, 0, 0));
  ASSERT_EQ(r.manifolds.size(), 1u);
  ASSERT_EQ(c.steps[1].contacts.size(), 1u);
  const tool::CaptureManifold& m = c.steps[1].contacts[0];
  const d2::Manifold& expected = r.manifolds[0].manifold;
  EXPECT_EQ(m.a, r.manifolds[0].pair.a.to_integer());
  EXPECT_EQ(m.normal, Vec3(expected.normal.x, expected.normal.y, 0));
  ASSERT_EQ(m.points.size(), std::size_t(expected.count));
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    EXPECT_EQ(m.points[i].a, Vec3(expected.points[i].point_a.x, expected.points[i].point_a.y, 0));
    EXPECT_EQ(m.points[i].depth, expected.points[i].depth);
    EXPECT_NEAR(m.points[i].depth, 0.1, 1e-5);
  }
  // The fills are the scene's meshes; the draw stream holds the outlines (4, 4 and the
  // capture's segments per turn) and the contacts, every vertex at z = 0.
  const DrawBuffer& draw = c.steps[1].draw;
  EXPECT_TRUE(draw.triangles.empty());
  EXPECT_GE(draw.lines.size(), 4 + 4 + std::size_t(debug::TessellationOptions{}.segments));
  EXPECT_TRUE(std::all_of(draw.lines.begin(), draw.lines.end(),
                          [](const DrawLine& l) { return l.from.z == 0 && l.to.z == 0; }));
  EXPECT_EQ(draw.points.size(), 2 * m.points.size() + r.impacts);  // markers at both witnesses, one per impact
}

TEST(Capture2D, RenderedFromAboveTheObjectsAreWhereTheWorldHasThem) {
  const Recorded2D r = record_2d(camera_above());
  std::istringstream in(r.text);
  const tool::Capture c = tool::read_capture(in).value();
  tool::RenderOptions options;
  options.width = options.height = 200;
  const Result<tool::Image> image = tool::render_image(c, 1, options);
  ASSERT_TRUE(image.ok()) << image.error().what();
  const auto at = [&](double x, double y) { return image->at(int(100 + 40 * x), int(100 - 40 * y)); };
  EXPECT_EQ(at(0, 1.2), debug::object_color(r.descs[1]));   // the crate, above its contact labels
  EXPECT_EQ(at(0, -0.3), debug::object_color(r.descs[0]));  // the ground
  EXPECT_EQ(at(-2.3, 2.3), options.background);
}

TEST(Capture2D, AFailingStreamIsAnErrorNamingOut) {
  d2::CollisionWorld world = d2::CollisionWorld::create().value();
  ASSERT_FALSE(world.step());
  std::ostringstream out;
  out.setstate(std::ios::badbit);
  debug::CaptureRecorder2D recorder(out);
  const std::optional<Error> error = recorder.record_step(world, Real(0.02));
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->field, "out");
  EXPECT_EQ(recorder.steps_recorded(), 0u);
}

}  // namespace proxima::test_capture_2d
