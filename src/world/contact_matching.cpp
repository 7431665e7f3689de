// Persistent contact points (see contact_matching.hpp for the steps and sources).
#include "world/contact_matching.hpp"

#include <array>
#include <limits>

namespace proxima::detail {

void match_contact_points(const WorldManifold* previous, const ContactManifold& now, std::uint32_t& next_id,
                          WorldManifold& out) {
  out.normal = now.normal;
  out.count = now.count;
  std::array<bool, kMaxContactPoints> used{};
  for (int k = 0; k < now.count; ++k) {
    const ContactPoint& c = now.points[k];
    WorldContactPoint& p = out.points[k];
    p = WorldContactPoint{};
    p.contact = c;
    int best = -1;
    Real best_d2 = std::numeric_limits<Real>::infinity();
    if (previous != nullptr) {
      for (int j = 0; j < previous->count; ++j) {
        const ContactPoint& o = previous->points[j].contact;
        if (used[j] || o.feature_id != c.feature_id || o.sub_a != c.sub_a || o.sub_b != c.sub_b) continue;
        const Vec3 d = o.point_a - c.point_a;
        const Real d2 = glm::dot(d, d);
        if (d2 < best_d2) {
          best_d2 = d2;
          best = j;
        }
      }
    }
    if (best >= 0) {
      used[best] = true;
      p.id = previous->points[best].id;
      p.user = previous->points[best].user;
      p.persisted = true;
    } else {
      p.id = next_id++;
    }
  }
}

}  // namespace proxima::detail
