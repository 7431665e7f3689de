// The 2D examples of docs/world-protocol.md (its ```world2d blocks) are real: each block is
// one `proxima world --2d` session, replayed here line by line and compared with the answers
// printed under the requests.
#include <gtest/gtest.h>

#include <optional>
#include <string>

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
  const Json unknown = session.answer_line(R"({"op":"hash"})", rejected);
  EXPECT_EQ(unknown["code"], "unknown_op");
}

}  // namespace test_world2d_protocol_doc
}  // namespace proxima
