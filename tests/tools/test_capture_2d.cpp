// A 2D world's capture (debug::CaptureRecorder2D) read back by the tool's reader and drawn by
// `proxima render`'s renderer: the header says dimension 2, the scene has no objects, each
// step carries the world's manifolds (the world's own numbers, at z = 0) and a draw stream
// in the plane z = 0 holding every object; through a known camera (40 pixels per metre, the
// origin at the picture's centre) the crate's colour lies where the crate is, the ground's
// below it, the background around; a failing stream is an error naming "out".
#include <gtest/gtest.h>

#include <proxima/d2/collision_world.hpp>
#include <proxima/debug/capture_recorder_2d.hpp>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "capture_reader.hpp"
#include "capture_render.hpp"

namespace proxima::test_capture_2d {

struct Recorded2D {
  std::string text;
  std::vector<d2::WorldManifold> manifolds;  ///< after the last step
  std::size_t impacts = 0;                   ///< of the last step
  std::vector<debug::WorldObject2D> objects;
};

/// A static ground box, a crate 0.2 above it, a sensor; two steps, the crate moved 0.1 into
/// the ground before the second.
Recorded2D record_2d(const debug::CaptureOptions& options) {
  Recorded2D r;
  d2::CollisionWorld world = d2::CollisionWorld::create().value();
  const auto add = [&](const d2::ObjectDesc& desc) {
    r.objects.push_back({world.add(desc).value(), desc});
    return r.objects.back().handle;
  };
  add({d2::Polygon::box(Real(2), Real(0.5)).value(), d2::Pose::identity(), d2::ObjectKind::Static});
  const d2::ObjectHandle crate =
      add({d2::Polygon::box(Real(0.5), Real(0.5)).value(), d2::Pose::from({0, Real(1.2)}, 0)});
  d2::ObjectDesc sensor{d2::Circle::create(Real(0.3)).value(), d2::Pose::from({Real(1.5), Real(1.5)}, 0)};
  sensor.sensor = true;
  add(sensor);
  std::ostringstream out;
  debug::CaptureRecorder2D recorder(out, options);
  EXPECT_FALSE(world.step());
  EXPECT_FALSE(recorder.record_step(world, r.objects, Real(0.02)));
  EXPECT_FALSE(world.move(crate, d2::Pose::from({0, Real(0.9)}, 0)));
  EXPECT_FALSE(world.step());
  EXPECT_FALSE(recorder.record_step(world, r.objects, Real(0.02)));
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

TEST(Capture2D, ReadsBackAsADimension2Capture) {
  const Recorded2D r = record_2d({});
  std::istringstream in(r.text);
  const Result<tool::Capture> read = tool::read_capture(in);
  ASSERT_TRUE(read.ok()) << read.error().what();
  const tool::Capture& c = read.value();
  EXPECT_EQ(c.dimension, 2);
  EXPECT_TRUE(c.objects.empty());
  EXPECT_TRUE(c.snapshot.empty());
  ASSERT_EQ(c.steps.size(), 2u);
  EXPECT_TRUE(c.steps[0].contacts.empty());  // the crate starts 0.2 above the ground
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
  // Fans of 4, 4 and 24 triangles (the capture's segments per turn), every vertex at z = 0.
  const DrawBuffer& draw = c.steps[1].draw;
  EXPECT_EQ(draw.triangles.size(), 4 + 4 + std::size_t(debug::TessellationOptions{}.segments));
  EXPECT_TRUE(std::all_of(draw.triangles.begin(), draw.triangles.end(),
                          [](const DrawTriangle& t) { return t.a.z == 0 && t.b.z == 0 && t.c.z == 0; }));
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
  EXPECT_EQ(at(0, 1.2), debug::object_color(r.objects[1].desc));   // the crate, above its contact labels
  EXPECT_EQ(at(0, -0.3), debug::object_color(r.objects[0].desc));  // the ground
  EXPECT_EQ(at(-2.3, 2.3), options.background);
}

TEST(Capture2D, AFailingStreamIsAnErrorNamingOut) {
  d2::CollisionWorld world = d2::CollisionWorld::create().value();
  ASSERT_FALSE(world.step());
  std::ostringstream out;
  out.setstate(std::ios::badbit);
  debug::CaptureRecorder2D recorder(out);
  const std::optional<Error> error = recorder.record_step(world, {}, Real(0.02));
  ASSERT_TRUE(error.has_value());
  EXPECT_EQ(error->field, "out");
  EXPECT_EQ(recorder.steps_recorded(), 0u);
}

}  // namespace proxima::test_capture_2d
