// End-to-end tests of `proxima mesh-info`: the report of a known tetrahedron (text), a cube
// file with a flipped triangle (JSON: the defect found in the input, one flip by repair, a
// closed outward mesh of volume 1 after), --no-repair, the shared icosphere (counts given in
// its header, BVH statistics present and within the build's depth limit), a missing file.
#include <gtest/gtest.h>

#include <proxima/spatial/bvh.hpp>

#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "cli_run.hpp"

namespace proxima {
namespace test_mesh_info {

using test::CliRun;
using test::data_file;
using test::run_cli;

TEST(CliMeshInfo, TetrahedronText) {
  const CliRun run = run_cli("mesh-info '" + data_file("tetrahedron.stl") + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  for (const char* line :
       {"input: 4 vertices, 4 triangles, 1 component(s)", "closed: yes, consistently oriented: yes",
        "volume: 0.1666666", "0 triangles flipped", "bounds: min [0, 0, 0], max [1, 1, 1]", "bvh: "}) {
    EXPECT_NE(run.output.find(line), std::string::npos) << line << "\n" << run.output;
  }
}

TEST(CliMeshInfo, FlippedTriangleIsReportedAndRepaired) {
  const auto path =
      std::filesystem::temp_directory_path() / ("proxima-mesh-info-" + std::to_string(::getpid()) + ".obj");
  {
    std::ofstream out(path);
    out << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nv 0 0 1\nv 1 0 1\nv 0 1 1\nv 1 1 1\n"
           "f 1 3 4\nf 1 4 2\nf 5 6 8\nf 5 8 7\nf 1 2 6\nf 1 6 5\n"
           "f 3 7 8\nf 3 8 4\nf 1 5 7\nf 1 7 3\nf 2 4 8\nf 2 6 8\n";  // the last one flipped
  }
  const CliRun run = run_cli("mesh-info --json '" + path.string() + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto info = nlohmann::json::parse(run.output);
  EXPECT_EQ(info["input"]["triangles"], 12);
  EXPECT_EQ(info["input"]["inconsistent_edges"], 3);
  EXPECT_EQ(info["input"]["oriented"], false);
  EXPECT_EQ(info["repair"]["flipped_triangles"], 1);
  EXPECT_EQ(info["mesh"]["vertices"], 8);
  EXPECT_EQ(info["mesh"]["closed"], true);
  EXPECT_EQ(info["mesh"]["oriented"], true);
  EXPECT_NEAR(info["mesh"]["volume"].get<double>(), 1.0, 1e-6);
  EXPECT_NEAR(info["mesh"]["surface_area"].get<double>(), 6.0, 1e-5);
  EXPECT_EQ(info["bounds"]["size"], nlohmann::json::parse("[1.0, 1.0, 1.0]"));
  EXPECT_GE(info["bvh"]["nodes"].get<int>(), 1);
  EXPECT_EQ(info["bvh"]["node_bytes"], sizeof(BvhNode));  // 32 in the float build

  const CliRun raw = run_cli("mesh-info --json --no-repair '" + path.string() + "'");
  ASSERT_EQ(raw.status, 0) << raw.output;
  const auto raw_info = nlohmann::json::parse(raw.output);
  EXPECT_FALSE(raw_info.contains("repair"));
  EXPECT_EQ(raw_info["mesh"]["inconsistent_edges"], 3);
  std::filesystem::remove(path);
}

TEST(CliMeshInfo, SharedIcosphere) {
  std::string dir = PROXIMA_DEFAULT_WORKLOAD_DIR;
  if (const char* env = std::getenv("PROXIMA_WORKLOADS"); env != nullptr && env[0] != '\0') dir = env;
  const std::string path = dir + "/mesh_icosphere.obj";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not found";
  const CliRun run = run_cli("mesh-info --json '" + path + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const auto info = nlohmann::json::parse(run.output);
  EXPECT_EQ(info["mesh"]["vertices"], 10242);
  EXPECT_EQ(info["mesh"]["triangles"], 20480);
  EXPECT_EQ(info["mesh"]["closed"], true);
  EXPECT_EQ(info["mesh"]["components"], 1);
  EXPECT_GT(info["bvh"]["leaves"].get<int>(), 20480 / 8);
  EXPECT_EQ(info["bvh"]["nodes"].get<int>(), 2 * info["bvh"]["leaves"].get<int>() - 1);
  EXPECT_LE(info["bvh"]["depth"].get<int>(), 64);
}

TEST(CliMeshInfo, MissingFileFails) {
  const CliRun run = run_cli("mesh-info '" + data_file("no_such_mesh.obj") + "' 2>&1");
  EXPECT_EQ(run.status, 1);
  EXPECT_NE(run.output.find("file: cannot read mesh file"), std::string::npos) << run.output;
  EXPECT_NE(run_cli("mesh-info 2>/dev/null").status, 0);
}

}  // namespace test_mesh_info
}  // namespace proxima
