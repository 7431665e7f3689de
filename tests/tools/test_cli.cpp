// End-to-end tests of the `proxima` executable: --version, --help, `demo` (statistics lines,
// a well-formed SVG with one polyline per ball, determinism) and `query` (a file of requests
// with known answers, errors naming their field, exit statuses, standard input).
#include <gtest/gtest.h>

#include <proxima/core/config.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "json_expect.hpp"

namespace proxima {
namespace test_cli {

using test::CliRun;
using test::data_file;
using test::run_cli;

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream file(path, std::ios::binary);
  std::stringstream buffer;
  buffer << file.rdbuf();
  return buffer.str();
}

std::size_t count_of(const std::string& text, const std::string& needle) {
  std::size_t count = 0;
  for (std::size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) ++count;
  return count;
}

// A scratch directory for the files a test writes, removed afterwards.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() / ("proxima-tools-" + name + "-" + std::to_string(::getpid()))) {
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  std::filesystem::path operator/(const std::string& file) const { return path_ / file; }

 private:
  std::filesystem::path path_;
};

// Well-formedness of the SVG's XML: every element is closed in order (a tag-level check,
// enough for the attribute-only elements the demo writes).
bool xml_tags_balanced(const std::string& xml) {
  std::vector<std::string> open;
  for (std::size_t at = xml.find('<'); at != std::string::npos; at = xml.find('<', at + 1)) {
    const std::size_t end = xml.find('>', at);
    if (end == std::string::npos) return false;
    const std::string tag = xml.substr(at + 1, end - at - 1);
    if (tag.empty()) return false;
    if (tag.front() == '/') {
      if (open.empty() || open.back() != tag.substr(1)) return false;
      open.pop_back();
    } else if (tag.back() != '/') {
      open.push_back(tag.substr(0, tag.find_first_of(" \t\n")));
    }
    at = end;
  }
  return open.empty();
}

TEST(Cli, VersionPrintsVersionAndPrecision) {
  const CliRun run = run_cli("--version");
  EXPECT_EQ(run.status, 0);
  const std::string expected =
      std::string("proxima ") + PROXIMA_VERSION_STRING + " (" + (PROXIMA_DOUBLE ? "double" : "float") + " precision)\n";
  EXPECT_EQ(run.output, expected);
}

TEST(Cli, HelpListsSubcommands) {
  const CliRun run = run_cli("--help");
  EXPECT_EQ(run.status, 0);
  EXPECT_NE(run.output.find("demo"), std::string::npos);
  EXPECT_NE(run.output.find("query"), std::string::npos);
  const CliRun query_help = run_cli("query --help");
  EXPECT_EQ(query_help.status, 0);
  for (const char* op : {"raycast", "contains", "closest_point", "bound", "fit", "mass", "halfspace"}) {
    EXPECT_NE(query_help.output.find(op), std::string::npos) << op;
  }
}

TEST(Cli, NoSubcommandPrintsHelpAndFails) {
  const CliRun run = run_cli("");
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("demo"), std::string::npos);
  EXPECT_NE(run_cli("frobnicate 2>/dev/null").status, 0);
}

