// proxima_make_workload: writes benchmark workloads of any size in the formats of
// shared/bench/FORMATS.md, deterministically from a seed.
//   1. one splitmix64 stream per file (uniform(a, b) = a + (b - a) * (u64 >> 11) 2^-53,
//      random unit vectors by z uniform in [-1, 1] and an azimuth, random rotations by
//      Shoemake's method with w >= 0);
//   2. the construction rules of FORMATS.md for each kind:
//      broadphase  uniform: centres uniform in the cube of edge (64 N / 1.5)^(1/3) so a
//                  box overlaps about 1.5 others, half extents in [0.5, 1.5], velocity a
//                  random direction times a speed in [0.05, 0.15];
//                  clustered: 90 % of the boxes in 10 Gaussian clusters (sigma 8, half
//                  extents [0.25, 0.75], speed [0.025, 0.075]), 10 % static boxes (half
//                  extents [1.5, 4.5]) uniform in the cube; the cube (240 for N = 100000)
//                  and sigma scale with N^(1/3) so the density stays the same;
//      convex      shapes: points on ellipsoids (semi-axes in [0.3, 1]); pairs: a random
//                  axis u, B placed along u at (support_A(u) + support_B(-u)) * f,
//                  f in [0.55, 1.45], so about half of the pairs are separated;
//      boxes       the same along a random axis with the boxes' projected radii,
//                  f in [0.3, 1.2] (about 61 % overlap);
//      spheres     centre distance (r1 + r2) * [0.5, 1.5] (about 50 % overlap);
//      capsules    centre distance (half lengths + radii) * [0, 1] (about 54 % overlap);
//   3. numbers printed with printf("%.Nf") (never "-0.000"), the decimals FORMATS.md uses.
// With the default seeds and the shared sizes the output equals the shared files on the
// platform they were made on (same draws, same rounding), which the tests check.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "support/workloads.hpp"

namespace {

using proxima::bench::Vec3d;

constexpr double kTwoPi = 2.0 * 3.14159265358979323846;

// ---------------------------------------------------------------------------------
// Random stream
// ---------------------------------------------------------------------------------

class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}

  std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  /// Uniform in [0, 1): 53 random bits.
  double unit() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }
  /// Uniform in [a, b).
  double uniform(double a, double b) { return a + (b - a) * unit(); }
  /// Integer in [0, n).
  std::uint64_t below(std::uint64_t n) { return next() % n; }
  /// Uniform on the unit sphere.
  Vec3d unit_vector() {
    const double z = uniform(-1.0, 1.0);
    const double phi = uniform(0.0, kTwoPi);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }
  /// Uniform rotation (w, x, y, z) with w >= 0 (Shoemake, "Uniform random rotations",
  /// Graphics Gems III).
  std::array<double, 4> rotation() {
    const double u1 = unit();
    const double u2 = unit();
    const double u3 = unit();
    const double a = std::sqrt(1.0 - u1);
    const double b = std::sqrt(u1);
    std::array<double, 4> q{b * std::cos(kTwoPi * u3), a * std::sin(kTwoPi * u2), a * std::cos(kTwoPi * u2),
                            b * std::sin(kTwoPi * u3)};
    if (q[0] < 0) {
      for (double& c : q) c = -c;
    }
    return q;
  }

 private:
  std::uint64_t state_;
};

// ---------------------------------------------------------------------------------
// Small vector helpers (double, evaluated left to right)
// ---------------------------------------------------------------------------------

