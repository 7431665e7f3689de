// The camera of `proxima render` (RenderCamera, capture_render.hpp): the capture's own
// (orthographic or perspective), or a default direction whose orthographic view is fitted
// to the frame's points with a 7 % margin on every side.
#include <algorithm>
#include <cmath>

#include "capture_render.hpp"

namespace proxima::tool {

namespace {

/// Unit forward and up directions of a default view.
std::pair<Vec3, Vec3> view_axes(RenderView view, int dimension) {
  if (view == RenderView::Auto) view = dimension == 2 ? RenderView::Top : RenderView::Iso;
  switch (view) {
    case RenderView::Top: return {Vec3(0, 0, -1), Vec3(0, 1, 0)};
    case RenderView::Front: return {Vec3(0, 1, 0), Vec3(0, 0, 1)};
    default: return {glm::normalize(Vec3(-0.6f, 1, -0.8f)), Vec3(0, 0, 1)};
  }
}

/// Every point the frame draws (half-spaces' squares left out: they would fill the view).
std::vector<Vec3> frame_points(const std::vector<CaptureObject>& objects, const DrawBuffer& draw) {
  std::vector<Vec3> points;
  for (const CaptureObject& o : objects) {
    if (o.geometry_type == "halfspace") continue;
    for (const Vec3& p : o.positions) points.push_back(o.pose.apply(p));
  }
  for (const DrawTriangle& t : draw.triangles) points.insert(points.end(), {t.a, t.b, t.c});
  for (const DrawLine& l : draw.lines) points.insert(points.end(), {l.from, l.to});
  for (const DrawPoint& p : draw.points) points.push_back(p.position);
  for (const DrawBox& b : draw.boxes)
    points.insert(points.end(), {b.center - b.half_extents, b.center + b.half_extents});
  return points;
}

}  // namespace

RenderCamera RenderCamera::for_frame(const Capture& capture, const std::vector<CaptureObject>& objects,
                                     const CaptureStep& step, const RenderOptions& options) {
  RenderCamera camera;
  camera.cx_ = options.width / 2.0;
  camera.cy_ = options.height / 2.0;
  if (options.capture_camera && capture.camera) {
    const debug::CaptureCamera& c = *capture.camera;
    const Vec3 forward = c.target - c.position;
    const Vec3 right = glm::cross(forward, c.up);
    if (glm::length(forward) > Real(0) && glm::length(right) > Real(1e-6) * glm::length(forward) * glm::length(c.up)) {
      camera.eye_ = c.position;
      camera.forward_ = glm::normalize(forward);
      camera.right_ = glm::normalize(right);
      camera.up_ = glm::cross(camera.right_, camera.forward_);
      camera.perspective_ = c.fov_degrees > Real(0) && c.fov_degrees < Real(180);
      camera.scale_ = camera.perspective_
                          ? options.height / 2.0 / std::tan(double(c.fov_degrees) * 3.14159265358979 / 360.0)
                          : options.height / std::max(double(c.ortho_height), 1e-9);
      return camera;
    }
  }
  const auto [forward, up_hint] = view_axes(options.view, capture.dimension);
  camera.forward_ = forward;
  camera.right_ = glm::normalize(glm::cross(forward, up_hint));
  camera.up_ = glm::cross(camera.right_, camera.forward_);
  const std::vector<Vec3> points = frame_points(objects, step.draw);
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double v[3] = {glm::dot(points[i], camera.right_), glm::dot(points[i], camera.up_),
                         glm::dot(points[i], camera.forward_)};
    for (int k = 0; k < 3; ++k) {
      lo[k] = i == 0 ? v[k] : std::min(lo[k], v[k]);
      hi[k] = i == 0 ? v[k] : std::max(hi[k], v[k]);
    }
  }
  const double w = std::max(hi[0] - lo[0], 1e-6), h = std::max(hi[1] - lo[1], 1e-6);
  camera.scale_ = std::min(options.width / (w * 1.15), options.height / (h * 1.15));
  // The eye sits on the view's centre line, behind everything.
  camera.eye_ = camera.right_ * Real((lo[0] + hi[0]) / 2) + camera.up_ * Real((lo[1] + hi[1]) / 2) +
                camera.forward_ * Real(lo[2] - 1 - (hi[2] - lo[2]));
  return camera;
}

Projected RenderCamera::project(const Vec3& p) const {
  const Vec3 v = p - eye_;
  const double depth = glm::dot(v, forward_);
  const double x = glm::dot(v, right_), y = glm::dot(v, up_);
  if (perspective_) {
    if (!(depth > 1e-9)) return {0, 0, -1};
    return {cx_ + scale_ * x / depth, cy_ - scale_ * y / depth, depth};
  }
  return {cx_ + scale_ * x, cy_ - scale_ * y, depth};
}

}  // namespace proxima::tool
