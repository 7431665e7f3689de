// Captures written by CaptureRecorder and read back by the tool's reader: what the world
// did is what the file says (poses bit for bit, moved objects only, added and removed
// objects, manifolds, the draw stream), the snapshot rebuilds the world, Python's json
// module reads every line, and malformed or truncated files get errors naming the line and
// the field.
#include <gtest/gtest.h>

#include <proxima/debug/capture_recorder.hpp>
#include <proxima/debug/tessellate.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "base64_decode.hpp"
#include "capture_reader.hpp"

namespace proxima::test_capture {

using test::decode_base64;

struct Recorded {
  std::string text;
  std::uint64_t hash_after_first_step = 0;
  ObjectHandle ground, box, ball;
};

/// Two boxes resting on each other and a sphere: step 0, the box moves (step 1), a sphere
/// is added (step 2) and the box removed (step 3).
Recorded record_scene() {
  Recorded r;
  CollisionWorld world = CollisionWorld::create().value();
  ObjectDesc ground;
  ground.geometry = Box::create(Vec3(2, 2, 0.5)).value();
  ground.kind = ObjectKind::Static;
  ObjectDesc box;
  box.geometry = Box::create(Vec3(0.5)).value();
  box.pose.position = Vec3(0, 0, 0.95f);
  r.ground = world.add(ground).value();
  r.box = world.add(box).value();
  std::ostringstream out;
  debug::CaptureRecorder recorder(out);
  EXPECT_FALSE(world.step(Real(0.02)));
  r.hash_after_first_step = world.state_hash();
  EXPECT_FALSE(recorder.record_step(world, Real(0.02)));
  EXPECT_FALSE(world.move(r.box, Transform{Vec3(0.1f, 0.2f, 0.9f), glm::normalize(Quat(1, 0, 0, 0.1f))}));
  EXPECT_FALSE(world.step(Real(0.02)));
  const Ray ray{Vec3(-5, 0.2f, 0.9f), Vec3(1, 0, 0)};
  const auto hits = world.raycast(ray, Real(10));
  recorder.record_ray(ray, Real(10), hits.value());
  EXPECT_FALSE(recorder.record_step(world, Real(0.02)));
  ObjectDesc ball;
  ball.geometry = Sphere::create(Real(0.3f)).value();
  ball.pose.position = Vec3(3, 0, 0);
  r.ball = world.add(ball).value();
  EXPECT_FALSE(world.step(Real(0.02)));
  EXPECT_FALSE(recorder.record_step(world, Real(0.02)));
  EXPECT_FALSE(world.remove(r.box));
  EXPECT_FALSE(world.step(Real(0.02)));
  EXPECT_FALSE(recorder.record_step(world, Real(0.02)));
  r.text = out.str();
  return r;
}

Result<tool::Capture> read_text(const std::string& text) {
  std::istringstream in(text);
  return tool::read_capture(in);
}

TEST(Capture, RoundTripsWhatTheWorldDid) {
  const Recorded r = record_scene();
  const Result<tool::Capture> read = read_text(r.text);
  ASSERT_TRUE(read.ok()) << read.error().what();
  const tool::Capture& c = read.value();
  EXPECT_EQ(c.version, 1);
  EXPECT_EQ(c.units, "m");
  ASSERT_EQ(c.objects.size(), 2u);
  EXPECT_EQ(c.objects[0].kind, "static");
  EXPECT_EQ(c.objects[1].geometry_type, "box");
  EXPECT_EQ(c.objects[1].indices.size(), 3 * debug::tessellate(*Box::create(Vec3(0.5))).triangle_count());
  ASSERT_EQ(c.steps.size(), 4u);
  EXPECT_TRUE(c.steps[0].poses.empty());
  ASSERT_EQ(c.steps[0].contacts.size(), 1u);
  EXPECT_EQ(c.steps[0].contacts[0].a, r.ground.to_integer());
  EXPECT_EQ(c.steps[0].draw.points.size(), 2 * c.steps[0].contacts[0].points.size());
  for (const tool::CapturePoint& p : c.steps[0].contacts[0].points) EXPECT_NEAR(p.depth, 0.05, 1e-4);
  ASSERT_EQ(c.steps[1].poses.size(), 1u);  // only the box moved
  EXPECT_EQ(c.steps[1].poses[0].first, r.box.to_integer());
  EXPECT_EQ(c.steps[1].poses[0].second.position, Vec3(0.1f, 0.2f, 0.9f));
  EXPECT_EQ(c.steps[1].poses[0].second.rotation, glm::normalize(Quat(1, 0, 0, 0.1f)));  // bit for bit
  EXPECT_EQ(c.steps[1].query_count, 1u);
  ASSERT_EQ(c.steps[2].added.size(), 1u);
  EXPECT_EQ(c.steps[2].added[0].geometry_type, "sphere");
  ASSERT_EQ(c.steps[3].removed.size(), 1u);
  EXPECT_EQ(c.steps[3].removed[0], r.box.to_integer());
  const auto at1 = tool::objects_at(c, 1);
  ASSERT_TRUE(at1.ok());
  ASSERT_EQ(at1.value().size(), 2u);
  EXPECT_EQ(at1.value()[1].pose.position, Vec3(0.1f, 0.2f, 0.9f));
  const auto at3 = tool::objects_at(c, 3);
  ASSERT_TRUE(at3.ok());
  ASSERT_EQ(at3.value().size(), 2u);
  EXPECT_EQ(at3.value()[1].id, r.ball.to_integer());
  EXPECT_FALSE(tool::objects_at(c, 4).ok());
}

TEST(Capture, SnapshotRebuildsTheWorld) {
  const Recorded r = record_scene();
  const tool::Capture c = read_text(r.text).value();
  ASSERT_FALSE(c.snapshot.empty());
  std::istringstream snapshot(decode_base64(c.snapshot));
  const Result<CollisionWorld> world = CollisionWorld::load(snapshot);
  ASSERT_TRUE(world.ok()) << world.error().what();
  EXPECT_EQ(world.value().state_hash(), r.hash_after_first_step);
}

TEST(Capture, PythonJsonReadsEveryLine) {
  if (!std::filesystem::exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  const std::string path = testing::TempDir() + "capture_python.jsonl";
  std::ofstream(path) << record_scene().text;
  const std::string command =
      "/usr/bin/python3 -c \"import json,sys; r=[json.loads(l) for l in open(sys.argv[1])]; "
      "assert r[0]['format']=='proxima-capture' and r[1]['type']=='scene' and "
      "len(r)==6 and max(abs(a-b) for a,b in zip(r[3]['poses'][0]['position'],[0.1,0.2,0.9]))<1e-6\" " +
      path;
  EXPECT_EQ(std::system(command.c_str()), 0);
}

/// The capture's lines, for editing.
std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

void expect_error(const std::string& text, const std::string& field, const std::string& message_part) {
  const Result<tool::Capture> read = read_text(text);
  ASSERT_FALSE(read.ok());
  EXPECT_EQ(read.error().field, field) << read.error().what();
  EXPECT_NE(read.error().message.find(message_part), std::string::npos) << read.error().what();
}

TEST(Capture, MalformedFilesNameTheLineAndField) {
  const std::vector<std::string> lines = lines_of(record_scene().text);
  expect_error("", "line 1", "no header");
  expect_error(lines[0] + "\n", "line 2", "no scene");
  std::vector<std::string> edited = lines;
  edited[0].replace(edited[0].find("\"version\":1"), 11, "\"version\":9");
  expect_error(joined(edited), "line 1: version", "not supported");
  edited = lines;
  edited[2].replace(edited[2].find("\"dt\":"), 5, "\"dT\":");
  expect_error(joined(edited), "line 3: dt", "missing");
  edited = lines;
  edited[3].replace(edited[3].find("\"index\":1"), 9, "\"index\":7");
  expect_error(joined(edited), "line 4: index", "expected step 1");
  // A truncated file: the last line cut in the middle.
  const std::string text = joined(lines);
  expect_error(text.substr(0, text.size() - 40), "line 6", "truncated");
  // A mesh index past the positions.
  edited = lines;
  const std::size_t at = edited[1].find("\"indices\":[") + 11;
  edited[1].replace(at, edited[1].find_first_of(",]", at) - at, "999");
  expect_error(joined(edited), "line 2: objects[0].mesh.indices[0]", "past the last position");
}

}  // namespace proxima::test_capture