Vec3d add(const Vec3d& a, const Vec3d& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Vec3d sub(const Vec3d& a, const Vec3d& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec3d mul(const Vec3d& a, double s) { return {a.x * s, a.y * s, a.z * s}; }
double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

using Mat3d = std::array<Vec3d, 3>;  // rows

/// Rotation matrix rows of a unit quaternion (w, x, y, z), FORMATS.md's formula.
Mat3d rotation_rows(const std::array<double, 4>& q) {
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  return {Vec3d{1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
          Vec3d{2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
          Vec3d{2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
}
Vec3d rotate(const Mat3d& m, const Vec3d& v) { return {dot(m[0], v), dot(m[1], v), dot(m[2], v)}; }

// ---------------------------------------------------------------------------------
// Text output
// ---------------------------------------------------------------------------------

/// printf("%.Nf"), never "-0.000".
std::string fixed(double x, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, x);
  if (buffer[0] == '-' && std::strtod(buffer, nullptr) == 0.0) return std::string(buffer + 1);
  return std::string(buffer);
}
/// The value a reader gets back from fixed(x, decimals).
double rounded(double x, int decimals) { return std::strtod(fixed(x, decimals).c_str(), nullptr); }
Vec3d rounded(const Vec3d& v, int decimals) {
  return {rounded(v.x, decimals), rounded(v.y, decimals), rounded(v.z, decimals)};
}
std::string fixed(const Vec3d& v, int decimals) {
  return fixed(v.x, decimals) + " " + fixed(v.y, decimals) + " " + fixed(v.z, decimals);
}

/// A quaternion rounded to 5 decimals as written, and its normalised value (what a reader
/// computes).
struct WrittenQuat {
  std::array<double, 4> text;
  std::array<double, 4> unit;
};
WrittenQuat written(const std::array<double, 4>& q) {
  WrittenQuat r;
  for (int i = 0; i < 4; ++i) r.text[i] = rounded(q[i], 5);
  const double n =
      std::sqrt(r.text[0] * r.text[0] + r.text[1] * r.text[1] + r.text[2] * r.text[2] + r.text[3] * r.text[3]);
  for (int i = 0; i < 4; ++i) r.unit[i] = r.text[i] / n;
  return r;
}
std::string fixed(const WrittenQuat& q) {
  return fixed(q.text[0], 5) + " " + fixed(q.text[1], 5) + " " + fixed(q.text[2], 5) + " " + fixed(q.text[3], 5);
}

constexpr int kPositionDecimals = 4;
constexpr int kExtentDecimals = 4;
constexpr int kPointDecimals = 5;
constexpr int kPrimitiveDecimals = 3;

class Output {
 public:
  void line(const std::string& s) {
    text_ += s;
    text_ += '\n';
  }
  bool write(const std::string& path) const {
    std::ofstream out(path, std::ios::binary);
    out << text_;
    out.close();
    if (!out) {
      std::cerr << "proxima_make_workload: cannot write " << path << "\n";
      return false;
    }
    return true;
  }

 private:
  std::string text_;
};

// ---------------------------------------------------------------------------------
// Generators
// ---------------------------------------------------------------------------------

std::string size_name(std::uint64_t n) { return n % 1000 == 0 ? std::to_string(n / 1000) + "k" : std::to_string(n); }

Output broadphase(std::uint64_t n, int frames, bool clustered, std::uint64_t seed, std::string name) {
  SplitMix64 rng(seed);
  struct Box {
    Vec3d c, h, v;
  };
  std::vector<Box> boxes;
  boxes.reserve(n);
  double edge = 0;
  if (!clustered) {
    // E[overlaps per box] ~ (N - 1) 8 E[h_i + h_j]^3 / L^3 = 64 (N - 1) / L^3 -> 1.5.
    edge = rounded(std::pow(64.0 * static_cast<double>(n) / 1.5, 1.0 / 3.0), 3);
    for (std::uint64_t i = 0; i < n; ++i) {
      Box b;
      b.c.x = rng.uniform(0, edge);
      b.c.y = rng.uniform(0, edge);
      b.c.z = rng.uniform(0, edge);
      b.h.x = rng.uniform(0.5, 1.5);
      b.h.y = rng.uniform(0.5, 1.5);
      b.h.z = rng.uniform(0.5, 1.5);
      const double speed = rng.uniform(0.05, 0.15);
      b.v = mul(rng.unit_vector(), speed);
      boxes.push_back(b);
    }
  } else {
    const double scale = std::cbrt(static_cast<double>(n) / 100000.0);
    edge = n == 100000 ? 240.0 : rounded(240.0 * scale, 3);
    const double sigma = n == 100000 ? 8.0 : 8.0 * scale;
    const std::uint64_t n_static = n / 10;
    const std::uint64_t n_moving = n - n_static;
    constexpr int kClusters = 10;
    std::array<Vec3d, kClusters> centres{};
    for (Vec3d& c : centres) {
      c.x = rng.uniform(0.2 * edge, 0.8 * edge);
      c.y = rng.uniform(0.2 * edge, 0.8 * edge);
      c.z = rng.uniform(0.2 * edge, 0.8 * edge);
    }
    for (std::uint64_t i = 0; i < n_moving; ++i) {
      const Vec3d& cc = centres[i % kClusters];
      Box b;
      for (int a = 0; a < 3; ++a) {
        // Box-Muller normal offset.
        const double u1 = rng.unit();
        const double u2 = rng.unit();
        const double g = std::sqrt(-2.0 * std::log(1.0 - u1)) * std::cos(kTwoPi * u2);
        b.c[a] = std::min(std::max(cc[a] + sigma * g, 0.0), edge);
      }
      b.h.x = rng.uniform(0.25, 0.75);
      b.h.y = rng.uniform(0.25, 0.75);
      b.h.z = rng.uniform(0.25, 0.75);
      const double speed = rng.uniform(0.025, 0.075);
      b.v = mul(rng.unit_vector(), speed);
      boxes.push_back(b);
    }
    for (std::uint64_t i = 0; i < n_static; ++i) {
      Box b;
      b.c.x = rng.uniform(0, edge);
      b.c.y = rng.uniform(0, edge);
      b.c.z = rng.uniform(0, edge);
      b.h.x = rng.uniform(1.5, 4.5);
      b.h.y = rng.uniform(1.5, 4.5);
      b.h.z = rng.uniform(1.5, 4.5);
      boxes.push_back(b);
    }
  }
  if (name.empty()) name = std::string("broadphase_") + (clustered ? "clustered_" : "uniform_") + size_name(n);
  Output out;
  out.line("broadphase 1 n=" + std::to_string(n) + " frames=" + std::to_string(frames) +
           " dt=1 lo=0 hi=" + fixed(edge, 3) + " name=" + name);
  for (const Box& b : boxes) out.line(fixed(b.c, 3) + " " + fixed(b.h, 3) + " " + fixed(b.v, 3));
  return out;
}

struct ConvexFiles {
  Output shapes;
  Output pairs;
};

ConvexFiles convex(int shape_count, int points, std::uint64_t pair_count, std::uint64_t shape_seed,
                   std::uint64_t pair_seed, const std::string& shapes_name) {
  ConvexFiles files;
  SplitMix64 rng(shape_seed);
  files.shapes.line("convex_shapes 1 count=" + std::to_string(shape_count) + " points=" + std::to_string(points));
  std::vector<std::vector<Vec3d>> parsed(static_cast<std::size_t>(shape_count));
  for (int s = 0; s < shape_count; ++s) {
    Vec3d axes;
    axes.x = rng.uniform(0.3, 1.0);
    axes.y = rng.uniform(0.3, 1.0);
    axes.z = rng.uniform(0.3, 1.0);
    files.shapes.line("shape " + std::to_string(s) + " " + std::to_string(points) + " " + fixed(axes, 4));
    for (int p = 0; p < points; ++p) {
      const Vec3d d = rng.unit_vector();
      const Vec3d point{axes.x * d.x, axes.y * d.y, axes.z * d.z};
      files.shapes.line(fixed(point, kPointDecimals));
      parsed[static_cast<std::size_t>(s)].push_back(rounded(point, kPointDecimals));
    }
  }
  rng = SplitMix64(pair_seed);
  files.pairs.line("convex_pairs 1 count=" + std::to_string(pair_count) + " shapes=" + shapes_name);
  for (std::uint64_t k = 0; k < pair_count; ++k) {
    const std::uint64_t a = rng.below(static_cast<std::uint64_t>(shape_count));
    const std::uint64_t b = rng.below(static_cast<std::uint64_t>(shape_count));
    Vec3d pa;
    pa.x = rng.uniform(-3, 3);
    pa.y = rng.uniform(-3, 3);
    pa.z = rng.uniform(-3, 3);
    const WrittenQuat qa = written(rng.rotation());
    const WrittenQuat qb = written(rng.rotation());
    const Vec3d u = rng.unit_vector();
    const double factor = rng.uniform(0.55, 1.45);
    const Mat3d ra = rotation_rows(qa.unit);
    const Mat3d rb = rotation_rows(qb.unit);
    double ha = -INFINITY;
    for (const Vec3d& p : parsed[a]) ha = std::max(ha, dot(rotate(ra, p), u));
    double hb = -INFINITY;
    for (const Vec3d& p : parsed[b]) hb = std::max(hb, -dot(rotate(rb, p), u));
    const Vec3d pb = add(pa, mul(u, (ha + hb) * factor));
    files.pairs.line(std::to_string(a) + " " + std::to_string(b) + " " + fixed(pa, kPositionDecimals) + " " +
                     fixed(qa) + " " + fixed(pb, kPositionDecimals) + " " + fixed(qb));
  }
  return files;
}

Output boxes(std::uint64_t count, std::uint64_t seed) {
  SplitMix64 rng(seed);
  Output out;
  out.line("box_pairs 1 count=" + std::to_string(count));
  for (std::uint64_t k = 0; k < count; ++k) {
    Vec3d ha, hb, pa;
    ha.x = rng.uniform(0.1, 1.0);
    ha.y = rng.uniform(0.1, 1.0);
    ha.z = rng.uniform(0.1, 1.0);
    ha = rounded(ha, kExtentDecimals);
    hb.x = rng.uniform(0.1, 1.0);
    hb.y = rng.uniform(0.1, 1.0);
    hb.z = rng.uniform(0.1, 1.0);
    hb = rounded(hb, kExtentDecimals);
    pa.x = rng.uniform(-3, 3);
    pa.y = rng.uniform(-3, 3);
    pa.z = rng.uniform(-3, 3);
    pa = rounded(pa, kPositionDecimals);
    const WrittenQuat qa = written(rng.rotation());
    const WrittenQuat qb = written(rng.rotation());
    const Vec3d u = rng.unit_vector();
    const double factor = rng.uniform(0.3, 1.2);
    const Mat3d ra = rotation_rows(qa.unit);
    const Mat3d rb = rotation_rows(qb.unit);
    // Projected radius of a box on u: sum_i h_i |column_i . u|.
    double sa = 0;
    double sb = 0;
    for (int i = 0; i < 3; ++i) {
      sa = sa + ha[i] * std::abs(ra[0][i] * u.x + ra[1][i] * u.y + ra[2][i] * u.z);
      sb = sb + hb[i] * std::abs(rb[0][i] * u.x + rb[1][i] * u.y + rb[2][i] * u.z);
    }
    const Vec3d pb = rounded(add(pa, mul(u, (sa + sb) * factor)), kPositionDecimals);
    out.line(fixed(ha, kExtentDecimals) + " " + fixed(pa, kPositionDecimals) + " " + fixed(qa) + "  " +
             fixed(hb, kExtentDecimals) + " " + fixed(pb, kPositionDecimals) + " " + fixed(qb));
  }
  return out;
}

Output spheres(std::uint64_t count, std::uint64_t repeat, std::uint64_t seed) {
  SplitMix64 rng(seed);
  Output out;
  out.line("sphere_pairs 1 count=" + std::to_string(count) + " repeat=" + std::to_string(repeat));
  for (std::uint64_t k = 0; k < count; ++k) {
    Vec3d c1;
    c1.x = rng.uniform(0, 10);
    c1.y = rng.uniform(0, 10);
    c1.z = rng.uniform(0, 10);
    c1 = rounded(c1, kPrimitiveDecimals);
    const double r1 = rounded(rng.uniform(0.1, 1.0), kExtentDecimals);
    const double r2 = rounded(rng.uniform(0.1, 1.0), kExtentDecimals);
    const Vec3d u = rng.unit_vector();
    const double factor = rng.uniform(0.5, 1.5);
    const Vec3d c2 = rounded(add(c1, mul(u, (r1 + r2) * factor)), kPrimitiveDecimals);
    out.line(fixed(c1, kPrimitiveDecimals) + " " + fixed(r1, kExtentDecimals) + " " + fixed(c2, kPrimitiveDecimals) +
             " " + fixed(r2, kExtentDecimals));
  }
  return out;
}

Output capsules(std::uint64_t count, std::uint64_t repeat, std::uint64_t seed) {
  SplitMix64 rng(seed);
  Output out;
  out.line("capsule_pairs 1 count=" + std::to_string(count) + " repeat=" + std::to_string(repeat));
  for (std::uint64_t k = 0; k < count; ++k) {
    Vec3d ca;
    ca.x = rng.uniform(0, 10);
    ca.y = rng.uniform(0, 10);
    ca.z = rng.uniform(0, 10);
    const double half_a = rng.uniform(0.1, 1.0);
    const Vec3d ua = rng.unit_vector();
    const double ra = rounded(rng.uniform(0.05, 0.5), kExtentDecimals);
    const double half_b = rng.uniform(0.1, 1.0);
    const Vec3d ub = rng.unit_vector();
    const double rb = rounded(rng.uniform(0.05, 0.5), kExtentDecimals);
    const double reach = half_a + half_b + ra + rb;
    const Vec3d offset_dir = rng.unit_vector();
    const double factor = rng.uniform(0.0, 1.0);
    const Vec3d cb = add(ca, mul(offset_dir, reach * factor));
    const Vec3d a0 = rounded(sub(ca, mul(ua, half_a)), kPrimitiveDecimals);
    const Vec3d a1 = rounded(add(ca, mul(ua, half_a)), kPrimitiveDecimals);
    const Vec3d b0 = rounded(sub(cb, mul(ub, half_b)), kPrimitiveDecimals);
    const Vec3d b1 = rounded(add(cb, mul(ub, half_b)), kPrimitiveDecimals);
    out.line(fixed(a0, kPrimitiveDecimals) + " " + fixed(a1, kPrimitiveDecimals) + " " + fixed(ra, kExtentDecimals) +
             "  " + fixed(b0, kPrimitiveDecimals) + " " + fixed(b1, kPrimitiveDecimals) + " " +
             fixed(rb, kExtentDecimals));
  }
  return out;
}

// ---------------------------------------------------------------------------------
// Command line
// ---------------------------------------------------------------------------------

constexpr const char* kUsage = R"(usage: proxima_make_workload <kind> [options] --out PATH

Writes a benchmark workload in the formats of shared/bench/FORMATS.md,
deterministically from --seed (splitmix64).

kinds and options (defaults in brackets; the default seeds and sizes are those of
the shared files):
  broadphase  --n N [10000] --frames F [100] --layout uniform|clustered [uniform]
              --seed S [101 uniform, 103 clustered] [--name NAME] --out FILE
  spheres     --count P [25000] --repeat R [40] --seed S [701] --out FILE
  capsules    --count P [25000] --repeat R [40] --seed S [702] --out FILE
  boxes       --count M [40000] --seed S [301] --out FILE
  convex      --points P [32] --shapes K [200] --count M [20000]
              --seed S [201/202/203 for P = 8/32/128, else 200] --out DIR
              (writes DIR/convex_shapes_<P>.txt and DIR/convex_pairs_<P>.txt;
              the pairs use seed S + 10)
)";

int usage_error(const std::string& message) {
  std::cerr << "proxima_make_workload: " << message << "\n\n" << kUsage;
  return 2;
}

struct Options {
  std::map<std::string, std::string> values;

  std::optional<std::uint64_t> integer(const std::string& key, std::uint64_t fallback, std::uint64_t lo,
                                       std::uint64_t hi, std::string& error) const {
    const auto it = values.find(key);
    if (it == values.end()) return fallback;
    char* end = nullptr;
    const unsigned long long v = std::strtoull(it->second.c_str(), &end, 10);
    if (it->second.empty() || *end != '\0' || it->second[0] == '-' || v < lo || v > hi) {
      error = "--" + key + " must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
      return std::nullopt;
    }
    return v;
  }
  std::string text(const std::string& key, const std::string& fallback = "") const {
    const auto it = values.find(key);
    return it == values.end() ? fallback : it->second;
  }
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage_error("missing the workload kind");
  const std::string kind = argv[1];
  if (kind == "--help" || kind == "-h" || kind == "help") {
    std::cout << kUsage;
    return 0;
  }
  Options options;
  for (int i = 2; i < argc; ++i) {
    std::string arg = argv[i];
    if (!arg.starts_with("--")) return usage_error("unexpected argument '" + arg + "'");
    arg.erase(0, 2);
    const std::size_t eq = arg.find('=');
    if (eq != std::string::npos) {
      options.values[arg.substr(0, eq)] = arg.substr(eq + 1);
    } else if (i + 1 < argc) {
      options.values[arg] = argv[++i];
    } else {
      return usage_error("--" + arg + " needs a value");
    }
  }
  const std::string out = options.text("out");
  if (out.empty()) return usage_error("missing --out");

  std::map<std::string, std::vector<std::string>> allowed = {
      {"broadphase", {"n", "frames", "layout", "seed", "name", "out"}},
      {"spheres", {"count", "repeat", "seed", "out"}},
      {"capsules", {"count", "repeat", "seed", "out"}},
      {"boxes", {"count", "seed", "out"}},
      {"convex", {"points", "shapes", "count", "seed", "out"}}};
  const auto kind_it = allowed.find(kind);
  if (kind_it == allowed.end()) return usage_error("unknown kind '" + kind + "'");
  for (const auto& [key, value] : options.values) {
    if (std::find(kind_it->second.begin(), kind_it->second.end(), key) == kind_it->second.end()) {
      return usage_error("option --" + key + " does not apply to " + kind);
    }
  }

  std::string error;
  constexpr std::uint64_t kMaxCount = 100000000;  // 1e8 records
  constexpr std::uint64_t kMaxSeed = ~std::uint64_t{0};
  if (kind == "broadphase") {
    const std::string layout = options.text("layout", "uniform");
    if (layout != "uniform" && layout != "clustered") return usage_error("--layout must be uniform or clustered");
    const bool clustered = layout == "clustered";
    const auto n = options.integer("n", 10000, 2, kMaxCount, error);
    const auto frames = options.integer("frames", 100, 0, 1000000, error);
    const auto seed = options.integer("seed", clustered ? 103 : 101, 0, kMaxSeed, error);
    if (!error.empty()) return usage_error(error);
    const std::string name = options.text("name");
    if (name.find_first_of(" \t\n") != std::string::npos) return usage_error("--name must not contain spaces");
    return broadphase(*n, static_cast<int>(*frames), clustered, *seed, name).write(out) ? 0 : 1;
  }
  if (kind == "spheres" || kind == "capsules") {
    const auto count = options.integer("count", 25000, 1, kMaxCount, error);
    const auto repeat = options.integer("repeat", 40, 1, kMaxCount, error);
    const auto seed = options.integer("seed", kind == "spheres" ? 701 : 702, 0, kMaxSeed, error);
    if (!error.empty()) return usage_error(error);
    const Output o = kind == "spheres" ? spheres(*count, *repeat, *seed) : capsules(*count, *repeat, *seed);
    return o.write(out) ? 0 : 1;
  }
  if (kind == "boxes") {
    const auto count = options.integer("count", 40000, 1, kMaxCount, error);
    const auto seed = options.integer("seed", 301, 0, kMaxSeed, error);
    if (!error.empty()) return usage_error(error);
    return boxes(*count, *seed).write(out) ? 0 : 1;
  }
  // convex
  const auto points = options.integer("points", 32, 1, 1000000, error);
  const auto shape_count = options.integer("shapes", 200, 1, 10000000, error);
  const auto count = options.integer("count", 20000, 1, kMaxCount, error);
  if (!error.empty()) return usage_error(error);
  const std::uint64_t default_seed = *points == 8 ? 201 : (*points == 32 ? 202 : (*points == 128 ? 203 : 200));
  const auto seed = options.integer("seed", default_seed, 0, kMaxSeed - 10, error);
  if (!error.empty()) return usage_error(error);
  const std::string shapes_name = "convex_shapes_" + std::to_string(*points) + ".txt";
  const std::string pairs_name = "convex_pairs_" + std::to_string(*points) + ".txt";
  const ConvexFiles files =
      convex(static_cast<int>(*shape_count), static_cast<int>(*points), *count, *seed, *seed + 10, shapes_name);
  const bool ok = files.shapes.write(proxima::bench::workload_path(out, shapes_name)) &&
                  files.pairs.write(proxima::bench::workload_path(out, pairs_name));
  return ok ? 0 : 1;
}
