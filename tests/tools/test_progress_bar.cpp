// Progress bars: the line's format, silence when disabled (standard error not a terminal:
// a pipe or a file gets nothing), at most a thousand redraws, and the commands that draw one:
// mesh-info's stages and a world run's request bytes when enabled, and no progress text from
// the executable when standard error is a pipe (its output unchanged).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

#include "cli_run.hpp"
#include "mesh_info.hpp"
#include "progress_bar.hpp"
#include "world_session.hpp"

namespace proxima::test_progress_bar {

TEST(ProgressBar, LineShowsTheFractionDone) {
  EXPECT_EQ(tool::progress_line(0, 10, "frames", 10), "\r[          ] 0/10 frames");
  EXPECT_EQ(tool::progress_line(5, 10, "frames", 10), "\r[#####     ] 5/10 frames");
  EXPECT_EQ(tool::progress_line(10, 10, "steps", 4), "\r[####] 10/10 steps");
  EXPECT_EQ(tool::progress_line(12, 10, "x", 4), "\r[####] 12/10 x");  // never past full
  EXPECT_EQ(tool::progress_line(0, 0, "x", 3), "\r[###] 0/0 x");
}

TEST(ProgressBar, SilentWhenDisabled) {
  std::ostringstream out;
  tool::ProgressBar bar(out, false, 3, "frames");
  for (std::size_t i = 1; i <= 3; ++i) bar.update(i);
  EXPECT_TRUE(out.str().empty());
}

TEST(ProgressBar, RedrawsOnlyOnChangeAndEndsWithANewline) {
  std::ostringstream out;
  tool::ProgressBar bar(out, true, 2, "frames");
  bar.update(1);
  bar.update(1);
  bar.update(2);
  EXPECT_EQ(out.str(), tool::progress_line(1, 2, "frames") + tool::progress_line(2, 2, "frames") + "\n");
}

TEST(ProgressBar, AtMostAThousandRedrawsAndNothingAfterTheEnd) {
  std::ostringstream out;
  tool::ProgressBar bar(out, true, 100000, "steps");
  for (std::size_t i = 1; i <= 100000; ++i) bar.update(i);
  bar.update(100000);
  const std::string text = out.str();
  EXPECT_EQ(std::count(text.begin(), text.end(), '\r'), 1001);  // the first update, then one per thousandth
  const std::string last = tool::progress_line(100000, 100000, "steps") + "\n";
  ASSERT_GE(text.size(), last.size());
  EXPECT_EQ(text.substr(text.size() - last.size()), last);
}

TEST(ProgressBar, MeshInfoShowsItsStagesFromTheGivenSize) {
  tool::MeshInfoOptions options;
  options.path = test::data_file("tetrahedron.stl");  // 4 triangles
  options.progress = true;
  options.progress_triangles = 4;
  std::ostringstream bar;
  const tool::Json with_bar = tool::mesh_info(options, &bar);
  const std::string unit = "stages (analysis, repair, hierarchy)";
  EXPECT_EQ(bar.str(),
            tool::progress_line(1, 3, unit) + tool::progress_line(2, 3, unit) + tool::progress_line(3, 3, unit) + "\n");
  options.progress_triangles = 5;
  std::ostringstream none;
  const tool::Json without = tool::mesh_info(options, &none);
  EXPECT_TRUE(none.str().empty());
  EXPECT_EQ(with_bar["bvh"]["nodes"], without["bvh"]["nodes"]);
}

TEST(ProgressBar, WorldRunCountsTheRequestBytesAndAnswersAlike) {
  std::string requests = R"({"op":"add","geometry":{"type":"sphere","radius":1}})"
                         "\n";
  for (int i = 0; i < 50; ++i) requests += "{\"op\":\"step\"}\n";
  std::ostringstream plain_out, bar_out, bar;
  std::istringstream plain_in(requests), bar_in(requests);
  ASSERT_EQ(tool::WorldSession::create().value().run(plain_in, plain_out).rejected, 0u);
  tool::ProgressBar progress(bar, true, requests.size(), "bytes of requests");
  ASSERT_EQ(tool::WorldSession::create().value().run(bar_in, bar_out, &progress).rejected, 0u);
  EXPECT_EQ(bar_out.str(), plain_out.str());
  const std::string last = tool::progress_line(requests.size(), requests.size(), "bytes of requests") + "\n";
  ASSERT_GE(bar.str().size(), last.size());
  EXPECT_EQ(bar.str().substr(bar.str().size() - last.size()), last);
}

TEST(ProgressBar, CommandsPrintNoProgressIntoAPipe) {
  const auto path =
      std::filesystem::temp_directory_path() / ("proxima-progress-" + std::to_string(::getpid()) + ".jsonl");
  {
    std::ofstream file(path);
    file << R"({"op":"add","geometry":{"type":"sphere","radius":1}})"
         << "\n";
    for (int i = 0; i < 2000; ++i) file << "{\"op\":\"step\"}\n";
  }
  const test::CliRun world = test::run_cli("world '" + path.string() + "' 2>&1");
  EXPECT_EQ(world.status, 0);
  EXPECT_EQ(std::count(world.output.begin(), world.output.end(), '\n'), 2001);
  EXPECT_EQ(world.output.find('\r'), std::string::npos);
  const test::CliRun mesh = test::run_cli("mesh-info '" + test::data_file("tetrahedron.stl") + "' 2>&1");
  EXPECT_EQ(mesh.status, 0);
  EXPECT_EQ(mesh.output.find('\r'), std::string::npos);
  EXPECT_EQ(mesh.output.find("stages"), std::string::npos);
  std::filesystem::remove(path);
}

}  // namespace proxima::test_progress_bar
