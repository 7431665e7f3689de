// The 2D examples of docs/world-protocol.md (its ```world2d blocks) are real: each block is
// one `proxima world --2d` session, replayed here line by line and compared with the answers
// printed under the requests; the state operations (hash, save, load) round-trip a world.
#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <unistd.h>

#include "doc_examples.hpp"
#include "json_expect.hpp"
#include "world2d_session.hpp"

namespace proxima {
namespace test_world2d_protocol_doc {

using tool::Json;

TEST(World2dProtocolDoc, ExamplesAreTheProgramsAnswers) {
  const auto examples = test::read_doc_examples(std::string(PROXIMA_SOURCE_DIR) + "/docs/world-protocol.md", "world2d");
  ASSERT_GE(examples.size(), 10u);
  int block = -1, rejected_count = 0;
  std::optional<tool::WorldSession2d> session;
  for (const test::DocExample& e : examples) {
    const std::string where = "docs line " + std::to_string(e.line);
    if (e.block != block) {
      block = e.block;
      session.emplace(tool::WorldSession2d::create().value());
    }
    bool rejected = false;
    const Json actual = session->answer_line(e.request, rejected);
    const Json expected = Json::parse(e.answer);
    rejected_count += rejected ? 1 : 0;
    EXPECT_EQ(rejected, expected.contains("error")) << where << ": " << actual.dump();
    test::expect_json_near(actual, expected, where, std::max(test::kJsonTolerance, 2e-5));
  }
  EXPECT_GE(rejected_count, 1);
}

TEST(World2dProtocol, ABadRequestChangesNothing) {
  tool::WorldSession2d session = tool::WorldSession2d::create().value();
  bool rejected = false;
  session.answer_line(R"({"op":"add","geometry":{"type":"circle","radius":1}})", rejected);
  ASSERT_FALSE(rejected);
  const Json bad = session.answer_line(R"({"op":"add","geometry":{"type":"chain","points":[[0,0],[1,0]]}})", rejected);
  EXPECT_TRUE(rejected);
  EXPECT_EQ(bad["field"], "kind");
  const Json bad_pose = session.answer_line(R"({"op":"move","object":0,"pose":{"position":[1,2,3]}})", rejected);
  EXPECT_EQ(bad_pose["field"], "pose.position");
  const Json found = session.answer_line(R"({"op":"overlap","geometry":{"type":"circle","radius":0.5}})", rejected);
  EXPECT_EQ(found["objects"], Json::array({0}));
  const Json unknown = session.answer_line(R"({"op":"attach"})", rejected);
  EXPECT_EQ(unknown["code"], "unknown_op");
}

/// Answers a line that must be accepted.
Json answer(tool::WorldSession2d& session, const std::string& line) {
  bool rejected = false;
  Json a = session.answer_line(line, rejected);
  EXPECT_FALSE(rejected) << line << " -> " << a.dump();
  return a;
}

TEST(World2dProtocol, ASavedWorldLoadsWithItsHashAndStepsOnAlike) {
  const std::string file =
      (std::filesystem::temp_directory_path() / ("proxima_world2d_" + std::to_string(getpid()) + ".pxw")).string();
  tool::WorldSession2d session = tool::WorldSession2d::create().value();
  answer(session, R"({"op":"add","geometry":{"type":"circle","radius":1}})");
  answer(session, R"({"op":"add","geometry":{"type":"box2d","half_extents":[1,1]},"pose":{"position":[1.5,0.2]}})");
  answer(session, R"({"op":"step"})");
  const Json hash = answer(session, R"({"op":"hash"})")["hash"];
  answer(session, R"({"op":"save","file":")" + file + R"("})");
  answer(session, R"({"op":"move","object":1,"pose":{"position":[5,0]}})");
  EXPECT_NE(answer(session, R"({"op":"hash"})")["hash"], hash);
  EXPECT_EQ(answer(session, R"({"op":"load","file":")" + file + R"("})")["objects"], 2);
  EXPECT_EQ(answer(session, R"({"op":"hash"})")["hash"], hash);
  EXPECT_EQ(answer(session, R"({"op":"step"})")["persist"], Json::array({Json::array({0, 1})}));
  bool rejected = false;
  const Json missing = session.answer_line(R"({"op":"load","file":"no/such/file.pxw"})", rejected);
  EXPECT_TRUE(rejected);
  EXPECT_EQ(missing["field"], "file");
  std::filesystem::remove(file);
}

}  // namespace test_world2d_protocol_doc
}  // namespace proxima
