// The `pairs` operation of the query protocol: every registered structure against a naive
// loop over all pairs of boxes written here, touching boxes, rejected boxes naming the field,
// and the help listing the structure names.
#include <gtest/gtest.h>

#include <proxima/broadphase/any_broadphase.hpp>

#include <array>
#include <cstdio>
#include <string>
#include <vector>

#include "query.hpp"
#include "query_test_util.hpp"
#include "support/random.hpp"

namespace proxima {
namespace test_query_pairs {

using test::answer, test::Json;

Json pairs_request(const std::vector<std::array<double, 6>>& boxes, std::string_view structure) {
  Json list = Json::array();
  for (const auto& b : boxes) list.push_back(Json::array({b[0], b[1], b[2], b[3], b[4], b[5]}));
  return Json{{"op", "pairs"}, {"boxes", list}, {"structure", std::string(structure)}};
}

TEST(QueryPairs, EveryStructureMatchesNaiveLoop) {
  test::Random rng(41);
  std::vector<std::array<double, 6>> boxes;
  for (int i = 0; i < 300; ++i) {
    std::array<double, 6> b{};
    for (int k = 0; k < 3; ++k) {
      b[k] = 0.5 * rng.integer(-40, 40);          // half-integer lattice: many exact touches
      b[k + 3] = b[k] + 0.5 * rng.integer(0, 8);  // zero-size edges included
    }
    boxes.push_back(b);
  }
  Json want = Json::array();
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    for (std::size_t j = i + 1; j < boxes.size(); ++j) {
      bool overlap = true;
      for (int k = 0; k < 3; ++k) {
        if (boxes[i][k] > boxes[j][k + 3] || boxes[j][k] > boxes[i][k + 3]) overlap = false;
      }
      if (overlap) want.push_back(Json::array({i, j}));
    }
  }
  ASSERT_GT(want.size(), 50u);
  for (std::string_view name : broadphase_names()) {
    const Json a = answer(pairs_request(boxes, name));
    EXPECT_EQ(a["pairs"], want) << name;
  }
}

TEST(QueryPairs, TouchingCountsAndDefaultStructure) {
  const Json a = answer(
      Json::parse(R"({"id":7,"op":"pairs","boxes":[[0,0,0,1,1,1],[1,0,0,2,1,1],[2.5,0,0,3,1,1],[2,1,1,2,1,1]]})"));
  EXPECT_EQ(a.dump(), R"({"id":7,"pairs":[[0,1],[1,3]]})");
  EXPECT_EQ(answer(Json::parse(R"({"op":"pairs","boxes":[]})"))["pairs"], Json::array());
}

void expect_rejected(const std::string& request, const std::string& field, const std::string& code) {
  const Json a = answer(Json::parse(request), false);
  EXPECT_EQ(a.value("field", ""), field) << request << " -> " << a.dump();
  EXPECT_EQ(a.value("code", ""), code) << request << " -> " << a.dump();
}

TEST(QueryPairs, BadInputNamesTheField) {
  expect_rejected(R"({"op":"pairs"})", "boxes", "missing");
  expect_rejected(R"({"op":"pairs","boxes":{}})", "boxes", "wrong_type");
  expect_rejected(R"({"op":"pairs","boxes":[[0,0,0,1,1,1],[0,0,0,1,1]]})", "boxes[1]", "wrong_type");
  expect_rejected(R"({"op":"pairs","boxes":[[0,0,0,1,1,1],[0,0,2,1,1,1]]})", "boxes[1]", "inverted");
  expect_rejected(R"({"op":"pairs","boxes":[[0,0,"a",1,1,1]]})", "boxes[0][2]", "wrong_type");
  expect_rejected(R"({"op":"pairs","boxes":[[0,0,0,1e300,1,1]]})", "boxes[0][3]", "out_of_range");
  expect_rejected(R"({"op":"pairs","boxes":[],"structure":"quadtree9"})", "structure", "invalid_argument");
  expect_rejected(R"({"op":"pairs","boxes":[],"structure":3})", "structure", "wrong_type");
  expect_rejected(R"({"op":"pairs","boxes":[],"colour":"red"})", "colour", "unknown_field");
}

TEST(QueryPairs, HelpListsStructureNames) {
  const std::string command = std::string("'") + PROXIMA_CLI_PATH + "' query --help";
  FILE* pipe = popen(command.c_str(), "r");
  ASSERT_NE(pipe, nullptr);
  std::string output;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), static_cast<int>(buffer.size()), pipe) != nullptr) output += buffer.data();
  EXPECT_EQ(pclose(pipe), 0);
  EXPECT_NE(output.find("pairs"), std::string::npos);
  for (std::string_view name : broadphase_names()) {
    EXPECT_NE(output.find(std::string(name)), std::string::npos) << name;
  }
}

}  // namespace test_query_pairs
}  // namespace proxima
