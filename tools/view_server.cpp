// `proxima view` (view_server.hpp): the web viewer and one capture over HTTP on 127.0.0.1.
//   1. find the viewer folder ($PROXIMA_VIEWER_DIR, the installed share/proxima/viewer, the
//      source tree's viewer/) and check the capture can be read;
//   2. bind 127.0.0.1 (port 0: the system picks a free one; a port in use is an error) with
//      cpp-httplib;
//   3. answer GET requests: /capture.jsonl is the capture, read afresh at each request (a
//      capture recorded again shows on reload); files are streamed, uncompressed; any other path goes through
//      resolve_viewer_file, which allows only plain segments under index.html, style.css,
//      src/ and node_modules/three/ and checks the canonical file stays inside them (no
//      link leads out); everything else is 404;
//   4. run_view blocks SIGINT and SIGTERM, serves on a thread, and waits for either signal
//      with sigwait, then stops the server and joins it.
#include "view_server.hpp"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <fstream>
#include <httplib.h>
#include <iostream>
#include <memory>
#include <pthread.h>
#include <signal.h>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

namespace proxima::tool {

namespace fs = std::filesystem;

namespace {

/// The page's files: a request must fall in one of these (a file, or a folder when it ends in '/').
constexpr std::array<std::string_view, 4> kServedRoots = {"index.html", "style.css", "src/", "node_modules/three/"};

bool has_index(const fs::path& dir) {
  std::error_code ec;
  return fs::is_regular_file(dir / "index.html", ec);
}

/// Splits "/a/b/c" into {"a", "b", "c"}; nothing when a segment is empty (but a trailing
/// '/'), ".", "..", hidden (leading '.'), or holds a backslash or a control character.
std::optional<std::vector<std::string>> plain_segments(std::string_view path) {
  if (path.empty() || path.front() != '/') return std::nullopt;
  std::vector<std::string> segments;
  std::size_t start = 1;
  while (start <= path.size()) {
    const std::size_t end = std::min(path.find('/', start), path.size());
    const std::string_view segment = path.substr(start, end - start);
    const bool last = end == path.size();
    if (segment.empty() && !(last && !segments.empty()) && !(last && start == 1)) return std::nullopt;
    if (!segment.empty()) {
      if (segment.front() == '.') return std::nullopt;  // ".", "..", hidden files
      const bool bad_char = std::any_of(segment.begin(), segment.end(), [](char c) {
        return c == '\\' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
      });
      if (bad_char) return std::nullopt;
      segments.emplace_back(segment);
    }
    start = end + 1;
  }
  return segments;
}

/// True when `relative` ("src/main.js") lies under one of kServedRoots; gives that root's folder (or file).
std::optional<std::string> served_root_of(const std::string& relative) {
  for (std::string_view root : kServedRoots) {
    const bool folder = root.back() == '/';
    if (folder ? relative.starts_with(root) && relative.size() > root.size() : relative == root) {
      return std::string(folder ? root.substr(0, root.size() - 1) : root);
    }
  }
  return std::nullopt;
}

/// True when canonical `file` is `root` or lies below it.
bool inside(const fs::path& file, const fs::path& root) {
  auto [root_end, file_it] = std::mismatch(root.begin(), root.end(), file.begin(), file.end());
  return root_end == root.end();
}

/// Answers with the file's bytes, streamed in chunks with its length known up front. A
/// sized stream is sent as it is, never compressed: on loopback, compressing megabytes of
/// three.js (brotli, what Chromium asks for) would take seconds and save nothing.
bool send_file(const fs::path& file, const std::string& content_type, httplib::Response& response) {
  auto in = std::make_shared<std::ifstream>(file, std::ios::binary);
  std::error_code ec;
  const auto size = fs::file_size(file, ec);
  if (!*in || ec) return false;
  response.status = 200;
  response.set_content_provider(static_cast<std::size_t>(size), content_type,
                                [in](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                                  std::array<char, 64 * 1024> buffer{};
                                  in->seekg(static_cast<std::streamoff>(offset));
                                  const std::size_t want = std::min(length, buffer.size());
                                  in->read(buffer.data(), static_cast<std::streamsize>(want));
                                  const auto got = static_cast<std::size_t>(in->gcount());
                                  return got > 0 && sink.write(buffer.data(), got);
                                });
  return true;
}

void not_found(httplib::Response& response) {
  response.status = 404;
  response.set_content("404 not found\n", "text/plain; charset=utf-8");
}

}  // namespace

Result<fs::path> find_viewer_dir(const fs::path& executable) {
  std::vector<fs::path> candidates;
  if (const char* env = std::getenv("PROXIMA_VIEWER_DIR"); env != nullptr && *env != '\0') candidates.emplace_back(env);
  if (!executable.empty()) candidates.push_back(executable.parent_path() / ".." / "share" / "proxima" / "viewer");
#ifdef PROXIMA_VIEWER_SOURCE_DIR
  candidates.emplace_back(PROXIMA_VIEWER_SOURCE_DIR);
#endif
  std::string tried;
  for (const fs::path& dir : candidates) {
    if (has_index(dir)) {
      std::error_code ec;
      fs::path canonical = fs::canonical(dir, ec);
      if (!ec) return canonical;
    }
    tried += (tried.empty() ? "" : ", ") + dir.string();
  }
  return make_error(ErrorCode::InvalidArgument, "viewer",
                    "no viewer folder with index.html (tried: " + (tried.empty() ? "nothing" : tried) +
                        "; set PROXIMA_VIEWER_DIR or --viewer-dir)");
}

std::optional<fs::path> resolve_viewer_file(const fs::path& viewer_dir, std::string_view path) {
  const auto segments = plain_segments(path);
  if (!segments) return std::nullopt;
  std::string relative;
  for (const std::string& segment : *segments) relative += (relative.empty() ? "" : "/") + segment;
  if (relative.empty()) relative = "index.html";
  const auto root = served_root_of(relative);
  if (!root) return std::nullopt;
  std::error_code ec;
  const fs::path file = fs::canonical(viewer_dir / relative, ec);
  if (ec || !fs::is_regular_file(file, ec)) return std::nullopt;
  const fs::path root_path = fs::canonical(viewer_dir / *root, ec);
  if (ec || !inside(file, root_path)) return std::nullopt;  // a link that leads out
  return file;
}

std::string content_type_of(const fs::path& file) {
  const std::string ext = file.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".jsonl") return "text/plain; charset=utf-8";
  if (ext == ".png") return "image/png";
  if (ext == ".svg") return "image/svg+xml";
  if (ext == ".wasm") return "application/wasm";
  return "application/octet-stream";
}