TEST(CliDemo, PrintsStatisticsAndWritesSvg) {
  const ScratchDir dir("demo");
  const auto svg_path = dir / "table.svg";
  const auto start = std::chrono::steady_clock::now();
  const CliRun run = run_cli("demo --svg '" + svg_path.string() + "'");
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ASSERT_EQ(run.status, 0) << run.output;
  const std::string& out = run.output;
  EXPECT_NE(out.find("16 balls, 4 cushions, 600 frames at 60 Hz (10.00 s)"), std::string::npos) << out;
  EXPECT_NE(out.find("collision world: 20 objects"), std::string::npos) << out;
  EXPECT_NE(out.find("broad phase \"tree\", 2400 steps (4 per frame)"), std::string::npos) << out;
  EXPECT_NE(out.find("events: "), std::string::npos) << out;
  EXPECT_NE(out.find("collisions resolved: "), std::string::npos) << out;
  EXPECT_NE(out.find("time per frame: mean "), std::string::npos) << out;
  EXPECT_NE(out.find("picture: " + svg_path.string()), std::string::npos) << out;
  EXPECT_EQ(out.find("warning"), std::string::npos) << out;
  EXPECT_LT(seconds, 20.0);  // well under a second in release; sanitizer builds are slower

  const std::string svg = read_text(svg_path);
  ASSERT_FALSE(svg.empty());
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_EQ(count_of(svg, "<polyline"), 16u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_TRUE(xml_tags_balanced(svg));
}

TEST(CliDemo, OptionsFramesQuietSeed) {
  const ScratchDir dir("demo-options");
  const CliRun quiet = run_cli("demo --quiet --frames 30 --svg '" + (dir / "a.svg").string() + "'");
  EXPECT_EQ(quiet.status, 0);
  EXPECT_EQ(quiet.output, "");
  const CliRun again = run_cli("demo -q --frames 30 --svg '" + (dir / "b.svg").string() + "'");
  EXPECT_EQ(again.status, 0);
  EXPECT_EQ(read_text(dir / "a.svg"), read_text(dir / "b.svg"));  // deterministic
  const CliRun other = run_cli("demo -q --frames 30 --seed 7 --svg '" + (dir / "c.svg").string() + "'");
  EXPECT_EQ(other.status, 0);
  EXPECT_NE(read_text(dir / "a.svg"), read_text(dir / "c.svg"));

  const CliRun short_run = run_cli("demo --frames 12 --svg ''");
  EXPECT_EQ(short_run.status, 0);
  EXPECT_NE(short_run.output.find("12 frames at 60 Hz"), std::string::npos) << short_run.output;
  EXPECT_NE(short_run.output.find("48 steps (4 per frame)"), std::string::npos) << short_run.output;
  const CliRun sap = run_cli("demo --frames 12 --svg '' --broadphase sap --substeps 2");
  EXPECT_EQ(sap.status, 0);
  EXPECT_NE(sap.output.find("broad phase \"sap\", 24 steps (2 per frame)"), std::string::npos) << sap.output;
  EXPECT_EQ(short_run.output.find("picture:"), std::string::npos);
}

TEST(CliDemo, UnwritableSvgFails) {
  const CliRun run = run_cli("demo -q --frames 2 --svg /nonexistent-directory/x.svg 2>/dev/null");
  EXPECT_EQ(run.status, 1);
}

TEST(CliDemo, BadOptionsAreRejected) {
  EXPECT_NE(run_cli("demo --frames -3 2>/dev/null").status, 0);
  EXPECT_NE(run_cli("demo --frames many 2>/dev/null").status, 0);
  EXPECT_NE(run_cli("demo --substeps 0 2>/dev/null").status, 0);
  EXPECT_EQ(run_cli("demo --broadphase nothing 2>/dev/null").status, 2);
  EXPECT_NE(run_cli("demo --speed nan 2>/dev/null").status, 0);
  EXPECT_NE(run_cli("demo --speed inf 2>/dev/null").status, 0);
  EXPECT_NE(run_cli("world --contact-distance nan - < /dev/null 2>/dev/null").status, 0);
  // A directory is not an input file.
  const CliRun dir_query = run_cli("query / 2>&1");
  EXPECT_EQ(dir_query.status, 1);
  EXPECT_NE(dir_query.output.find("not a readable file"), std::string::npos) << dir_query.output;
  EXPECT_EQ(run_cli("world / 2>/dev/null").status, 1);
}

// The answers to a file of requests, line by line, against the expected file.
void expect_answers(const std::string& output, const std::string& expected_file) {
  const auto answers = lines_of(output);
  std::ifstream expected_in(data_file(expected_file));
  std::string line;
  std::size_t i = 0;
  for (; std::getline(expected_in, line); ++i) {
    ASSERT_LT(i, answers.size()) << "missing answer " << i;
    const auto actual = nlohmann::ordered_json::parse(answers[i]);
    const auto expected = nlohmann::ordered_json::parse(line);
    test::expect_json_near(actual, expected, "line " + std::to_string(i + 1));
  }
  EXPECT_EQ(answers.size(), i);
}

TEST(CliQuery, FileWithErrorsAnswersEveryLineInOrderAndExitsTwo) {
  const CliRun run = run_cli("query '" + data_file("requests.jsonl") + "'");
  EXPECT_EQ(run.status, 2);
  expect_answers(run.output, "expected.jsonl");
}

TEST(CliQuery, GoodFileExitsZero) {
  const CliRun run = run_cli("query '" + data_file("good.jsonl") + "'");
  EXPECT_EQ(run.status, 0);
  expect_answers(run.output, "good_expected.jsonl");
}

TEST(CliQuery, StandardInputDashOrAbsent) {
  const CliRun dash = run_cli("query - < '" + data_file("good.jsonl") + "'");
  EXPECT_EQ(dash.status, 0);
  expect_answers(dash.output, "good_expected.jsonl");
  const CliRun absent = run_cli("query < '" + data_file("requests.jsonl") + "'");
  EXPECT_EQ(absent.status, 2);
  expect_answers(absent.output, "expected.jsonl");
}

TEST(CliQuery, BlankLinesAreSkippedAndIdsEchoed) {
  const CliRun run = run_cli(
      "query <<'EOF'\n"
      "\n"
      "{\"id\":{\"k\":[1,2]},\"op\":\"contains\",\"target\":{\"type\":\"point\"},\"point\":[0,0,0]}\n"
      "   \n"
      "{\"id\":null,\"op\":\"contains\",\"target\":{\"type\":\"point\"},\"point\":[1,0,0]}\n"
      "{\"op\":\"contains\",\"target\":{\"type\":\"point\"},\"point\":[1,0,0]}\n"
      "EOF");
  EXPECT_EQ(run.status, 0);
  const auto answers = lines_of(run.output);
  ASSERT_EQ(answers.size(), 3u);
  EXPECT_EQ(answers[0], R"({"id":{"k":[1,2]},"inside":true})");
  EXPECT_EQ(answers[1], R"({"id":null,"inside":false})");
  EXPECT_EQ(answers[2], R"({"inside":false})");
}

TEST(CliQuery, MissingFileFails) {
  const CliRun run = run_cli("query /nonexistent-directory/requests.jsonl 2>/dev/null");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(run.output, "");
}

}  // namespace test_cli
}  // namespace proxima
