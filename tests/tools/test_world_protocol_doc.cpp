// The examples of docs/world-protocol.md are real: each plain code block is one session,
// answered again here from an empty world with the default options and compared with the
// document (numbers within the precision's tolerance, strings exactly). State hashes differ
// between builds, so a documented hash only has to be 16 hex digits, and equal documented
// hashes of a block must be equal answers (different ones different).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <string>
#include <unistd.h>

#include "doc_examples.hpp"
#include "json_expect.hpp"
#include "world_session.hpp"

namespace proxima {
namespace test_world_protocol_doc {

using tool::Json;

TEST(WorldProtocolDoc, ExamplesAreTheProgramsAnswers) {
  const auto examples = test::read_doc_examples(std::string(PROXIMA_SOURCE_DIR) + "/docs/world-protocol.md");
  ASSERT_GE(examples.size(), 60u);
  // save / load examples write their files in a scratch directory.
  const std::filesystem::path saved = std::filesystem::current_path();
  const std::filesystem::path scratch =
      std::filesystem::temp_directory_path() / ("proxima_world_doc_" + std::to_string(getpid()));
  std::filesystem::create_directories(scratch);
  std::filesystem::current_path(scratch);

  const std::regex hex16("[0-9a-f]{16}");
  int block = -1;
  int blocks = 0;
  int rejected_count = 0;
  std::optional<tool::WorldSession> session;
  std::map<std::string, std::string> doc_to_actual;
  std::map<std::string, std::string> actual_to_doc;
  for (const test::DocExample& e : examples) {
    const std::string where = "docs line " + std::to_string(e.line);
    if (e.block != block) {
      block = e.block;
      ++blocks;
      session.emplace(tool::WorldSession::create().value());
      doc_to_actual.clear();
      actual_to_doc.clear();
    }
    bool rejected = false;
    Json actual = session->answer_line(e.request, rejected);
    const Json expected = Json::parse(e.answer);
    rejected_count += rejected ? 1 : 0;
    EXPECT_EQ(rejected, expected.contains("error")) << where << ": " << actual.dump();
    if (expected.contains("hash") && actual.contains("hash") && actual["hash"].is_string()) {
      const std::string doc = expected["hash"].get<std::string>();
      const std::string got = actual["hash"].get<std::string>();
      EXPECT_TRUE(std::regex_match(doc, hex16)) << where;
      EXPECT_TRUE(std::regex_match(got, hex16)) << where;
      const auto [d, d_new] = doc_to_actual.emplace(doc, got);
      const auto [a, a_new] = actual_to_doc.emplace(got, doc);
      EXPECT_EQ(d->second, got) << where << ": the document's equal hashes differ here";
      EXPECT_EQ(a->second, doc) << where << ": the document's different hashes are equal here";
      actual["hash"] = doc;
    }
    // The document shows the float build's answers: compare at float precision in both builds.
    test::expect_json_near(actual, expected, where, std::max(test::kJsonTolerance, 2e-5));
  }
  EXPECT_GE(blocks, 7);
  EXPECT_GE(rejected_count, 12);
  std::filesystem::current_path(saved);
  std::filesystem::remove_all(scratch);
}

}  // namespace test_world_protocol_doc
}  // namespace proxima