/// The server and what it serves.
struct ViewServer::State {
  httplib::Server http;
  fs::path viewer_dir;
  fs::path capture;
  int port = 0;
  std::atomic<bool> entered_run{false};
  std::atomic<bool> finished_run{false};
  std::atomic<bool> stop_requested{false};

  void answer(const httplib::Request& request, httplib::Response& response) const {
    response.set_header("Cache-Control", "no-store");
    response.set_header("X-Content-Type-Options", "nosniff");
    const bool is_capture = request.path == kCaptureUrlPath;
    const std::optional<fs::path> file =
        is_capture ? std::optional(capture) : resolve_viewer_file(viewer_dir, request.path);
    if (!file) return not_found(response);
    if (!send_file(*file, is_capture ? "text/plain; charset=utf-8" : content_type_of(*file), response)) {
      not_found(response);
    }
  }
};

ViewServer::ViewServer(std::unique_ptr<State> state) : state_(std::move(state)) {}
ViewServer::ViewServer(ViewServer&&) noexcept = default;
ViewServer& ViewServer::operator=(ViewServer&&) noexcept = default;
ViewServer::~ViewServer() = default;

Result<ViewServer> ViewServer::create(const ViewOptions& options) {
  std::error_code ec;
  std::ifstream capture(options.capture, std::ios::binary);
  if (!capture || fs::is_directory(options.capture, ec)) {
    return make_error(ErrorCode::InvalidArgument, "capture",
                      "cannot open " + options.capture + " (not a readable file)");
  }
  if (!has_index(options.viewer_dir)) {
    return make_error(ErrorCode::InvalidArgument, "viewer", options.viewer_dir.string() + " holds no index.html");
  }
  if (options.port < 0 || options.port > 65535) {
    return make_error(ErrorCode::OutOfRange, "port", "must be 0..65535, not " + std::to_string(options.port));
  }
  auto state = std::make_unique<State>();
  state->viewer_dir = fs::canonical(options.viewer_dir, ec);
  state->capture = fs::absolute(options.capture, ec);
  State* raw = state.get();
  state->http.Get(
      ".*", [raw](const httplib::Request& request, httplib::Response& response) { raw->answer(request, response); });
  state->http.set_keep_alive_timeout(1);
  // SO_REUSEADDR only: httplib's default SO_REUSEPORT would let a second server bind the same
  // port and take half of the first one's connections.
  state->http.set_socket_options([](socket_t socket) {
    int yes = 1;
    setsockopt(socket, SOL_SOCKET, SO_REUSEADDR, &yes, sizeof yes);
  });
  const char* host = "127.0.0.1";
  if (options.port == 0) {
    state->port = state->http.bind_to_any_port(host);
  } else {
    state->port = state->http.bind_to_port(host, options.port) ? options.port : -1;
  }
  if (state->port <= 0) {
    return make_error(ErrorCode::InvalidArgument, "port",
                      "cannot listen on " + std::string(host) + ":" + std::to_string(options.port) + " (in use?)");
  }
  return ViewServer(std::move(state));
}

