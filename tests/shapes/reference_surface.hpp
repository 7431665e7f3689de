#pragma once
// A brute-force reference surface built from parametric patches in double, for the tests of
// the curved shapes. Each test writes its shape's surface as patches (a map from a
// rectangle of parameters to points, a periodic first parameter for angles); the surface
// gives dense samples for brute-force answers, and minimizes or maximizes a function over
// the surface by a pattern search started from the best sample of each patch, which
// refines the answer to the precision of double (support, world box, closest point). It
// never calls the code under test.
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>

#include <algorithm>
#include <cstddef>
#include <functional>
#include <limits>
#include <utility>
#include <vector>

namespace proxima::test {

using DVec3 = glm::dvec3;
inline constexpr double kPiD = 3.14159265358979323846;

// One parametric patch: at(a, b) for a in [a0, a1], b in [b0, b1], sampled on an na x nb grid.
struct Patch {
  double a0, a1;  // first parameter range (an angle when wrap_a: then it is not clamped)
  double b0, b1;  // second parameter range (clamped)
  bool wrap_a;
  int na, nb;  // sample counts
  std::function<DVec3(double, double)> at;
};

// A surface sample: the point, its patch and its parameters.
struct Sample {
  DVec3 p;
  int patch;
  double a, b;
};

// The surface: the union of the patches, with its dense samples.
class RefSurface {
 public:
  explicit RefSurface(std::vector<Patch> patches) : patches_(std::move(patches)) {
    for (int k = 0; k < static_cast<int>(patches_.size()); ++k) {
      const Patch& pa = patches_[static_cast<std::size_t>(k)];
      for (int i = 0; i < pa.na; ++i) {
        for (int j = 0; j < pa.nb; ++j) {
          const double a = pa.a0 + (pa.a1 - pa.a0) * i / (pa.na - 1);
          const double b = pa.b0 + (pa.b1 - pa.b0) * j / (pa.nb - 1);
          samples_.push_back({pa.at(a, b), k, a, b});
        }
      }
    }
  }

  const std::vector<Sample>& samples() const { return samples_; }

  // Minimum of f over the surface: the best sample of each patch refined by a pattern
  // search (8 neighbours, steps halved when no neighbour improves). The value is always
  // that of a true surface point, so it bounds the exact minimum from above.
  template <class F>
  std::pair<double, DVec3> minimize(F f) const {
    const std::size_t np = patches_.size();
    std::vector<double> best(np, std::numeric_limits<double>::infinity());
    std::vector<const Sample*> arg(np, nullptr);
    for (const Sample& s : samples_) {
      const double v = f(s.p);
      const std::size_t k = static_cast<std::size_t>(s.patch);
      if (v < best[k]) {
        best[k] = v;
        arg[k] = &s;
      }
    }
    std::pair<double, DVec3> result{std::numeric_limits<double>::infinity(), DVec3(0.0)};
    for (std::size_t k = 0; k < np; ++k) {
      if (arg[k] == nullptr) continue;
      const auto r = refine(patches_[k], *arg[k], f);
      if (r.first < result.first) result = r;
    }
    return result;
  }

  // Largest value of f over the surface (refined as minimize).
  template <class F>
  double maximize(F f) const {
    return -minimize([&f](const DVec3& p) { return -f(p); }).first;
  }

 private:
  template <class F>
  static std::pair<double, DVec3> refine(const Patch& pa, const Sample& s, F f) {
    double a = s.a;
    double b = s.b;
    double sa = (pa.a1 - pa.a0) / (pa.na - 1);
    double sb = (pa.b1 - pa.b0) / (pa.nb - 1);
    const double stop_a = 1e-15 * (pa.a1 - pa.a0);
    const double stop_b = 1e-15 * (pa.b1 - pa.b0);
    DVec3 p = s.p;
    double v = f(p);
    for (int it = 0; it < 3000 && (sa > stop_a || sb > stop_b); ++it) {
      bool moved = false;
      for (int da = -1; da <= 1; ++da) {
        for (int db = -1; db <= 1; ++db) {
          if (da == 0 && db == 0) continue;
          double na = a + da * sa;
          if (!pa.wrap_a) na = std::clamp(na, pa.a0, pa.a1);
          const double nb = std::clamp(b + db * sb, pa.b0, pa.b1);
          const DVec3 q = pa.at(na, nb);
          const double w = f(q);
          if (w < v) {
            v = w;
            p = q;
            a = na;
            b = nb;
            moved = true;
          }
        }
      }
      if (!moved) {
        sa *= 0.5;
        sb *= 0.5;
      }
    }
    return {v, p};
  }

  std::vector<Patch> patches_;
  std::vector<Sample> samples_;
};

// A Real vector in double.
inline DVec3 to_d(const Vec3& v) { return DVec3(v.x, v.y, v.z); }

// A pose in double (the same rotation and position, evaluated without Real rounding).
struct DPose {
  glm::dmat3 r;
  DVec3 t;
  explicit DPose(const Transform& pose)
      : r(glm::mat3_cast(glm::dquat(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z))),
        t(to_d(pose.position)) {}
  DVec3 apply(const DVec3& p) const { return r * p + t; }
};

// Reference ray cast: march on the test's implicit function, then bisect on contains().
struct MarchResult {
  bool deep = false;  // some sample is inside by more than the tolerance
  double t_deep = 0;  // first such sample
  bool entered = false;
  double t_bisect = 0;  // entry refined by bisection on contains()
};

template <class Implicit, class Contains>
inline MarchResult march(Implicit f, Contains contains, const Ray& ray, Real max_t, double tol, int steps) {
  MarchResult m;
  const DVec3 o = to_d(ray.origin);
  const DVec3 d = to_d(ray.direction);
  double prev = 0;
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(max_t) * i / steps;
    const double v = f(o + t * d);
    if (!m.entered && contains(ray.at(static_cast<Real>(t)))) {
      m.entered = true;
      double lo = prev;
      double hi = t;
      if (i == 0) {
        m.t_bisect = 0;
      } else {
        for (int k = 0; k < 200; ++k) {
          const double mid = 0.5 * (lo + hi);
          if (mid <= lo || mid >= hi) break;
          (contains(ray.at(static_cast<Real>(mid))) ? hi : lo) = mid;
        }
        m.t_bisect = hi;
      }
    }
    if (v < -tol) {
      m.deep = true;
      m.t_deep = t;
      break;
    }
    prev = t;
  }
  return m;
}

}  // namespace proxima::test
