// The README's usage example: build a box, place it, ask for its bounds, a ray cast and a
// closest point.
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/placed.hpp>

#include <cstdio>

int main() {
  using namespace proxima;
  Box box = Box::create(Vec3(1, 2, 0.5)).value();  // validated: throws on bad sizes
  Transform pose{Vec3(0, 0, 10), glm::angleAxis(Real(0.3), Vec3(0, 1, 0))};
  Aabb bounds = box.world_aabb(pose);  // exact box of the rotated box
  auto hit = raycast(box, pose, Ray{Vec3(0), Vec3(0, 0, 1)}, Real(100));
  if (hit) std::printf("hit at t=%g, normal z=%g\n", double(hit->t), double(hit->normal.z));
  SurfacePoint cp = closest_point(box, pose, Vec3(3, 0, 10));  // signed distance, outward normal
  std::printf("bounds z in [%g, %g], distance %g\n", double(bounds.min.z), double(bounds.max.z),
              double(cp.signed_distance));
  return hit ? 0 : 1;
}
