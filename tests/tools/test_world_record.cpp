// `proxima world --record FILE`: every step request writes one step of a capture that the
// tool's reader accepts, holding the session's objects, moves, contacts and ray queries;
// with --2d, a 2D capture of the 2D world's objects, moves, removals and contacts.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>

#include "capture_reader.hpp"
#include "cli_run.hpp"

namespace proxima::test_world_record {

const char* const kRequests =
    R"({"op":"add","geometry":{"type":"box","half_extents":[2,2,0.5]},"kind":"static"}
{"op":"add","geometry":{"type":"sphere","radius":0.5},"pose":{"position":[0,0,0.9]}}
{"op":"step","dt":0.02}
{"op":"move","object":1,"pose":{"position":[0,0,3]}}
{"op":"raycast","origin":[-5,0,3],"direction":[1,0,0]}
{"op":"step","dt":0.02}
{"op":"set_geometry","object":1,"geometry":{"type":"capsule","radius":0.25,"half_length":0.5}}
{"op":"step"}
)";

TEST(WorldRecord, EveryStepIsRecorded) {
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "record_requests.jsonl") << kRequests;
  const std::string capture_path = dir + "record.capture.jsonl";
  const test::CliRun run = test::run_cli("world --record '" + capture_path + "' '" + dir + "record_requests.jsonl'");
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(capture_path);
  const Result<tool::Capture> read = tool::read_capture(in);
  ASSERT_TRUE(read.ok()) << read.error().what();
  const tool::Capture& c = read.value();
  ASSERT_EQ(c.objects.size(), 2u);
  ASSERT_EQ(c.steps.size(), 3u);
  ASSERT_EQ(c.steps[0].contacts.size(), 1u);
  EXPECT_NEAR(c.steps[0].contacts[0].points[0].depth, 0.1, 1e-4);
  ASSERT_EQ(c.steps[1].poses.size(), 1u);
  EXPECT_EQ(c.steps[1].poses[0].second.position, Vec3(0, 0, 3));
  EXPECT_TRUE(c.steps[1].contacts.empty());
  EXPECT_EQ(c.steps[1].query_count, 1u);
  ASSERT_EQ(c.steps[2].added.size(), 1u);  // the new geometry
  EXPECT_EQ(c.steps[2].added[0].geometry_type, "capsule");
  EXPECT_NEAR(c.steps[2].dt, 1.0 / 60, 1e-7);
}

const char* const kRequests2d =
    R"({"op":"add","geometry":{"type":"chain","points":[[10,0],[5,0],[0,0],[-5,0]]},"kind":"static"}
{"op":"add","geometry":{"type":"box2d","half_extents":[0.5,0.5]},"pose":{"position":[2,0.49]}}
{"op":"add","geometry":{"type":"circle","radius":0.25},"pose":{"position":[-3,4]}}
{"op":"step"}
{"op":"move","object":1,"pose":{"position":[2,3],"angle":0.5}}
{"op":"remove","object":2}
{"op":"step"}
)";

TEST(WorldRecord, Every2dStepIsRecorded) {
  const std::string dir = testing::TempDir();
  std::ofstream(dir + "record_requests_2d.jsonl") << kRequests2d;
  const std::string capture_path = dir + "record_2d.capture.jsonl";
  const test::CliRun run =
      test::run_cli("world --2d --record '" + capture_path + "' '" + dir + "record_requests_2d.jsonl'");
  ASSERT_EQ(run.status, 0) << run.output;
  std::ifstream in(capture_path);
  const Result<tool::Capture> read = tool::read_capture(in);
  ASSERT_TRUE(read.ok()) << read.error().what();
  const tool::Capture& c = read.value();
  EXPECT_EQ(c.dimension, 2);
  ASSERT_EQ(c.objects.size(), 3u);
  EXPECT_EQ(c.objects[0].geometry_type, "chain");
  EXPECT_EQ(c.objects[1].geometry_type, "polygon");
  EXPECT_EQ(c.objects[2].geometry_type, "circle");
  EXPECT_FALSE(c.snapshot.empty());
  ASSERT_EQ(c.steps.size(), 2u);
  ASSERT_EQ(c.steps[0].contacts.size(), 1u);  // the box rests 0.01 deep on the chain
  EXPECT_NEAR(c.steps[0].contacts[0].points[0].depth, 0.01, 1e-5);
  ASSERT_EQ(c.steps[1].poses.size(), 1u);
  EXPECT_EQ(c.steps[1].poses[0].second.position, Vec3(2, 3, 0));
  EXPECT_NEAR(c.steps[1].poses[0].second.rotation.z, std::sin(0.25), 1e-6);
  ASSERT_EQ(c.steps[1].removed.size(), 1u);
  EXPECT_EQ(c.steps[1].removed[0], c.objects[2].id);
  EXPECT_TRUE(c.steps[1].contacts.empty());
  EXPECT_EQ(c.steps[1].dt, 1);
}

TEST(WorldRecord, UnwritableFileFailsBeforeAnything) {
  const test::CliRun run = test::run_cli("world --record /nonexistent-dir/x.jsonl < /dev/null 2>/dev/null");
  EXPECT_EQ(run.status, 1);
  const test::CliRun two_d = test::run_cli("world --2d --record /nonexistent-dir/x.jsonl < /dev/null 2>/dev/null");
  EXPECT_EQ(two_d.status, 1);
}

}  // namespace proxima::test_world_record
