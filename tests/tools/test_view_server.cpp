// `proxima view` (tools/view_server.hpp): which request paths reach which files, the server
// in-process on a free port answered over a raw socket (so that `..`, `%2e%2e` and absolute
// targets reach it exactly as written), its errors, and the executable as a subprocess that
// prints its address and exits 0 on SIGTERM.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <array>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <netinet/in.h>
#include <poll.h>
#include <regex>
#include <signal.h>
#include <spawn.h>
#include <string>
#include <sys/socket.h>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

#include "view_server.hpp"

extern char** environ;

namespace proxima::test_view_server {

namespace {

namespace fs = std::filesystem;

/// A status line and body from the server.
struct HttpAnswer {
  int status = 0;    ///< 0 when there was no answer
  std::string body;  ///< the bytes after the headers
};

/// Sends "GET target" to 127.0.0.1:port over a plain socket, exactly as written, and reads the
/// answer to the end (5 s limits on every read and write).
HttpAnswer http_get(int port, const std::string& target) {
  HttpAnswer answer;
  const int fd = socket(AF_INET, SOCK_STREAM, 0);
  if (fd < 0) return answer;
  timeval limit{5, 0};
  setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &limit, sizeof limit);
  setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(static_cast<std::uint16_t>(port));
  inet_pton(AF_INET, "127.0.0.1", &address.sin_addr);
  std::string raw;
  if (connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0) {
    const std::string request = "GET " + target + " HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n";
    if (send(fd, request.data(), request.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(request.size())) {
      std::array<char, 8192> buffer{};
      ssize_t n = 0;
      while ((n = recv(fd, buffer.data(), buffer.size(), 0)) > 0)
        raw.append(buffer.data(), static_cast<std::size_t>(n));
    }
  }
  close(fd);
  std::smatch status;
  if (std::regex_search(raw, status, std::regex("^HTTP/1\\.[01] (\\d{3})"))) answer.status = std::stoi(status[1]);
  const std::size_t body = raw.find("\r\n\r\n");
  if (body != std::string::npos) answer.body = raw.substr(body + 4);
  return answer;
}

void write_file(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

/// A viewer folder of known files beside a secret outside it and a capture.
struct Site {
  fs::path root;     ///< holds viewer/, secret.txt, run.capture.jsonl
  fs::path viewer;   ///< the viewer folder (canonical)
  fs::path capture;  ///< the capture file

  explicit Site(const std::string& name) : root(fs::path(testing::TempDir()) / name) {
    fs::remove_all(root);
    const fs::path v = root / "viewer";
    write_file(v / "index.html", "<title>page</title>");
    write_file(v / "style.css", "body {}");
    write_file(v / "src" / "main.js", "export const main = 1;");
    write_file(v / "node_modules" / "three" / "build" / "three.module.js", "export const three = 1;");
    write_file(v / "node_modules" / "other" / "index.js", "other package");
    write_file(v / "package.json", "{}");
    write_file(v / "src" / ".hidden.js", "hidden");
    write_file(v / "test" / "browser.test.mjs", "test");
    write_file(root / "secret.txt", "secret");
    fs::create_symlink(root / "secret.txt", v / "src" / "link.js");
    capture = root / "run.capture.jsonl";
    write_file(capture, "{\"format\":\"proxima-capture\",\"version\":1}\n");
    viewer = fs::canonical(v);
  }
  ~Site() {
    std::error_code ec;
    fs::remove_all(root, ec);
  }
};

/// The request paths (decoded) that the server must refuse.
const std::array<const char*, 15> kRefusedPaths = {
    "/../secret.txt", "/src/../../secret.txt",  "/src/./main.js",
    "/./index.html",  "//etc/passwd",           "/etc/passwd",
    "/package.json",  "/test/browser.test.mjs", "/node_modules/other/index.js",
    "/src/link.js",   "/src/.hidden.js",        "/node_modules/three",
    "/src//main.js",  "/src\\main.js",          "index.html"};

}  // namespace

TEST(ViewServer, ServesOnlyThePageFiles) {
  const Site site("view_resolve");
  EXPECT_EQ(tool::resolve_viewer_file(site.viewer, "/"), site.viewer / "index.html");
  EXPECT_EQ(tool::resolve_viewer_file(site.viewer, "/index.html"), site.viewer / "index.html");
  EXPECT_EQ(tool::resolve_viewer_file(site.viewer, "/style.css"), site.viewer / "style.css");
  EXPECT_EQ(tool::resolve_viewer_file(site.viewer, "/src/main.js"), site.viewer / "src" / "main.js");
  EXPECT_EQ(tool::resolve_viewer_file(site.viewer, "/node_modules/three/build/three.module.js"),
            site.viewer / "node_modules" / "three" / "build" / "three.module.js");
  for (const char* path : kRefusedPaths) {
    EXPECT_FALSE(tool::resolve_viewer_file(site.viewer, path).has_value()) << path;
  }
  EXPECT_FALSE(tool::resolve_viewer_file(site.viewer, std::string_view("/src/main.js\0x", 15)).has_value());
  EXPECT_EQ(tool::content_type_of("a/b.js"), "text/javascript; charset=utf-8");
  EXPECT_EQ(tool::content_type_of("index.html"), "text/html; charset=utf-8");
}

TEST(ViewServer, AnswersOverHttpAndRefusesTraversal) {
  const Site site("view_http");
  auto server = tool::ViewServer::create({site.capture.string(), 0, site.viewer});
  ASSERT_TRUE(server.ok()) << server.error().what();
  const int port = server.value().port();
  ASSERT_GT(port, 0);
  EXPECT_EQ(server.value().address(), "http://127.0.0.1:" + std::to_string(port) + "/");
  std::thread serving([&] { EXPECT_TRUE(server.value().run()); });

  const HttpAnswer page = http_get(port, "/");
  EXPECT_EQ(page.status, 200);
  EXPECT_EQ(page.body, "<title>page</title>");
  const HttpAnswer capture = http_get(port, "/capture.jsonl");
  EXPECT_EQ(capture.status, 200);
  EXPECT_EQ(capture.body, "{\"format\":\"proxima-capture\",\"version\":1}\n");
  EXPECT_EQ(http_get(port, "/src/main.js?v=1").body, "export const main = 1;");
  EXPECT_EQ(http_get(port, "/node_modules/three/build/three.module.js").status, 200);
  for (const char* path : kRefusedPaths) {
    if (path[0] == '/' && std::string_view(path).find('\\') == std::string_view::npos) {
      EXPECT_EQ(http_get(port, path).status, 404) << path;
    }
  }
  for (const std::string& encoded : std::vector<std::string>{
           "/%2e%2e/secret.txt", "/src/%2E%2E/%2e%2e/secret.txt", "/%2e%2e%2fsecret.txt", "/src/..%2f..%2fsecret.txt",
           "/%2fetc%2fpasswd", "/src%5cmain.js", "/src/main.js%00.css", "http://127.0.0.1/etc/passwd",
           "/" + site.root.string() + "/secret.txt"}) {
    const HttpAnswer answer = http_get(port, encoded);
    EXPECT_EQ(answer.status, 404) << encoded;
    EXPECT_EQ(answer.body.find("secret"), std::string::npos) << encoded;
  }
  server.value().stop();
  serving.join();
}

TEST(ViewServer, ErrorsNameTheField) {
  const Site site("view_errors");
  const auto missing = tool::ViewServer::create({(site.root / "none.jsonl").string(), 0, site.viewer});
  ASSERT_FALSE(missing.ok());
  EXPECT_EQ(missing.error().field, "capture");
  const auto no_page = tool::ViewServer::create({site.capture.string(), 0, site.root});
  ASSERT_FALSE(no_page.ok());
  EXPECT_EQ(no_page.error().field, "viewer");
  auto first = tool::ViewServer::create({site.capture.string(), 0, site.viewer});
  ASSERT_TRUE(first.ok());
  const auto taken = tool::ViewServer::create({site.capture.string(), first.value().port(), site.viewer});
  ASSERT_FALSE(taken.ok());
  EXPECT_EQ(taken.error().field, "port");
  first.value().stop();  // before run(): run() then returns at once
  EXPECT_TRUE(first.value().run());
}

TEST(ViewServer, FindsTheSourceTreeViewer) {
  const auto dir = tool::find_viewer_dir("/nonexistent/bin/proxima");
  ASSERT_TRUE(dir.ok()) << dir.error().what();
  EXPECT_TRUE(fs::exists(dir.value() / "index.html"));
}

TEST(ViewServer, CommandPrintsItsAddressAndStopsOnSigterm) {
  const Site site("view_command");
  int out[2];
  ASSERT_EQ(pipe(out), 0);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, out[1], STDOUT_FILENO);
  posix_spawn_file_actions_addclose(&actions, out[0]);
  const std::string capture = site.capture.string();
  const std::string viewer = site.viewer.string();
  std::array<const char*, 8> argv = {PROXIMA_CLI_PATH, "view",         capture.c_str(), "--port", "0",
                                     "--viewer-dir",   viewer.c_str(), nullptr};
  pid_t pid = 0;
  ASSERT_EQ(posix_spawn(&pid, PROXIMA_CLI_PATH, &actions, nullptr, const_cast<char**>(argv.data()), environ), 0);
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);

