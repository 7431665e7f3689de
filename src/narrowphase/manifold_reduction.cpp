// Contact reduction: see manifold_reduction.hpp for the steps (deepest, farthest, largest
// triangle, largest quadrilateral) and the reference.
#include "narrowphase/manifold_reduction.hpp"

namespace proxima::narrow {

int reduce_contacts(std::span<const ContactPoint> points, const Vec3& normal, int k,
                    std::array<ContactPoint, kMaxContactPoints>& out) {
  std::array<int, 4> chosen{};
  const int n = static_cast<int>(points.size());
  const auto at = [&](int i) -> const ContactPoint& { return points[static_cast<std::size_t>(i)]; };
  const int count = select_contacts(
      n, [&](int i) { return (at(i).point_a + at(i).point_b) * Real(0.5); }, [&](int i) { return at(i).depth; },
      [](int) { return true; }, normal, k, chosen);
  for (int i = 0; i < count; ++i) out[static_cast<std::size_t>(i)] = at(chosen[static_cast<std::size_t>(i)]);
  return count;
}

}  // namespace proxima::narrow