int ViewServer::port() const { return state_->port; }

std::string ViewServer::address() const { return "http://127.0.0.1:" + std::to_string(state_->port) + "/"; }

const fs::path& ViewServer::viewer_dir() const { return state_->viewer_dir; }

bool ViewServer::run() {
  state_->entered_run = true;
  bool ok = true;
  if (!state_->stop_requested) ok = state_->http.listen_after_bind();
  state_->finished_run = true;
  return ok || state_->stop_requested;
}

void ViewServer::stop() {
  state_->stop_requested = true;
  // run() may be between its check of stop_requested and httplib's start: wait for either end.
  while (state_->entered_run && !state_->finished_run && !state_->http.is_running()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  state_->http.stop();
}

int run_view(const ViewOptions& options, const fs::path& executable, std::ostream& out, std::ostream& err) {
  ViewOptions resolved = options;
  if (resolved.viewer_dir.empty()) {
    auto dir = find_viewer_dir(executable);
    if (!dir.ok()) {
      err << "proxima view: " << dir.error().what() << "\n";
      return 1;
    }
    resolved.viewer_dir = dir.value();
  }
  auto server = ViewServer::create(resolved);
  if (!server.ok()) {
    err << "proxima view: " << server.error().what() << "\n";
    return 1;
  }
  std::error_code ec;
  if (!fs::is_regular_file(server.value().viewer_dir() / "node_modules" / "three" / "build" / "three.module.js", ec)) {
    err << "proxima view: warning: " << (server.value().viewer_dir() / "node_modules" / "three").string()
        << " is missing: run `npm ci` in " << server.value().viewer_dir().string() << "\n";
  }
  // Block the signals in every thread (the server's inherit the mask) and take them here.
  sigset_t signals;
  sigemptyset(&signals);
  sigaddset(&signals, SIGINT);
  sigaddset(&signals, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);
  const pthread_t main_thread = pthread_self();
  std::atomic<bool> failed{false};
  std::thread serving([&] {
    failed = !server.value().run();
    if (failed) pthread_kill(main_thread, SIGTERM);  // wake the sigwait below
  });
  out << "proxima view: serving " << options.capture << " and the viewer " << server.value().viewer_dir().string()
      << " at " << server.value().address() << " (Ctrl-C stops)" << std::endl;
  int received = 0;
  sigwait(&signals, &received);
  server.value().stop();
  serving.join();
  pthread_sigmask(SIG_UNBLOCK, &signals, nullptr);
  if (failed) {
    err << "proxima view: the server stopped: listening failed\n";
    return 1;
  }
  out << "proxima view: stopped (" << (received == SIGINT ? "SIGINT" : "SIGTERM") << ")" << std::endl;
  return 0;
}

}  // namespace proxima::tool
