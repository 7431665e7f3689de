// The exact smallest enclosing sphere (Welzl's algorithm, move-to-front with pivoting).
//
// Steps:
//  1. Validate; copy the points to double precision relative to the first point (far from
//     the origin the relative coordinates keep their precision); shuffle the copy with
//     Fisher-Yates driven by splitmix64 from a fixed seed (deterministic on every platform).
//  2. Move-to-front Welzl (Gaertner): mtf(end) walks the list before `end`; a point outside
//     the current ball is pushed onto the support set, the ball of the support set is
//     recomputed, mtf recurses on the points before it, and the point is moved to the
//     front of the list. Recursion depth <= 4 (a support set has at most 4 points).
//  3. Pivoting (Gaertner): repeatedly take the point of largest excess as a pivot and run
//     mtf with it in the support set, while the radius grows.
//  4. Support-set solver: the smallest ball with all support points on its boundary has
//     its centre in their affine hull: c = s0 + sum l_i (s_i - s0) with the Gram system
//     2 (v_i . v_j) l = |v_i|^2. A support set that is affinely dependent (collinear or
//     coplanar beyond its dimension, repeated points) is rejected (push fails) and the
//     point is skipped, as in Gaertner's implementation; the final pass guarantees
//     containment anyway.
//  5. Convert the centre to Real and take the radius as the largest distance (evaluated as
//     BoundingSphere::contains does), nudged up by ulps until every point passes.
// Sources: E. Welzl, "Smallest enclosing disks (balls and ellipsoids)", LNCS 555, 1991;
// B. Gaertner, "Fast and Robust Smallest Enclosing Balls", ESA 1999.
#include <proxima/bounds/fit_sphere.hpp>

#include <glm/geometric.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "bounds/fit_util.hpp"

namespace proxima {
namespace detail {
namespace {

// Points in a doubly linked list over indices (move-to-front without allocation).
class Miniball {
 public:
  explicit Miniball(std::span<const glm::dvec3> points) : p_(points) {
    const int n = static_cast<int>(points.size());
    next_.resize(static_cast<std::size_t>(n) + 1);
    prev_.resize(static_cast<std::size_t>(n) + 1);
    // Node n is the sentinel (end of the list).
    for (int i = 0; i <= n; ++i) {
      next_[static_cast<std::size_t>(i)] = i == n ? 0 : i + 1;
      prev_[static_cast<std::size_t>(i)] = i == 0 ? n : i - 1;
    }
    if (n == 0) next_[0] = prev_[0] = 0;
    end_ = n;
    double scale = 0.0;
    for (const glm::dvec3& p : points) scale = std::max(scale, glm::dot(p, p));
    tiny_ = 1e-28 * scale;
  }

  void run() {
    if (end_ == 0) return;
    int t = next(begin());  // the first point seeds the ball
    mtf(t);
    for (int guard = 0; guard < 10000; ++guard) {
      int pivot = end_;
      double max_e = 0.0;
      for (int k = t; k != end_; k = next(k)) {
        const double e = excess(p_[static_cast<std::size_t>(k)]);
        if (e > max_e) {
          max_e = e;
          pivot = k;
        }
      }
      if (!(max_e > 0.0) || pivot == end_) break;
      t = support_end_;
      if (t == pivot) t = next(t);
      const double old_r2 = r2_;
      if (push(p_[static_cast<std::size_t>(pivot)])) {
        mtf(support_end_);
        pop();
      }
      move_to_front(pivot);
      if (!(r2_ > old_r2)) break;
    }
  }

  glm::dvec3 center() const { return c_; }
  double radius_squared() const { return std::max(r2_, 0.0); }

 private:
  int begin() const { return next_[static_cast<std::size_t>(end_)]; }
  int next(int i) const { return next_[static_cast<std::size_t>(i)]; }

  double excess(const glm::dvec3& p) const {
    const glm::dvec3 d = p - c_;
    // Points within a relative 1e-12 of the boundary count as inside (the final pass
    // covers them); this keeps rounding from cycling the algorithm.
    return glm::dot(d, d) - r2_ - 1e-12 * r2_ - tiny_;
  }

  void mtf(int end) {
    support_end_ = begin();
    if (support_count_ == 4) return;
    for (int k = begin(); k != end;) {
      const int j = k;
      k = next(k);
      if (excess(p_[static_cast<std::size_t>(j)]) > 0.0) {
        if (push(p_[static_cast<std::size_t>(j)])) {
          mtf(j);
          pop();
          move_to_front(j);
        }
      }
    }
  }

  // Moves a point to the front of the list, keeping support_end_ past the support points.
  void move_to_front(int j) {
    if (support_end_ == j) support_end_ = next(j);
    if (begin() == j) return;
    const auto uj = static_cast<std::size_t>(j);
    next_[static_cast<std::size_t>(prev_[uj])] = next_[uj];
    prev_[static_cast<std::size_t>(next_[uj])] = prev_[uj];
    const int first = begin();
    next_[uj] = first;
    prev_[uj] = end_;
    prev_[static_cast<std::size_t>(first)] = j;
    next_[static_cast<std::size_t>(end_)] = j;
  }

