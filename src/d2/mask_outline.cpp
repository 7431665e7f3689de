/// @file mask_outline.cpp
/// Outlines of sprite masks: boundary edges between set and clear pixels, linked into
/// loops with the left-turn rule at saddles (marching squares on pixel corners, with the
/// set region 4-connected), collinear corners dropped, then optional Douglas-Peucker
/// simplification (Douglas and Peucker, 1973) of each closed loop split at the vertex
/// farthest from its first one.

#include <proxima/d2/mask_outline.hpp>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <utility>

namespace proxima::d2 {
namespace {

/// Directions of unit edges between corners: +x, +y, -x, -y (counter-clockwise order in
/// the math frame, so (d + 1) mod 4 is a left turn).
constexpr int kStepX[4] = {1, 0, -1, 0};
constexpr int kStepY[4] = {0, 1, 0, -1};

/// The directed boundary edges leaving each corner: bit d of corners[v] is the edge in
/// direction d from corner v = y (width + 1) + x.
class CornerEdges {
 public:
  explicit CornerEdges(const SpriteMask& mask)
      : stride_(static_cast<std::int64_t>(mask.width()) + 1),
        edges_(static_cast<std::size_t>(stride_ * (mask.height() + 1)), 0) {
    for (std::int32_t y = 0; y < mask.height(); ++y) {
      for (std::int32_t x = 0; x < mask.width(); ++x) {
        if (!mask.get(x, y)) continue;
        if (!mask.get(x, y - 1)) add(x, y, 0);
        if (!mask.get(x + 1, y)) add(x + 1, y, 1);
        if (!mask.get(x, y + 1)) add(x + 1, y + 1, 2);
        if (!mask.get(x - 1, y)) add(x, y + 1, 3);
      }
    }
  }

  /// Corner index of (x, y).
  std::int64_t corner(std::int64_t x, std::int64_t y) const { return y * stride_ + x; }
  /// Number of corners.
  std::int64_t corner_count() const { return static_cast<std::int64_t>(edges_.size()); }
  /// Edges leaving corner v (bit d = direction d).
  std::uint8_t leaving(std::int64_t v) const { return edges_[static_cast<std::size_t>(v)]; }
  /// The loop that starts with the edge in direction `d` from corner v, as corner points;
  /// its edges are removed.
  OutlineLoop take_loop(std::int64_t v, int d);

 private:
  void add(std::int64_t x, std::int64_t y, int d) { edges_[static_cast<std::size_t>(corner(x, y))] |= 1u << d; }

  std::int64_t stride_;
  std::vector<std::uint8_t> edges_;
};

OutlineLoop CornerEdges::take_loop(std::int64_t v, int d) {
  OutlineLoop loop;
  std::int64_t x = v % stride_, y = v / stride_;
  int previous = -1;  // direction of the edge that reached (x, y)
  while (true) {
    edges_[static_cast<std::size_t>(corner(x, y))] &= static_cast<std::uint8_t>(~(1u << d));
    if (d != previous) loop.push_back(Vec2(static_cast<Real>(x), static_cast<Real>(y)));
    x += kStepX[d];
    y += kStepY[d];
    previous = d;
    const std::uint8_t out = leaving(corner(x, y));
    if (out == 0) return loop;          // back at the start: the loop's edges are all taken
    for (const int turn : {1, 0, 3}) {  // left, straight, right
      if (out & (1u << ((d + turn) % 4))) {
        d = (d + turn) % 4;
        break;
      }
    }
  }
}

/// Distance from p to the segment [a, b], in double.
double distance_to_segment(const Vec2& p, const Vec2& a, const Vec2& b) {
  const double abx = double(b.x) - a.x, aby = double(b.y) - a.y, apx = double(p.x) - a.x, apy = double(p.y) - a.y;
  const double length2 = abx * abx + aby * aby;
  const double t = length2 > 0 ? std::clamp((apx * abx + apy * aby) / length2, 0.0, 1.0) : 0.0;
  return std::hypot(apx - t * abx, apy - t * aby);
}

/// Douglas-Peucker on the vertices strictly between `first` and `last` (indices modulo
/// the loop size): marks in `keep` those that the chord cannot replace within tolerance.
void keep_needed(const OutlineLoop& loop, std::size_t first, std::size_t last, double tolerance,
                 std::vector<bool>& keep) {
  std::vector<std::pair<std::size_t, std::size_t>> pending = {{first, last}};
  while (!pending.empty()) {
    const auto [i, j] = pending.back();
    pending.pop_back();
    double farthest = tolerance;
    std::size_t split = i;
    for (std::size_t k = i + 1; k < j; ++k) {
      const double d = distance_to_segment(loop[k], loop[i], loop[j % loop.size()]);
      if (d > farthest) farthest = d, split = k;
    }
    if (split == i) continue;
    keep[split] = true;
    pending.push_back({i, split});
    pending.push_back({split, j});
  }
}

/// The loop simplified within `tolerance` (at least 3 vertices).
OutlineLoop simplified(const OutlineLoop& loop, double tolerance) {
  const std::size_t n = loop.size();
  std::size_t far = 0;
  for (std::size_t k = 1; k < n; ++k) {
    if (distance_to_segment(loop[k], loop[0], loop[0]) > distance_to_segment(loop[far], loop[0], loop[0])) far = k;
  }
  std::vector<bool> keep(n, false);
  keep[0] = keep[far] = true;
  keep_needed(loop, 0, far, tolerance, keep);
  keep_needed(loop, far, n, tolerance, keep);
  if (std::count(keep.begin(), keep.end(), true) < 3) {  // a thin loop: keep its corners
    keep_needed(loop, 0, far, 0.0, keep);
    keep_needed(loop, far, n, 0.0, keep);
  }
  OutlineLoop out;
  for (std::size_t k = 0; k < n; ++k) {
    if (keep[k]) out.push_back(loop[k]);
  }
  return out;
}

}  // namespace

std::vector<OutlineLoop> mask_outline(const SpriteMask& mask, double tolerance) {
  CornerEdges edges(mask);
  std::vector<OutlineLoop> loops;
  for (std::int64_t v = 0; v < edges.corner_count(); ++v) {
    while (edges.leaving(v) != 0) {
      OutlineLoop loop = edges.take_loop(v, std::countr_zero(edges.leaving(v)));
      loops.push_back(tolerance > 0 && loop.size() > 3 ? simplified(loop, tolerance) : std::move(loop));
    }
  }
  return loops;
}

double signed_area(const OutlineLoop& loop) {
  double twice = 0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Vec2& a = loop[i];
    const Vec2& b = loop[(i + 1) % loop.size()];
    twice += double(a.x) * double(b.y) - double(b.x) * double(a.y);
  }
  return twice / 2;
}

}  // namespace proxima::d2
