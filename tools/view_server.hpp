#pragma once
// `proxima view`: serves the web viewer (viewer/) and one capture on 127.0.0.1 with
// cpp-httplib, and nothing else. The page's files are index.html, style.css, src/ and
// node_modules/three/ of the viewer folder; the capture is /capture.jsonl. Every other
// request (a `..` or `.` segment, an encoded one, an absolute path, a hidden file, a file
// outside those folders or reached through a link that leaves them) gets 404.
#include <proxima/core/result.hpp>

#include <filesystem>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace proxima::tool {

/// Options of `proxima view`.
struct ViewOptions {
  std::string capture;               ///< the capture file served as /capture.jsonl
  int port = 8765;                   ///< TCP port on 127.0.0.1 (0: a free one)
  std::filesystem::path viewer_dir;  ///< the viewer folder (empty: find_viewer_dir)
};

/// URL path of the capture in the served site.
inline constexpr std::string_view kCaptureUrlPath = "/capture.jsonl";

/// The viewer folder for the executable at `executable`: the first of
/// $PROXIMA_VIEWER_DIR, `<executable's dir>/../share/proxima/viewer` (an installed tool) and
/// the source tree's viewer/ (a tool run from its build tree) that holds index.html.
/// Error "viewer" naming the places tried when none does.
Result<std::filesystem::path> find_viewer_dir(const std::filesystem::path& executable);

/// The file a request for URL path `path` (already percent-decoded) is answered with, or
/// nothing (404). `viewer_dir` must be canonical. "/" is index.html; the capture path is not
/// resolved here.
std::optional<std::filesystem::path> resolve_viewer_file(const std::filesystem::path& viewer_dir,
                                                         std::string_view path);

/// The Content-Type of a served file, by its extension.
std::string content_type_of(const std::filesystem::path& file);

/// A running HTTP server of the viewer and one capture, bound to 127.0.0.1.
class ViewServer {
 public:
  /// Checks the capture is a readable file and the viewer folder holds index.html, then
  /// binds the port. Errors: "capture", "viewer", "port" (in use or not allowed).
  static Result<ViewServer> create(const ViewOptions& options);
  ViewServer(ViewServer&&) noexcept;
  ViewServer& operator=(ViewServer&&) noexcept;
  ~ViewServer();

  /// The bound port (the free one picked when the options said 0).
  int port() const;
  /// "http://127.0.0.1:PORT/".
  std::string address() const;
  /// The canonical viewer folder served.
  const std::filesystem::path& viewer_dir() const;
  /// Answers requests until stop() (from another thread). False when listening failed.
  bool run();
  /// Makes run() return; safe from any thread, and before run() starts.
  void stop();

 private:
  struct State;
  explicit ViewServer(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

/// `proxima view`: serves until SIGINT or SIGTERM, printing the address to `out` first.
/// Exit status 0 after a signal, 1 when the server cannot start (the reason on `err`).
int run_view(const ViewOptions& options, const std::filesystem::path& executable, std::ostream& out, std::ostream& err);

}  // namespace proxima::tool