  // Ball with all support points (plus p) on its boundary; false when degenerate.
  bool push(const glm::dvec3& p) {
    support_[static_cast<std::size_t>(support_count_)] = p;
    glm::dvec3 c;
    double r2;
    if (!ball_of(support_.data(), support_count_ + 1, c, r2)) return false;
    ++support_count_;
    c_ = c;
    r2_ = r2;
    return true;
  }
  void pop() { --support_count_; }

  static bool ball_of(const glm::dvec3* s, int count, glm::dvec3& c, double& r2) {
    const glm::dvec3& s0 = s[0];
    const std::size_t m = static_cast<std::size_t>(count) - 1;
    if (m == 0) {
      c = s0;
      r2 = 0.0;
      return true;
    }
    glm::dvec3 v[3];
    for (std::size_t i = 0; i < m; ++i) v[i] = s[i + 1] - s0;
    double a[3][3];
    double b[3];
    for (std::size_t i = 0; i < m; ++i) {
      for (std::size_t j = 0; j < m; ++j) a[i][j] = 2.0 * glm::dot(v[i], v[j]);
      b[i] = glm::dot(v[i], v[i]);
    }
    // Gaussian elimination with partial pivoting; reject nearly singular systems
    // (affinely dependent support points) relative to the diagonal (Hadamard bound).
    double hadamard = 1.0;
    for (std::size_t i = 0; i < m; ++i) hadamard *= a[i][i];
    if (!(hadamard > 0.0)) return false;
    double det = 1.0;
    for (std::size_t col = 0; col < m; ++col) {
      std::size_t piv = col;
      for (std::size_t r = col + 1; r < m; ++r) {
        if (std::abs(a[r][col]) > std::abs(a[piv][col])) piv = r;
      }
      if (piv != col) {
        for (std::size_t k = 0; k < m; ++k) std::swap(a[col][k], a[piv][k]);
        std::swap(b[col], b[piv]);
        det = -det;
      }
      det *= a[col][col];
      if (a[col][col] == 0.0) return false;
      for (std::size_t r = col + 1; r < m; ++r) {
        const double f = a[r][col] / a[col][col];
        for (std::size_t k = col; k < m; ++k) a[r][k] -= f * a[col][k];
        b[r] -= f * b[col];
      }
    }
    if (!(std::abs(det) > 1e-10 * hadamard)) return false;
    double l[3] = {0.0, 0.0, 0.0};
    for (std::size_t i = m; i-- > 0;) {
      double sum = b[i];
      for (std::size_t k = i + 1; k < m; ++k) sum -= a[i][k] * l[k];
      l[i] = sum / a[i][i];
    }
    glm::dvec3 rel(0.0);
    for (std::size_t i = 0; i < m; ++i) rel += l[i] * v[i];
    if (!std::isfinite(rel.x) || !std::isfinite(rel.y) || !std::isfinite(rel.z)) return false;
    c = s0 + rel;
    r2 = glm::dot(rel, rel);
    return true;
  }

  std::span<const glm::dvec3> p_;
  std::vector<int> next_;
  std::vector<int> prev_;
  int end_ = 0;
  std::array<glm::dvec3, 4> support_{};
  int support_count_ = 0;
  int support_end_ = 0;
  glm::dvec3 c_{0.0};
  double r2_ = -1.0;
  double tiny_ = 0.0;
};

}  // namespace

void minimal_ball(std::span<const glm::dvec3> points, glm::dvec3& center, double& radius_squared) {
  std::vector<glm::dvec3> shuffled(points.begin(), points.end());
  std::uint64_t state = 0x5EED0F5F1E5EEDull;
  for (std::size_t i = shuffled.size(); i > 1; --i) {
    const std::size_t j = static_cast<std::size_t>(splitmix64(state) % i);
    std::swap(shuffled[i - 1], shuffled[j]);
  }
  Miniball mb(shuffled);
  mb.run();
  center = mb.center();
  radius_squared = mb.radius_squared();
}

}  // namespace detail

Result<BoundingSphere> fit_sphere_minimal(std::span<const Vec3> points) {
  if (auto e = detail::validate_points(points)) return *e;
  const glm::dvec3 origin(points[0]);
  std::vector<glm::dvec3> rel;
  rel.reserve(points.size());
  for (const Vec3& p : points) rel.push_back(glm::dvec3(p) - origin);
  glm::dvec3 c;
  double r2;
  detail::minimal_ball(rel, c, r2);
  return detail::finish_sphere(points, Vec3(c + origin));
}

}  // namespace proxima
