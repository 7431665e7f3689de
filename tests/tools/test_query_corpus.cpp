// The answer corpus: 5,235 requests over every operation and every shape kind
// (tests/tools/corpus/requests.jsonl, written by make_corpus.py beside it) and the answers
// `proxima query` gave for them in each precision, recorded before the geometry redesign.
// The answers must stay byte-identical: a refactoring that changes one digit of one answer
// fails here, with the line and both texts.
#include <gtest/gtest.h>

#include <proxima/core/math.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "query.hpp"

namespace proxima {
namespace test_query_corpus {

std::vector<std::string> lines_of(std::istream& in) {
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

TEST(QueryCorpus, AnswersAreByteIdenticalToTheRecordedOnes) {
  // Mesh files in the corpus are named relative to the repository root.
  const std::filesystem::path root = PROXIMA_SOURCE_DIR;
  const std::filesystem::path corpus = root / "tests/tools/corpus";
  const char* answers_name = sizeof(Real) == sizeof(float) ? "answers_float.jsonl" : "answers_double.jsonl";
  std::ifstream requests(corpus / "requests.jsonl");
  std::ifstream recorded(corpus / answers_name);
  ASSERT_TRUE(requests && recorded) << "corpus files missing under " << corpus;

  const std::filesystem::path previous = std::filesystem::current_path();
  std::filesystem::current_path(root);
  std::ostringstream out;
  const tool::QuerySummary summary = tool::run_queries(requests, out);
  std::filesystem::current_path(previous);

  std::istringstream answered_text(out.str());
  const std::vector<std::string> answered = lines_of(answered_text);
  const std::vector<std::string> expected = lines_of(recorded);
  ASSERT_EQ(answered.size(), expected.size());
  EXPECT_GT(summary.answered, std::size_t(5000));
  int mismatches = 0;
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (answered[i] == expected[i]) continue;
    if (++mismatches <= 10) {
      ADD_FAILURE() << "line " << (i + 1) << " of " << answers_name << "\n  recorded: " << expected[i]
                    << "\n  answered: " << answered[i];
    }
  }
  EXPECT_EQ(mismatches, 0) << "answers that changed";
}

}  // namespace test_query_corpus
}  // namespace proxima
