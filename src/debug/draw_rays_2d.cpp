// Emitters of 2D rays (debug/draw_rays_2d.hpp): the ray and its hit lifted to z = 0 and
// drawn by the 3D emitter.
#include <proxima/debug/draw_rays_2d.hpp>
#include <proxima/debug/draw_shapes_2d.hpp>

namespace proxima::debug {

void draw_ray_2d(DebugDraw& sink, const d2::Ray& ray, Real max_t, const std::optional<d2::RayHit>& hit,
                 const RayDrawOptions& options) {
  const Ray lifted{plane_point(ray.origin), plane_point(ray.direction)};
  std::optional<RayHit> lifted_hit;
  if (hit) lifted_hit = RayHit{hit->t, plane_point(hit->point), plane_point(hit->normal), {}};
  draw_ray(sink, lifted, max_t, lifted_hit, options);
}

}  // namespace proxima::debug