  // The first line gives the address (10 s at most).
  std::string printed;
  std::smatch match;
  const std::regex address("http://127\\.0\\.0\\.1:(\\d+)/");
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!std::regex_search(printed, match, address) && std::chrono::steady_clock::now() < deadline) {
    pollfd ready{out[0], POLLIN, 0};
    if (poll(&ready, 1, 100) <= 0) continue;
    std::array<char, 512> buffer{};
    const ssize_t n = read(out[0], buffer.data(), buffer.size());
    if (n <= 0) break;
    printed.append(buffer.data(), static_cast<std::size_t>(n));
  }
  const bool serving = std::regex_search(printed, match, address);
  if (serving) {
    const int port = std::stoi(match[1]);
    EXPECT_EQ(http_get(port, "/").body, "<title>page</title>");
    EXPECT_EQ(http_get(port, "/../secret.txt").status, 404);
  }
  kill(pid, SIGTERM);
  int status = 0;
  for (int i = 0; i < 500 && waitpid(pid, &status, WNOHANG) == 0; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  if (waitpid(pid, &status, WNOHANG) == 0) {
    kill(pid, SIGKILL);
    waitpid(pid, &status, 0);
    ADD_FAILURE() << "proxima view did not stop within 5 s of SIGTERM";
  }
  close(out[0]);
  ASSERT_TRUE(serving) << printed;
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
}

}  // namespace proxima::test_view_server
