#pragma once
// Running the built `proxima` executable from the end-to-end tests (test_cli.cpp,
// test_mesh_info.cpp): its exit status and standard output, and the path of a file in the
// tests' data folder. PROXIMA_CLI_PATH and PROXIMA_TOOLS_TEST_DATA come from
// tests/tools/CMakeLists.txt.
#include <array>
#include <cstdio>
#include <string>
#include <sys/wait.h>

namespace proxima::test {

/// The outcome of one run of the executable.
struct CliRun {
  int status = -1;     ///< exit status of the program (-1: it did not exit normally)
  std::string output;  ///< its standard output
};

/// Runs `arguments` (shell syntax: quoting and redirections apply) with the built proxima
/// executable and collects its standard output.
inline CliRun run_cli(const std::string& arguments) {
  const std::string command = std::string("'") + PROXIMA_CLI_PATH + "' " + arguments;
  CliRun run;
  FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return run;
  std::array<char, 4096> buffer{};
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0) run.output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  return run;
}

/// Path of `name` in the tools tests' data folder.
inline std::string data_file(const std::string& name) { return std::string(PROXIMA_TOOLS_TEST_DATA) + "/" + name; }

}  // namespace proxima::test
