#pragma once
// Independent text access for the workload tests: the files are read here with
// std::getline and std::strtod, not with the readers under test, so that spot checks
// compare two separate parsers.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "support/workloads.hpp"

namespace proxima::bench::test_util {

/// Every line of a file (without the '\n').
inline std::vector<std::string> read_lines(const std::string& path) {
  std::vector<std::string> lines;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

/// The numbers of a line, in order, skipping words ("sphere", "box", "hull", "|", "v", "f").
inline std::vector<double> numbers(const std::string& line) {
  std::vector<double> out;
  std::istringstream in(line);
  for (std::string token; in >> token;) {
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (end != token.c_str() && *end == '\0') out.push_back(v);
  }
  return out;
}

/// The pose at `at` in a number list, quaternion divided by its length as FORMATS.md says.
inline Pose pose_at(const std::vector<double>& v, std::size_t at) {
  const double n =
      std::sqrt(v[at + 3] * v[at + 3] + v[at + 4] * v[at + 4] + v[at + 5] * v[at + 5] + v[at + 6] * v[at + 6]);
  return {{v[at], v[at + 1], v[at + 2]}, {v[at + 3] / n, v[at + 4] / n, v[at + 5] / n, v[at + 6] / n}};
}

/// Quaternion length minus one.
inline double unit_error(const Quatd& q) {
  return std::abs(std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z) - 1);
}

/// The shared data folder, or "" when it is absent (tests then skip).
inline std::string shared_dir() {
  const std::string dir = workload_dir();
  return std::filesystem::exists(workload_path(dir, "MANIFEST.txt")) ? dir : std::string();
}

/// MANIFEST.txt: file name -> {bytes, notes}.
struct ManifestEntry {
  std::uintmax_t bytes = 0;
  std::string notes;
};
inline std::map<std::string, ManifestEntry> read_manifest(const std::string& dir) {
  std::map<std::string, ManifestEntry> out;
  for (const std::string& line : read_lines(workload_path(dir, "MANIFEST.txt"))) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream in(line);
    std::string name;
    ManifestEntry e;
    in >> name >> e.bytes;
    std::getline(in, e.notes);
    out[name] = e;
  }
  return out;
}

/// The integer captured by `pattern` (one group) in `text`, or -1.
inline long long capture(const std::string& text, const std::string& pattern) {
  std::smatch m;
  if (!std::regex_search(text, m, std::regex(pattern))) return -1;
  return std::stoll(m[1].str());
}

/// Writes `text` to a fresh file of the test temp folder and returns its path.
inline std::string temp_file(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "proxima_workload_tests";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / name).string();
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

/// 15-axis separating-axis test of two closed oriented boxes in double (Gottschalk et al.,
/// "OBBTree", SIGGRAPH 1996), the reference for the box workloads' overlap fraction.
inline bool boxes_overlap(const BoxPair& p) {
  auto columns = [](const Quatd& q) {
    const Pose pose{{}, q};
    return std::array<Vec3d, 3>{apply(pose, {1, 0, 0}), apply(pose, {0, 1, 0}), apply(pose, {0, 0, 1})};
  };
  auto dot = [](const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  auto cross = [](const Vec3d& a, const Vec3d& b) {
    return Vec3d{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
  };
  const auto a = columns(p.pose_a.rotation);
  const auto b = columns(p.pose_b.rotation);
  const Vec3d t{p.pose_b.position.x - p.pose_a.position.x, p.pose_b.position.y - p.pose_a.position.y,
                p.pose_b.position.z - p.pose_a.position.z};
  std::vector<Vec3d> axes(a.begin(), a.end());
  axes.insert(axes.end(), b.begin(), b.end());
  for (const Vec3d& u : a) {
    for (const Vec3d& v : b) {
      const Vec3d c = cross(u, v);
      if (dot(c, c) > 1e-18) axes.push_back(c);
    }
  }
  for (const Vec3d& axis : axes) {
    double ra = 0, rb = 0;
    for (int i = 0; i < 3; ++i) {
      ra += p.half_extents_a[i] * std::abs(dot(a[i], axis));
      rb += p.half_extents_b[i] * std::abs(dot(b[i], axis));
    }
    if (std::abs(dot(t, axis)) > ra + rb) return false;
  }
  return true;
}

/// Distance between segments p1q1 and p2q2 in double (Ericson, Real-Time Collision
/// Detection, 5.1.9, the clamped closed-form solution).
inline double segment_distance(const Vec3d& p1, const Vec3d& q1, const Vec3d& p2, const Vec3d& q2) {
  auto sub = [](const Vec3d& a, const Vec3d& b) { return Vec3d{a.x - b.x, a.y - b.y, a.z - b.z}; };
  auto dot = [](const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; };
  const Vec3d d1 = sub(q1, p1), d2 = sub(q2, p2), r = sub(p1, p2);
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, r);
  double s = 0, t = 0;
  if (a <= 1e-12 && e <= 1e-12) return std::sqrt(dot(r, r));
  if (a <= 1e-12) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = dot(d1, r);
    if (e <= 1e-12) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = dot(d1, d2);
      const double denom = a * e - b * b;
      s = denom > 1e-12 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = std::clamp(-c / a, 0.0, 1.0);
      } else if (t > 1) {
        t = 1;
        s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  const Vec3d c1{p1.x + d1.x * s, p1.y + d1.y * s, p1.z + d1.z * s};
  const Vec3d c2{p2.x + d2.x * t, p2.y + d2.y * t, p2.z + d2.z * t};
  const Vec3d d = sub(c1, c2);
  return std::sqrt(dot(d, d));
}

}  // namespace proxima::bench::test_util
