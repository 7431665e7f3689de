// The examples of docs/query-protocol.md are real: every request/answer pair in its plain
// code blocks is answered again here and compared (numbers within the precision's
// tolerance, strings exactly), so the document cannot drift from the program.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "doc_examples.hpp"
#include "json_expect.hpp"
#include "query.hpp"

namespace proxima {
namespace test_protocol_doc {

// An oriented box's axes may come in any order and with either sign: replace "axes" and
// "half_extents" by the (half extent, axis) pairs sorted by half extent, each axis turned so
// that its largest component is positive.
tool::Json canonical_obb(tool::Json answer) {
  if (!answer.contains("axes")) return answer;
  std::vector<std::array<double, 4>> pairs;
  for (std::size_t i = 0; i < 3; ++i) {
    std::array<double, 4> p{answer["half_extents"][i].get<double>(), answer["axes"][i][0].get<double>(),
                            answer["axes"][i][1].get<double>(), answer["axes"][i][2].get<double>()};
    std::size_t big = 1;
    for (std::size_t k = 2; k < 4; ++k) {
      if (std::abs(p[k]) > std::abs(p[big]) + 1e-3) big = k;
    }
    if (p[big] < 0) {
      for (std::size_t k = 1; k < 4; ++k) p[k] = -p[k];
    }
    pairs.push_back(p);
  }
  std::sort(pairs.begin(), pairs.end());
  tool::Json list = tool::Json::array();
  for (const auto& p : pairs) list.push_back({p[0], p[1], p[2], p[3]});
  answer.erase("axes");
  answer.erase("half_extents");
  answer["extent_axis_pairs"] = list;
  return answer;
}

TEST(ProtocolDoc, ExamplesAreTheProgramsAnswers) {
  const auto examples = test::read_doc_examples(PROXIMA_QUERY_PROTOCOL_DOC);
  ASSERT_GE(examples.size(), 25u);
  // Mesh files in the examples are named from the repository root, where the document's
  // commands are run.
  const std::filesystem::path saved = std::filesystem::current_path();
  std::filesystem::current_path(std::filesystem::path(PROXIMA_TOOLS_TEST_DATA) / ".." / ".." / "..");
  int rejected_count = 0;
  for (const test::DocExample& e : examples) {
    bool rejected = false;
    const tool::Json actual = tool::answer_line(e.request, rejected);
    const auto expected = tool::Json::parse(e.answer);
    rejected_count += rejected ? 1 : 0;
    EXPECT_EQ(rejected, expected.contains("error")) << "docs line " << e.line;
    // The document shows the float build's answers: compare at float precision in both builds.
    test::expect_json_near(canonical_obb(actual), canonical_obb(expected), "docs line " + std::to_string(e.line),
                           std::max(test::kJsonTolerance, 2e-5));
  }
  EXPECT_GE(rejected_count, 8);
  std::filesystem::current_path(saved);
}

}  // namespace test_protocol_doc
}  // namespace proxima
